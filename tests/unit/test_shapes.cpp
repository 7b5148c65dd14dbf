// Unit tests of the shape functions (shape.hpp): LinearShape (standard MPM) and UGIMPShape
// (the paper's PMPM, eq. 14-15, 20), through the 2D tensor-product weights() that every kernel
// uses, and CPGIMPShape (shape_cpgimp.hpp: uGIMP's block with a half-size up to one cell).
// Properties checked at many random particles (fixed seed):
//   partition of unity, zero gradient sum, linear completeness of weights and gradients,
//   PMPM == linear for a block inside one cell, the PMPM weight as a block average of the 2D hat
//   (numerical quadrature) and its gradient (finite differences), and continuity of the PMPM
//   weights and gradients as a block crosses a cell face (where the linear gradient jumps);
//   cpGIMP: the same properties for blocks up to one cell, cpGIMP == uGIMP for blocks up to half
//   a cell (F = I), and its half-size from F; the second derivatives of the mpm and pmpm weights
//   (weight_hessians, the implicit solver's reset-grid tangent) against differences of gradients.
#include "check.hpp"
#include "pmpm/core/shape.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace pmpm;

namespace {

// The sequence these tests were written with (pmpm_test::Lcg).
struct Lcg : pmpm_test::Lcg {
  Lcg() : pmpm_test::Lcg(0x2545F4914F6CDD1Dull) {}
  explicit Lcg(std::uint64_t seed) : pmpm_test::Lcg(seed) {}
};

// A grid that is not aligned with 0 and a cell size that is not a power of two, so that the
// conversions x -> xi = (x - origin)/h round.
const double H = 0.37;
const double ORIGIN[DIM] = {-1.3, 0.7};
const int NSAMPLE = 2000;
// Smallest PMPM half-size drawn in the random tests, in cell units. The weight is a difference of
// two hat integrals of size O(1) divided by 2 l: its round-off is ~ eps / l, i.e. ~ 1e-15 for
// l >= 0.05 h, which the 1e-14 tolerances below accept. (Smaller l only amplifies round-off.)
const double LMIN = 0.05;

template <class Shape> double node_x(const Weights<Shape> &W, int k, int d) {
  const int a = (d == 0) ? k % Shape::NS : k / Shape::NS;
  return ORIGIN[d] + (W.base[d] + a) * H;
}

// Weight and gradient of global node (i, j), zero outside the support.
template <class Shape>
void at_node(const Weights<Shape> &W, int i, int j, double &w, double g[DIM]) {
  w = g[0] = g[1] = 0.0;
  const int a = i - W.base[0], b = j - W.base[1];
  if (a < 0 || a >= Shape::NS || b < 0 || b >= Shape::NS) return;
  const int k = b * Shape::NS + a;
  w = W.w[k];
  g[0] = W.grad[k][0];
  g[1] = W.grad[k][1];
}

// lmax: the largest half-size drawn, in cells (uGIMP 0.5; cpGIMP up to 1).
void random_particle(Lcg &r, double x[DIM], double l[DIM], double lmax = 0.5) {
  for (int d = 0; d < DIM; ++d) {
    const double li = r.uniform(LMIN, lmax);
    double xi = r.uniform(2.0, 12.0);
    // Now and then put a block edge just past a cell face (by 1e-7 to 1e-1 cells): that is where
    // uGIMP's first support node changes, and where an off-by-one support loses a small weight.
    if (r.next() < 0.2) {
      const double c = std::floor(xi), delta = std::pow(10.0, r.uniform(-7.0, -1.0));
      xi = (r.next() < 0.5) ? c + li - delta : c - li + delta;
    }
    x[d] = ORIGIN[d] + xi * H;
    l[d] = li * H;
  }
  // Hit the largest admissible block (l = lmax h) exactly now and then.
  if (r.next() < 0.1) l[0] = lmax * H;
  if (r.next() < 0.1) l[1] = lmax * H;
}

// Partition of unity, zero gradient sum and linear completeness.
template <class Shape> void test_basic_properties(Lcg &r, double lmax = 0.5) {
  Weights<Shape> W;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM];
    random_particle(r, x, l, lmax);
    weights<Shape>(x, l, ORIGIN, H, W);
    double sw = 0, sg[DIM] = {0, 0}, swx[DIM] = {0, 0}, sgx[DIM][DIM] = {{0, 0}, {0, 0}};
    bool nonneg = true;
    for (int k = 0; k < Weights<Shape>::NN; ++k) {
      sw += W.w[k];
      nonneg = nonneg && W.w[k] >= 0.0;
      for (int d = 0; d < DIM; ++d) {
        sg[d] += W.grad[k][d];
        swx[d] += W.w[k] * node_x(W, k, d);
        for (int e = 0; e < DIM; ++e) sgx[d][e] += W.grad[k][e] * node_x(W, k, d);
      }
    }
    // Nine (cpGIMP: sixteen) O(1) products summed: round-off a few 1e-16.
    CHECK_CLOSE(sw, 1.0, 1e-14);
    CHECK(nonneg);
    // Gradients are O(1/h) (uGIMP: up to 1/h): their sum has round-off ~ 1e-15/h.
    for (int d = 0; d < DIM; ++d) CHECK_CLOSE(sg[d], 0.0, 1e-12 / H);
    // sum w_k x_k: node coordinates are O(5) m, so round-off is ~ 1e-15 * 5; 1e-13 m leaves room.
    for (int d = 0; d < DIM; ++d) CHECK_CLOSE(swx[d], x[d], 1e-13);
    // sum_k x_k (grad_k)^T = I (row d: coordinate d; column e: derivative direction e). The terms
    // are |x_k| / h ~ 15, so cancellation leaves ~ 1e-14; 1e-12 is a safe bound.
    for (int d = 0; d < DIM; ++d)
      for (int e = 0; e < DIM; ++e) CHECK_CLOSE(sgx[d][e], d == e ? 1.0 : 0.0, 1e-12);
  }
}

