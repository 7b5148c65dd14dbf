// The step's optional physics in the order the phases call them (step_hooks.hpp). The chains and
// the interface never run together (the interface's own grid exists only without chains).
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

extern const StepHook interface_hook, fbar_hook, chain_hook, sheet_hook, eigenstrain_hook,
    support_hook;

const std::vector<const StepHook *> &StepHooks() {
  static const std::vector<const StepHook *> hooks = {
      &interface_hook, &fbar_hook, &chain_hook, &sheet_hook, &eigenstrain_hook, &support_hook};
  return hooks;
}

ActiveHooks ActiveStepHooks(const Simulation &sim, const Load &load) {
  ActiveHooks a;
  for (const StepHook *h : StepHooks())
    if (h->active(sim, load)) {
      a.hook[a.n++] = h;
      a.reads_gradient = a.reads_gradient || h->reads_gradient;
    }
  return a;
}

PetscErrorCode RunHooks(const ActiveHooks &h, PetscErrorCode (*StepHook::*member)(StepState &),
                        StepState &S) {
  PetscFunctionBeginUser;
  for (int k = 0; k < h.n; ++k)
    if (h.hook[k]->*member) PetscCall((h.hook[k]->*member)(S));
  PetscFunctionReturn(0);
}

} // namespace pmpm
