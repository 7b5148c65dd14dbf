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

// This rank's first outgrown block in dimension D: [ratio, pid, x, y, z, direction, stretch
// V_dd, l0] (ratio 0: none).
template <int D> void FirstOutgrown(const ParticleView &P, double lmax, double info[8]) {
  for (PetscInt p = 0; p < P.n; ++p) {
    double lb[D];
    const double *l = CPGIMPShape::half<D>(P.lp + p * D, P.F + p * D * D, lb);
    for (int d = 0; d < D; ++d)
      if (l[d] > lmax) {
        const double r[8] = {l[d] / lmax,
                             (double)P.pid[p],
                             P.x[p * D],
                             P.x[p * D + 1],
                             D == 3 ? P.x[p * D + D - 1] : 0.0,
                             (double)d,
                             l[d] / P.lp[p * D + d],
                             P.lp[p * D + d]};
        for (int k = 0; k < 8; ++k) info[k] = r[k];
        return;
      }
  }
}

PetscErrorCode CheckSupport(StepState &S) { // runs in 2D and under -dim 3 (its after_step only)
  Simulation &sim = S.sim;
  ParticleView P;
  PetscFunctionBeginUser;
  PmpmLogEventScope(
      step_events.support); // to the end: the error's broadcast too, only when it fails
  PetscCall(ParticlesGetView(sim.parts, P));
  const double lmax = CPGIMPShape::kMaxHalf * sim.grid.h;
  double info[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  if (sim.set.dim == 3)
    FirstOutgrown<3>(P, lmax, info);
  else
    FirstOutgrown<DIM>(P, lmax, info);
  PetscCall(ParticlesRestoreView(sim.parts, P));
  struct {
    double v;
    int rank;
  } in = {info[0], sim.rank}, out;
  PetscCallMPI(MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  if (out.v == 0) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(info, 8, MPI_DOUBLE, out.rank, sim.comm));
  const char *axis = "xyz" + (int)info[5];
  char at[96];
  if (sim.set.dim == 3)
    PetscCall(PetscSNPrintf(at, sizeof at, "(%g, %g, %g)", info[2], info[3], info[4]));
  else
    PetscCall(PetscSNPrintf(at, sizeof at, "(%g, %g)", info[2], info[3]));
  SETERRQ(sim.comm, PETSC_ERR_NOT_CONVERGED,
          "cpGIMP support outgrown at step %" PetscInt_FMT ": particle %.0f at x = %s m is "
          "stretched by V_%c%c = %g, so its half-size %g m (initially %g m) exceeds one cell h = "
          "%g m, the "
          "largest block the 4-node support holds (stretch 2 at -ppc 1, 4 at -ppc 2). Raise -ppc "
          "(smaller initial blocks), or use -shape pmpm.",
          sim.run.step, info[1], at, axis[0], axis[0], info[6], info[0] * lmax, info[7],
          sim.grid.h);
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