// PMPM reduces to linear MPM when the block [x - l, x + l] lies inside one cell in both directions.
void test_pmpm_equals_linear_inside_cell(Lcg &r) {
  Weights<LinearShape> WL;
  Weights<UGIMPShape> WU;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM];
    for (int d = 0; d < DIM; ++d) {
      const double li = r.uniform(LMIN, 0.499);
      const int c = 2 + static_cast<int>(r.next() * 10);
      // centre in (c + li, c + 1 - li), kept 1e-6 away from the ends so rounding of xi cannot
      // move the block edge onto the neighbour cell
      const double xi = c + r.uniform(li + 1e-6, 1.0 - li - 1e-6);
      x[d] = ORIGIN[d] + xi * H;
      l[d] = li * H;
    }
    weights<LinearShape>(x, l, ORIGIN, H, WL);
    weights<UGIMPShape>(x, l, ORIGIN, H, WU);
    CHECK(WL.base[0] == WU.base[0] && WL.base[1] == WU.base[1]);
    // every node of either support, compared by global index (uGIMP's third node must be 0)
    double maxdw = 0, maxdg = 0;
    for (int j = WU.base[1]; j < WU.base[1] + 3; ++j)
      for (int i = WU.base[0]; i < WU.base[0] + 3; ++i) {
        double wl, gl[DIM], wu, gu[DIM];
        at_node(WL, i, j, wl, gl);
        at_node(WU, i, j, wu, gu);
        maxdw = std::max(maxdw, std::fabs(wl - wu));
        for (int d = 0; d < DIM; ++d) maxdg = std::max(maxdg, std::fabs(gl[d] - gu[d]));
      }
    // uGIMP computes 1 - s as [(1 - s + l)^2 - (1 - s - l)^2] / 4l: round-off ~ eps / l < 1e-14.
    CHECK_CLOSE(maxdw, 0.0, 1e-14);
    // gradients: the same relative round-off, times 1/h
    CHECK_CLOSE(maxdg, 0.0, 1e-14 / H);
  }
}

