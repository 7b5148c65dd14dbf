// cpGIMP's support check after every explicit step (-shape cpgimp, shape_cpgimp.hpp): every
// block must fit the 4-node support for the next step (half-size <= one cell); otherwise stop
// with the particle, its stretch and what to change.
#include "pmpm/core/shape_cpgimp.hpp"
#include "pmpm/step/step_hooks.hpp"

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return sim.set.shape == ShapeKind::CPGIMP;
}

PetscErrorCode CheckSupport(StepState &S) {
  Simulation &sim = S.sim;
  ParticleView P;
  PetscFunctionBeginUser;
  PmpmLogEventScope(
      step_events.support); // to the end: the error's broadcast too, only when it fails
  PetscCall(ParticlesGetView(sim.parts, P));
  const double lmax = CPGIMPShape::kMaxHalf * sim.grid.h;
  // [ratio, pid, x, y, direction, stretch V_dd, l0] of this rank's first outgrown block
  double info[7] = {0, 0, 0, 0, 0, 0, 0};
  for (PetscInt p = 0; p < P.n && info[0] == 0; ++p) {
    double lb[DIM];
    const double *l = CPGIMPShape::half(P.lp + p * DIM, P.F + p * DIM * DIM, lb);
    for (int d = 0; d < DIM; ++d)
      if (l[d] > lmax) {
        const double r[7] = {l[d] / lmax,      (double)P.pid[p], P.x[p * DIM],
                             P.x[p * DIM + 1], (double)d,        l[d] / P.lp[p * DIM + d],
                             P.lp[p * DIM + d]};
        for (int k = 0; k < 7; ++k) info[k] = r[k];
        break;
      }
  }
  PetscCall(ParticlesRestoreView(sim.parts, P));
  struct {
    double v;
    int rank;
  } in = {info[0], sim.rank}, out;
  PetscCallMPI(MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  if (out.v == 0) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(info, 7, MPI_DOUBLE, out.rank, sim.comm));
  SETERRQ(sim.comm, PETSC_ERR_NOT_CONVERGED,
          "cpGIMP support outgrown at step %" PetscInt_FMT ": particle %.0f at x = (%g, %g) m is "
          "stretched by V_%s%s = %g, so its half-size %g m (initially %g m) exceeds one cell h = "
          "%g m, the "
          "largest block the 4-node support holds (stretch 2 at -ppc 1, 4 at -ppc 2). Raise -ppc "
          "(smaller initial blocks), or use -shape pmpm.",
          sim.run.step, info[1], info[2], info[3], info[4] == 0 ? "x" : "y",
          info[4] == 0 ? "x" : "y", info[5], info[0] * lmax, info[6], sim.grid.h);
}
} // namespace

extern const StepHook support_hook = [] {
  StepHook h{};
  h.name = "cpgimp_support";
  h.active = Active;
  h.after_step = CheckSupport;
  return h;
}();

} // namespace pmpm
