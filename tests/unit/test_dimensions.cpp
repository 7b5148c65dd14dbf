// The dimension-generic kernels (developer guide, "Dimensions") in 2D and 3D, for every shape
// (mpm, pmpm, cpgimp), on plain arrays:
//   weights<Shape, D>: partition of unity, linear reproduction, gradients summing to zero and
//                      reproducing the identity (sum_i x_i grad S_ip^T = I), at random positions
//                      and at positions on and next to cell faces;
//   p2g<Shape, D>:     mass and momentum conserved (FLIP and APIC); the internal force of a uniform
//                      stress vanishes at interior nodes and the nodes on either side of a
//                      mid-plane carry the face's traction -sigma n A; its first moment is -V
//                      sigma;
//   g2p<Shape, D>:     PIC gather of an affine nodal field returns v(x_p) and L = A; APIC's P2G
//   then
//                      G2P of an affine particle field returns v_p and B_p (C_p = A);
//   grid_update<D>:    the momentum balance and the faces' held dofs;
//   p2g_traction:      the face load's sum and first moment; the 3D stress storage round trip;
//   a 3D explicit cycle of an elastic cube under gravity: momentum p_0 + t M g at every step.
// These are identities of the tensor-product weights (sum_i S_i = 1, sum_i S_i x_i = x,
// sum_i grad S_i = 0, sum_i grad S_i x_i^T = I), exact in real arithmetic: the tolerances are
// round-off, a few hundred ulps of the sums' magnitude (at most 4^3 = 64 nodes per particle and a
// few thousand particles per sum), not model error.
#include "check.hpp"
#include "pmpm/core/affine.hpp"
#include "pmpm/core/transfers.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

using namespace pmpm;

namespace {

constexpr double EPS = 1e-13; // round-off tolerance for O(1) sums of up to 64 terms (~300 ulp)

template <int D> struct TestGrid {
  std::vector<double> data;
  GridViewT<D> G;
  TestGrid(PetscInt n, double h) {
    G.h = h;
    for (int d = 0; d < D; ++d) {
      G.origin[d] = -0.7 + 0.3 * d;
      G.ncell[d] = n;
      G.gs[d] = -2;
      G.gm[d] = n + 5;
    }
    size_t nn = 1;
    for (int d = 0; d < D; ++d) nn *= G.gm[d];
    data.assign(nn * GridDofT<D>::NDOF, 0.0);
    G.data = data.data();
  }
  void zero() { std::fill(data.begin(), data.end(), 0.0); }
  // f(n, x, node) for every node
  template <class F> void for_nodes(F f) const {
    const PetscInt k1 = D == 3 ? G.gm[2] : 1;
    PetscInt n[D];
    double x[D];
    for (PetscInt k = 0; k < k1; ++k)
      for (PetscInt j = 0; j < G.gm[1]; ++j)
        for (PetscInt i = 0; i < G.gm[0]; ++i) {
          n[0] = G.gs[0] + i;
          n[1] = G.gs[1] + j;
          if (D == 3) n[D - 1] = G.gs[D - 1] + k;
          for (int d = 0; d < D; ++d) x[d] = G.origin[d] + n[d] * G.h;
          f(n, x, G.node(n));
        }
  }
};

template <int D> struct TestParticles {
  std::vector<double> x, x0, v, lp, mass, vol, vol0, weight, stress, F, colour, B, dudx;
  std::vector<PetscInt> mat, pid;
  ParticleView P;
  TestParticles(const TestParticles &) = delete;
  explicit TestParticles(PetscInt n, bool apic = false) {
    x.assign(n * D, 0.0);
    x0.assign(n * D, 0.0);
    v.assign(n * D, 0.0);
    lp.assign(n * D, 0.0);
    mass.assign(n, 1.0);
    vol.assign(n, 1.0);
    vol0.assign(n, 1.0);
    weight.assign(n, 0.0);
    stress.assign(n * NStress<D>, 0.0);
    F.assign(n * D * D, 0.0);
    for (PetscInt p = 0; p < n; ++p)
      for (int d = 0; d < D; ++d) F[p * D * D + d * D + d] = 1.0;
    colour.assign(n, 0.0);
    B.assign(n * D * D, 0.0);
    dudx.assign(n * D * D, 0.0);
    mat.assign(n, 0);
    pid.resize(n);
    for (PetscInt p = 0; p < n; ++p) pid[p] = p;
    P.n = n;
    P.x = x.data();
    P.x0 = x0.data();
    P.v = v.data();
    P.lp = lp.data();
    P.mass = mass.data();
    P.vol = vol.data();
    P.vol0 = vol0.data();
    P.weight = weight.data();
    P.stress = stress.data();
    P.F = F.data();
    P.colour = colour.data();
    P.mat = mat.data();
    P.pid = pid.data();
    P.B = apic ? B.data() : nullptr;
  }
};

// A random position in cells [1, n - 1) of the grid; with probability 1/2 each coordinate is put
// on a cell face, a hair (1e-12 cells) to either side of one, or where the block (half-size l)
// ends on a face: the weights' case boundaries.
double coordinate(pmpm_test::Lcg &r, double o, double h, PetscInt n, double l) {
  const double c = 1.0 + std::floor(r.uniform(0.0, n - 2.0));
  double f = r.next();
  const double u = r.next();
  if (u < 0.1)
    f = 0.0;
  else if (u < 0.2)
    f = 1e-12;
  else if (u < 0.3)
    f = 1.0 - 1e-12;
  else if (u < 0.4)
    f = l / h; // block's left end on the face
  else if (u < 0.5)
    f = 1.0 - l / h; // right end
  return o + (c + f) * h;
}

// A random deformation gradient near I (stretches within [0.6, 1.6]): cpGIMP's block follows it.
template <int D> void random_F(pmpm_test::Lcg &r, double *F) {
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) F[i * D + j] = (i == j ? 1.0 : 0.0) + r.uniform(-0.3, 0.3);
}