// Independent 1D hat of node i at physical coordinate x in direction d.
double hat1d(int i, double x, int d) {
  return std::max(0.0, 1.0 - std::fabs((x - ORIGIN[d]) / H - i));
}

// Midpoint-rule average over [x - l, x + l] of the 1D hat of node i in direction d.
double hat_average(int i, double x, double l, int d, int nq) {
  double sum = 0.0;
  for (int q = 0; q < nq; ++q) sum += hat1d(i, x - l + (q + 0.5) * (2.0 * l / nq), d);
  return sum / nq;
}

// PMPM weight = block average of the 2D hat N_i(x) N_j(y) (eq. 14-15): n x n midpoint rule over
// the block. The 2D hat is a product, so the n x n midpoint sum is exactly (up to round-off) the
// product of the two 1D midpoint sums; that is how it is evaluated (n^2 = 4e6 points per node
// would be too slow). The quadrature uses its own hat, independent of shape.hpp.
//
// Error bound: the hat is piecewise linear, so the 1D midpoint rule is exact on every quadrature
// cell that no kink (node - h, node, node + h) crosses. A kink with slope jump J inside a
// quadrature cell of width q = 2l/n errs by <= J q^2 / 8; the jumps add up to 4/h, so the error
// of the average is <= (4/h) q^2 / 8 / (2 l) = l / (h n^2). For the product of two averages (both
// <= 1) the errors add: (l_x + l_y) / (h n^2) <= 2.5e-7 for n = 2000 and l <= h/2. A wrong weight
// formula errs by O(1e-2) or more.
//
// cpGIMP (lmax = 1): the same bound, (l_x + l_y) / (h n^2) <= 5e-7.
template <class Shape> void test_pmpm_weight_is_block_average(Lcg &r, double lmax = 0.5) {
  const int NQ = 2000, NP = 200, NA = Shape::NS + 2;
  Weights<Shape> W;
  for (int n = 0; n < NP; ++n) {
    double x[DIM], l[DIM];
    random_particle(r, x, l, lmax);
    weights<Shape>(x, l, ORIGIN, H, W);
    const double tol = (l[0] + l[1]) / (H * NQ * double(NQ)) + 1e-14;
    double ax[NA], ay[NA];
    for (int a = 0; a < NA; ++a) {
      ax[a] = hat_average(W.base[0] - 1 + a, x[0], l[0], 0, NQ);
      ay[a] = hat_average(W.base[1] - 1 + a, x[1], l[1], 1, NQ);
    }
    double maxerr = 0.0, maxw = 0.0;
    // nodes one beyond the support too: the block average must vanish there as well
    for (int b = 0; b < NA; ++b)
      for (int a = 0; a < NA; ++a) {
        double w, g[DIM];
        at_node(W, W.base[0] - 1 + a, W.base[1] - 1 + b, w, g);
        maxerr = std::max(maxerr, std::fabs(w - ax[a] * ay[b]));
        maxw = std::max(maxw, w);
      }
    CHECK_CLOSE(maxerr, 0.0, tol);
    CHECK(maxw > 0.1); // the comparison is not vacuous
  }
}

// The weights at x moved by +- delta cells along direction e (central differences).
template <class Shape>
void weights_shifted(const double *x, const double *l, int e, double delta, Weights<Shape> &Wp,
                     Weights<Shape> &Wm) {
  double xp[DIM] = {x[0], x[1]}, xm[DIM] = {x[0], x[1]};
  xp[e] += delta * H;
  xm[e] -= delta * H;
  weights<Shape>(xp, l, ORIGIN, H, Wp);
  weights<Shape>(xm, l, ORIGIN, H, Wm);
}

