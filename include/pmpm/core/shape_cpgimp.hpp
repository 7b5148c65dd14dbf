// cpGIMP (after Wallstedt & Guilkey 2008, "convected particle domain" GIMP): uGIMP's
// block-averaged hat with a half-size that follows the deformation, l_d = l0_d V_dd, V_dd the
// diagonal of the left stretch tensor V = sqrt(F F^T) (the spatial-frame stretch along axis d:
// sum_i lambda_i (n_i . e_d)^2 over the principal stretches lambda_i and directions n_i). Under a
// stretch the blocks grow with the body and keep tiling it, so the body's end, the traction face
// and the leading node's mass move with the material; uGIMP's fixed blocks stop tiling past about
// 40 % stretch (docs/cpgimp.md).
//
// Why V_dd and not F_dd (Wallstedt & Guilkey's diagonal): both are the same block when F is
// diagonal (the bar, the column; measured equal there), but a rigid rotation by theta shrinks the
// F_dd block by cos(theta): the rotating block (options/block.opts, -block_omega 10) with F_dd
// inverts a particle at step 389, a quarter turn; with V_dd (= I under any rotation) it keeps
// uGIMP's blocks and runs its 3.2 turns. In simple shear, F = [[1, g], [0, 1]], V_dd = 1 + O(g^2)
// where F_dd = 1: the blocks overlap by O(g^2). V has a closed form in 2D:
// V = (B + J I) / sqrt(tr B + 2 J), B = F F^T, J = |det F|; in 3D it is F R^T, R the polar
// decomposition's rotation (polar_stretch_diagonal).
//
// Support: a block of half-size l <= h (in cell units li <= 1) starting in cell base spans at most
// three cells, NS = 4 nodes, inside the grid's two ghost layers (grid.cpp). A larger block is
// reported with the particle and what to change (cycle.cpp, CheckSupport); kMaxHalf is that bound.
#pragma once
#include "pmpm/core/shape.hpp"
#include <Eigen/Dense>
#include <algorithm>

namespace pmpm {

struct CPGIMPShape {
  static constexpr int NS = 4;
  static constexpr const char *name = "cpgimp";
  static constexpr double kMaxHalf = 1.0;     // largest half-size, in cells, the support holds
  static constexpr double kMinStretch = 1e-3; // floor on V_dd (a collapsed F only)

  // V's diagonal in 3D: V = F R^T with R the rotation of the polar decomposition F = R U, found
  // by Newton's iteration X <- (X + X^-T) / 2 from X = F (quadratic; a stretch of 4 takes 7
  // iterations). It keeps round-off at machine precision where the eigenvalues of F F^T nearly
  // coincide (F near a rotation, the common case), which the closed-form cubic of Eigen's
  // computeDirect does not: it was 1e-12 off the 2D closed form on extruded gradients. A singular
  // F (det = 0: no rotation to find) takes the eigen decomposition of B = F F^T.
  static void polar_stretch_diagonal(const double *F, double V[3]) {
    double X[9];
    for (int i = 0; i < 9; ++i) X[i] = F[i];
    bool singular = false;
    for (int it = 0; it < 40; ++it) {
      // X^-T = cof(X) / det X
      const double c[9] = {
          X[4] * X[8] - X[5] * X[7], X[5] * X[6] - X[3] * X[8], X[3] * X[7] - X[4] * X[6],
          X[2] * X[7] - X[1] * X[8], X[0] * X[8] - X[2] * X[6], X[1] * X[6] - X[0] * X[7],
          X[1] * X[5] - X[2] * X[4], X[2] * X[3] - X[0] * X[5], X[0] * X[4] - X[1] * X[3]};
      const double det = X[0] * c[0] + X[1] * c[1] + X[2] * c[2];
      if (!(std::fabs(det) > 1e-300) || !std::isfinite(det)) {
        singular = true;
        break;
      }
      const double inv = 0.5 / det;
      double delta = 0.0;
      for (int i = 0; i < 9; ++i) {
        const double xn = 0.5 * X[i] + inv * c[i];
        delta = std::max(delta, std::fabs(xn - X[i]));
        X[i] = xn;
      }
      if (delta < 1e-10) break; // X's error is now about delta^2: machine precision
    }
    if (!singular) {
      for (int d = 0; d < 3; ++d)
        V[d] = F[3 * d] * X[3 * d] + F[3 * d + 1] * X[3 * d + 1] + F[3 * d + 2] * X[3 * d + 2];
      return;
    }
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Fm(F);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Fm * Fm.transpose());
    const Eigen::Vector3d sl = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    for (int d = 0; d < 3; ++d) {
      V[d] = 0.0;
      for (int i = 0; i < 3; ++i) V[d] += sl[i] * es.eigenvectors()(d, i) * es.eigenvectors()(d, i);
    }
  }