template <class Shape> constexpr bool is_cpgimp = std::is_same<Shape, CPGIMPShape>::value;

// weights<Shape, D>: the four identities at random positions and half-sizes.
template <class Shape, int D> void check_weights() {
  pmpm_test::Lcg r(0x1234u + D * 7 + Shape::NS);
  const double h = 0.37, origin[3] = {-0.7, -0.4, -0.1};
  const PetscInt n = 8;
  Weights<Shape, D> W;
  double worst[4] = {0, 0, 0, 0};
  for (int t = 0; t < 2000; ++t) {
    double lp[D], x[D], Fm[D * D], lb[D];
    for (int d = 0; d < D; ++d) lp[d] = h * r.uniform(0.15, 0.5);
    random_F<D>(r, Fm);
    const double *l = Shape::template half<D>(lp, Fm, lb);
    for (int d = 0; d < D; ++d) x[d] = coordinate(r, origin[d], h, n, l[d]);
    weights<Shape, D>(x, l, origin, h, W);
    double sw = 0, sx[D] = {}, sg[D] = {}, sgx[D][D] = {};
    for (int k = 0; k < W.NN; ++k) {
      double xi[D];
      for (int d = 0, q = k; d < D; ++d, q /= Shape::NS)
        xi[d] = origin[d] + (W.base[d] + q % Shape::NS) * h;
      sw += W.w[k];
      for (int d = 0; d < D; ++d) {
        sx[d] += W.w[k] * xi[d];
        sg[d] += W.grad[k][d];
        for (int e = 0; e < D; ++e) sgx[d][e] += xi[d] * W.grad[k][e];
      }
      CHECK(W.w[k] >= -EPS); // non-negative weights
    }
    worst[0] = std::fmax(worst[0], std::fabs(sw - 1.0));
    for (int d = 0; d < D; ++d) {
      worst[1] = std::fmax(worst[1], std::fabs(sx[d] - x[d]));
      worst[2] = std::fmax(worst[2], std::fabs(sg[d]) * h);
      for (int e = 0; e < D; ++e)
        worst[3] = std::fmax(worst[3], std::fabs(sgx[d][e] - (d == e ? 1.0 : 0.0)));
    }
  }
  std::printf("  weights %-6s %dD: |sum S - 1| %.2g, |sum S x - x| %.2g m, |sum grad S| h %.2g, "
              "|sum x grad S^T - I| %.2g\n",
              Shape::name, D, worst[0], worst[1], worst[2], worst[3]);
  CHECK(worst[0] <= EPS);
  CHECK(worst[1] <= EPS); // |x| ~ 3 m
  CHECK(worst[2] <= EPS);
  CHECK(worst[3] <= 10 * EPS); // x_i grad S: terms of |x| / h ~ 10
}

