// Unit tests of the implicit kernels (implicit_kernels.hpp) on plain arrays:
//   piola_tangent: dP/dG against central differences of the material's own update followed by
//   implicit_piola, in 2D (plane strain) and 3D (piola_tangent3: G and F 3 x 3, the six
//   stresses), at random G (|G| up to 0.1), committed stress and F, for linear elastic
//   (Jaumann rate) and neo-Hookean: the consistent tangent of the residual Newton solves;
//   the same for von Mises (elastic, perfectly plastic, hardening, softening) and Drucker-Prager
//   (elastic, cone associated and not, with and without hardening, apex with hardening or
//   dilation, the fixed apex, tension cut-off and its corner with the cone): each return branch
//   forced by the parameters and the random state, checked to 1e-6 of the tangent's largest
//   entry, the branch the same at G and G +- eps (else the trial is skipped, and counted);
//   implicit_gradient: a linear nodal displacement u_i = A x_i gives G = A and u_p = A x_p at every
//   particle (linear completeness of both shapes), and implicit_internal_force of a uniform P sums
//   to zero over the nodes (the gradients of a partition of unity sum to zero); in 3D also one
//   particle's stiffness (particle_stiffness, and through add_particle_blocks' node blocks) times
//   a random du against the internal force of the linear P = A4 : G(du); the reset grid's 3D
//   terms: the weights' second derivatives against differences of their gradients, and a plane
//   problem's 3D reset force and stiffness summed along z against the 2D kernels'.
#include "check.hpp"
#include "pmpm/solvers/implicit_kernels.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/materials/von_mises.hpp"
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

using namespace pmpm;

