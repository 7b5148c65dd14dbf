// Unit tests of the implicit kernels (implicit_kernels.hpp) on plain arrays:
//   piola_tangent: dP/dG against central differences of the material's own update followed by
//   implicit_piola, at random G (|G| up to 0.1), committed stress and F, for linear elastic
//   (Jaumann rate) and neo-Hookean: the consistent tangent of the residual Newton solves;
//   implicit_gradient: a linear nodal displacement u_i = A x_i gives G = A at every particle
//   (linear completeness of both shapes), and implicit_internal_force of a uniform P sums to zero
//   over the nodes (the gradients of a partition of unity sum to zero).
#include "check.hpp"
#include "pmpm/implicit_kernels.hpp"
#include "pmpm/materials/elastic.hpp"
#include <vector>

using namespace pmpm;

namespace {

// P(G) of one particle by the material's update on copies and implicit_piola.
void piola_of(const Material &m, const double *G, const double *s_old, const double *Fn, double *P,
              double *s_new) {
  double s[NSTRESS], F[4], ep = 0;
  for (int k = 0; k < NSTRESS; ++k) s[k] = s_old[k];
  implicit_deformation(1, G, Fn, F);
  const int idx = 0;
  StressBatch b;
  b.n = 1;
  b.idx = &idx;
  b.dudx = G;
  b.F = F;
  b.stress = s;
  b.eps_p = &ep;
  m.update_stress(b);
  implicit_piola(1, G, s, P);
  if (s_new)
    for (int k = 0; k < NSTRESS; ++k) s_new[k] = s[k];
}

void test_tangent(TangentKind kind) {
  const ElasticConstants el{1.0, 0.3}; // E = 1: stresses and tangents of order 1
  LinearElastic lin(el);
  NeoHookean neo(el);
  const Material &m = kind == TangentKind::NeoHookean ? static_cast<const Material &>(neo) : lin;
  pmpm_test::Lcg rng(kind == TangentKind::NeoHookean ? 7 : 3);
  for (int trial = 0; trial < 20; ++trial) {
    double G[4], Fn[4] = {1, 0, 0, 1}, s_old[NSTRESS], s_new[NSTRESS], P[4], A[16];
    for (double &g : G) g = 0.2 * (rng.next() - 0.5);
    for (double &f : Fn) f += 0.2 * (rng.next() - 0.5);
    if (kind == TangentKind::NeoHookean) { // the committed stress is the one of Fn
      const Mat3 s = neo_hookean_stress(el, Fn);
      tensor_to_stress(s, s_old);
    } else {
      for (double &s : s_old) s = 0.02 * (rng.next() - 0.5);
    }
    piola_of(m, G, s_old, Fn, P, s_new);
    piola_tangent(kind, el, G, s_old, s_new, Fn, A);
    // central differences: truncation eps^2 |P'''| ~ 1e-12, round-off 1e-16 / eps ~ 1e-10 for
    // P and A of order 1; 1e-7 leaves a margin of 1000 and catches any missing term (>= 1e-3)
    const double eps = 1e-6;
    for (int q = 0; q < 4; ++q) {
      double Gp[4], Gm[4], Pp[4], Pm[4];
      for (int k = 0; k < 4; ++k) Gp[k] = Gm[k] = G[k];
      Gp[q] += eps;
      Gm[q] -= eps;
      piola_of(m, Gp, s_old, Fn, Pp, nullptr);
      piola_of(m, Gm, s_old, Fn, Pm, nullptr);
      for (int r = 0; r < 4; ++r) CHECK_CLOSE(A[r * 4 + q], (Pp[r] - Pm[r]) / (2 * eps), 1e-7);
    }
  }
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
  ParticleView P;
  P.n = n;
  P.x = x.data();
  P.lp = lp.data();
  P.vol = vol.data();
  implicit_gradient<Shape>(P, U, M, G.data());
  for (int p = 0; p < n; ++p)
    for (int k = 0; k < 4; ++k) CHECK_CLOSE(G[4 * p + k], A[k], 1e-15);
  implicit_internal_force<Shape>(P, Pk.data(), R);
  double sum[2] = {0, 0};
  for (int q = 0; q < 36; ++q)
    for (int a = 0; a < 2; ++a) sum[a] += r[2 * q + a];
  CHECK_CLOSE(sum[0], 0.0, 1e-14);
  CHECK_CLOSE(sum[1], 0.0, 1e-14);
}

} // namespace

int main() {
  test_tangent(TangentKind::LinearElastic);
  test_tangent(TangentKind::NeoHookean);
  test_completeness<LinearShape>();
  test_completeness<UGIMPShape>();
  return pmpm_test::report("implicit");
}