// Random particles, each with its own half-size, deformation gradient (cpGIMP) and velocity.
template <class Shape, int D>
void random_particles(pmpm_test::Lcg &r, TestParticles<D> &T, const GridViewT<D> &G) {
  for (PetscInt p = 0; p < T.P.n; ++p) {
    double lb[D];
    for (int d = 0; d < D; ++d) T.lp[p * D + d] = G.h * r.uniform(0.15, 0.5);
    if (is_cpgimp<Shape>) random_F<D>(r, &T.F[p * D * D]);
    const double *l = Shape::template half<D>(&T.lp[p * D], &T.F[p * D * D], lb);
    for (int d = 0; d < D; ++d) {
      T.x[p * D + d] = coordinate(r, G.origin[d], G.h, G.ncell[d], l[d]);
      T.v[p * D + d] = r.uniform(-1.0, 1.0);
    }
    T.mass[p] = r.uniform(0.5, 2.0);
  }
}

// P2G conserves mass and momentum (FLIP and APIC: sum_i a_ip = D^-1 sum_i w (x_i - x_p) = 0).
template <class Shape, int D> void check_conservation(bool apic) {
  pmpm_test::Lcg r(0x777u + D + Shape::NS + (apic ? 100 : 0));
  TestGrid<D> TG(7, 0.31);
  TestParticles<D> T(400, apic);
  random_particles<Shape, D>(r, T, TG.G);
  if (apic)
    for (auto &b : T.B) b = r.uniform(-0.05, 0.05);
  LoadT<D> load;
  p2g<Shape, D>(T.P, load, TG.G);
  double m = 0, mn = 0, pm[D] = {}, pn[D] = {};
  for (PetscInt p = 0; p < T.P.n; ++p) {
    m += T.mass[p];
    for (int d = 0; d < D; ++d) pm[d] += T.mass[p] * T.v[p * D + d];
  }
  TG.for_nodes([&](const PetscInt *, const double *, const double *node) {
    mn += node[GridDofT<D>::M];
    for (int d = 0; d < D; ++d) pn[d] += node[GridDofT<D>::P + d];
  });
  std::printf("  p2g %-6s %dD %s: mass %.3g, momentum", Shape::name, D, apic ? "apic" : "flip",
              std::fabs(mn - m) / m);
  CHECK_CLOSE(mn / m, 1.0, EPS);
  for (int d = 0; d < D; ++d) {
    std::printf(" %.3g", std::fabs(pn[d] - pm[d]) / m);
    CHECK_CLOSE(pn[d] / m, pm[d] / m, EPS); // momenta ~ 0.1 m, sums of ~1e4 terms
  }
  std::printf("\n");
}