namespace {

// P(G) of one particle by the material's update on copies and implicit_piola.
// D = 2 (plane strain) or 3.
template <int D>
void piola_of(const Material &m, const double *G, const double *s_old, const double *Fn, double *P,
              double *s_new, double ep = 0) {
  constexpr int NS = NStress<D>;
  double s[NS], F[D * D];
  for (int k = 0; k < NS; ++k) s[k] = s_old[k];
  implicit_deformation<D>(1, G, Fn, F);
  double Gmid[D * D]; // the rate-form update reads the midpoint gradient, as newton.cpp passes it
  implicit_midpoint_gradient<D>(1, G, Gmid);
  const int idx = 0;
  StressBatch b;
  b.dim = D;
  b.n = 1;
  b.idx = &idx;
  b.dudx = Gmid;
  b.F = F;
  b.stress = s;
  b.eps_p = &ep;
  m.update_stress(b);
  implicit_piola<D>(1, G, s, P);
  if (s_new)
    for (int k = 0; k < NS; ++k) s_new[k] = s[k];
}

// The identity in D x D, row-major.
template <int D> void identity(double *F) {
  for (int k = 0; k < D * D; ++k) F[k] = k % (D + 1) == 0 ? 1.0 : 0.0;
}

template <int D> void test_tangent(bool neo_hookean) {
  constexpr int NS = NStress<D>, DD = D * D;
  const ElasticConstants el{1.0, 0.3}; // E = 1: stresses and tangents of order 1
  LinearElastic lin(el);
  NeoHookean neo(el);
  const Material &m = neo_hookean ? static_cast<const Material &>(neo) : lin;
  pmpm_test::Lcg rng(neo_hookean ? 7 : 3);
  for (int trial = 0; trial < 20; ++trial) {
    double G[DD], Fn[DD], s_old[NS], s_new[NS], P[DD], A[DD * DD];
    identity<D>(Fn);
    for (double &g : G) g = 0.2 * (rng.next() - 0.5);
    for (double &f : Fn) f += 0.2 * (rng.next() - 0.5);
    if (neo_hookean) { // the committed stress is the one of Fn
      const Mat3 s = neo_hookean_stress<D>(el, Fn);
      tensor_to_stress<D>(s, s_old);
    } else {
      for (double &s : s_old) s = 0.02 * (rng.next() - 0.5);
    }
    piola_of<D>(m, G, s_old, Fn, P, s_new);
    piola_tangent<D>(m, G, s_old, s_new, Fn, 0.0, A);
    // central differences: truncation eps^2 |P'''| ~ 1e-12, round-off 1e-16 / eps ~ 1e-10 for
    // P and A of order 1; 1e-7 leaves a margin of 1000 and catches any missing term (>= 1e-3)
    const double eps = 1e-6;
    for (int q = 0; q < DD; ++q) {
      double Gp[DD], Gm[DD], Pp[DD], Pm[DD];
      for (int k = 0; k < DD; ++k) Gp[k] = Gm[k] = G[k];
      Gp[q] += eps;
      Gm[q] -= eps;
      piola_of<D>(m, Gp, s_old, Fn, Pp, nullptr);
      piola_of<D>(m, Gm, s_old, Fn, Pm, nullptr);
      for (int r = 0; r < DD; ++r) CHECK_CLOSE(A[r * DD + q], (Pp[r] - Pm[r]) / (2 * eps), 1e-7);
    }
  }
}

// The return branch of a plastic material's update at G: 0 elastic, 1 von Mises / DP cone,
// 2 DP cut-off, 3 DP corner (cone and cut-off), 4 DP apex, 5 DP apex clamped to the cut-off.
ReturnResult return_of(const VonMises &m, Mat3 &s, double ep) {
  return von_mises_return(m.params(), s, ep);
}
ReturnResult return_of(const DruckerPrager &m, Mat3 &s, double ep) {
  return drucker_prager_return(m.params(), m.coefficients(), s, ep);
}
template <int D, class Law>
int branch_of(const Law &m, const double *G, const double *s_old, double ep) {
  Mat3 de, dw;
  double Gmid[D * D];
  implicit_midpoint_gradient<D>(1, G, Gmid);
  strain_and_spin<D>(Gmid, de, dw);
  Mat3 s = jaumann_rotate(stress_to_tensor<D>(s_old), dw) + elastic_increment(m.params().el, de);
  const ReturnResult r = return_of(m, s, ep);
  if (!r.yielded) return 0;
  if (r.apex) return r.tension ? 5 : 4;
  if (r.tension) return r.dgamma > 0 ? 3 : 2;
  return 1;
}

// One plastic case: random G (|G_ij| <= g), committed stress s0 + random (+- ds), committed
// eps_p in [0, 0.02]; trials at the wanted branch are checked until `want` of them passed the
// branch test at G +- eps (at most 5000 draws); at least `want` must be checked.
template <int D, class Law>
void test_plastic_case(const char *what, const Law &m, int branch, double g, const double *s0,
                       double ds, unsigned seed, int want = 20) {
  constexpr int NS = NStress<D>, DD = D * D;
  pmpm_test::Lcg rng(seed);
  int checked = 0, skipped = 0;
  double worst = 0;
  for (int draw = 0; draw < 5000 && checked < want; ++draw) {
    double G[DD], Fn[DD], s_old[NS], s_new[NS], P[DD], A[DD * DD];
    identity<D>(Fn);
    for (double &x : G) x = g * (2 * rng.next() - 1);
    for (double &f : Fn) f += 0.1 * (rng.next() - 0.5);
    for (int k = 0; k < NS; ++k) s_old[k] = s0[k] + ds * (2 * rng.next() - 1);
    const double ep = 0.02 * rng.next();
    if (branch_of<D>(m, G, s_old, ep) != branch) continue;
    // central differences: the return's third derivatives scale as 1 / q_tr^2 (q_tr >= 1e-3
    // here), eps^2 / q_tr^2 <= 1e-8 of the tangent; round-off 1e-16 |P| / eps ~ 1e-10
    const double eps = 1e-7;
    bool same = true;
    double Afd[DD * DD];
    for (int q = 0; q < DD && same; ++q) {
      double Gp[DD], Gm[DD], Pp[DD], Pm[DD];
      for (int k = 0; k < DD; ++k) Gp[k] = Gm[k] = G[k];
      Gp[q] += eps;
      Gm[q] -= eps;
      same = branch_of<D>(m, Gp, s_old, ep) == branch && branch_of<D>(m, Gm, s_old, ep) == branch;
      piola_of<D>(m, Gp, s_old, Fn, Pp, nullptr, ep);
      piola_of<D>(m, Gm, s_old, Fn, Pm, nullptr, ep);
      for (int r = 0; r < DD; ++r) Afd[r * DD + q] = (Pp[r] - Pm[r]) / (2 * eps);
    }
    if (!same) {
      ++skipped;
      continue;
    }
    piola_of<D>(m, G, s_old, Fn, P, s_new, ep);
    piola_tangent<D>(m, G, s_old, s_new, Fn, ep, A);
    double scale = 0;
    for (double a : Afd) scale = std::fmax(scale, std::fabs(a));
    for (int k = 0; k < DD * DD; ++k) {
      CHECK_CLOSE(A[k], Afd[k], 1e-6 * scale);
      worst = std::fmax(worst, std::fabs(A[k] - Afd[k]) / scale);
    }
    ++checked;
  }
  CHECK(checked >= want);
  std::printf("  %dD %-44s branch %d: %2d states, %d skipped at a branch edge, worst %.1e\n", D,
              what, branch, checked, skipped, worst);
}

template <int D> void test_plastic_tangents() {
  constexpr int NS = NStress<D>;
  const double INF = std::numeric_limits<double>::infinity();
  const ElasticConstants el{1.0, 0.3}; // E = 1, G = 0.385, K = 0.833
  // von Mises: the trial deviator of |G| <= 0.05 reaches q_tr ~ 0.03-0.1
  const double zero[NS] = {};
  struct VmCase {
    const char *what;
    double sy, H;
    int branch;
  } vm_cases[] = {{"von Mises elastic", 1.0, 0.0, 0},
                  {"von Mises perfectly plastic", 0.01, 0.0, 1},
                  {"von Mises hardening H = 0.2 E", 0.01, 0.2, 1},
                  {"von Mises softening H = -0.05 E", 0.02, -0.05, 1}};
  unsigned seed = 101;
  for (const VmCase &c : vm_cases) {
    VonMisesParams prm;
    prm.el = el;
    prm.sigma_y0 = c.sy;
    prm.hardening = c.H;
    VonMises m(prm);
    test_plastic_case<D>(c.what, m, c.branch, 0.05, zero, 0.01, seed++);
  }
  // Drucker-Prager around a committed compressive state p = -0.05 (cone, elastic), or a
  // tensile trial (apex, cut-off, corner)
  const double comp[NS] = {-0.05, -0.05, -0.05}; // shear components zero
  const double tens[NS] = {0.02, 0.02, 0.02};
  struct DpCase {
    const char *what;
    double c, phi, psi, H, t;
    DPMatch match;
    int branch;
    const double *s0;
    double g;
  } dp_cases[] = {
      {"Drucker-Prager elastic", 1.0, 30, 0, 0, INF, DPMatch::Outer, 0, comp, 0.02},
      {"DP cone, associated, H = 0", 0.005, 30, 30, 0, INF, DPMatch::Outer, 1, comp, 0.05},
      {"DP cone, psi = 5 deg, H = 0.1 E", 0.005, 30, 5, 0.1, INF, DPMatch::Inner, 1, comp, 0.05},
      {"DP cone, psi = 0, H = 0, plane-strain match", 0.005, 35, 0, 0, INF, DPMatch::PlaneStrain, 1,
       comp, 0.05},
      {"DP apex, associated, H = 0", 0.001, 30, 30, 0, INF, DPMatch::Outer, 4, tens, 0.01},
      {"DP apex, psi = 0, H = 0.1 E", 0.001, 30, 0, 0.1, INF, DPMatch::Outer, 4, tens, 0.01},
      {"DP apex fixed (psi = 0, H = 0)", 0.001, 30, 0, 0, INF, DPMatch::Outer, 4, tens, 0.01},
      {"DP apex clamped to the cut-off", 0.001, 30, 0, 0.1, 0.005, DPMatch::Outer, 5, tens, 0.002},
      {"DP tension cut-off", 0.05, 30, 10, 0, 0.005, DPMatch::Outer, 2, tens, 0.01},
      {"DP corner cone / cut-off", 0.01, 30, 10, 0.1, 0.005, DPMatch::Outer, 3, tens, 0.03}};
  for (const DpCase &c : dp_cases) {
    DruckerPragerParams prm;
    prm.el = el;
    prm.cohesion = c.c;
    prm.phi_deg = c.phi;
    prm.psi_deg = c.psi;
    prm.hardening = c.H;
    prm.tension_cutoff = c.t;
    prm.match = c.match;
    DruckerPrager m(prm);
    test_plastic_case<D>(c.what, m, c.branch, c.g, c.s0, 0.01, seed++);
  }
}

// A particle view of n particles over positions, half-sizes and volumes.
ParticleView view_of(int n, std::vector<double> &x, std::vector<double> &lp,
                     std::vector<double> &vol) {
  ParticleView P;
  P.n = n;
  P.x = x.data();
  P.lp = lp.data();
  P.vol = vol.data();
  return P;
}

template <class Shape> void test_completeness() {
  // a 6 x 6 node patch, h = 0.5 from (-1, 2); particles inside its interior cells
  const double h = 0.5;
  NodalView U, M, R;
  std::vector<double> u(36 * 2), mk(36 * 2, 1.0), r(36 * 2, 0.0);
  for (NodalView *v : {&U, &M, &R}) {
    v->h = h;
    v->origin[0] = -1.0;
    v->origin[1] = 2.0;
    v->gm[0] = v->gm[1] = 6;
  }
  U.data = u.data();
  M.data = mk.data();
  R.data = r.data();
  const double A[4] = {0.01, -0.02, 0.03, 0.005};
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const double x = -1.0 + i * h, y = 2.0 + j * h;
      U.node(i, j)[0] = A[0] * x + A[1] * y;
      U.node(i, j)[1] = A[2] * x + A[3] * y;
    }
  pmpm_test::Lcg rng(11);
  const int n = 12;
  std::vector<double> x(2 * n), lp(2 * n, 0.25 * h), vol(n, 0.01), G(4 * n), Pk(4 * n);
  for (int p = 0; p < n; ++p) {
    x[2 * p] = -1.0 + h * (1.0 + 3.0 * rng.next());
    x[2 * p + 1] = 2.0 + h * (1.0 + 3.0 * rng.next());
    for (int k = 0; k < 4; ++k) Pk[4 * p + k] = 1.0 + k;
  }
  ParticleView P = view_of(n, x, lp, vol);
  std::vector<double> up(2 * n);
  implicit_gradient<Shape>(P, U, M, G.data(), up.data());
  for (int p = 0; p < n; ++p) {
    for (int k = 0; k < 4; ++k) CHECK_CLOSE(G[4 * p + k], A[k], 1e-15);
    // the weights reproduce the linear field at the particle: u_p = A x_p (values ~ 0.1, 1e-15)
    CHECK_CLOSE(up[2 * p], A[0] * x[2 * p] + A[1] * x[2 * p + 1], 1e-15);
    CHECK_CLOSE(up[2 * p + 1], A[2] * x[2 * p] + A[3] * x[2 * p + 1], 1e-15);
  }
  implicit_internal_force<Shape>(P, Pk.data(), R);
  double sum[2] = {0, 0};
  for (int q = 0; q < 36; ++q)
    for (int a = 0; a < 2; ++a) sum[a] += r[2 * q + a];
  CHECK_CLOSE(sum[0], 0.0, 1e-14);
  CHECK_CLOSE(sum[1], 0.0, 1e-14);
}

