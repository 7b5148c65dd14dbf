// The stage loop: the equilibrium solver (solver.hpp: dynamic relaxation, relaxation.cpp, or
// Newton load steps under -solver newton, newton.cpp) called once per stage. Stage 0 is the scene's
// initial state under its loads (for a cover, the geostatic state); each later stage is a change
// the scene makes (waste shrinks, a void opens) followed by a new equilibrium, which the scene
// records.
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/step/cycle.hpp"
#include <cmath>
#include <cstdio>

namespace pmpm {

PetscErrorCode RunStages(Simulation &sim) {
  PetscFunctionBeginUser;
  const PetscInt n = sim.scene->stages();
  sim.nstages = n;
  // a restarted run (checkpoint.hpp) continues at the checkpoint's stage: inside it, or at its
  // start after the previous stage's end
  const PetscInt k0 = sim.resume ? sim.stage : 0;
  if (!sim.resume) {
    sim.run.all_converged = true;
    sim.run.capped_stages.clear();
  }
  double later = 0; // wall time of the stages after stage 0
  for (PetscInt k = k0; k <= n; ++k) {
    sim.stage = k;
    if (!(sim.resume && sim.resume_in_stage)) {
      sim.stage_ramp = 0;
      sim.stage_shrink = 0;
      PetscCall(sim.scene->begin_stage(sim, k));
    }
    PetscCall(sim.solver->solve_stage(sim)); // clears sim.resume
    PetscCall(SheetsComplete(sim));          // whole for the scene's record and the outputs
    sim.run.all_converged = sim.run.all_converged && sim.run.converged;
    PetscCall(sim.scene->end_stage(sim, k));
    // a stage that stopped short of -tol, unless the scene ended it (a collapse is its answer)
    if (!sim.run.converged && !sim.set.dynamic && !sim.run.stop_stage && !sim.scene->finished())
      sim.run.capped_stages.push_back(static_cast<int>(k));
    if (sim.scene->finished()) break;
    if (k < n) PetscCall(BalanceRun(sim)); // -balance run: the partition follows the particles
    // after the scene's record: a checkpoint at every stage's end, or at a -checkpoint_every step
    // that ended the stage (relaxation writes the others)
    const PetscInt every = sim.set.checkpoint_every;
    if (sim.set.checkpoint_stage_end || (every > 0 && sim.run.step % every == 0))
      PetscCall(CheckpointWrite(sim, false));
    if (n > 0 && k < n && !sim.set.quiet) {
      // the later stages each make a change of the same size: their mean time, or stage 0's
      // until one has run
      if (k > 0) later += sim.run.stage_seconds;
      const double per = k > 0 ? later / double(k) : sim.run.stage_seconds;
      PetscCall(PetscPrintf(sim.comm, "stage %d/%d done (%.1f s); %d to go, ETA about %.0f s\n",
                            (int)k, (int)n, sim.run.stage_seconds, (int)(n - k),
                            per * double(n - k)));
    }
  }
  sim.resume = false;
  sim.stage = n; // also after a restart from the last stage's end
  sim.run.converged = sim.run.all_converged;
  PetscFunctionReturn(0);
}

} // namespace pmpm
