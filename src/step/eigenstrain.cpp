// An imposed eigenstrain in the explicit step (a stage's shrinkage of degrading waste,
// degradation.hpp): this step's increment per particle, and its power, which the stress update
// subtracts from the strain increment.
#include "pmpm/core/degradation.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &, const Load &load) {
  return load.shrink != 0;
}

// 6. Before the materials' update, in its event (2D and 3D: three normal components a particle).
template <int D> PetscErrorCode Increment(StepStateT<D> &S) {
  Simulation &sim = S.sim;
  PetscFunctionBeginUser;
  S.rep.eigen_power =
      shrinkage_increment<D>(S.P, sim.model.shrink, S.load.shrink, sim.scratch.eigen);
  S.eigen = sim.scratch.eigen.data();
  PetscFunctionReturn(0);
}
} // namespace

extern const StepHook eigenstrain_hook = [] {
  StepHook h{};
  h.name = "eigenstrain";
  h.active = Active;
  h.reads_gradient = true;
  h.phases.stress = Increment<2>;
  h.phases3.stress = Increment<3>;
  return h;
}();

} // namespace pmpm
