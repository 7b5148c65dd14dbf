// The partition of the grid over the ranks and how evenly it shares the particles.
// A DMDA partition is a tensor product: the process grid m x n (PETSc's choice, or
// -da_processors_x/y) and the node counts of each rank column (lx) and row (ly).
#pragma once
#include "pmpm/simulation.hpp"
#include <string>

namespace pmpm {

// The "partition" block of summary.json (rank-collective): process grid, owned nodes per rank
// column and row, the cell ranges they own, particles per rank and the imbalance max / mean.
PetscErrorCode PartitionJson(Simulation &sim, std::string &json);

} // namespace pmpm