// The internal force of a uniform stress on a box of particles that fills cells [c0, c1)^D
// (2 particles per direction per cell; blocks of half-size h/4 tile the box). Their quadrature
// integrates grad N_i over the box exactly (uGIMP and cpGIMP average over the blocks exactly;
// linear hats: the midpoint rule on each sub-cell is exact for the multilinear grad N_i), so
//   f_i = -sigma int_box grad N_i = -sigma oint_box N_i n dA:
// zero at nodes whose support lies inside the box, and the nodes beyond the box's mid-plane
// normal to e carry -sigma e A (A the face's area), those before it +sigma e A.
template <class Shape, int D> void check_uniform_stress() {
  pmpm_test::Lcg r(0x999u + D + Shape::NS);
  const PetscInt n = 8, c0 = 2, c1 = 7; // 5 cells: the mid-plane is inside a cell
  TestGrid<D> TG(n, 0.25);
  const double h = TG.G.h;
  PetscInt np = 1;
  for (int d = 0; d < D; ++d) np *= 2 * (c1 - c0);
  TestParticles<D> T(np);
  const double Vp = std::pow(0.5 * h, D);
  double sig[6];
  for (double &s : sig) s = r.uniform(-1.0, 1.0);
  for (PetscInt p = 0; p < np; ++p) {
    for (int d = 0, q = p; d < D; ++d, q /= 2 * (c1 - c0))
      T.x[p * D + d] = TG.G.origin[d] + (c0 + 0.25 + 0.5 * (q % (2 * (c1 - c0)))) * h;
    for (int d = 0; d < D; ++d) T.lp[p * D + d] = 0.25 * h;
    T.vol[p] = T.vol0[p] = Vp;
    for (int k = 0; k < NStress<D>; ++k) T.stress[p * NStress<D> + k] = sig[k];
  }
  LoadT<D> load;
  p2g<Shape, D>(T.P, load, TG.G);
  const double A = std::pow((c1 - c0) * h, D - 1), mid = 0.5 * (c0 + c1);
  const double scale = A; // |sigma| <= 1: forces of order A
  double interior = 0, side = 0, moment = 0;
  double hi[D][D] = {}, lo[D][D] = {}, M[D][D] = {}; // [normal e][component d]
  TG.for_nodes([&](const PetscInt *ni, const double *x, const double *node) {
    const double *f = node + GridDofT<D>::F;
    bool inside = true;
    for (int d = 0; d < D; ++d) inside = inside && ni[d] > c0 && ni[d] < c1;
    if (inside)
      for (int d = 0; d < D; ++d) interior = std::fmax(interior, std::fabs(f[d]));
    for (int e = 0; e < D; ++e)
      for (int d = 0; d < D; ++d) {
        (ni[e] > mid ? hi : lo)[e][d] += f[d];
        M[d][e] += f[d] * x[e];
      }
  });
  const double V = np * Vp;
  for (int e = 0; e < D; ++e)
    for (int d = 0; d < D; ++d) {
      const double s = sig[stress_slot(d, e)];
      side = std::fmax(side, std::fabs(hi[e][d] + s * A));
      side = std::fmax(side, std::fabs(lo[e][d] - s * A));
      moment = std::fmax(moment, std::fabs(M[d][e] + V * s));
    }
  std::printf("  uniform stress %-6s %dD: interior |f| %.2g, face sums %.2g, first moment %.2g "
              "(of A = %.3g)\n",
              Shape::name, D, interior / scale, side / scale, moment / scale, A);
  CHECK(interior <= EPS * scale);
  CHECK(side <= EPS * scale);
  CHECK(moment <= EPS * scale);
}

