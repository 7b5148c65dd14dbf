// One explicit PMPM step and the relaxation loop around it.
#pragma once
#include "pmpm/simulation.hpp"

namespace pmpm {

struct StepReport {
  GridStats grid;
  G2PStats g2p;
  InterfaceStats iface;
  ContactStats contact;   // chains only
  double eigen_power = 0; // this rank's power of the imposed eigenstrain (degradation.hpp)
};

PetscErrorCode LogRegister();
// One step of the cycle (see cycle.cpp for the phases). Collective.
PetscErrorCode Step(Simulation &sim, const Load &load, double dt, StepReport &rep);
// Initial stable step from the wave speeds at rest.
PetscErrorCode InitialWaveSpeed(Simulation &sim, double *max_speed);
// The unbalanced-force ratio of the current particle state evaluated with the given shape
// functions (full load): the paper's equilibrium residual, eq. 13 (mpm) against eq. 19 (pmpm).
PetscErrorCode StaticResidual(Simulation &sim, ShapeKind shape, double *ratio);
// Dynamic relaxation of the current stage (Simulation::stage) to equilibrium, or the step cap.
// Stage 0 ramps the loads over -ramp_steps; a later stage applies its shrinkage over
// Simulation::stage_ramp steps. Collective.
PetscErrorCode Relax(Simulation &sim);
// The stage loop: stage 0 (the scene's initial state under its loads), then the scene's stages,
// each relaxed to equilibrium by Relax and recorded by the scene (stages.cpp). Collective.
PetscErrorCode RunStages(Simulation &sim);

} // namespace pmpm
