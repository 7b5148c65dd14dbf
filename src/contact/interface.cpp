#include "pmpm/contact/interface.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

namespace {
// Both normal kernels give the colour gradient times h: O(1) where the colour jumps by O(1)
// across a cell, and round-off (1e-16) where it is uniform. Below this there is no normal: a
// direction drawn from round-off would depend on the summation order, that is on the ranks.
constexpr double kNoNormal = 1e-8;
// A share of a node's mass at or below this is round-off (the body does not reach the node).
constexpr double kRoundOff = 1e-12;
} // namespace

void interface_update(const GridView &T, const GridView &B, const InterfaceParams &prm,
                      InterfaceStats &st) {
  const double dt = prm.dt, alpha = prm.damping_alpha;
  for (PetscInt j = T.gs[1]; j < T.gs[1] + T.gm[1]; ++j)
    for (PetscInt i = T.gs[0]; i < T.gs[0] + T.gm[0]; ++i) {
      double *t = T.node(i, j), *b = B.node(i, j);
      const double m = t[GridDof::M], m1 = b[GridDof::M];
      if (m1 <= 0.0) continue;
      bool held[DIM];
      held_dofs(i, j, T.ncell, prm.face, held);
      double vcm[DIM], acm[DIM], v1[DIM], v1old[DIM];
      for (int d = 0; d < DIM; ++d) {
        vcm[d] = t[GridDof::P + d];
        acm[d] = t[GridDof::F + d];
        // body 1 on its own: the same damped momentum balance as the total field
        v1old[d] = b[GridDof::P + d] / m1;
        double f = b[GridDof::F + d];
        if (alpha > 0.0 && v1old[d] != 0.0) f -= alpha * std::fabs(f) * (v1old[d] > 0 ? 1 : -1);
        v1[d] = held[d] ? 0.0 : v1old[d] + dt * f / m1;
      }
      const double m2 = m - m1;
      const double gx = b[GridDof::FEXT], gy = b[GridDof::FEXT + 1], gn = std::hypot(gx, gy);
      // A contact node needs a normal and both bodies' mass; every share above round-off counts.
      if (m1 <= kRoundOff * m || m2 <= kRoundOff * m || gn <= kNoNormal) {
        for (int d = 0; d < DIM; ++d) {
          b[GridDof::P + d] = vcm[d];
          b[GridDof::F + d] = acm[d];
        }
        continue;
      }
      double v2old[DIM]; // body 2's old velocity from the old total and body-1 momenta
      for (int d = 0; d < DIM; ++d) v2old[d] = (m * (vcm[d] - dt * acm[d]) - m1 * v1old[d]) / m2;
      // A body with a tail share (uGIMP's blocks reach the next row of nodes with shares down
      // to 1e-8) has an unreliable own acceleration f/m there: it takes the common acceleration
      // and keeps its velocity relative to the other body. Bonding such nodes instead glued the
      // sliding block on the incline (4.7 % slow at mu = 0 for shares below 1e-3, 1 % below
      // 1e-6); their own f/m made the friction landfill relax 3.9x slower (7142 steps, not 1823).
      if (m1 < prm.tail_share * m) {
        for (int d = 0; d < DIM; ++d) v1[d] = held[d] ? 0.0 : v1old[d] + dt * acm[d];
      } else if (m2 < prm.tail_share * m) { // v1 such that body 2 takes the common acceleration
        for (int d = 0; d < DIM; ++d)
          v1[d] = held[d] ? 0.0 : (m * vcm[d] - m2 * (v2old[d] + dt * acm[d])) / m1;
      }
      st.contact_nodes += 1;
      const double n[DIM] = {gx / gn, gy / gn};
      double dv[DIM] = {v1[0] - vcm[0], v1[1] - vcm[1]};
      const double dn = dv[0] * n[0] + dv[1] * n[1];
      if (prm.type == InterfaceType::Paper || dn > 0.0) {
        const double impulse = m1 * dn; // on body 1, along -n: what keeps the normals common
        if (impulse > 0.0)
          st.compression += impulse;
        else
          st.tension -= impulse;
        const double tv[DIM] = {dv[0] - dn * n[0], dv[1] - dn * n[1]};
        const double tn = std::hypot(tv[0], tv[1]);
        const double mu = n[0] * prm.up[0] + n[1] * prm.up[1] > 0 ? prm.mu_top : prm.mu_bottom;
        // Coulomb needs compression: only an approaching normal velocity gives friction capacity
        const double cap = mu * std::fmax(dn, 0.0);
        const double keep = tn > cap ? 1.0 - cap / tn : 0.0;
        if (keep > 0.0) st.slip_nodes += 1;
        for (int d = 0; d < DIM; ++d) dv[d] = keep * tv[d];
      }
      for (int d = 0; d < DIM; ++d) {
        const double v1n = held[d] ? 0.0 : vcm[d] + dv[d];
        const double v2n = held[d] ? 0.0 : vcm[d] - m1 / m2 * dv[d];
        b[GridDof::P + d] = v1n;
        b[GridDof::F + d] = (v1n - v1old[d]) / dt;
        t[GridDof::P + d] = v2n;
        t[GridDof::F + d] = (v2n - v2old[d]) / dt;
      }
    }
}