// PIC gather of an affine nodal field v(x) = v0 + A x: v_p = v(x_p), L_p = A, x_p += dt v(x_p),
// F_p = (I + dt A) F_p. (The grid field is set at the nodes: P2G of an affine particle field gives
// mass-weighted averages, affine at the nodes only with APIC, checked below.)
template <class Shape, int D> void check_pic_affine() {
  pmpm_test::Lcg r(0x4242u + D + Shape::NS);
  TestGrid<D> TG(7, 0.29);
  TestParticles<D> T(300);
  random_particles<Shape, D>(r, T, TG.G);
  double v0[D], A[D * D];
  for (double &a : v0) a = r.uniform(-1, 1);
  for (double &a : A) a = r.uniform(-1, 1);
  TG.for_nodes([&](const PetscInt *, const double *x, double *node) {
    node[GridDofT<D>::M] = 1.0;
    for (int d = 0; d < D; ++d) {
      double v = v0[d];
      for (int e = 0; e < D; ++e) v += A[d * D + e] * x[e];
      node[GridDofT<D>::P + d] = v;
      node[GridDofT<D>::F + d] = 0.0;
    }
  });
  std::vector<double> xold = T.x, Fold = T.F;
  G2PParamsT<D> prm;
  prm.dt = 1e-3;
  prm.pic = 1.0;
  CellRangeT<D> own;
  for (int d = 0; d < D; ++d) own.hi[d] = TG.G.ncell[d];
  G2PStatsT<D> st;
  const double wave[1] = {1.0};
  g2p<Shape, D>(T.P, TG.G, nullptr, own, prm, wave, T.dudx.data(), st);
  double ev = 0, eL = 0, ex = 0, eF = 0;
  for (PetscInt p = 0; p < T.P.n; ++p) {
    const double *xo = &xold[p * D];
    for (int d = 0; d < D; ++d) {
      double v = v0[d];
      for (int e = 0; e < D; ++e) v += A[d * D + e] * xo[e];
      ev = std::fmax(ev, std::fabs(T.v[p * D + d] - v));
      ex = std::fmax(ex, std::fabs(T.x[p * D + d] - (xo[d] + prm.dt * v)));
      for (int e = 0; e < D; ++e) {
        eL = std::fmax(eL, std::fabs(T.dudx[p * D * D + d * D + e] / prm.dt - A[d * D + e]));
        double Fn = 0;
        for (int k = 0; k < D; ++k)
          Fn += ((d == k ? 1.0 : 0.0) + prm.dt * A[d * D + k]) * Fold[p * D * D + k * D + e];
        eF = std::fmax(eF, std::fabs(T.F[p * D * D + d * D + e] - Fn));
      }
    }
  }
  std::printf("  g2p pic %-6s %dD: |v - v(x)| %.2g, |L - A| %.2g, |dx| %.2g, |dF| %.2g, bad %d\n",
              Shape::name, D, ev, eL, ex, eF, static_cast<int>(st.bad));
  CHECK(st.bad == 0);
  CHECK(ev <= 10 * EPS);        // |v| ~ 4 m/s
  CHECK(eL <= 10 * EPS / 0.29); // gradient sums: terms of |v| / h
  CHECK(ex <= EPS);
  CHECK(eF <= EPS);
}

// APIC: particles carrying the affine field (v_p = v(x_p), B_p = A D_p) send each node the field's
// value, m_i v_i = sum_p w m (v_p + A (x_i - x_p)) = m_i v(x_i); G2P then returns
// v_p = sum_i w v(x_i) = v(x_p) and B_p = sum_i w v(x_i) (x_i - x_p)^T = A D_p.
template <class Shape, int D> void check_apic_roundtrip() {
  pmpm_test::Lcg r(0x5151u + D + Shape::NS);
  TestGrid<D> TG(7, 0.29);
  TestParticles<D> T(500, true);
  random_particles<Shape, D>(r, T, TG.G);
  double v0[D], A[D * D];
  for (double &a : v0) a = r.uniform(-1, 1);
  for (double &a : A) a = r.uniform(-1, 1);
  std::vector<double> vref(T.P.n * D), Bref(T.P.n * D * D);
  for (PetscInt p = 0; p < T.P.n; ++p) {
    double Dp[D], lb[D];
    const double *l = Shape::template half<D>(&T.lp[p * D], &T.F[p * D * D], lb);
    affine_inertia<Shape, D>(&T.x[p * D], l, TG.G.origin, TG.G.h, Dp);
    for (int d = 0; d < D; ++d) {
      double v = v0[d];
      for (int e = 0; e < D; ++e) v += A[d * D + e] * T.x[p * D + e];
      T.v[p * D + d] = vref[p * D + d] = v;
      for (int e = 0; e < D; ++e)
        T.B[p * D * D + d * D + e] = Bref[p * D * D + d * D + e] = A[d * D + e] * Dp[e];
    }
  }
  LoadT<D> load;
  p2g<Shape, D>(T.P, load, TG.G);
  GridUpdateParamsT<D> gp; // dt = 0: v_i = p_i / m_i
  GridStatsT<D> gs;
  grid_update<D>(TG.G, gp, gs);
  G2PParamsT<D> prm;
  g2p_velocity<Shape, D>(T.P, TG.G, nullptr, prm);
  double ev = 0, eB = 0;
  for (PetscInt p = 0; p < T.P.n; ++p) {
    for (int d = 0; d < D; ++d) ev = std::fmax(ev, std::fabs(T.v[p * D + d] - vref[p * D + d]));
    for (int k = 0; k < D * D; ++k)
      eB = std::fmax(eB, std::fabs(T.B[p * D * D + k] - Bref[p * D * D + k]));
  }
  std::printf("  apic p2g+g2p %-6s %dD: |v - v_p| %.2g, |B - B_p| %.2g m^2/s\n", Shape::name, D, ev,
              eB);
  CHECK(ev <= 10 * EPS); // |v| ~ 4 m/s
  CHECK(eB <= EPS);      // |B| ~ |A| h^2 ~ 0.1
}

