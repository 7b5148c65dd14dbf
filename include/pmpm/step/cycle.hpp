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
// The stage loop: stage 0 (the scene's initial state under its loads), then the scene's stages,
// each brought to equilibrium by Simulation::solver and recorded by the scene (stages.cpp).
// Collective.
PetscErrorCode RunStages(Simulation &sim);

} // namespace pmpm
