static const char help[] =
    "pmpm: large-deformation quasi-static geomechanics with the partition Material Point Method.\n"
    "Usage: mpirun -n N pmpm -options_file options/<scene>.opts [-option value ...]\n"
    "Scenes: bar, column, landfill, incline, layers, block, catenary, pullout, trench, cover, "
    "footing, trapdoor.\n"
    "-help lists every option.\n\n";

#include "pmpm/checkpoint.hpp"
#include "pmpm/cycle.hpp"
#include "pmpm/options.hpp"
#include "pmpm/output.hpp"
#include <cstdio>
#include <cstring>
#include <string>

using namespace pmpm;

// Every option has been read by the end of setup: one that was not is misspelled, or meant for
// another scene or material model, and would silently leave its default in place (on a cluster,
// a wasted allocation). Name it and stop before the run.
static PetscErrorCode CheckUnusedOptions(MPI_Comm comm, const std::string &scene, bool newton) {
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string list;
  PetscInt unused = 0;
  for (PetscInt k = 0; k < n; ++k) {
    // under -solver newton MUMPS reads its -mat_mumps_* options at the first factorisation,
    // after this check
    if (newton && !std::strncmp(names[k], "mat_mumps_", 10)) continue;
    list += std::string(unused++ ? ", -" : "-") + names[k];
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  PetscCheck(unused == 0, comm, PETSC_ERR_USER_INPUT,
             "option%s %s not used by scene %s (misspelled, or meant for another scene or "
             "material model): -help lists the options this run reads",
             unused > 1 ? "s" : "", list.c_str(), scene.c_str());
  PetscFunctionReturn(0);
}

static PetscErrorCode Run() {
  Simulation sim;
  PetscLogStage st_setup, st_relax, st_output;
  PetscFunctionBeginUser;
  PetscCall(LogRegister());
  PetscCall(PetscLogStageRegister("Setup", &st_setup));
  PetscCall(PetscLogStageRegister("Relaxation", &st_relax));
  PetscCall(PetscLogStageRegister("Output", &st_output));

  PetscCall(PetscLogStagePush(st_setup));
  PetscCall(SimulationSetup(sim));
  PetscCall(PetscLogStagePop());
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help) { // every option has been listed by now; run nothing, write nothing
    PetscCall(SimulationDestroy(sim));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckUnusedOptions(sim.comm, sim.set.scene, sim.set.solver == Solver::Newton));
  // -restart: the state set up from the options is replaced by the checkpoint's
  if (!sim.set.restart.empty()) PetscCall(CheckpointRead(sim, sim.set.restart));

  PetscCall(PetscLogStagePush(st_relax));
  PetscCall(RunStages(sim));
  PetscCall(PetscLogStagePop());

  // Output only after a run that ended cleanly (an instability returns an error above).
  PetscCall(PetscLogStagePush(st_output));
  std::string results;
  PetscCall(sim.scene->results(sim, results));
  PetscCall(OutputPrepareDirectory(sim));
  PetscCall(OutputParticles(sim, "particles.h5"));
  PetscCall(OutputSeriesFinish(sim));
  PetscCall(OutputChains(sim));
  PetscCall(sim.scene->write_files(sim));
  PetscCall(OutputSummary(sim, results));
  PetscCall(PetscLogStagePop());
  if (!sim.set.quiet)
    PetscCall(PetscPrintf(sim.comm, "wrote %s/summary.json and particles.h5/.xmf\n",
                          sim.set.output_dir.c_str()));
  PetscCall(SimulationDestroy(sim));
  PetscFunctionReturn(0);
}

// Errors come back as codes (no PETSc traceback) and are printed as one line naming the cause.
int main(int argc, char **argv) {
  // PETSc reads -options_file inside PetscInitialize, before any handler of ours: check the files
  // (and the files they include) first; every rank finds the same, rank 0 prints it.
  const std::string bad_files = CheckOptionsFiles(argc, argv);
  if (!bad_files.empty()) {
    int rank = 0;
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) std::fprintf(stderr, "pmpm: error: %s\n", bad_files.c_str());
    MPI_Finalize();
    return 1;
  }
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  const PetscErrorCode ierr = Run();
  PetscCall(PetscPopErrorHandler());
  if (ierr) {
    const char *text = nullptr;
    char *specific = nullptr;
    PetscMPIInt rank, size;
    PetscErrorMessage(ierr, &text, &specific);
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
    const char *msg = specific && specific[0] ? specific : (text ? text : "unknown error");
    // An error every rank met (bad input, a collective check) is printed once, by rank 0, and
    // the run ends cleanly. One that only some ranks met cannot wait for the others (they may be
    // blocked in a collective): those ranks print it with their number and abort the job.
    bool all = size == 1;
    if (size > 1) {
      MPI_Request req;
      int done = 0;
      MPI_Ibarrier(PETSC_COMM_WORLD, &req);
      const double t0 = MPI_Wtime();
      while (!done && MPI_Wtime() - t0 < 2.0) MPI_Test(&req, &done, MPI_STATUS_IGNORE);
      all = done != 0;
    }
    if (all) {
      if (rank == 0) std::fprintf(stderr, "pmpm: error: %s\n", msg);
      std::fflush(stderr);
      PetscFinalize();
      return 1;
    }
    std::fprintf(stderr, "pmpm: error on rank %d: %s\n", rank, msg);
    std::fflush(stderr);
    MPI_Abort(PETSC_COMM_WORLD, 1);
    return 1;
  }
  PetscCall(PetscFinalize());
  return 0;
}
