// Affine particle-in-cell transfers (APIC; Jiang et al. 2015, 2017) for the shapes of shape.hpp.
//
// With -transfer apic every particle carries, besides v_p, the matrix (row-major, B[d*DIM+e])
//   B_p = sum_i w_ip v_i (x_i - x_p)^T                                   (G2P)
// and P2G sends the momentum of the particle's affine field v_p + C_p (x - x_p), C_p = B_p D_p^-1:
//   (m v)_i += m_p w_ip (v_p + B_p D_p^-1 (x_i - x_p)) = m_p (w_ip v_p + B_p a_ip),
// with D_p = sum_i w_ip (x_i - x_p)(x_i - x_p)^T, the inertia-like tensor of the shape in use at
// the particle's position at that P2G, and a_ip = w_ip D_p^-1 (x_i - x_p) the affine weights.
//
// Angular momentum is kept to round-off. Both shapes reproduce linear fields (sum_i w_ip = 1,
// sum_i w_ip x_i = x_p), so D_p of a tensor product is diagonal and sum_i a_ip (x_i - x_p)^T = I:
// P2G gives the grid the particles' angular momentum sum_p m_p (x_p x v_p + B_yx - B_xy) (the
// last two terms are the particle's spin, eps : B_p). Internal forces -V sigma grad w_ip with a
// symmetric sigma exert no torque (sum_i grad w_ip x_i^T = I), and G2P returns sum_i m_i x_i x v_i
// to the particles when they move by dt v_p (x_p^{n+1} x v_p = x_p^n x v_p).
//
// Per direction: D = h^2 sum_a w_a r_a^2, r_a = base + a - xi the node's offset in cells, and
// a_a = w_a r_a / (h sum_a w_a r_a^2) per metre; node (a, b) has the 2D affine weight
// (ax_a wy_b, wx_a ay_b).
//   Linear hats: D = h^2 r (1 - r), zero on a node line, and w_a r_a / D is exactly the hat's
//   derivative: a_ip = grad w_ip and C_p = sum_i v_i grad w_ip^T, taken without the division
//   (the singularity cancels; Jiang et al. 2015 on multilinear weights).
//   uGIMP: D = l^2 / 3 + the block average of h^2 r (1 - r) >= l^2 / 3 > 0 (not the quadratic
//   B-spline's constant h^2 / 4); the general formula.
// A new shape gets the general formula, which is right for any shape that reproduces linear
// fields, unless it is listed in AffineIsGradient.
#pragma once
#include "pmpm/core/shape.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include <type_traits>

namespace pmpm {

enum class Transfer { Flip = 0, Apic = 1 };
inline constexpr const char *TransferNames[] = {"flip", "apic", "Transfer", "TRANSFER_", nullptr};

// Shapes whose affine weights are their gradients (w D^-1 (x_i - x_p) = grad w, exactly).
template <class Shape> struct AffineIsGradient : std::false_type {};
template <> struct AffineIsGradient<LinearShape> : std::true_type {};

// One direction: node offsets r (m) and affine weights a (per metre) from the shape's weights w
// and derivatives dw (per cell, as eval1d returns them) at xi (cells) with first node base.
template <class Shape>
inline void affine1d(double xi, int base, const double *w, const double *dw, double h, double *r,
                     double *a) {
  constexpr int NS = Shape::NS;
  double s2 = 0.0; // sum_a w_a r_a^2 (cells^2)
  for (int k = 0; k < NS; ++k) {
    const double rk = (base + k) - xi;
    r[k] = rk * h;
    s2 += w[k] * rk * rk;
  }
  const double invh = 1.0 / h;
  if (AffineIsGradient<Shape>::value) {
    for (int k = 0; k < NS; ++k) a[k] = dw[k] * invh;
  } else {
    const double f = s2 > 0.0 ? invh / s2 : 0.0; // s2 >= l^2/(3 h^2) > 0 for uGIMP
    for (int k = 0; k < NS; ++k) a[k] = w[k] * (r[k] * invh) * f;
  }
}

// The particle's D_p (diagonal, m^2) at x with half-size l, in D dimensions.
template <class Shape, int D = DIM>
inline void affine_inertia(const double *x, const double *l, const double *origin, double h,
                           double *Dp) {
  constexpr int NS = Shape::NS;
  double w[NS], dw[NS];
  int base;
  for (int d = 0; d < D; ++d) {
    const double xi = (x[d] - origin[d]) / h;
    Shape::eval1d(xi, l[d] / h, base, w, dw);
    double s2 = 0.0;
    for (int k = 0; k < NS; ++k) s2 += w[k] * ((base + k) - xi) * ((base + k) - xi);
    Dp[d] = s2 * h * h;
  }
}
// The same for the run's shape, from the particle's initial half-size lp and its deformation
// gradient F (the shape's half(): cpGIMP's block follows F).
template <int D = DIM>
inline void affine_inertia(ShapeKind shape, const double *x, const double *lp, const double *F,
                           const double *origin, double h, double *Dp) {
  double lb[D];
  if (shape == ShapeKind::Linear)
    affine_inertia<LinearShape, D>(x, lp, origin, h, Dp);
  else if (shape == ShapeKind::CPGIMP)
    affine_inertia<CPGIMPShape, D>(x, CPGIMPShape::half<D>(lp, F, lb), origin, h, Dp);
  else
    affine_inertia<UGIMPShape, D>(x, lp, origin, h, Dp);
}

// The particle's spin angular momentum (about its own centre), m_p eps : B_p = m (B_yx - B_xy)
// (2D; in 3D the spin is the vector m (B_zy - B_yz, B_xz - B_zx, B_yx - B_xy)).
inline double affine_spin(double m, const double *B) {
  return m * (B[2] - B[1]);
}

// The kinetic energy of the particle's affine part, 1/2 m tr(B D^-1 B^T) = 1/2 m sum_i w_ip
// |C_p (x_i - x_p)|^2: what it brings to the grid's kinetic energy beyond 1/2 m |v_p|^2 at the
// next P2G. A direction with D = 0 (a linear hat's particle on a node line) has no affine part.
// With linear hats D_p at a new position can be small while B_p (taken at the old one) is not:
// there this measure is large although the momentum it sends is bounded (uGIMP: D >= l^2 / 3).
template <int D = DIM> inline double affine_kinetic(double m, const double *B, const double *Dp) {
  double e = 0.0;
  for (int d = 0; d < D; ++d)
    for (int k = 0; k < D; ++k)
      if (Dp[k] > 0.0) e += B[d * D + k] * B[d * D + k] / Dp[k];
  return 0.5 * m * e;
}

} // namespace pmpm
