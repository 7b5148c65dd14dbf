static const char help[] =
    "pmpm: large-deformation quasi-static geomechanics with the partition Material Point Method.\n"
    "Usage: mpirun -n N pmpm -options_file options/<scene>.opts [-option value ...]\n"
    "Scenes: bar, column, landfill, incline, layers, block, catenary, pullout, trench, cover.\n"
    "-help lists every option.\n\n";

#include "pmpm/cycle.hpp"
#include "pmpm/output.hpp"
#include <cstdio>
#include <string>

using namespace pmpm;

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
  // PETSc reads -options_file inside PetscInitialize, before any handler of ours: check it first.
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "-options_file") {
      if (FILE *f = std::fopen(argv[i + 1], "r"))
        std::fclose(f);
      else {
        std::fprintf(stderr,
                     "pmpm: error: cannot open options file %s (given to -options_file; "
                     "paths are relative to the current directory)\n",
                     argv[i + 1]);
        return 1;
      }
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
    std::fprintf(stderr, "pmpm: error%s: %s\n",
                 size > 1 ? (" on rank " + std::to_string(rank)).c_str() : "",
                 specific && specific[0] ? specific : (text ? text : "unknown error"));
    std::fflush(stderr);
    if (size > 1) MPI_Abort(PETSC_COMM_WORLD, 1); // the other ranks may be waiting in a collective
    PetscFinalize();
    return 1;
  }
  PetscCall(PetscFinalize());
  return 0;
}