// PMPM gradient = derivative of the weight: centred finite differences in x and in y.
//
// Error bound: per direction the weight is (I(s + l) - I(s - l)) / 2l with I the hat's integral,
// a piecewise quadratic, so the weight is piecewise quadratic in xi and C1. The centred difference
// is exact for quadratics; a jump J of the second derivative within +-delta errs by <= J delta/4.
// The jumps of S'' = (hat'(s + l) - hat'(s - l)) / 2l add up to <= 8 / 2l = 4/l, so the
// truncation error is <= delta / l (cell units). Round-off: ~ 2 eps / (2 delta). In physical units
// both are divided by h. With delta = 1e-7 cells: <= 2e-6 / h + 1e-9 / h. cpGIMP's weight is the
// same block average (any l), so the same bound holds for its blocks up to one cell.
template <class Shape> void test_pmpm_gradient_is_derivative(Lcg &r, double lmax = 0.5) {
  const double delta = 1e-7; // cell units
  Weights<Shape> W, Wp, Wm;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM];
    random_particle(r, x, l, lmax);
    weights<Shape>(x, l, ORIGIN, H, W);
    for (int e = 0; e < DIM; ++e) {
      weights_shifted(x, l, e, delta, Wp, Wm);
      const double tol = (delta / (l[e] / H) + 1e-9) / H;
      double maxerr = 0.0;
      for (int j = W.base[1] - 1; j <= W.base[1] + Shape::NS; ++j)
        for (int i = W.base[0] - 1; i <= W.base[0] + Shape::NS; ++i) {
          double w, g[DIM], wp, gp[DIM], wm, gm[DIM];
          at_node(W, i, j, w, g);
          at_node(Wp, i, j, wp, gp);
          at_node(Wm, i, j, wm, gm);
          maxerr = std::max(maxerr, std::fabs(g[e] - (wp - wm) / (2.0 * delta * H)));
        }
      CHECK_CLOSE(maxerr, 0.0, tol);
    }
  }
}

// weight_hessians (the implicit solver's reset-grid tangent): the second derivatives are the
// central differences of the gradients, where no kink lies within the differences' reach (the
// gradients are piecewise linear in the position, so there the differences are exact up to
// round-off: xi ~ 12 rounds to 3e-15 cells, the gradients' slope is up to 1 / (2 l) = 10 per cell,
// so ~ 3e-14 / (2 delta) = 2e-8 / h^2 (measured 1.4e-7 at worst), against values up to
// 1 / (2 l h^2) = 10 / h^2 and a wrong term of order 1 / h^2; bound 1e-6 / h^2); and their sum and
// first moment vanish everywhere (sum S_k = 1 and sum x_k S_k = x for every position).
template <class Shape> bool near_kink(double xi, double li) {
  const double tol = 1e-5; // cells: well beyond the differences' reach of 1e-6
  auto near_int = [&](double v) { return std::fabs(v - std::round(v)) < tol; };
  return Shape::NS == 2 ? near_int(xi) : near_int(xi - li) || near_int(xi + li);
}

template <class Shape> void test_hessian_is_derivative(Lcg &r) {
  constexpr int NN = Weights<Shape>::NN;
  const double delta = 1e-6; // cell units
  Weights<Shape> W, Wp, Wm;
  double Hs[NN][3];
  int compared = 0;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM];
    random_particle(r, x, l);
    weights<Shape>(x, l, ORIGIN, H, W);
    weight_hessians<Shape>(x, l, ORIGIN, H, Hs);
    double sum[3] = {0, 0, 0}, mom[DIM][3] = {{0, 0, 0}, {0, 0, 0}};
    for (int k = 0; k < NN; ++k)
      for (int q = 0; q < 3; ++q) {
        sum[q] += Hs[k][q];
        for (int d = 0; d < DIM; ++d) mom[d][q] += node_x(W, k, d) * Hs[k][q];
      }
    // terms up to 20 / h^2 (times |x_k| ~ 5 for the moment): round-off ~ 1e-14 / h^2
    for (int q = 0; q < 3; ++q) {
      CHECK_CLOSE(sum[q], 0.0, 1e-12 / (H * H));
      for (int d = 0; d < DIM; ++d) CHECK_CLOSE(mom[d][q], 0.0, 1e-11 / (H * H));
    }
    bool kink = false;
    for (int d = 0; d < DIM; ++d) kink = kink || near_kink<Shape>((x[d] - ORIGIN[d]) / H, l[d] / H);
    if (kink) continue;
    ++compared;
    for (int e = 0; e < DIM; ++e) {
      weights_shifted(x, l, e, delta, Wp, Wm);
      double maxerr = 0.0;
      for (int k = 0; k < NN; ++k)
        for (int d = 0; d < DIM; ++d) {
          // d/dx_e of grad_d: H index xx = 0, xy = 1, yy = 2
          const double fd = (Wp.grad[k][d] - Wm.grad[k][d]) / (2.0 * delta * H);
          maxerr = std::max(maxerr, std::fabs(Hs[k][d + e] - fd));
        }
      CHECK_CLOSE(maxerr, 0.0, 1e-6 / (H * H));
    }
  }
  CHECK(compared > NSAMPLE / 2);
}