// grid_update<D>: v = p/m + dt f/m on a free node, the held dofs of fixed and roller faces.
template <int D> void check_grid_update() {
  TestGrid<D> TG(3, 0.5);
  TG.for_nodes([&](const PetscInt *, const double *, double *node) {
    node[GridDofT<D>::M] = 2.0;
    for (int d = 0; d < D; ++d) {
      node[GridDofT<D>::P + d] = 2.0 * (d + 1); // v = d + 1
      node[GridDofT<D>::F + d] = 4.0 * (d + 1); // a = 2 (d + 1)
    }
  });
  GridUpdateParamsT<D> gp;
  gp.dt = 0.25;
  gp.face[XMAX] = FaceBC::Roller;
  gp.face[2 * (D - 1)] = FaceBC::Fixed; // the bottom (YMIN in 2D, ZMIN in 3D)
  GridStatsT<D> st;
  grid_update<D>(TG.G, gp, st);
  int bad = 0, nodes = 0;
  TG.for_nodes([&](const PetscInt *n, const double *, const double *node) {
    if (n[0] < 0 || n[0] > 3 || n[1] < 0 || n[1] > 3 || n[D - 1] < 0 || n[D - 1] > 3) return;
    ++nodes;
    for (int d = 0; d < D; ++d) {
      const bool held = n[D - 1] == 0 || (d == 0 && n[0] == 3);
      const double v = held ? 0.0 : (d + 1) * 1.5, a = held ? 0.0 : 2.0 * (d + 1);
      if (node[GridDofT<D>::P + d] != v || node[GridDofT<D>::F + d] != a) ++bad;
    }
  });
  std::printf("  grid_update %dD: %d box nodes, %d wrong dofs\n", D, nodes, bad);
  CHECK(bad == 0);
}

