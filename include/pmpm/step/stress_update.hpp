// The stress update of every particle (eq. 6): one batch per material (StressBatch, material.hpp)
// over this rank's particles of that material. The explicit step (cycle.cpp) and Newton's trial
// and committed states (newton.cpp) call the same function.
#pragma once
#include "pmpm/model/simulation.hpp"

namespace pmpm {

// dudx: L dt (or Newton's midpoint gradient), DIM*DIM per particle; F the deformation gradient
// after the step; stress and eps_p updated in place; eigen the imposed eigenstrain increment
// (3 per particle) or null.
void UpdateStresses(Simulation &sim, const double *dudx, const double *F, double *stress,
                    double *eps_p, const double *eigen);

} // namespace pmpm
