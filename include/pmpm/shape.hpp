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
// fixed size, a deformed size written to buf (DIM values) for cpGIMP. Tensor products build the
// DIM-D weights (weights() below). A new shape (quadratic B-spline, cpGIMP with a deforming
// half-size) is one new struct in one new header, plus one line in the dispatch of cycle.cpp. A
// shape that is not a tensor product (CPDI) provides its own weights() with the same output layout.
#pragma once
#include "pmpm/config.hpp"
#include <cmath>

namespace pmpm {

enum class ShapeKind { Linear = 0, UGIMP = 1, CPGIMP = 2 };
inline constexpr const char *ShapeKindNames[] = {"mpm",       "pmpm",   "cpgimp",
                                                 "ShapeKind", "SHAPE_", nullptr};

// Standard MPM: piecewise-linear hat of the node, evaluated at the particle centre.
struct LinearShape {
  static constexpr int NS = 2;
  static constexpr const char *name = "mpm";
  static const double *half(const double *lp, const double *, double *) { return lp; }
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
  static const double *half(const double *lp, const double *, double *) { return lp; }
  // Closed form: with the block [a, b] in the coordinates of its first cell (0 <= a < 1,
  // b = a + 2 li <= a + 1), integrate the three hats piecewise. No branch: with
  // c = min(b, 1) and e = max(b - 1, 0) (the part in the second cell) one expression covers
  // both cases, and a block inside one cell gets e = 0 and the same values bit for bit as the
  // branch (b > 1) it replaces, which at -ppc 2 was mispredicted for about half the particles
  // (their blocks end on a cell face; BENCHMARKS.md, "A leaner explicit cycle").
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