// p2g_traction: a face load t at x + tface spreads by linear hats: the nodal loads sum to t and
// their first moment is t x_f^T (linear reproduction).
template <int D> struct FaceLoad { double traction[D], tface[D]; };
template <int D> void check_traction() {
  pmpm_test::Lcg r(0x31u + D);
  TestGrid<D> TG(6, 0.4);
  TestParticles<D> T(50);
  std::vector<PetscInt> load(T.P.n), idx;
  std::vector<FaceLoad<D>> loads(T.P.n);
  T.P.load = load.data();
  double ft[D] = {}, mt[D][D] = {};
  for (PetscInt p = 0; p < T.P.n; ++p) {
    for (int d = 0; d < D; ++d) {
      T.lp[p * D + d] = 0.1;
      T.x[p * D + d] = coordinate(r, TG.G.origin[d], TG.G.h, 6, 0.1);
      loads[p].traction[d] = r.uniform(-1, 1);
      loads[p].tface[d] = d == p % D ? 0.1 : 0.0;
    }
    load[p] = p;
    idx.push_back(p);
    for (int d = 0; d < D; ++d) {
      ft[d] += 2.0 * loads[p].traction[d];
      for (int e = 0; e < D; ++e)
        mt[d][e] += 2.0 * loads[p].traction[d] * (T.x[p * D + e] + loads[p].tface[e]);
    }
  }
  p2g_traction<UGIMPShape, D>(T.P, loads, idx, 2.0, TG.G);
  double fs[D] = {}, ms[D][D] = {};
  TG.for_nodes([&](const PetscInt *, const double *x, const double *node) {
    for (int d = 0; d < D; ++d) {
      fs[d] += node[GridDofT<D>::F + d];
      CHECK(node[GridDofT<D>::F + d] == node[GridDofT<D>::FEXT + d]);
      for (int e = 0; e < D; ++e) ms[d][e] += node[GridDofT<D>::F + d] * x[e];
    }
  });
  double ef = 0, em = 0;
  for (int d = 0; d < D; ++d) {
    ef = std::fmax(ef, std::fabs(fs[d] - ft[d]));
    for (int e = 0; e < D; ++e) em = std::fmax(em, std::fabs(ms[d][e] - mt[d][e]));
  }
  std::printf("  p2g_traction %dD: |sum f - sum t| %.2g, first moment %.2g\n", D, ef, em);
  CHECK(ef <= EPS);
  CHECK(em <= 10 * EPS); // moments of 100 terms of |t x| ~ 3
}

void check_stress_storage() {
  const double s3[6] = {1, 2, 3, 4, 5, 6};
  const Mat3 t = stress_to_tensor<3>(s3);
  CHECK(t(0, 1) == 4 && t(1, 0) == 4 && t(1, 2) == 5 && t(2, 1) == 5 && t(0, 2) == 6 &&
        t(2, 0) == 6 && t(0, 0) == 1 && t(1, 1) == 2 && t(2, 2) == 3);
  double back[6];
  tensor_to_stress<3>(t, back);
  for (int k = 0; k < 6; ++k) CHECK(back[k] == s3[k]);
  const double s2[4] = {1, 2, 3, 4};
  const Mat3 t2 = stress_to_tensor<2>(s2);
  CHECK(t2(0, 1) == 4 && t2(0, 2) == 0 && t2(1, 2) == 0 && t2(2, 2) == 3);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) CHECK(t(a, b) == s3[stress_slot(a, b)]);
}