// Largest change of any node's weight and gradient between particles at xa and xb.
template <class Shape>
void node_jumps(const double *xa, const double *xb, const double *l, double &dw, double &dg) {
  Weights<Shape> Wa, Wb;
  weights<Shape>(xa, l, ORIGIN, H, Wa);
  weights<Shape>(xb, l, ORIGIN, H, Wb);
  dw = dg = 0.0;
  const int i0 = std::min(Wa.base[0], Wb.base[0]), j0 = std::min(Wa.base[1], Wb.base[1]);
  for (int j = j0; j <= j0 + Shape::NS; ++j)
    for (int i = i0; i <= i0 + Shape::NS; ++i) {
      double wa, ga[DIM], wb, gb[DIM];
      at_node(Wa, i, j, wa, ga);
      at_node(Wb, i, j, wb, gb);
      dw = std::max(dw, std::fabs(wa - wb));
      for (int d = 0; d < DIM; ++d) dg = std::max(dg, std::fabs(ga[d] - gb[d]));
    }
}

// Crossing a cell face. PMPM: the block's edge (where the support's base node changes) or its
// centre crosses the face at xi = c; stepping x by 2e-9 h across it changes the weights by <= 2e-9
// (|dS/dxi| <= 1) and the gradients by <= 2e-9 / l / h (|d2S/dxi2| <= 1/l), plus round-off
// ~ eps/l; the bounds below are these with a factor 2 to 5 of margin. Linear MPM: the weights are
// continuous but the x-gradient of node c jumps by 2/h (from the right to the left hat slope,
// times the y weight) as the centre crosses the face. That jump, felt by the internal force of
// every particle entering a new cell, is the cell-crossing noise the paper attributes to linear
// shape functions (its eq. 13); PMPM's block average removes it.
void test_face_crossing(Lcg &r) {
  const double step = 1e-9; // cell units, on each side of the face
  for (int n = 0; n < 200; ++n) {
    const int c = 3 + static_cast<int>(r.next() * 8);
    double l[DIM] = {r.uniform(LMIN, 0.5) * H, r.uniform(LMIN, 0.5) * H};
    if (n % 10 == 0) l[0] = 0.5 * H; // both block edges on faces at once
    const double y = ORIGIN[1] + r.uniform(2.0, 12.0) * H;
    const double li = l[0] / H;
    // 0: left block edge on the face; 1: right edge; 2: centre on the face
    const double centre[3] = {c + li, c - li, double(c)};
    for (double xc : centre) {
      const double xa[DIM] = {ORIGIN[0] + (xc - step) * H, y};
      const double xb[DIM] = {ORIGIN[0] + (xc + step) * H, y};
      double dw, dg;
      node_jumps<UGIMPShape>(xa, xb, l, dw, dg);
      CHECK_CLOSE(dw, 0.0, 5e-9);
      CHECK_CLOSE(dg, 0.0, (5e-9 / li + 1e-13) / H);
    }
    {
      const double xa[DIM] = {ORIGIN[0] + (c - step) * H, y};
      const double xb[DIM] = {ORIGIN[0] + (c + step) * H, y};
      double dw, dg;
      node_jumps<LinearShape>(xa, xb, l, dw, dg);
      CHECK_CLOSE(dw, 0.0, 5e-9); // linear weights are continuous ...
      // ... their x-gradients jump: node c's slope goes from +1/h to -1/h, times its y weight,
      // which is >= 1/2 for the nearer row of nodes
      CHECK(dg > 0.99 / H);
    }
  }
}

