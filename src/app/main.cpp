#include "pmpm/io/checkpoint.hpp"
#include "pmpm/step/cycle.hpp"
#include "pmpm/util/options.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/model/simulation.hpp"
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace pmpm;

static PetscLogStage st_setup, st_relax, st_output;

// Every option has been read by the end of setup: one that was not is misspelled, or meant for
// another scene or material model, and would silently leave its default in place (on a cluster,
// a wasted allocation). Name it and stop before the run.
static PetscErrorCode CheckUnusedOptions(MPI_Comm comm, const std::string &scene,
                                         const EquilibriumSolver &solver) {
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string list;
  PetscInt unused = 0;
  for (PetscInt k = 0; k < n; ++k) {
    // the solver's options read after this check (Newton's MUMPS at its first factorisation)
    if (solver.reads_later(names[k])) continue;
    list += std::string(unused++ ? ", -" : "-") + names[k];
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  PetscCheck(unused == 0, comm, PETSC_ERR_USER_INPUT,
             "option%s %s not used by scene %s (misspelled, or meant for another scene or "
             "material model): -help lists the options this run reads",
             unused > 1 ? "s" : "", list.c_str(), scene.c_str());
  PetscFunctionReturn(0);
}

// One run of the scene at the options' cell size (or `h` when > 0): setup, the stages, the
// output. Its design answers and the stages that stopped at their cap come back; `design` is the
// verdict block summary.json gets (design_json), computed by the caller from every mesh run so far
// through `judge` once this run's answers are known.
struct MeshRun {
  double h = 0;
  DesignRecord design;
  std::vector<int> capped;
  bool newton = false; // -solver newton (how a capped stage ended)
  bool help = false;
};
using Judge = std::function<std::string(const MeshRun &)>;

static PetscErrorCode RunScene(double h, bool estimating, bool aside, const Judge &judge,
                               MeshRun &mr) {
  Simulation sim;
  PetscFunctionBeginUser;
  if (h > 0) {
    char v[32];
    snprintf(v, sizeof(v), "%.17g", h);
    PetscCall(PetscOptionsSetValue(nullptr, "-cell_size", v));
  }
  PetscCall(PetscLogStagePush(st_setup));
  PetscCall(SimulationSetup(sim));
  PetscCall(PetscLogStagePop());
  PetscBool help = PETSC_FALSE;
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  if (help) { // every option has been listed by now; run nothing, write nothing
    mr.help = true;
    PetscCall(SimulationDestroy(sim));
    PetscFunctionReturn(0);
  }
  PetscCall(CheckUnusedOptions(sim.comm, sim.set.scene, *sim.solver));
  if (estimating) {
    PetscCheck(sim.set.restart.empty(), sim.comm, PETSC_ERR_ARG_INCOMP,
               "-estimate_error cannot follow -restart (it runs every mesh from the start)");
    PetscCheck(sim.scene->has_design(), sim.comm, PETSC_ERR_ARG_INCOMP,
               "-estimate_error: scene %s reports no design answers (the cover scene does)",
               sim.set.scene.c_str());
  }
  if (aside) { // a coarser mesh of -estimate_error
    char d[64];
    snprintf(d, sizeof(d), "/mesh_h%.6g", sim.set.h);
    sim.set.output_dir += d;
  }
  // -restart: the state set up from the options is replaced by the checkpoint's
  if (!sim.set.restart.empty()) PetscCall(CheckpointRead(sim, sim.set.restart));
  OutputSeriesReset();

  PetscCall(PetscLogStagePush(st_relax));
  PetscCall(RunStages(sim));
  PetscCall(PetscLogStagePop());

  // Output only after a run that ended cleanly (an instability returns an error above); a run
  // with stages that stopped at their cap is written too, and says so in its verdict.
  PetscCall(PetscLogStagePush(st_output));
  std::string results;
  PetscCall(sim.scene->results(sim, results));
  mr.h = sim.set.h;
  mr.capped = sim.run.capped_stages;
  mr.newton = sim.set.solver == "newton";
  PetscCall(sim.scene->design(sim, mr.design));
  PetscCall(OutputPrepareDirectory(sim));
  PetscCall(OutputParticles(sim, "particles.h5"));
  PetscCall(OutputSeriesFinish(sim));
  PetscCall(OutputChains(sim));
  PetscCall(OutputSheets(sim));
  PetscCall(sim.scene->write_files(sim));
  PetscCall(OutputSummary(sim, results, judge(mr)));
  PetscCall(PetscLogStagePop());
  if (!sim.set.quiet)
    PetscCall(PetscPrintf(sim.comm, "wrote %s/summary.json and particles.h5/.xmf\n",
                          sim.set.output_dir.c_str()));
  PetscCall(SimulationDestroy(sim));
  PetscFunctionReturn(0);
}

// -estimate_error: the scene at its cell size and at half of it (and a quarter, ...), one after
// the other on the same ranks; the coarser meshes write under DIR/mesh_h<h>/, the finest (whose
// answers are reported, with their error) in DIR. Without it, one run.
struct EstimateOptions {
  PetscBool on = PETSC_FALSE;
  PetscInt levels = 2;
  double order = 1.0;
};

static PetscErrorCode ReadEstimateOptions(MPI_Comm comm, EstimateOptions &e) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Design answers: error estimate (docs/outputs.md)", nullptr);
  PetscCall(PetscOptionsBool("-estimate_error",
                             "Run at -cell_size and at half of it and report every design answer "
                             "with its estimated discretisation error (Richardson / GCI); the "
                             "verdict uses it",
                             nullptr, e.on, &e.on, nullptr));
  PetscCall(PmpmOptionsInt("-estimate_error_levels",
                           "Meshes for -estimate_error, each half the last (2..4; 3 or more "
                           "observe the order of convergence)",
                           nullptr, e.levels, &e.levels, nullptr));
  PetscCall(PmpmOptionsReal("-estimate_error_order",
                            "Order of convergence assumed with two meshes (0.5..4)", nullptr,
                            e.order, &e.order, nullptr));
  PetscOptionsEnd();
  PmpmCheckInput(e.levels >= 2 && e.levels <= 4, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-estimate_error_levels %d: must be 2, 3 or 4", (int)e.levels);
  PmpmCheckInput(e.order >= 0.5 && e.order <= 4, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-estimate_error_order %g: must be in [0.5, 4]", e.order);
  PetscFunctionReturn(0);
}

// The whole process: the meshes, then the verdict as the log's last line. *code is the exit
// code the verdict asks for (docs/outputs.md: exit codes).
static PetscErrorCode Run(int *code) {
  MPI_Comm comm = PETSC_COMM_WORLD;
  EstimateOptions est;
  PetscFunctionBeginUser;
  PetscCall(LogRegister());
  PetscCall(PetscLogStageRegister("Setup", &st_setup));
  PetscCall(PetscLogStageRegister("Relaxation", &st_relax));
  PetscCall(PetscLogStageRegister("Output", &st_output));
  PetscCall(ReadEstimateOptions(comm, est));
  const PetscInt levels = est.on ? est.levels : 1;
  std::vector<MeshRun> runs;
  Assessment a;
  auto judge = [&](const MeshRun &mr) {
    std::vector<MeshRun> all = runs;
    all.push_back(mr);
    std::vector<double> h;
    std::vector<DesignRecord> d;
    std::vector<CappedStages> c;
    for (const MeshRun &m : all) {
      h.push_back(m.h);
      d.push_back(m.design);
      c.push_back({m.h, m.capped, m.newton});
    }
    a = assess(h, d, c, est.order);
    return design_json(a);
  };
  for (PetscInt j = 0; j < levels; ++j) {
    MeshRun mr;
    const double h = j > 0 ? runs[0].h / double(1 << j) : 0.0; // 0: the options' cell size
    PetscCall(RunScene(h, est.on, j + 1 < levels, judge, mr));
    if (mr.help) PetscFunctionReturn(0);
    runs.push_back(mr);
  }
  const std::string log = design_log(a);
  if (!log.empty()) PetscCall(PetscPrintf(comm, "%s", log.c_str()));
  *code = a.verdict == Verdict::NotConverged ? 3 : a.verdict == Verdict::Inconclusive ? 4 : 0;
  PetscFunctionReturn(0);
}

// The process's exit code for an error (docs/outputs.md: exit codes): 1 for input the run refused
// (an option, an options file, a checkpoint), 2 for a run that failed (an instability, a file that
// could not be written, too little memory).
static int ExitCodeFor(PetscErrorCode e) {
  switch (e) {
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_SIZ:
  case PETSC_ERR_SUP:
  case PETSC_ERR_FILE_OPEN:
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_UNEXPECTED:
    return 1;
  default:
    return 2;
  }
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
  // PETSc prints this above -help's listing
  static const std::string help =
      "pmpm: large-deformation quasi-static geomechanics with the partition Material Point "
      "Method.\nUsage: mpirun -n N pmpm -options_file options/<scene>.opts [-option value ...]\n"
      "Scenes: " +
      SceneList() + ".\n-help lists every option (-scene NAME -help: that scene's).\n\n";
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help.c_str()));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  int code = 0;
  const PetscErrorCode ierr = Run(&code);
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
      return ExitCodeFor(ierr);
    }
    std::fprintf(stderr, "pmpm: error on rank %d: %s\n", rank, msg);
    std::fflush(stderr);
    MPI_Abort(PETSC_COMM_WORLD, ExitCodeFor(ierr));
    return ExitCodeFor(ierr);
  }
  PetscCall(PetscFinalize());
  return code;
}