  // The current half-size: buf_d = lp_d max(V_dd, kMinStretch); F row-major D x D. 2D: the
  // closed form above. 3D: polar_stretch_diagonal.
  template <int D = DIM> static const double *half(const double *lp, const double *F, double *buf) {
    static_assert(D == 2 || D == 3, "2D or 3D");
    double V[D];
    if constexpr (D == 2) {
      const double B00 = F[0] * F[0] + F[1] * F[1], B11 = F[2] * F[2] + F[3] * F[3];
      const double J = std::fabs(F[0] * F[3] - F[1] * F[2]);
      const double inv = 1.0 / std::sqrt(B00 + B11 + 2.0 * J); // F = 0 only: inf, V NaN, floored
      V[0] = (B00 + J) * inv;
      V[1] = (B11 + J) * inv;
    } else {
      polar_stretch_diagonal(F, V);
    }
    for (int d = 0; d < D; ++d) buf[d] = lp[d] * (V[d] > kMinStretch ? V[d] : kMinStretch);
    return buf;
  }

  // The block [xi - li, xi + li] in the coordinates of its first cell, [a, b] with 0 <= a < 1,
  // b = a + 2 li <= a + 2; node k (0..3) of the support is at k. As uGIMP: each hat's block
  // average, (H_k(b) - H_k(a)) / 2 li with H_k the hat's integral from -infinity, and its
  // derivative (N_k(b) - N_k(a)) / 2 li. At a only nodes 0 and 1 are non-zero; b lies in cell m
  // (0..2) at e = b - m, where H_k(b) is 1 for k < m, 1 - (1 - e)^2 / 2 at m, e^2 / 2 at m + 1.
  // Nodes the block does not reach get exactly zero weight and gradient (the transfers skip them).
  static void eval1d(double xi, double li, int &base, double w[NS], double dw[NS]) {
    const double lo = xi - li;
    base = static_cast<int>(std::floor(lo));
    const double a = lo - base, b = a + 2.0 * li, inv = 0.5 / li;
    int m = static_cast<int>(b); // b >= 0
    if (m > 2) m = 2;            // b = 3 by round-off only: its last node's full weight
    const double e = b - m, q = 1.0 - 0.5 * (1.0 - e) * (1.0 - e), r = 0.5 * e * e;
    // selects rather than an indexed array: the weights stay in registers (measured 10 % of a step)
    const double Hb[NS] = {m == 0 ? q : 1.0, m == 0 ? r : (m == 1 ? q : 1.0),
                           m == 0 ? 0.0 : (m == 1 ? r : q), m == 2 ? r : 0.0};
    const double Nb[NS] = {m == 0 ? 1.0 - e : 0.0, m == 0 ? e : (m == 1 ? 1.0 - e : 0.0),
                           m == 1 ? e : (m == 2 ? 1.0 - e : 0.0), m == 2 ? e : 0.0};
    w[0] = (Hb[0] - (1.0 - 0.5 * (1.0 - a) * (1.0 - a))) * inv;
    w[1] = (Hb[1] - 0.5 * a * a) * inv;
    w[2] = Hb[2] * inv;
    w[3] = Hb[3] * inv;
    dw[0] = (Nb[0] - (1.0 - a)) * inv;
    dw[1] = (Nb[1] - a) * inv;
    dw[2] = Nb[2] * inv;
    dw[3] = Nb[3] * inv;
  }
};

} // namespace pmpm