// cpGIMP with F = I is uGIMP: for blocks up to half a cell (uGIMP's range) every node's weight and
// gradient agree, compared by global node index (cpGIMP's fourth node must be 0). Both are
// differences of hat integrals over 2 l: round-off ~ eps / l <= 5e-15 for l >= LMIN.
void test_cpgimp_equals_ugimp(Lcg &r) {
  Weights<UGIMPShape> WU;
  Weights<CPGIMPShape> WC;
  const double F[DIM * DIM] = {1.0, 0.0, 0.0, 1.0};
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM], lb[DIM];
    random_particle(r, x, l);
    const double *lc = CPGIMPShape::half(l, F, lb);
    CHECK(lc[0] == l[0] && lc[1] == l[1]); // F = I: the initial half-size exactly
    weights<UGIMPShape>(x, l, ORIGIN, H, WU);
    weights<CPGIMPShape>(x, lc, ORIGIN, H, WC);
    CHECK(WU.base[0] == WC.base[0] && WU.base[1] == WC.base[1]);
    double maxdw = 0, maxdg = 0;
    for (int j = WC.base[1] - 1; j <= WC.base[1] + 4; ++j)
      for (int i = WC.base[0] - 1; i <= WC.base[0] + 4; ++i) {
        double wu, gu[DIM], wc, gc[DIM];
        at_node(WU, i, j, wu, gu);
        at_node(WC, i, j, wc, gc);
        maxdw = std::max(maxdw, std::fabs(wu - wc));
        for (int d = 0; d < DIM; ++d) maxdg = std::max(maxdg, std::fabs(gu[d] - gc[d]));
      }
    CHECK_CLOSE(maxdw, 0.0, 1e-14);
    CHECK_CLOSE(maxdg, 0.0, 1e-14 / H);
  }
}

