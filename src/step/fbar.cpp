// F-bar (-fbar, antilock.hpp) in the explicit step: the groups the particles start the step in
// (and, with -fbar_pressure cell, the group pressure P2G's internal force takes, conjugate to the
// averaged volume change), then each particle's volume change over the step replaced by its
// group's.
#include "pmpm/core/antilock.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return sim.set.fbar;
}

// 0. The cells the particles start the step in (this rank owns them all), and with
//    -fbar_pressure cell the internal force's pressure averaged over them.
PetscErrorCode Groups(StepState &S) {
  Simulation &sim = S.sim;
  const Grid &g = sim.grid;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.fbar);
  fbar_groups(S.P, g.origin, g.h, g.cell_lo, g.cell_hi, g.nbody, sim.scratch.fbar_group);
  if (sim.set.fbar_pressure == FbarPressure::Cell) {
    fbar_pressure_shift(S.P, sim.scratch.fbar_group, sim.scratch.fbar_sums, sim.scratch.fbar_shift);
    S.pshift = sim.scratch.fbar_shift.data();
  }
  PetscFunctionReturn(0);
}

// 5'. Each particle's volume change over the step replaced by its cell's.
PetscErrorCode Apply(StepState &S) {
  Simulation &sim = S.sim;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.fbar);
  fbar_apply(S.P, sim.scratch.fbar_group, sim.scratch.fbar_sums, sim.scratch.dudx.data());
  PetscFunctionReturn(0);
}
} // namespace

extern const StepHook fbar_hook = [] {
  StepHook h{};
  h.name = "fbar";
  h.active = Active;
  h.reads_gradient = true;
  h.before_p2g = Groups;
  h.after_g2p = Apply;
  return h;
}();

} // namespace pmpm
