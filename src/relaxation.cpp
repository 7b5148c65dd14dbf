// Quasi-static loading by dynamic relaxation: load ramp, damping (local Cundall and/or kinetic),
// the stable time step from the current wave speeds, instability detection, and convergence by
// the unbalanced-force ratio max|f_int + f_ext| / mean|f_ext|.
#include "pmpm/cycle.hpp"
#include "pmpm/output.hpp"
#include <cmath>

namespace pmpm {

namespace {
// Kinetic damping: at each peak of the particle kinetic energy, stop every particle.
PetscErrorCode ZeroParticleVelocities(Simulation &sim) {
  ParticleView P;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  for (PetscInt q = 0; q < P.n * DIM; ++q) P.v[q] = 0.0;
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscFunctionReturn(0);
}

void FormatSeconds(double s, char *buf, size_t n) {
  if (!std::isfinite(s) || s < 0)
    snprintf(buf, n, "?");
  else if (s < 120)
    snprintf(buf, n, "%.0f s", s);
  else if (s < 7200)
    snprintf(buf, n, "%.1f min", s / 60);
  else
    snprintf(buf, n, "%.1f h", s / 3600);
}
} // namespace

PetscErrorCode Relax(Simulation &sim) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  Load load;
  StepReport rep;
  double c0;
  PetscFunctionBeginUser;
  for (int d = 0; d < DIM; ++d) load.gdir[d] = s.gdir[d];
  PetscCall(InitialWaveSpeed(sim, &c0));
  run.max_speed = c0;
  run.dt = s.cfl * s.h / c0;
  const bool kinetic = s.damping == Damping::Kinetic || s.damping == Damping::Both;
  const double t_start = MPI_Wtime();
  double t_last = t_start, log_ratio_last = 0;
  PetscInt step_last = 0;
  double ke_window = -1; // kinetic energy 100 steps ago, for the growth test
  if (!s.quiet)
    PetscCall(PetscPrintf(sim.comm,
                          "pmpm %s: %" PetscInt_FMT " x %" PetscInt_FMT " cells, h = %g m, "
                          "shape %s, dt = %.3e s (cfl %g), tolerance %g\n",
                          s.scene.c_str(), sim.ncell[0], sim.ncell[1], s.h,
                          ShapeKindNames[(int)s.shape], run.dt, s.cfl, s.tol));

  for (run.step = 1; run.step <= s.max_steps; ++run.step) {
    load.factor = s.ramp_steps > 0 ? std::fmin(1.0, double(run.step) / s.ramp_steps) : 1.0;
    PetscCall(Step(sim, load, run.dt, rep));
    run.time += run.dt;
    PetscCall(sim.scene->monitor(sim));
    run.kinetic = rep.g2p.kinetic;
    const double mean_ext = rep.grid.n_ext > 0 ? rep.grid.sum_ext / rep.grid.n_ext : 0.0;
    run.ratio = mean_ext > 0 ? rep.grid.max_unbalanced / mean_ext
                             : (rep.grid.max_unbalanced > 0 ? 1e300 : 0.0);

    // Instability: a non-finite ratio or step, particle speeds beyond the wave speed (an
    // explicit step above the stable limit grows exponentially), or sustained energy growth.
    const bool ramped = run.step >= s.ramp_steps;
    const double vmax = rep.g2p.max_speed - c0;
    const char *why = nullptr;
    if (!std::isfinite(run.ratio) || !std::isfinite(rep.g2p.max_speed))
      why = "non-finite nodal force or wave speed";
    else if (vmax > c0)
      why = "particle speed exceeds the material wave speed";
    if (ramped && run.step % 100 == 0) {
      if (ke_window > 0 && run.kinetic > 1e8 * ke_window && !s.dynamic)
        why = "kinetic energy grew 1e8-fold in 100 steps after the load ramp";
      ke_window = run.kinetic;
    }
    PetscCheck(!why, sim.comm, PETSC_ERR_NOT_CONVERGED,
               "Instability at step %" PetscInt_FMT " (t = %g s, dt = %g s): %s. Reduce -cfl "
               "(now %g; 0.5 is safe for both shapes) or raise -damping_alpha.",
               run.step, run.time, run.dt, why, s.cfl);

    if (kinetic && !s.dynamic) {
      if (run.kinetic < run.kinetic_prev) {
        PetscCall(ZeroParticleVelocities(sim));
        run.kinetic_prev = 0;
        ++run.kinetic_resets;
      } else {
        run.kinetic_prev = run.kinetic;
      }
    }
    if (s.output_every > 0 && run.step % s.output_every == 0) PetscCall(OutputSeriesFrame(sim));

    run.converged = !s.dynamic && ramped && run.ratio <= s.tol;
    // Progress on rank 0 at most every progress_interval seconds.
    const double now = MPI_Wtime();
    if (!s.quiet && (now - t_last >= s.progress_seconds || run.converged)) {
      const double lr = std::log10(std::fmax(run.ratio, 1e-300));
      const double per_step = (now - t_last) / double(run.step - step_last);
      double left = double(s.max_steps - run.step);
      if (step_last > 0 && ramped && lr < log_ratio_last) {
        const double rate = (log_ratio_last - lr) / double(run.step - step_last);
        left = std::fmin(left, (lr - std::log10(s.tol)) / rate);
      } else if (!ramped) {
        left = std::fmin(left, double(s.ramp_steps - run.step) * 2.0);
      }
      char eta[32];
      FormatSeconds(left * per_step, eta, sizeof(eta));
      PetscCall(PetscPrintf(sim.comm,
                            "  step %8" PetscInt_FMT "  t %.4e s  ratio %.3e  load %.2f  "
                            "KE %.3e  ETA %s\n",
                            run.step, run.time, run.ratio, load.factor, run.kinetic, eta));
      t_last = now;
      step_last = run.step;
      log_ratio_last = lr;
    }
    if (run.converged) break;
    run.max_speed = rep.g2p.max_speed;
    run.dt = s.cfl * s.h / run.max_speed; // stable step from the current wave speeds
  }
  if (run.step > s.max_steps) run.step = s.max_steps;
  run.wall_seconds = MPI_Wtime() - t_start;
  if (!s.quiet) {
    if (s.dynamic)
      PetscCall(PetscPrintf(sim.comm, "dynamic run: %" PetscInt_FMT " steps, t = %g s, %.2f s\n",
                            run.step, run.time, run.wall_seconds));
    else if (run.converged)
      PetscCall(PetscPrintf(sim.comm,
                            "converged: unbalanced-force ratio %.3e <= %g after %" PetscInt_FMT
                            " steps (%.2f s)\n",
                            run.ratio, s.tol, run.step, run.wall_seconds));
    else
      PetscCall(PetscPrintf(sim.comm,
                            "NOT converged: step cap %" PetscInt_FMT " reached with "
                            "unbalanced-force ratio %.3e > %g (%.2f s)\n",
                            s.max_steps, run.ratio, s.tol, run.wall_seconds));
  }
  PetscFunctionReturn(0);
}

} // namespace pmpm
