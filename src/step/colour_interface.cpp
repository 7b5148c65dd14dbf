// The colour interface (-interface_type other than bonded, without chains; interface.hpp) in the
// explicit step: body 1 (colour 1) has its own nodal field on a second grid, whose velocities
// the friction-limited interface update sets where the bodies meet; G2P reads both fields.
#include "pmpm/contact/interface.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return sim.iface_grid.active;
}

template <class Shape> void BodyToGrid(StepState &S, const GridView &G) {
  Simulation &sim = S.sim;
  const PetscInt nb = static_cast<PetscInt>(sim.iface_idx.size());
  p2g<Shape>(S.P, S.load, G, sim.iface_idx.data(), nb, S.pshift);
  if (sim.model.iface.normals == InterfaceNormals::Cells)
    p2g_cell_colour(S.P, G); // all particles
  else
    p2g_colour_gradient<Shape>(S.P, sim.iface_idx.data(), nb, G); // in FEXT slots
}

// 1b. Body 1's own mass, momentum, force, and its colour gradient (the normals).
PetscErrorCode ParticlesToGrid(StepState &S) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.iface);
  PetscCall(GridWithLocal(S.sim.iface_grid.body, true, [&](const GridView &G) {
    switch (S.sim.set.shape) {
    case ShapeKind::Linear:
      BodyToGrid<LinearShape>(S, G);
      break;
    case ShapeKind::UGIMP:
      BodyToGrid<UGIMPShape>(S, G);
      break;
    case ShapeKind::CPGIMP:
      BodyToGrid<CPGIMPShape>(S, G);
      break;
    }
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode GhostAdd(StepState &S) {
  PetscFunctionBeginUser;
  PetscCall(GridLocalToGlobalAdd(S.sim.iface_grid.body));
  PetscFunctionReturn(0);
}

// 2b. The paper's normals: central differences of the cell-average colour need the
//     neighbouring cells' sums, one more ghost exchange of the body grid.
PetscErrorCode CellNormals(StepState &S) {
  Grid &gb = S.sim.iface_grid.body;
  PetscFunctionBeginUser;
  if (S.sim.model.iface.normals != InterfaceNormals::Cells) PetscFunctionReturn(0);
  PmpmLogEventScope(step_events.iface);
  PetscCall(GridGlobalToLocal(gb));
  PetscCall(GridWithLocal(gb, false, [&](const GridView &C) {
    return GridWithGlobal(gb, [&](const GridView &B) { cell_colour_normals(C, B); });
  }));
  PetscFunctionReturn(0);
}

// 3b. Friction-limited velocities of body 1 and body 2 where they meet.
PetscErrorCode Update(StepState &S) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.iface);
  InterfaceParams ip = S.sim.model.iface;
  ip.dt = S.dt;
  ip.damping_alpha = S.gp.damping_alpha;
  PetscCall(GridWithGlobal(S.sim.iface_grid.body,
                           [&](const GridView &B) { interface_update(S.G, B, ip, S.rep.iface); }));
  PetscFunctionReturn(0);
}

PetscErrorCode GhostScatter(StepState &S) {
  PetscFunctionBeginUser;
  PetscCall(GridGlobalToLocal(S.sim.iface_grid.body));
  PetscFunctionReturn(0);
}

// 5. G2P reads body 1's velocities for its particles.
PetscErrorCode BodyView(StepState &S) {
  PetscFunctionBeginUser;
  PetscCall(GridGetLocal(S.sim.iface_grid.body, false, S.body));
  S.G1 = &S.body;
  PetscFunctionReturn(0);
}

PetscErrorCode BodyViewEnd(StepState &S) {
  PetscFunctionBeginUser;
  PetscCall(GridRestoreLocal(S.sim.iface_grid.body, S.body));
  S.G1 = nullptr;
  PetscFunctionReturn(0);
}
} // namespace

extern const StepHook interface_hook = [] {
  StepHook h{};
  h.name = "interface";
  h.active = Active;
  h.phases.p2g = ParticlesToGrid;
  h.phases.ghost_add = GhostAdd;
  h.phases.after_ghost_add = CellNormals;
  h.phases.grid_update = Update;
  h.phases.ghost_scatter = GhostScatter;
  h.phases.before_g2p = BodyView;
  h.phases.after_g2p = BodyViewEnd;
  return h;
}();

} // namespace pmpm