void cell_colour_normals(const GridView &C, const GridView &B) {
  // Average colour of cell (i, j); a cell without particles has colour 0 (a free surface is an
  // edge of the body), a cell off the grid that of the nearest cell on it (a box face is not).
  auto avg = [&C](PetscInt i, PetscInt j) {
    i = std::min(std::max(i, PetscInt(0)), C.ncell[0] - 1);
    j = std::min(std::max(j, PetscInt(0)), C.ncell[1] - 1);
    const double *c = C.node(i, j);
    return c[GridDof::FEXT + 1] > 0.0 ? c[GridDof::FEXT] / c[GridDof::FEXT + 1] : 0.0;
  };
  // The gradient at a cell centre is the central difference between its neighbours' centres;
  // a node takes the mean of its four cells' gradients (it reaches cells i - 2 .. i + 1, within
  // the ghost width of 2). Minus the gradient points out of body 1.
  const double s = 0.125; // 1/4 of the four cells times 1/2: the gradient times h, O(1) at a jump
  for (PetscInt j = B.gs[1]; j < B.gs[1] + B.gm[1]; ++j)
    for (PetscInt i = B.gs[0]; i < B.gs[0] + B.gm[0]; ++i) {
      double g[DIM] = {0.0, 0.0};
      for (PetscInt cj = j - 1; cj <= j; ++cj)
        for (PetscInt ci = i - 1; ci <= i; ++ci) {
          g[0] += avg(ci + 1, cj) - avg(ci - 1, cj);
          g[1] += avg(ci, cj + 1) - avg(ci, cj - 1);
        }
      double *b = B.node(i, j);
      b[GridDof::FEXT + 0] = -s * g[0];
      b[GridDof::FEXT + 1] = -s * g[1];
    }
}

PetscErrorCode InterfaceGridCreate(Grid &g, InterfaceGrid &ig) {
  const PetscInt *lx, *ly;
  PetscMPIInt px, py;
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da, &lx, &ly, nullptr));
  ig.body = g;
  PetscCall(DMDACreate2d(PetscObjectComm((PetscObject)g.da), DM_BOUNDARY_GHOSTED,
                         DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX, g.ncell[0] + 1, g.ncell[1] + 1, px,
                         py, GridDof::NDOF, 2, lx, ly, &ig.body.da));
  PetscCall(DMSetUp(ig.body.da));
  // the body grid keeps its global vector on one rank too: cell_colour_normals writes the slots
  // it reads from the neighbouring nodes
  ig.body.shared = false;
  PetscCall(DMCreateLocalVector(ig.body.da, &ig.body.local));
  PetscCall(DMCreateGlobalVector(ig.body.da, &ig.body.global));
  ig.active = true;
  PetscFunctionReturn(0);
}

PetscErrorCode InterfaceGridDestroy(InterfaceGrid &ig) {
  PetscFunctionBeginUser;
  if (ig.active) PetscCall(GridDestroy(ig.body));
  ig.active = false;
  PetscFunctionReturn(0);
}

} // namespace pmpm
