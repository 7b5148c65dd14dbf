// Shape functions behind one small interface.
//
// A shape is a struct with
//   static constexpr int NS;      // nodes per direction in the support
//   static constexpr const char *name;
//   static void eval1d(double xi, double li, int &base, double w[NS], double dw[NS]);
//   static const double *half(const double *lp, const double *F, double *buf);
// where xi = (x - origin)/h is the particle position in cell units, li = l/h its half-size in
// cell units, base the first node index of the support, w the weights and dw their derivatives
// with respect to xi (divide by h for physical gradients). half() gives the particle's current
// half-size from its initial one lp and its deformation gradient F: lp itself for a block of
// fixed size, a deformed size written to buf (D values; half<D>, D = DIM by default) for cpGIMP.
// Tensor products build the D-dimensional weights (weights() below). A new shape (quadratic
// B-spline, cpGIMP with a deforming half-size) is one new struct in one new header, plus one line
// in the dispatch of cycle.cpp. A shape that is not a tensor product (CPDI) provides its own
// weights() with the same output layout. The shapes the implicit solver runs on (mpm, pmpm) also
// give the second derivatives of w with respect to xi, d2w1d(xi, li, d2w) over the same support as
// eval1d (weight_hessians() below): the reset grid's tangent (implicit_kernels.hpp) differentiates
// grad S_i in the particle's position.
#pragma once
#include "pmpm/util/config.hpp"
#include <cmath>

