// The stage loop: one equilibrium solver (dynamic relaxation, relaxation.cpp) called once per
// stage. Stage 0 is the scene's initial state under its loads (for a cover, the geostatic state);
// each later stage is a change the scene makes (waste shrinks, a void opens) followed by a new
// equilibrium, which the scene records.
#include "pmpm/cycle.hpp"
#include <cmath>
#include <cstdio>

namespace pmpm {

PetscErrorCode RunStages(Simulation &sim) {
  PetscFunctionBeginUser;
  const PetscInt n = sim.scene->stages();
  sim.nstages = n;
  bool all = true;
  double later = 0; // wall time of the stages after stage 0
  for (PetscInt k = 0; k <= n; ++k) {
    sim.stage = k;
    sim.stage_ramp = 0;
    sim.stage_shrink = 0;
    PetscCall(sim.scene->begin_stage(sim, k));
    PetscCall(Relax(sim));
    all = all && sim.run.converged;
    PetscCall(sim.scene->end_stage(sim, k));
    if (sim.scene->finished()) break;
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
  sim.run.converged = all;
  PetscFunctionReturn(0);
}

} // namespace pmpm
