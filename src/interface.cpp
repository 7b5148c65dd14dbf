#include "pmpm/interface.hpp"
#include <cmath>

namespace pmpm {

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
      // A contact node needs both bodies with a real share of its mass: where one body barely
      // reaches a node its own velocity f/m is unbounded (the small-mass problem), so such
      // nodes, and nodes without a normal, keep the single field (bonded).
      if (m1 < prm.min_share * m || m2 < prm.min_share * m || gn <= 0.0) {
        for (int d = 0; d < DIM; ++d) {
          b[GridDof::P + d] = vcm[d];
          b[GridDof::F + d] = acm[d];
        }
        continue;
      }
      st.contact_nodes += 1;
      // sum_p V_p c_p grad S_ip points out of body 1 (S_i falls away from node i)
      const double n[DIM] = {gx / gn, gy / gn};
      double dv[DIM] = {v1[0] - vcm[0], v1[1] - vcm[1]};
      const double dn = dv[0] * n[0] + dv[1] * n[1];
      if (prm.type == InterfaceType::Paper || dn > 0.0) {
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
        // body 2's old velocity from the old total and body-1 momenta
        const double vcm_old = vcm[d] - dt * acm[d];
        const double v2old = (m * vcm_old - m1 * v1old[d]) / m2;
        b[GridDof::P + d] = v1n;
        b[GridDof::F + d] = (v1n - v1old[d]) / dt;
        t[GridDof::P + d] = v2n;
        t[GridDof::F + d] = (v2n - v2old) / dt;
      }
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