// A short explicit 3D cycle on the kernels alone (P2G, grid update, G2P with PIC, a small-strain
// elastic update of the 6 stresses from dudx): an elastic cube with random velocities under
// gravity, free faces. The internal forces sum to zero at every step (sum_i grad S_ip = 0) and PIC
// hands the grid's momentum back to the particles (sum_p m_p sum_i S_ip v_i = sum_i m_i v_i), so
// the particles' momentum is p_0 + t M g to round-off after each step.
template <class Shape> void check_cycle_3d() {
  constexpr int D = 3, NSt = NStress<3>;
  pmpm_test::Lcg r(0xC1C1u + Shape::NS);
  TestGrid<D> TG(8, 0.25);
  const double h = TG.G.h, rho = 2000.0, E = 1e6, nu = 0.3;
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), G2 = E / (1 + nu);
  const PetscInt nc = 4, c0 = 2; // a 4^3-cell cube from cell 2, 2^3 particles a cell
  TestParticles<D> T(8 * nc * nc * nc);
  const double Vp = std::pow(0.5 * h, 3);
  for (PetscInt p = 0; p < T.P.n; ++p) {
    for (int d = 0, q = p; d < D; ++d, q /= 2 * nc) {
      T.x[p * D + d] = TG.G.origin[d] + (c0 + 0.25 + 0.5 * (q % (2 * nc))) * h;
      T.lp[p * D + d] = 0.25 * h;
      T.v[p * D + d] = r.uniform(-0.01, 0.01);
    }
    T.vol[p] = T.vol0[p] = Vp;
    T.mass[p] = rho * Vp;
    T.weight[p] = rho * 9.81 * Vp;
  }
  LoadT<D> load;
  load.gdir[0] = load.gdir[1] = 0.0;
  load.gdir[2] = -1.0;
  double M = 0, p0[D] = {};
  for (PetscInt p = 0; p < T.P.n; ++p) {
    M += T.mass[p];
    for (int d = 0; d < D; ++d) p0[d] += T.mass[p] * T.v[p * D + d];
  }
  const double dt = 0.2 * h / std::sqrt((lam + G2) / rho);
  G2PParamsT<D> prm;
  prm.dt = dt;
  prm.pic = 1.0;
  CellRangeT<D> own;
  for (int d = 0; d < D; ++d) own.hi[d] = TG.G.ncell[d];
  const double wave[1] = {lam + G2};
  double worst = 0;
  PetscInt bad = 0;
  for (int step = 1; step <= 20; ++step) {
    TG.zero();
    p2g<Shape, D>(T.P, load, TG.G);
    GridUpdateParamsT<D> gp;
    gp.dt = dt;
    GridStatsT<D> gs;
    grid_update<D>(TG.G, gp, gs);
    G2PStatsT<D> st;
    g2p<Shape, D>(T.P, TG.G, nullptr, own, prm, wave, T.dudx.data(), st);
    bad += st.bad;
    for (PetscInt p = 0; p < T.P.n; ++p) { // sigma += lambda tr(de) I + 2G de
      const double *g = &T.dudx[p * D * D];
      double *s = &T.stress[p * NSt];
      const double tr = g[0] + g[4] + g[8];
      for (int a = 0; a < D; ++a)
        for (int b = a; b < D; ++b)
          s[stress_slot(a, b)] +=
              (a == b ? lam * tr : 0.0) + 0.5 * G2 * (g[a * D + b] + g[b * D + a]);
    }
    double pm[D] = {};
    for (PetscInt p = 0; p < T.P.n; ++p)
      for (int d = 0; d < D; ++d) pm[d] += T.mass[p] * T.v[p * D + d];
    for (int d = 0; d < D; ++d) {
      const double want = p0[d] + step * dt * M * 9.81 * load.gdir[d];
      worst = std::fmax(worst, std::fabs(pm[d] - want) / (M * 9.81 * step * dt));
    }
  }
  double smax = 0;
  for (const double s : T.stress) smax = std::fmax(smax, std::fabs(s));
  std::printf("  3D cycle %-6s: 20 steps, momentum against p0 + t M g: %.2g of M g t; max |sigma| "
              "%.3g Pa, bad %d\n",
              Shape::name, worst, smax, static_cast<int>(bad));
  CHECK(bad == 0);
  CHECK(worst <= EPS);
  CHECK(smax > 0.0); // the cube deforms: the check saw a stress field, not a rigid body
}

template <class Shape, int D> void check_shape() {
  check_weights<Shape, D>();
  check_conservation<Shape, D>(false);
  check_conservation<Shape, D>(true);
  check_uniform_stress<Shape, D>();
  check_pic_affine<Shape, D>();
  check_apic_roundtrip<Shape, D>();
}

} // namespace

int main() {
  check_shape<LinearShape, 2>();
  check_shape<UGIMPShape, 2>();
  check_shape<CPGIMPShape, 2>();
  check_shape<LinearShape, 3>();
  check_shape<UGIMPShape, 3>();
  check_shape<CPGIMPShape, 3>();
  check_cycle_3d<LinearShape>();
  check_cycle_3d<UGIMPShape>();
  check_cycle_3d<CPGIMPShape>();
  check_grid_update<2>();
  check_grid_update<3>();
  check_traction<2>();
  check_traction<3>();
  check_stress_storage();
  return pmpm_test::report("test_dimensions");
}
