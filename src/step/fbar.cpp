// F-bar (-fbar, antilock.hpp) in the explicit step: the groups the particles start the step in
// (and, with -fbar_pressure cell, the group pressure P2G's internal force takes, conjugate to the
// averaged volume change), then each particle's volume change over the step replaced by its
// group's. In 2D and 3D (-dim 3).
#include "pmpm/core/antilock.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return sim.set.fbar;
}

// 0. The cells the particles start the step in (this rank owns them all), and with
//    -fbar_pressure cell the internal force's pressure averaged over them.
template <int D> PetscErrorCode Groups(StepStateT<D> &S) {
  Simulation &sim = S.sim;
  const GridT<D> &g = sim.grid_of<D>();
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.fbar);
  fbar_groups<D>(S.P, g.origin, g.h, g.cell_lo, g.cell_hi, g.nbody, sim.scratch.fbar_group);
  if (sim.set.fbar_pressure == FbarPressure::Cell) {
    fbar_pressure_shift<D>(S.P, sim.scratch.fbar_group, sim.scratch.fbar_sums,
                           sim.scratch.fbar_shift);
    S.pshift = sim.scratch.fbar_shift.data();
  }
  PetscFunctionReturn(0);
}

// 5'. Each particle's volume change over the step replaced by its cell's.
template <int D> PetscErrorCode Apply(StepStateT<D> &S) {
  Simulation &sim = S.sim;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.fbar);
  const double *hoop = sim.scratch.hoop.empty() ? nullptr : sim.scratch.hoop.data(); // axisym.
  fbar_apply<D>(S.P, sim.scratch.fbar_group, sim.scratch.fbar_sums, sim.scratch.dudx.data(), hoop);
  PetscFunctionReturn(0);
}
} // namespace

extern const StepHook fbar_hook = [] {
  StepHook h{};
  h.name = "fbar";
  h.active = Active;
  h.reads_gradient = true;
  h.phases.before_p2g = Groups<2>;
  h.phases.after_g2p = Apply<2>;
  h.phases3.before_p2g = Groups<3>;
  h.phases3.after_g2p = Apply<3>;
  return h;
}();

} // namespace pmpm
