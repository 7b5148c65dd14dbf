// The implicit quasi-static solver (-solver newton): each stage's loads applied in load steps,
// each one PETSc SNES solve for the nodal displacement increment (implicit_kernels.hpp), the
// particles moved and their stresses committed after it converged. A peer of Relax (cycle.hpp).
#pragma once
#include "pmpm/simulation.hpp"

namespace pmpm {

// Read the -newton_* options, refuse what Newton cannot solve yet (chains, frictional interfaces,
// staged scenes, materials without a consistent tangent, ...) with a clear error, and create the
// SNES on its own DMDA (DIM dofs per node, box stencil as wide as the shape's support) with every
// -snes_/-ksp_/-pc_ option applied. With -help only lists the options. Collective.
PetscErrorCode NewtonSetup(Simulation &sim);
PetscErrorCode NewtonDestroy(Simulation &sim);
// Equilibrium of the current stage by load steps (-newton_load_steps), then equilibrium steps at
// full load until the unbalanced-force ratio of relaxation (StaticResidual) is <= -tol.
// Collective.
PetscErrorCode Newton(Simulation &sim);

} // namespace pmpm
