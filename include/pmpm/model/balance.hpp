// The partition of the grid over the ranks and how evenly it shares the particles.
// A DMDA partition is a tensor product: the process grid m x n (PETSc's choice, or
// -da_processors_x/y) and the node counts of each rank column (lx) and row (ly). PETSc splits
// the nodes evenly; -balance setup splits the particles instead: after the scene has generated
// its particles on PETSc's partition, the particles per cell column and per cell row (summed over
// the ranks) are cut at their cumulative quantiles into m columns and n rows, and if that lowers
// the imbalance (max / mean particles per rank) by more than -balance_gain, the grid is recreated
// with those lx, ly and the particles are generated again. Each direction is balanced on its
// own: every rank column then holds about 1/m of the particles and every rank row 1/n, but a
// rank (a column-row block) holds 1/(mn) only if the particles are spread like a product of the
// two marginals; a tensor product cannot do better for the general 2D distribution.
#pragma once
#include "pmpm/core/particles.hpp"
#include <petscsys.h>
#include <string>
#include <vector>

namespace pmpm {

struct Simulation;

enum class BalanceMode { None = 0, Setup = 1, Run = 2 };
inline constexpr const char *BalanceModeNames[] = {"none",        "setup",    "run",
                                                   "BalanceMode", "BALANCE_", nullptr};

struct Balance {
  BalanceMode mode = BalanceMode::Setup;
  double gain = 0.05;   // -balance_gain: smallest relative drop of the imbalance worth a rebuild
  double before = 1.0;  // imbalance on PETSc's partition (after the first generation)
  double after = 1.0;   // imbalance on the partition the run uses (after setup)
  double seconds = 0.0; // wall time of the balancing: counting, planning, rebuild, regeneration
  bool rebuilt = false; // the grid was recreated with particle-balanced lx, ly
  // -balance run: at every stage's end, rebalance when the imbalance exceeds the threshold
  double threshold = 1.1;   // -balance_threshold
  PetscInt rebalances = 0;  // rebuilds during the run
  double last_before = 1.0; // the imbalance before the last of them
  double last_after = 1.0;  // and after it
  double run_seconds = 0.0; // wall time of the run's checks and rebuilds

  // The checkpointed fields (checkpoint.cpp, /run attributes): f(name, field) for each.
  template <class F> PetscErrorCode checkpoint_fields(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("rebalances", rebalances));
    PetscCall(f("rebalance_before", last_before));
    PetscCall(f("rebalance_after", last_after));
    PetscFunctionReturn(0);
  }
};

// Read -balance and -balance_gain (every run reads them).
PetscErrorCode BalanceFromOptions(MPI_Comm comm, Balance &b);
// Setup-time balancing, called after the scene's first generate() into init: measures the
// imbalance and, if the particle-balanced partition pays, recreates the grid (and the interface
// grid and the swarm on it) and generates init again.
PetscErrorCode BalanceSetup(Simulation &sim, ParticleList &init);
// -dim 3 (extrude.cpp), after the 3D grid is created on PETSc's partition and before any 3D
// particle exists: every rank holds the whole plane and each plane particle becomes the same
// number of particles along z, so the particles per cell column and row are the plane's. They are
// cut into px columns and py rows as in 2D; the z slabs keep PETSc's even split (the particles
// are uniform along z). If that lowers the imbalance by more than -balance_gain, the 3D grid (and
// the empty swarm on it) is recreated with those lx, ly. The imbalances before and after are
// exact (counted from the plane), and nothing is generated twice.
PetscErrorCode BalanceSetupExtruded(Simulation &sim, const ParticleList &plane);
// -balance run, at a stage's end (rank-collective): if the imbalance exceeds -balance_threshold
// and the particle-balanced partition lowers it by more than -balance_gain, the grid is rebuilt
// with that partition and the particles move to the ranks owning their cells (particle_records).
// Nothing else changes: the nodal fields are rebuilt from the particles every step.
PetscErrorCode BalanceRun(Simulation &sim);
// Recreate the grid (and the interface grid, and an empty swarm on it) with px x py ranks owning
// lx, ly nodes per rank column and row.
PetscErrorCode BalanceRebuildGrid(Simulation &sim, PetscInt px, PetscInt py,
                                  const std::vector<PetscInt> &lx, const std::vector<PetscInt> &ly);
// The current partition as [px, py, lx..., ly...] (a checkpoint keeps it).
PetscErrorCode BalancePartition(Simulation &sim, std::vector<PetscInt> &part);
// (-dim 3: px, py, pz and lx, ly, lz of the 3D grid.)

// The "partition" and "balance" blocks of summary.json (rank-collective): process grid, owned
// nodes per rank column and row, the cell ranges they own, particles per rank and the imbalance
// now; the setup balancing's imbalance before and after.
PetscErrorCode PartitionJson(Simulation &sim, std::string &json);

} // namespace pmpm