// The 3D kernels on a 6 x 6 x 6 node patch (h = 0.5 from (-1, 2, 0.5)), particles inside its
// interior cells: a linear nodal displacement u_i = A x_i gives G = A and u_p = A x_p (linear
// completeness); a uniform P's internal force sums to zero; and one particle's stiffness is the
// derivative of its internal force: with P = A4 : G (A4 random), the force of G(du) equals K du
// from particle_stiffness, and the same product through add_particle_blocks' 3D node blocks.
template <class Shape> void test_kernels3d() {
  constexpr int D = 3, NN = Weights<Shape, 3>::NN, NS = Shape::NS, N1 = 6, NODES = N1 * N1 * N1;
  const double h = 0.5, o[3] = {-1.0, 2.0, 0.5};
  NodalViewT<3> U, M, R;
  std::vector<double> u(NODES * D), mk(NODES * D, 1.0), r(NODES * D, 0.0);
  for (NodalViewT<3> *v : {&U, &M, &R}) {
    v->h = h;
    for (int d = 0; d < D; ++d) {
      v->origin[d] = o[d];
      v->gm[d] = N1;
    }
  }
  U.data = u.data();
  M.data = mk.data();
  R.data = r.data();
  const double A[9] = {0.01, -0.02, 0.03, 0.005, 0.02, -0.01, 0.015, -0.025, 0.004};
  for (int k = 0; k < N1; ++k)
    for (int j = 0; j < N1; ++j)
      for (int i = 0; i < N1; ++i) {
        const double X[3] = {o[0] + i * h, o[1] + j * h, o[2] + k * h};
        for (int a = 0; a < D; ++a)
          U.node(i, j, k)[a] = A[3 * a] * X[0] + A[3 * a + 1] * X[1] + A[3 * a + 2] * X[2];
      }
  pmpm_test::Lcg rng(13);
  const int n = 12;
  std::vector<double> x(D * n), lp(D * n, 0.25 * h), vol(n, 0.01), G(9 * n), Pk(9 * n);
  for (int p = 0; p < n; ++p)
    for (int d = 0; d < D; ++d) x[D * p + d] = o[d] + h * (1.0 + 3.0 * rng.next());
  for (int p = 0; p < n; ++p)
    for (int k = 0; k < 9; ++k) Pk[9 * p + k] = 1.0 + k;
  ParticleView P = view_of(n, x, lp, vol);
  std::vector<double> up(D * n);
  implicit_gradient<Shape, 3>(P, U, M, G.data(), up.data());
  for (int p = 0; p < n; ++p) {
    for (int k = 0; k < 9; ++k) CHECK_CLOSE(G[9 * p + k], A[k], 1e-15);
    for (int a = 0; a < D; ++a)
      CHECK_CLOSE(up[D * p + a],
                  A[3 * a] * x[D * p] + A[3 * a + 1] * x[D * p + 1] + A[3 * a + 2] * x[D * p + 2],
                  1e-15);
  }
  implicit_internal_force<Shape, 3>(P, Pk.data(), R);
  for (int a = 0; a < D; ++a) {
    double sum = 0;
    for (int q = 0; q < NODES; ++q) sum += r[D * q + a];
    CHECK_CLOSE(sum, 0.0, 1e-14);
  }
  // one particle's stiffness against its linear internal force
  double A4[81];
  for (double &a : A4) a = rng.next() - 0.5;
  for (double &v : u) v = rng.next() - 0.5; // a random du
  ParticleView P1 = P;
  P1.n = 1;
  double G1[9], P1k[9];
  implicit_gradient<Shape, 3>(P1, U, M, G1);
  for (int a = 0; a < D; ++a)
    for (int j = 0; j < D; ++j) {
      double v = 0;
      for (int q = 0; q < 9; ++q) v += A4[(a * D + j) * 9 + q] * G1[q];
      P1k[a * D + j] = v;
    }
  std::fill(r.begin(), r.end(), 0.0);
  implicit_internal_force<Shape, 3>(P1, P1k, R);
  Weights<Shape, 3> W;
  weights<Shape, 3>(P1.x, P1.lp, U.origin, U.h, W);
  std::vector<double> K(NN * D * NN * D);
  particle_stiffness<Shape, 3>(W, vol[0], A4, K.data());
  const int w = NS - 1, nb = 2 * w + 1;
  std::vector<double> blocks(static_cast<size_t>(NODES) * nb * nb * nb * 9, 0.0);
  NodeBlocksT<3> B;
  B.w = w;
  B.data = blocks.data();
  for (int d = 0; d < D; ++d) B.gm[d] = N1;
  add_particle_blocks<Shape, 3>(W, K.data(), B);
  double scale = 0;
  for (double v : r) scale = std::fmax(scale, std::fabs(v));
  CHECK(scale > 0);
  for (int k = 0; k < NN; ++k) {
    const int ki = k % NS, kj = (k / NS) % NS, kk = k / (NS * NS);
    for (int a = 0; a < D; ++a) {
      double Kdu = 0, Bdu = 0;
      for (int m = 0; m < NN; ++m) {
        const int mi = m % NS, mj = (m / NS) % NS, mk = m / (NS * NS);
        const double *dum = U.node(W, m);
        const double *b =
            B.block(W.base[0] + ki, W.base[1] + kj, W.base[2] + kk, mi - ki, mj - kj, mk - kk);
        for (int c = 0; c < D; ++c) {
          Kdu += K[(k * D + a) * NN * D + (m * D + c)] * dum[c];
          Bdu += b[a * D + c] * dum[c];
        }
      }
      CHECK_CLOSE(Kdu, R.node(W, k)[a], 1e-13 * scale);
      CHECK_CLOSE(Bdu, Kdu, 1e-13 * scale);
    }
  }
}

