// Helpers shared by scenes: filling regions with regularly spaced particles, options checks and
// global reductions over particles.
#pragma once
#include "pmpm/simulation.hpp"
#include <functional>

namespace pmpm {

// Which material (index) a point belongs to, or -1 for none.
using MaterialAt = std::function<int(const double x[DIM])>;

// ppc^DIM particles per cell at sub-cell centres, for the cells this rank owns, each assigned
// by `at`. Particle ids are rank-independent: (cell index * ppc^DIM + sub-index).
void FillRegular(const Simulation &sim, const MaterialAt &at, std::vector<ParticleInit> &out);

// A length must be a positive whole number of cells (so faces fall on grid lines).
PetscErrorCode CheckCells(MPI_Comm comm, const char *option, double length, double h,
                          PetscInt *cells);

// Sum of values over all ranks.
PetscErrorCode SumAll(MPI_Comm comm, double *v, int n);

} // namespace pmpm
