// One explicit PMPM step and the relaxation loop around it.
#pragma once
#include "pmpm/simulation.hpp"

namespace pmpm {

struct StepReport {
  GridStats grid;
  G2PStats g2p;
  InterfaceStats iface;
  ContactStats contact; // chains only
};

PetscErrorCode LogRegister();
// One step of the cycle (see cycle.cpp for the phases). Collective.
PetscErrorCode Step(Simulation &sim, const Load &load, double dt, StepReport &rep);
// Initial stable step from the wave speeds at rest.
PetscErrorCode InitialWaveSpeed(Simulation &sim, double *max_speed);
// The unbalanced-force ratio of the current particle state evaluated with the given shape
// functions (full load): the paper's equilibrium residual, eq. 13 (mpm) against eq. 19 (pmpm).
PetscErrorCode StaticResidual(Simulation &sim, ShapeKind shape, double *ratio);
// Dynamic relaxation to equilibrium (or the step cap). Collective.
PetscErrorCode Relax(Simulation &sim);

} // namespace pmpm
