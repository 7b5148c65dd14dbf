// One explicit PMPM step (the relaxation solver, relaxation.cpp, loops over it), and the stage
// loop that calls the equilibrium solver (solver.hpp) once per stage.
#pragma once
#include "pmpm/model/simulation.hpp"

namespace pmpm {

struct StepReport {
  GridStats grid;
  G2PStats g2p;
  InterfaceStats iface;
  ContactStats contact;   // chains only
  double eigen_power = 0; // this rank's power of the imposed eigenstrain (degradation.hpp)
};

// -damping fire (relaxation.cpp): the nodal velocities mixed toward the force by `mix`, the force
// scaled by `scale` (grid_update, transfers.hpp).
struct FireMix {
  bool on = false;
  double mix = 0, scale = 0;
};

PetscErrorCode LogRegister();
// One step of the cycle (see cycle.cpp for the phases). Collective.
PetscErrorCode Step(Simulation &sim, const Load &load, double dt, const FireMix &fire,
                    StepReport &rep);
// Initial stable step from the wave speeds at rest.
PetscErrorCode InitialWaveSpeed(Simulation &sim, double *max_speed);
// The unbalanced-force ratio of the current particle state evaluated with the given shape
// functions (full load): the paper's equilibrium residual, eq. 13 (mpm) against eq. 19 (pmpm).
PetscErrorCode StaticResidual(Simulation &sim, ShapeKind shape, double *ratio);
// Gravity's unit direction in D dimensions: the scene's, in its plane, and under -dim 3 its z
// component (the incline's turned fall line, Settings::gdir_z).
template <int D> void GravityDirection(const Simulation &sim, double g[D]) {
  g[0] = sim.set.gdir[0];
  g[1] = sim.set.gdir[1];
  if constexpr (D == 3) g[2] = sim.set.gdir_z;
}
// P2G of the whole load with one shape: the internal and external forces, and the scene's face
// tractions (under -dim 3 the extruded table, extrude.hpp). StaticResidual's and Newton's loads.
template <class Shape, int D>
void StaticForces(const Simulation &sim, const ParticleView &P, const LoadT<D> &load,
                  const GridViewT<D> &G) {
  p2g<Shape>(P, load, G);
  if (sim.traction_idx.empty()) return;
  if constexpr (D == 3)
    p2g_traction<Shape>(P, sim.model.loads3, sim.traction_idx, load.factor, G);
  else
    p2g_traction<Shape>(P, sim.model.loads, sim.traction_idx, load.factor, G);
}
// Send the particles that left this rank's cells to their owners and index them again (the step's
// phase 8; Newton's commit). Collective.
PetscErrorCode Migrate(Simulation &sim);
// The stage loop: stage 0 (the scene's initial state under its loads), then the scene's stages,
// each brought to equilibrium by Simulation::solver and recorded by the scene (stages.cpp).
// Collective.
PetscErrorCode RunStages(Simulation &sim);

// Under MPI each rank holds current only the 3D sheets' points of its own and its neighbours'
// cells and computes only the triangles near its cells (sheets.cpp); this makes every point's
// position, velocity, slips, pressures, force and normal, and every triangle's strains, forces
// and plastic state, whole on every rank, as the reports, the outputs and a checkpoint read them.
// Collective.
PetscErrorCode SheetsComplete(Simulation &sim);

} // namespace pmpm
