// Checkpoint and restart. -checkpoint_every K (steps) and -checkpoint_at_stage_end write the
// complete state of the run to <output_dir>/checkpoint_<step>.h5 (HDF5, PetscViewerHDF5): every
// swarm field of every particle (per-rank blocks in rank order, so a restart on the same rank
// count gives each rank back its own particles in their order), every chain's point and segment
// state, the run's progress (RunState: step, stage step, time, step size), the solver's own
// state (EquilibriumSolver::checkpoint_write: relaxation's kinetic damping and energy budget), the
// stage, and the scene's own state (Scene::checkpoint_write). A checkpoint is written under a .tmp
// name and renamed when complete, so none is ever half-written.
//
// -restart FILE: the run is set up from the options as usual (the same options files), then its
// state is replaced by the checkpoint's, and the stage loop continues from there. The restarted
// run ends bit for bit as the uninterrupted one on the rank count that wrote the checkpoint; on
// another rank count the particles are redistributed to the ranks owning their cells and the
// result agrees to round-off. A checkpoint of another scene, cell size, grid or particle set is
// refused, and so is a file that is not a complete pmpm checkpoint, with one line naming
// -restart and the file. The checkpoint keeps every option its run was given; a restart that
// adds, drops or changes one other than run control (-max_steps, -output_*, -checkpoint_*,
// -progress_interval, -quiet, -memory_limit, -balance*, -da_processors_*) is refused naming it.
#pragma once
#include "pmpm/model/simulation.hpp"
#include <string>
#include <vector>

namespace pmpm {

// Write <output_dir>/checkpoint_<step>.h5. in_stage: between two steps of the current stage
// (else after the stage's end, before the next one's start). Collective.
PetscErrorCode CheckpointWrite(Simulation &sim, bool in_stage);
// Replace the state of a set-up run by the checkpoint's and mark the stage loop to resume.
// Collective.
PetscErrorCode CheckpointRead(Simulation &sim, const std::string &file);

// For Scene::checkpoint_write / checkpoint_read, in the viewer's current group (/scene):
// an array every rank holds alike (written from rank 0; read onto every rank) ...
PetscErrorCode CheckpointWriteArray(PetscViewer v, const char *name, const std::vector<double> &a);
PetscErrorCode CheckpointReadArray(PetscViewer v, const char *name, std::vector<double> &a);
// ... and one number (an attribute of the group), T double or PetscInt.
template <class T> PetscErrorCode CheckpointWriteNumber(PetscViewer v, const char *name, T x);
template <class T> PetscErrorCode CheckpointReadNumber(PetscViewer v, const char *name, T *x);
inline constexpr auto CheckpointWriteReal = CheckpointWriteNumber<double>;
inline constexpr auto CheckpointReadReal = CheckpointReadNumber<double>;
inline constexpr auto CheckpointWriteInt = CheckpointWriteNumber<PetscInt>;
inline constexpr auto CheckpointReadInt = CheckpointReadNumber<PetscInt>;
// For EquilibriumSolver::checkpoint_write / checkpoint_read: each rank's share of a sum (one
// dataset of the current group, one entry per rank), and back: on the rank count that wrote it
// each rank's own share, on another the whole sum on rank 0. `ranks`: the writer's rank count.
PetscErrorCode CheckpointWriteRankShare(MPI_Comm comm, PetscViewer v, const char *name, double x);
PetscErrorCode CheckpointReadRankShare(MPI_Comm comm, PetscViewer v, const char *name,
                                       const std::string &file, PetscInt ranks, double *x);

} // namespace pmpm