namespace pmpm {

enum class ShapeKind { Linear = 0, UGIMP = 1, CPGIMP = 2 };
inline constexpr const char *ShapeKindNames[] = {"mpm",       "pmpm",   "cpgimp",
                                                 "ShapeKind", "SHAPE_", nullptr};

// Standard MPM: piecewise-linear hat of the node, evaluated at the particle centre.
struct LinearShape {
  static constexpr int NS = 2;
  static constexpr const char *name = "mpm";
  template <int D = DIM> static const double *half(const double *lp, const double *, double *) {
    return lp;
  }
  static void eval1d(double xi, double /*li*/, int &base, double w[NS], double dw[NS]) {
    base = static_cast<int>(std::floor(xi));
    const double r = xi - base;
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
  // piecewise linear: no curvature inside a cell (the kinks at the nodes have measure zero)
  static void d2w1d(double, double, double d2w[NS]) { d2w[0] = d2w[1] = 0.0; }
};

// Partition MPM (the paper's PMPM, eq. 14-15, 20; uGIMP): the particle is a block of constant
// half-size l (its undeformed size), and its weight for node i is the block-average of the hat,
//   S_i = (1/2l) int_{x-l}^{x+l} N_i dx,  dS_i/dx = (N_i(x+l) - N_i(x-l)) / 2l.
// Crossing a cell face is then gradual. Inside one cell S_i equals the linear hat at the centre.
struct UGIMPShape {
  static constexpr int NS = 3;
  static constexpr const char *name = "pmpm";
  template <int D = DIM> static const double *half(const double *lp, const double *, double *) {
    return lp;
  }
  // Closed form: with the block [a, b] in the coordinates of its first cell (0 <= a < 1,
  // b = a + 2 li <= a + 1), integrate the three hats piecewise. No branch: with
  // c = min(b, 1) and e = max(b - 1, 0) (the part in the second cell) one expression covers
  // both cases, and a block inside one cell gets e = 0 and the same values bit for bit as the
  // branch (b > 1) it replaces, which at -ppc 2 was mispredicted for about half the particles
  // (their blocks end on a cell face; docs/benchmarks/lean_cycle.md).
  static void eval1d(double xi, double li, int &base, double w[NS], double dw[NS]) {
    const double lo = xi - li;
    base = static_cast<int>(std::floor(lo));
    const double a = lo - base, b = a + 2.0 * li, inv = 0.5 / li;
    const double c = b < 1.0 ? b : 1.0; // end of the block's part in the first cell
    const double e = b > 1.0 ? b - 1.0 : 0.0;
    const double half = 0.5 * (c * c - a * a), e2 = 0.5 * e * e;
    const double I0 = (c - a) - half, I1 = half + (e - e2), I2 = e2;
    const double N0b = 1.0 - c, N1b = c - e, N2b = e; // hats at the block's right end
    w[0] = I0 * inv;
    w[1] = I1 * inv;
    w[2] = I2 * inv;
    dw[0] = (N0b - (1.0 - a)) * inv;
    dw[1] = (N1b - a) * inv;
    dw[2] = N2b * inv;
  }
  // d(dw)/dxi (a, b, c and e as in eval1d, da = db = 1): a block inside one cell averages a linear
  // hat, so no curvature; a block across a face bends the three weights by (1, -2, 1) / 2li.
  static void d2w1d(double xi, double li, double d2w[NS]) {
    const double lo = xi - li, b = lo - std::floor(lo) + 2.0 * li, inv = 0.5 / li;
    d2w[0] = b >= 1.0 ? inv : 0.0;
    d2w[2] = b > 1.0 ? inv : 0.0;
    d2w[1] = -d2w[0] - d2w[2];
  }
};

// D-dimensional tensor-product weights of one particle (D = 2, 3; D = DIM by default). Node a
// (0 <= a < NS^D) is at base + (a % NS, (a / NS) % NS, a / NS^2): x fastest; grad is the
// physical gradient (per metre). Each weight and gradient is the product of the 1D factors taken
// in the order x, y, z (the gradient's own direction with the derivative), so the 2D values are
// those of the 2D tensor product written out, bit for bit.
constexpr int ipow(int n, int d) {
  return d == 0 ? 1 : n * ipow(n, d - 1);
}
template <class Shape, int D = DIM> struct Weights {
  static_assert(D == 2 || D == 3, "2D or 3D");
  static constexpr int NS = Shape::NS;
  static constexpr int NN = ipow(NS, D);
  int base[D];
  double w[NN];
  double grad[NN][D];
};

template <class Shape, int D>
inline void weights(const double *x, const double *l, const double *origin, double h,
                    Weights<Shape, D> &W) {
  constexpr int NS = Shape::NS, NN = Weights<Shape, D>::NN;
  double w1[D][NS], dw1[D][NS];
  const double invh = 1.0 / h;
  for (int d = 0; d < D; ++d)
    Shape::eval1d((x[d] - origin[d]) * invh, l[d] * invh, W.base[d], w1[d], dw1[d]);
  for (int k = 0; k < NN; ++k) {
    int i[D];
    for (int d = 0, r = k; d < D; ++d, r /= NS) i[d] = r % NS;
    double w = w1[0][i[0]];
    for (int d = 1; d < D; ++d) w *= w1[d][i[d]];
    W.w[k] = w;
    for (int e = 0; e < D; ++e) {
      double g = e == 0 ? dw1[0][i[0]] : w1[0][i[0]];
      for (int d = 1; d < D; ++d) g *= d == e ? dw1[d][i[d]] : w1[d][i[d]];
      W.grad[k][e] = g * invh;
    }
  }
}

// The second derivatives of the D-dimensional weights in the particle's position (per metre
// squared), node k as in weights(), packed as the upper triangle row by row: in 2D
// H[k] = {d2S/dx2, d2S/dxdy, d2S/dy2}, in 3D {xx, xy, xz, yy, yz, zz} (hessian_index). For the
// implicit solver's reset-grid tangent.
template <int D> constexpr int NHess = D *(D + 1) / 2;
template <int D> constexpr int hessian_index(int b, int c) {
  const int r = b < c ? b : c, q = b < c ? c : b;
  return r * D - r * (r - 1) / 2 + (q - r);
}
template <class Shape, int D = DIM>
inline void weight_hessians(const double *x, const double *l, const double *origin, double h,
                            double H[][NHess<D>]) {
  constexpr int NS = Shape::NS, NN = ipow(NS, D);
  double w1[D][NS], dw1[D][NS], d2[D][NS];
  int base[D];
  const double invh = 1.0 / h;
  for (int d = 0; d < D; ++d) {
    const double xi = (x[d] - origin[d]) * invh;
    Shape::eval1d(xi, l[d] * invh, base[d], w1[d], dw1[d]);
    Shape::d2w1d(xi, l[d] * invh, d2[d]);
  }
  const double ih2 = invh * invh;
  for (int k = 0; k < NN; ++k) {
    int i[D];
    for (int d = 0, r = k; d < D; ++d, r /= NS) i[d] = r % NS;
    for (int b = 0; b < D; ++b)
      for (int c = b; c < D; ++c) {
        // the product over the directions of w, dw or d2w (x_d differentiated 0, 1 or 2 times),
        // then 1 / h^2: in 2D d2x wy, dwx dwy, wx d2y times 1 / h^2, as before
        double v = 1.0;
        for (int d = 0; d < D; ++d) {
          const int n = (d == b) + (d == c);
          const double f = n == 0 ? w1[d][i[d]] : n == 1 ? dw1[d][i[d]] : d2[d][i[d]];
          v = d == 0 ? f : v * f;
        }
        H[k][hessian_index<D>(b, c)] = v * ih2;
      }
  }
}

} // namespace pmpm