// The reset grid's 3D terms. (a) weight_hessians<Shape, 3> against central differences of the
// 3D gradients (delta 1e-6 cells; positions away from the weights' kinks, where the gradients are
// linear and the differences exact to round-off, ~1e-8 / h^2 against values ~10 / h^2: bound
// 1e-6 / h^2). (b) A plane problem in 3D: a particle, its stress (no out-of-plane shear), du and u
// without z components; the 3D reset force and reset stiffness summed over each column of nodes
// along z (the z weights sum to one) equal the verified 2D kernels' to round-off (1e-13).
template <class Shape> void test_reset3d() {
  constexpr int NS = Shape::NS, NN3 = Weights<Shape, 3>::NN, NN2 = Weights<Shape, 2>::NN;
  const double h = 0.5, o[3] = {-1.0, 2.0, 0.5};
  pmpm_test::Lcg rng(17);
  // (a)
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    double x[3], l[3];
    bool kink = false;
    for (int d = 0; d < 3; ++d) {
      x[d] = o[d] + h * (2.0 + 2.0 * rng.next());
      l[d] = 0.25 * h;
      const double xi = (x[d] - o[d]) / h, li = l[d] / h;
      auto near = [](double v) { return std::fabs(v - std::round(v)) < 1e-5; };
      kink = kink || (NS == 2 ? near(xi) : near(xi - li) || near(xi + li));
    }
    if (kink) continue;
    ++compared;
    double Hs[NN3][NHess<3>];
    weight_hessians<Shape, 3>(x, l, o, h, Hs);
    for (int e = 0; e < 3; ++e) {
      Weights<Shape, 3> Wp, Wm;
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
      xp[e] += 1e-6 * h;
      xm[e] -= 1e-6 * h;
      weights<Shape, 3>(xp, l, o, h, Wp);
      weights<Shape, 3>(xm, l, o, h, Wm);
      for (int k = 0; k < NN3; ++k)
        for (int d = 0; d < 3; ++d)
          CHECK_CLOSE(Hs[k][hessian_index<3>(d, e)], (Wp.grad[k][d] - Wm.grad[k][d]) / (2e-6 * h),
                      1e-6 / (h * h));
    }
  }
  CHECK(compared >= 20);
  // (b) one particle at (x, y, z), nodes 6 x 6 (x 6 along z)
  constexpr int N1 = 6;
  double x3[3], lp3[3] = {0.25 * h, 0.25 * h, 0.25 * h};
  for (int d = 0; d < 3; ++d) x3[d] = o[d] + h * (2.0 + rng.next());
  const double u3[3] = {0.01 * (rng.next() - 0.5), 0.01 * (rng.next() - 0.5), 0.0};
  double G3[9] = {}, G2[4];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) G3[a * 3 + b] = G2[a * 2 + b] = 0.05 * (rng.next() - 0.5);
  double s3[6] = {}, s2[4];
  for (int q = 0; q < 3; ++q) s3[q] = s2[q] = rng.next() - 0.5; // xx yy zz
  s3[3] = s2[3] = rng.next() - 0.5;                             // xy; yz = xz = 0
  const double gw3[3] = {0.3, -1.0, 0.0}, weight = 2.0, V = 0.01;
  double P3[9], P2[4];
  implicit_piola<3>(1, G3, s3, P3);
  implicit_piola<2>(1, G2, s2, P2);
  ParticleView Q3, Q2;
  Q3.n = Q2.n = 1;
  double vol = V, wt = weight, x2[2] = {x3[0], x3[1]}, lp2[2] = {lp3[0], lp3[1]};
  Q3.x = x3;
  Q3.lp = lp3;
  Q2.x = x2;
  Q2.lp = lp2;
  Q3.vol = Q2.vol = &vol;
  Q3.weight = Q2.weight = &wt;
  NodalViewT<3> R3;
  NodalViewT<2> R2;
  std::vector<double> r3(N1 * N1 * N1 * 3, 0.0), r2(N1 * N1 * 2, 0.0);
  R3.h = R2.h = h;
  for (int d = 0; d < 3; ++d) {
    R3.origin[d] = o[d];
    R3.gm[d] = N1;
    if (d < 2) {
      R2.origin[d] = o[d];
      R2.gm[d] = N1;
    }
  }
  R3.data = r3.data();
  R2.data = r2.data();
  const double u2[2] = {u3[0], u3[1]};
  CHECK((reset_internal_force<Shape, 3>(Q3, G3, s3, P3, u3, gw3, R3) == 0));
  CHECK((reset_internal_force<Shape, 2>(Q2, G2, s2, P2, u2, gw3, R2) == 0));
  double scale = 0;
  for (double v : r2) scale = std::fmax(scale, std::fabs(v));
  CHECK(scale > 0);
  for (int j = 0; j < N1; ++j)
    for (int i = 0; i < N1; ++i) {
      double sum[3] = {0, 0, 0};
      for (int k = 0; k < N1; ++k)
        for (int a = 0; a < 3; ++a) sum[a] += R3.node(i, j, k)[a];
      for (int a = 0; a < 2; ++a) CHECK_CLOSE(sum[a], R2.node(i, j)[a], 1e-13 * scale);
      CHECK_CLOSE(sum[2], 0.0, 1e-13 * scale);
    }
  // the stiffness: K3 summed over the z offsets of its row and column nodes, in-plane entries
  Weights<Shape, 3> W3;
  Weights<Shape, 2> W2;
  weights<Shape, 3>(x3, lp3, o, h, W3);
  weights<Shape, 2>(x2, lp2, o, h, W2);
  double H3[NN3][NHess<3>], H2[NN2][NHess<2>];
  weight_hessians<Shape, 3>(x3, lp3, o, h, H3);
  weight_hessians<Shape, 2>(x2, lp2, o, h, H2);
  std::vector<double> K3(NN3 * 3 * NN3 * 3, 0.0), K2(NN2 * 2 * NN2 * 2, 0.0);
  particle_reset_stiffness<Shape, 3>(W3, H3, V, G3, s3, weight, gw3, K3.data());
  particle_reset_stiffness<Shape, 2>(W2, H2, V, G2, s2, weight, gw3, K2.data());
  double kscale = 0;
  for (double v : K2) kscale = std::fmax(kscale, std::fabs(v));
  CHECK(kscale > 0);
  for (int k2 = 0; k2 < NN2; ++k2)
    for (int m2 = 0; m2 < NN2; ++m2)
      for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c) {
          double sum = 0;
          for (int kz = 0; kz < NS; ++kz)
            for (int mz = 0; mz < NS; ++mz) {
              const int k3 = k2 + NN2 * kz, m3 = m2 + NN2 * mz;
              sum += K3[(k3 * 3 + a) * NN3 * 3 + (m3 * 3 + c)];
            }
          CHECK_CLOSE(sum, K2[(k2 * 2 + a) * NN2 * 2 + (m2 * 2 + c)], 1e-13 * kscale);
        }
}

} // namespace

int main() {
  test_tangent<2>(false); // linear elastic
  test_tangent<2>(true);  // neo-Hookean
  test_plastic_tangents<2>();
  test_tangent<3>(false); // the same in 3D (piola_tangent3)
  test_tangent<3>(true);
  test_plastic_tangents<3>();
  test_completeness<LinearShape>();
  test_completeness<UGIMPShape>();
  test_kernels3d<LinearShape>();
  test_kernels3d<UGIMPShape>();
  test_reset3d<LinearShape>();
  test_reset3d<UGIMPShape>();
  return pmpm_test::report("implicit");
}
