// cpGIMP (Wallstedt & Guilkey 2008, "convected particle domain" GIMP): uGIMP's block-averaged
// hat with a half-size that follows the deformation, l_d = l0_d |F_dd| (the diagonal of F).
// Under a stretch the blocks grow with the body and keep tiling it, so the body's end, the
// traction face and the leading node's mass move with the material; uGIMP's fixed blocks stop
// tiling past about 40 % stretch (README, "Shapes whose blocks follow the deformation").
//
// Why the diagonal and not the principal stretches: on the bar and the column F is diagonal and
// both give the same block; under a simple shear F = [[1, g], [0, 1]] the sheared rows still tile
// the body with their undeformed height, which the diagonal keeps (F_yy = 1, block area
// l_x l_y = J l0_x l0_y) while the stretch of the material edge, sqrt(1 + g^2), overlaps the rows.
// A rigid rotation by theta shrinks the diagonal block by cos(theta); |F_dd| is floored at
// kMinStretch so a block never degenerates (it then acts as the linear hat at the centre).
//
// Support: a block of half-size l <= h (in cell units li <= 1) starting in cell base spans at most
// three cells, NS = 4 nodes, inside the grid's two ghost layers (grid.cpp). A larger block is
// reported with the particle and what to change (cycle.cpp, CheckSupport); kMaxHalf is that bound.
#pragma once
#include "pmpm/shape.hpp"

namespace pmpm {

struct CPGIMPShape {
  static constexpr int NS = 4;
  static constexpr const char *name = "cpgimp";
  static constexpr double kMaxHalf = 1.0;     // largest half-size, in cells, the support holds
  static constexpr double kMinStretch = 1e-3; // floor on |F_dd|

  // The current half-size: buf_d = lp_d max(|F_dd|, kMinStretch); F row-major DIM x DIM.
  static const double *half(const double *lp, const double *F, double *buf) {
    for (int d = 0; d < DIM; ++d) {
      const double s = std::fabs(F[d * DIM + d]);
      buf[d] = lp[d] * (s > kMinStretch ? s : kMinStretch);
    }
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
