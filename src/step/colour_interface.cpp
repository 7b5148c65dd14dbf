// The colour interface (-interface_type other than bonded, without chains; interface.hpp) in the
// explicit step: body 1 (colour 1) has its own nodal field on a second grid, whose velocities
// the friction-limited interface update sets where the bodies meet; G2P reads both fields. The
// same phases in 2D and 3D (the body grid beside sim.grid or sim.grid3).
#include "pmpm/contact/interface.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return sim.iface_grid.active;
}

template <class Shape, int D> void BodyToGrid(StepStateT<D> &S, const GridViewT<D> &G) {
  Simulation &sim = S.sim;
  const PetscInt nb = static_cast<PetscInt>(sim.iface_idx.size());
  p2g<Shape>(S.P, S.load, G, sim.iface_idx.data(), nb, S.pshift);
  if (sim.model.iface.normals == InterfaceNormals::Cells)
    p2g_cell_colour(S.P, G); // all particles
  else
    p2g_colour_gradient<Shape>(S.P, sim.iface_idx.data(), nb, G); // in FEXT slots
}

template <int D> GridT<D> &BodyGrid(StepStateT<D> &S) {
  return S.sim.iface_grid.template body_of<D>();
}

// 1b. Body 1's own mass, momentum, force, and its colour gradient (the normals).
template <int D> PetscErrorCode ParticlesToGrid(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.iface);
  PetscCall(GridWithLocal(BodyGrid(S), true, [&](const GridViewT<D> &G) {
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

template <int D> PetscErrorCode GhostAdd(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PetscCall(GridLocalToGlobalAdd(BodyGrid(S)));
  PetscFunctionReturn(0);
}

// 2b. The paper's normals: central differences of the cell-average colour need the
//     neighbouring cells' sums, one more ghost exchange of the body grid.
template <int D> PetscErrorCode CellNormals(StepStateT<D> &S) {
  GridT<D> &gb = BodyGrid(S);
  PetscFunctionBeginUser;
  if (S.sim.model.iface.normals != InterfaceNormals::Cells) PetscFunctionReturn(0);
  PmpmLogEventScope(step_events.iface);
  PetscCall(GridGlobalToLocal(gb));
  PetscCall(GridWithLocal(gb, false, [&](const GridViewT<D> &C) {
    return GridWithGlobal(gb, [&](const GridViewT<D> &B) { cell_colour_normals(C, B); });
  }));
  PetscFunctionReturn(0);
}

// 3b. Friction-limited velocities of body 1 and body 2 where they meet.
template <int D> PetscErrorCode Update(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.iface);
  InterfaceParams ip = S.sim.model.iface;
  ip.dt = S.dt;
  ip.damping_alpha = S.gp.damping_alpha;
  if (D == 3) { // the z faces (-bc_zmin, -bc_zmax) and gravity's z component
    for (int f = 4; f < 6; ++f) ip.face[f] = S.sim.model.face[f];
    ip.up[2] = -S.sim.set.gdir_z;
  }
  PetscCall(GridWithGlobal(
      BodyGrid(S), [&](const GridViewT<D> &B) { interface_update(S.G, B, ip, S.rep.iface); }));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GhostScatter(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PetscCall(GridGlobalToLocal(BodyGrid(S)));
  PetscFunctionReturn(0);
}

// 5. G2P reads body 1's velocities for its particles.
template <int D> PetscErrorCode BodyView(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PetscCall(GridGetLocal(BodyGrid(S), false, S.body));
  S.G1 = &S.body;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode BodyViewEnd(StepStateT<D> &S) {
  PetscFunctionBeginUser;
  PetscCall(GridRestoreLocal(BodyGrid(S), S.body));
  S.G1 = nullptr;
  PetscFunctionReturn(0);
}

template <int D> HookPhasesT<D> PhasesIn() {
  HookPhasesT<D> p{};
  p.p2g = ParticlesToGrid<D>;
  p.ghost_add = GhostAdd<D>;
  p.after_ghost_add = CellNormals<D>;
  p.grid_update = Update<D>;
  p.ghost_scatter = GhostScatter<D>;
  p.before_g2p = BodyView<D>;
  p.after_g2p = BodyViewEnd<D>;
  return p;
}
} // namespace

extern const StepHook interface_hook = [] {
  StepHook h{};
  h.name = "interface";
  h.active = Active;
  h.phases = PhasesIn<2>();
  h.phases3 = PhasesIn<3>();
  return h;
}();

} // namespace pmpm
