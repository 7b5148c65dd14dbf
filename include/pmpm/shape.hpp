// Shape functions behind one small interface.
//
// A shape is a struct with
//   static constexpr int NS;      // nodes per direction in the support
//   static constexpr const char *name;
//   static void eval1d(double xi, double li, int &base, double w[NS], double dw[NS]);
// where xi = (x - origin)/h is the particle position in cell units, li = l/h its half-size in
// cell units, base the first node index of the support, w the weights and dw their derivatives
// with respect to xi (divide by h for physical gradients). Tensor products build the DIM-D
// weights (weights() below). A new shape (quadratic B-spline, cpGIMP with a deforming half-size)
// is one new struct in one new header, plus one line in the dispatch of cycle.cpp. A shape that is
// not a tensor product (CPDI) provides its own weights() with the same output layout.
#pragma once
#include "pmpm/config.hpp"
#include <cmath>

namespace pmpm {

enum class ShapeKind { Linear = 0, UGIMP = 1 };
inline constexpr const char *ShapeKindNames[] = {"mpm", "pmpm", "ShapeKind", "SHAPE_", nullptr};

// Standard MPM: piecewise-linear hat of the node, evaluated at the particle centre.
struct LinearShape {
  static constexpr int NS = 2;
  static constexpr const char *name = "mpm";
  static void eval1d(double xi, double /*li*/, int &base, double w[NS], double dw[NS]) {
    base = static_cast<int>(std::floor(xi));
    const double r = xi - base;
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
};

// Partition MPM (the paper's PMPM, eq. 14-15, 20; uGIMP): the particle is a block of constant
// half-size l (its undeformed size), and its weight for node i is the block-average of the hat,
//   S_i = (1/2l) int_{x-l}^{x+l} N_i dx,  dS_i/dx = (N_i(x+l) - N_i(x-l)) / 2l.
// Crossing a cell face is then gradual. Inside one cell S_i equals the linear hat at the centre.
struct UGIMPShape {
  static constexpr int NS = 3;
  static constexpr const char *name = "pmpm";
  // Integral of the hat centred at 0 (unit cell) from -inf to s.
  static double hat_integral(double s) {
    if (s <= -1.0) return 0.0;
    if (s <= 0.0) return 0.5 * (1.0 + s) * (1.0 + s);
    if (s <= 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
    return 1.0;
  }
  static double hat(double s) {
    const double a = std::fabs(s);
    return a < 1.0 ? 1.0 - a : 0.0;
  }
  static void eval1d(double xi, double li, int &base, double w[NS], double dw[NS]) {
    base = static_cast<int>(std::floor(xi - li));
    const double inv = 0.5 / li;
    for (int a = 0; a < NS; ++a) {
      const double s = xi - (base + a);
      w[a] = (hat_integral(s + li) - hat_integral(s - li)) * inv;
      dw[a] = (hat(s + li) - hat(s - li)) * inv;
    }
  }
};

// DIM-D tensor-product weights of one particle. Node a (0 <= a < NS^DIM) is at
// base + (a % NS, a / NS); grad is the physical gradient (per metre).
template <class Shape> struct Weights {
  static constexpr int NS = Shape::NS;
  static constexpr int NN = NS * NS; // DIM == 2
  int base[DIM];
  double w[NN];
  double grad[NN][DIM];
};

template <class Shape>
inline void weights(const double *x, const double *l, const double origin[DIM], double h,
                    Weights<Shape> &W) {
  constexpr int NS = Shape::NS;
  static_assert(DIM == 2, "tensor product written for 2D");
  double wx[NS], dwx[NS], wy[NS], dwy[NS];
  const double invh = 1.0 / h;
  Shape::eval1d((x[0] - origin[0]) * invh, l[0] * invh, W.base[0], wx, dwx);
  Shape::eval1d((x[1] - origin[1]) * invh, l[1] * invh, W.base[1], wy, dwy);
  for (int b = 0; b < NS; ++b)
    for (int a = 0; a < NS; ++a) {
      const int k = b * NS + a;
      W.w[k] = wx[a] * wy[b];
      W.grad[k][0] = dwx[a] * wy[b] * invh;
      W.grad[k][1] = wx[a] * dwy[b] * invh;
    }
}

} // namespace pmpm