// The half-size follows V_dd, V = sqrt(F F^T), computed here independently from B's eigenpairs
// (V_dd = sum_i sqrt(mu_i) (n_i . e_d)^2); a rigid rotation keeps the block (V = I), a stretch
// then a quarter turn stretches the other axis, and a collapsed F is floored at kMinStretch.
void test_cpgimp_half_size() {
  const double lp[DIM] = {0.25 * H, 0.125 * H};
  double lb[DIM];
  {
    const double F[DIM * DIM] = {1.7, 0.3, -0.2, 0.55}; // stretch x, compress y, some shear
    const double B00 = F[0] * F[0] + F[1] * F[1], B11 = F[2] * F[2] + F[3] * F[3];
    const double B01 = F[0] * F[2] + F[1] * F[3];
    const double m = 0.5 * (B00 + B11), r = std::sqrt(0.25 * (B00 - B11) * (B00 - B11) + B01 * B01);
    const double mu[2] = {m + r, m - r};
    double V[DIM] = {0, 0};
    for (int i = 0; i < 2; ++i) {
      double n0 = B01, n1 = mu[i] - B00; // (B - mu I) n = 0
      const double nn = std::hypot(n0, n1);
      n0 /= nn;
      n1 /= nn;
      V[0] += std::sqrt(mu[i]) * n0 * n0;
      V[1] += std::sqrt(mu[i]) * n1 * n1;
    }
    const double *l = CPGIMPShape::half(lp, F, lb);
    // O(1) entries, a square root and a division each way: round-off a few 1e-16 relative
    CHECK_CLOSE(l[0], V[0] * lp[0], 1e-14 * lp[0]);
    CHECK_CLOSE(l[1], V[1] * lp[1], 1e-14 * lp[1]);
  }
  {
    const double c = std::cos(0.7), s = std::sin(0.7);
    const double R[DIM * DIM] = {c, -s, s, c}; // rigid rotation: the block is unchanged
    const double *l = CPGIMPShape::half(lp, R, lb);
    CHECK_CLOSE(l[0], lp[0], 1e-15 * lp[0]);
    CHECK_CLOSE(l[1], lp[1], 1e-15 * lp[1]);
    const double Q[DIM * DIM] = {0.0, -1.0, 1.5, 0.0}; // diag(1.5, 1) then a quarter turn
    l = CPGIMPShape::half(lp, Q, lb);
    CHECK_CLOSE(l[0], lp[0], 1e-15 * lp[0]);
    CHECK_CLOSE(l[1], 1.5 * lp[1], 1e-15 * lp[1]);
    const double D[DIM * DIM] = {1.7, 0.0, 0.0, 0.55}; // diagonal F: V = F
    l = CPGIMPShape::half(lp, D, lb);
    CHECK_CLOSE(l[0], 1.7 * lp[0], 1e-15 * lp[0]);
    CHECK_CLOSE(l[1], 0.55 * lp[1], 1e-15 * lp[1]);
    const double Z[DIM * DIM] = {0.0, 0.0, 0.0, 0.0}; // collapsed
    l = CPGIMPShape::half(lp, Z, lb);
    CHECK(l[0] == CPGIMPShape::kMinStretch * lp[0] && l[1] == CPGIMPShape::kMinStretch * lp[1]);
  }
  // the largest block, l = h, centred at xi = 5.5: spans [4.5, 6.5], nodes 4..7, all non-zero
  int base;
  double w[CPGIMPShape::NS], dw[CPGIMPShape::NS];
  CPGIMPShape::eval1d(5.5, CPGIMPShape::kMaxHalf, base, w, dw);
  CHECK(base == 4);
  // exact: block averages over [0.5, 2.5] of the hats at 0..3: 1/16, 7/16, 7/16, 1/16
  CHECK_CLOSE(w[0], 1.0 / 16, 1e-15);
  CHECK_CLOSE(w[1], 7.0 / 16, 1e-15);
  CHECK_CLOSE(w[2], 7.0 / 16, 1e-15);
  CHECK_CLOSE(w[3], 1.0 / 16, 1e-15);
  // derivative (N_k(2.5) - N_k(0.5)) / 2: -1/4, -1/4, 1/4, 1/4
  CHECK_CLOSE(dw[0], -0.25, 1e-15);
  CHECK_CLOSE(dw[1], -0.25, 1e-15);
  CHECK_CLOSE(dw[2], 0.25, 1e-15);
  CHECK_CLOSE(dw[3], 0.25, 1e-15);
  // a small block inside one cell: two nodes, the other two exactly zero (the transfers skip them)
  CPGIMPShape::eval1d(5.5, 0.2, base, w, dw);
  CHECK(base == 5 && w[2] == 0.0 && dw[2] == 0.0 && w[3] == 0.0 && dw[3] == 0.0);
}

} // namespace

// The 3D half-size (polar_stretch_diagonal: V = F R^T, Newton's polar iteration): on an extruded
// gradient it equals the 2D closed form with V_zz = 1; on random 3D gradients it equals V from an
// independent method (Eigen's iterative, QL-based eigen decomposition of F F^T, accurate to a
// few eps: 1e-13 for entries up to 3); rotations keep the block, a stretch then a quarter turn
// about z swaps x and y, and a singular F (no rotation to find) takes the eigen decomposition.
void test_cpgimp_half_size_3d(Lcg &r) {
  const double lp[3] = {0.25 * H, 0.125 * H, 0.2 * H};
  double lb2[2], lb3[3];
  for (int n = 0; n < NSAMPLE; ++n) {
    double F2[4];
    for (int k = 0; k < 4; ++k) F2[k] = (k == 0 || k == 3 ? 1.0 : 0.0) + r.uniform(-0.5, 0.5);
    if (F2[0] * F2[3] - F2[1] * F2[2] < 0.1) continue;
    const double F3[9] = {F2[0], F2[1], 0.0, F2[2], F2[3], 0.0, 0.0, 0.0, 1.0};
    const double *l2 = CPGIMPShape::half<2>(lp, F2, lb2);
    const double *l3 = CPGIMPShape::half<3>(lp, F3, lb3);
    CHECK_CLOSE(l3[0], l2[0], 1e-15 * H);
    CHECK_CLOSE(l3[1], l2[1], 1e-15 * H);
    CHECK_CLOSE(l3[2], lp[2], 1e-15 * H);
  }
  for (int n = 0; n < NSAMPLE; ++n) {
    double F[9];
    for (int k = 0; k < 9; ++k) F[k] = (k % 4 == 0 ? 1.0 : 0.0) + r.uniform(-0.6, 0.6);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Fm(F);
    if (std::fabs(Fm.determinant()) < 0.05) continue;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Fm * Fm.transpose());
    const Eigen::Matrix3d V = es.eigenvectors() * es.eigenvalues().cwiseSqrt().asDiagonal() *
                              es.eigenvectors().transpose();
    const double *l = CPGIMPShape::half<3>(lp, F, lb3);
    for (int d = 0; d < 3; ++d) CHECK_CLOSE(l[d], V(d, d) * lp[d], 1e-13 * lp[d]);
  }
  // a rotation by 0.9 about the axis (1, 2, 2) / 3: V = I
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  double FR[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) FR[3 * i + j] = R(i, j);
  const double *l = CPGIMPShape::half<3>(lp, FR, lb3);
  for (int d = 0; d < 3; ++d) CHECK_CLOSE(l[d], lp[d], 1e-15 * H);
  // diag(1.5, 0.7, 1.2), then a quarter turn about z: x <- -y, y <- x, so V = diag(0.7, 1.5, 1.2)
  const double Q[9] = {0.0, -0.7, 0.0, 1.5, 0.0, 0.0, 0.0, 0.0, 1.2};
  l = CPGIMPShape::half<3>(lp, Q, lb3);
  CHECK_CLOSE(l[0], 0.7 * lp[0], 1e-15 * H);
  CHECK_CLOSE(l[1], 1.5 * lp[1], 1e-15 * H);
  CHECK_CLOSE(l[2], 1.2 * lp[2], 1e-15 * H);
  // singular: flattened along z (the eigen decomposition's path), and collapsed (floored)
  const double S[9] = {1.5, 0.0, 0.0, 0.0, 0.8, 0.0, 0.0, 0.0, 0.0};
  l = CPGIMPShape::half<3>(lp, S, lb3);
  CHECK_CLOSE(l[0], 1.5 * lp[0], 1e-14 * H);
  CHECK_CLOSE(l[1], 0.8 * lp[1], 1e-14 * H);
  CHECK(l[2] == CPGIMPShape::kMinStretch * lp[2]);
  const double Z[9] = {};
  l = CPGIMPShape::half<3>(lp, Z, lb3);
  for (int d = 0; d < 3; ++d) CHECK(l[d] == CPGIMPShape::kMinStretch * lp[d]);
}

int main() {
  Lcg r;
  test_basic_properties<LinearShape>(r);
  test_basic_properties<UGIMPShape>(r);
  test_pmpm_equals_linear_inside_cell(r);
  test_pmpm_weight_is_block_average<UGIMPShape>(r);
  test_pmpm_gradient_is_derivative<UGIMPShape>(r);
  test_face_crossing(r);
  test_hessian_is_derivative<LinearShape>(r);
  test_hessian_is_derivative<UGIMPShape>(r);
  // cpGIMP, a sequence of its own (the tests above keep theirs)
  Lcg c(0x9E3779B97F4A7C15ull);
  test_basic_properties<CPGIMPShape>(c, CPGIMPShape::kMaxHalf);
  test_pmpm_weight_is_block_average<CPGIMPShape>(c, CPGIMPShape::kMaxHalf);
  test_pmpm_gradient_is_derivative<CPGIMPShape>(c, CPGIMPShape::kMaxHalf);
  test_cpgimp_equals_ugimp(c);
  test_cpgimp_half_size();
  test_cpgimp_half_size_3d(r);
  return pmpm_test::report("test_shapes");
}
