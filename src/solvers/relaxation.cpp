// Quasi-static loading by dynamic relaxation: load ramp, damping (local Cundall and/or kinetic),
// the stable time step from the current wave speeds, instability detection, and convergence by
// the unbalanced-force ratio max|f_int + f_ext| / mean|f_ext|.
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/step/cycle.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/model/solver.hpp"
#include <petscviewerhdf5.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace pmpm {

namespace {
// What relaxation carries from one step of a stage to the next (a checkpoint saves it, but for
// FIRE's): the wave speed at the stage's start (the instability test's speed limit), the kinetic
// energy 100 steps back (growth test), the last step's kinetic energy (kinetic damping) and the
// resets so far; the energy budget: kinetic + elastic energy at the stage's start, this rank's
// share of the loads' work since, and the round-off floor; -damping fire's mixing now, steps
// since its last restart, and the last step's global sum m v^2 and sum f^2 / m (the mixing's
// scale; not checkpointed: a resumed stage restarts them).
struct RelaxationState {
  double c0 = 0;
  double ke_window = -1;
  double kinetic_prev = 0;
  PetscInt kinetic_resets = 0;
  double budget_e0 = 0, budget_w_local = 0, budget_floor = 0;
  double fire_mix = 0, fire_mv2 = 0, fire_f2m = 0;
  PetscInt fire_steps = 0;
};

// Kinetic damping: at each peak of the particle kinetic energy, stop every particle.
PetscErrorCode ZeroParticleVelocities(Simulation &sim) {
  ParticleView P;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  const int D = sim.parts.dim;
  for (PetscInt q = 0; q < P.n * D; ++q) P.v[q] = 0.0;
  if (P.B) // -transfer apic: the affine part too
    for (PetscInt q = 0; q < P.n * D * D; ++q) P.B[q] = 0.0;
  PetscCall(ParticlesRestoreView(sim.parts, P));
  for (Chain &c : sim.chains) std::fill(c.v.begin(), c.v.end(), 0.0);
  for (Sheet &sh : sim.sheets) std::fill(sh.v.begin(), sh.v.end(), 0.0);
  PetscFunctionReturn(0);
}

// Energy balance, the instability test that does not wait for a particle to invert. Damping,
// plasticity, friction and kinetic resets only remove energy, so at every step of a stage
//   E_kin + U_el <= E_kin(0) + U_el(0) + W_ext,   W_ext = sum over steps of dt sum_p f_p . v_p,
// with f_p the particle's load (ramped weight and traction) plus the work of any imposed
// eigenstrain (degradation.hpp), and U_el the elastic energy of the current stresses (small-strain
// compliance of each material). A step above the stable limit creates energy: the unstable mode
// grows by a constant factor per step (1.5-2x measured on the column at -cfl 0.65-0.75) and passes
// the budget a few steps after it becomes visible, whereas with local damping the step size then
// shrinks with the speeds and the run can "converge" to a tangled state (column -cfl 0.75: stress
// error 31x). The factor 2 covers the small-strain estimate of U_el at large strain (30 % over at
// 30 % compression for neo-Hookean) and the half-step offset of v and x in undamped runs; the floor
// (the elastic energy of a strain of about 1e-7) keeps round-off in unloaded bodies from tripping
// it. Checked every kEnergyEvery steps (one allreduce of two numbers); the power is summed locally
// every step.
constexpr PetscInt kEnergyEvery = 5;
constexpr double kEnergyFactor = 2.0;
// The paper interface's tension warning: the share of tensile normal impulse above which it
// speaks. The friction's over-grip follows that share: on the incline with PIC, 0.47 % tension
// made the slide 0.45 % slow, 5 % made it 4.6 % slow; undamped, 76 % stopped it. The
// quasi-static landfill shows 1.9e-4 (mu 0.3) and 1.3e-3 (mu 0).
constexpr double kTensionWarn = 0.01;

// sum_p f_p . v_p over this rank's particles (the load's power after the step).
// Power of the surface tractions on this rank's loaded particles (per unit load factor); the
// body forces' share comes from G2P (G2PStats::weight_power).
template <int D>
double TractionPower(const ParticleView &P, const std::vector<ParticleLoadT<D>> &loads,
                     const std::vector<PetscInt> &idx) {
  double pw = 0;
  for (const PetscInt p : idx)
    for (int d = 0; d < D; ++d) pw += loads[P.load[p]].traction[d] * P.v[p * D + d];
  return pw;
}

// Elastic energy of the chains, on rank 0 only (every rank holds them: counted once).
double ChainsElasticEnergy(const Simulation &sim) {
  double u = 0;
  if (sim.rank == 0)
    for (const Chain &ch : sim.chains) u += chain_elastic_energy(ch);
  return u;
}

// Elastic energy of this rank's particles: V sigma : C^-1 : sigma / 2 (plane strain, sigma_zz
// kept), each material with its own E and nu (elastic_energy, material.hpp); and the chains'.
double ElasticEnergy(const Simulation &sim, const ParticleView &P) {
  double u = 0;
  const bool three = sim.parts.dim == 3;
  for (PetscInt p = 0; p < P.n; ++p) {
    const ElasticConstants &c = sim.model.mats[P.mat[p]].el;
    u += three ? elastic_energy<3>(c.E, c.nu, P.vol[p], P.stress + p * NStress<3>)
               : elastic_energy(c.E, c.nu, P.vol[p], P.stress + p * NSTRESS);
  }
  return u + ChainsElasticEnergy(sim);
}

// The budget lives in RelaxationState (budget_e0: kinetic + elastic energy before the stage's
// first step; budget_w_local: this rank's part of W_ext; budget_floor: 1e-14 sum_p M_p V_p), so a
// checkpoint carries it.
PetscErrorCode EnergyBudgetInit(Simulation &sim, RelaxationState &st) {
  ParticleView P;
  double s[2] = {0, 0};
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  const int D = sim.parts.dim;
  for (PetscInt p = 0; p < P.n; ++p) {
    const double *v = P.v + p * D;
    s[0] += 0.5 * P.mass[p] * (v[0] * v[0] + v[1] * v[1] + (D == 3 ? v[2] * v[2] : 0.0));
    s[1] += sim.wave_modulus[P.mat[p]] * P.vol[p];
  }
  const double u = ElasticEnergy(sim, P); // a later stage starts from a loaded state
  PetscCall(ParticlesRestoreView(sim.parts, P));
  if (sim.rank == 0)
    for (const Chain &c : sim.chains)
      for (int k = 0; k + 1 < c.n; ++k) s[1] += c.law.J * c.l0[k];
  s[0] += u;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 2, MPI_DOUBLE, MPI_SUM, sim.comm));
  st.budget_e0 = s[0];
  st.budget_w_local = 0;
  st.budget_floor = 1e-14 * s[1];
  PetscFunctionReturn(0);
}

// The fastest particle (where an unstable mode lives): id, position and speed on every rank.
PetscErrorCode FastestParticle(Simulation &sim, double info[5]) {
  ParticleView P;
  struct {
    double v;
    int rank;
  } loc = {-1.0, sim.rank}, glob;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  const int D = sim.parts.dim;
  for (PetscInt p = 0; p < P.n; ++p) {
    const double *v = P.v + p * D,
                 sp = D == 3 ? std::hypot(v[0], v[1], v[2]) : std::hypot(v[0], v[1]);
    if (sp > loc.v || !std::isfinite(sp)) {
      loc.v = std::isfinite(sp) ? sp : 1e300;
      info[0] = static_cast<double>(P.pid[p]);
      for (int d = 0; d < D; ++d) info[1 + d] = P.x[p * D + d];
      info[4] = sp;
    }
  }
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  PetscCallMPI(MPI_Bcast(info, 5, MPI_DOUBLE, glob.rank, sim.comm));
  PetscFunctionReturn(0);
}

// The largest unbalanced force over the ranks and the node it sits at (collective: one MAXLOC
// reduction and a broadcast of the node from the rank that holds it).
PetscErrorCode LargestUnbalanced(const Simulation &sim, double *value, double at[3]) {
  struct {
    double v;
    int rank;
  } loc = {sim.run.local_unbalanced, sim.rank}, glob;
  PetscFunctionBeginUser;
  for (int d = 0; d < 3; ++d) at[d] = sim.run.local_unbalanced_at[d]; // z: 0 in 2D
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  PetscCallMPI(MPI_Bcast(at, 3, MPI_DOUBLE, glob.rank, sim.comm));
  *value = glob.v;
  PetscFunctionReturn(0);
}

// One -relax_history row: the node of the largest unbalanced force over the ranks (collective).
PetscErrorCode HistoryRow(Simulation &sim, const RelaxationState &st, FILE *f, PetscInt k) {
  const RunState &run = sim.run;
  double largest, at[3];
  PetscFunctionBeginUser;
  PetscCall(LargestUnbalanced(sim, &largest, at));
  if (f)
    fprintf(f, "%d,%" PetscInt_FMT ",%.6e,%.6e,%" PetscInt_FMT ",%.6e,%.6g,%.6g\n", (int)sim.stage,
            k, run.ratio, run.kinetic, st.kinetic_resets, largest, at[0], at[1]);
  if (f) fflush(f); // readable while the run goes on
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
// A stage that reached its step cap: where the residual sits (the node of the largest unbalanced
// force, one reduction) and the trend over the cap's second half.
PetscErrorCode NotConverged(Simulation &sim, const char *tag, double ratio_half) {
  const Settings &s = sim.set;
  const RunState &run = sim.run;
  double largest, at[3];
  PetscFunctionBeginUser;
  PetscCall(LargestUnbalanced(sim, &largest, at));
  char node[96]; // 2D: forces per unit thickness at (x, y); 3D: forces at (x, y, z)
  if (s.dim == 3)
    snprintf(node, sizeof(node), "(%.3g N) is at the node (%g, %g, %g) m", largest, at[0], at[1],
             at[2]);
  else
    snprintf(node, sizeof(node), "(%.3g N/m) is at the node (%g, %g) m", largest, at[0], at[1]);
  // the trend over the second half: a ratio that hardly falls may be a mechanism (a creep at
  // constant rate, which more steps do not cure; docs/method.md, section 3)
  char trend[384] = "";
  if (ratio_half > 0) {
    const double fell = ratio_half / std::fmax(run.ratio, 1e-300);
    snprintf(trend, sizeof(trend),
             " Over the second half of the cap the ratio went from %.3e to %.3e%s.", ratio_half,
             run.ratio,
             fell < 2 ? ": less than 2x, so more steps will help little; if the model "
                        "still moves there at a constant rate, it is a mechanism "
                        "(bench/relaxation_creep.py compares checkpoints)"
                      : "");
  }
  PetscCall(PetscPrintf(sim.comm,
                        "%sNOT converged: step cap %" PetscInt_FMT " reached with "
                        "unbalanced-force ratio %.3e > %g (%.2f s); the largest unbalanced "
                        "force %s. Raise -max_steps or -tol%s.%s\n",
                        tag, s.max_steps, run.ratio, s.tol, run.stage_seconds, node,
                        sim.chains.empty() ? ""
                                           : "; at a membrane's node, the contact may be "
                                             "chattering (docs/limitations.md)",
                        trend));
  PetscFunctionReturn(0);
}

// What one stage's progress lines need: its tag, its start, and the last line's step and ratio.
struct Progress {
  char tag[48] = "";
  double t_start = 0, t_last = 0, log_ratio_last = 0;
  PetscInt step_last = 0;
};

// Dynamic relaxation of the current stage (Simulation::stage) to equilibrium, or the step cap.
// Stage 0 ramps the loads over -ramp_steps; a later stage applies its shrinkage over
// Simulation::stage_ramp steps.
class RelaxationSolver final : public EquilibriumSolver {
public:
  const char *name() const override { return "relaxation"; }
  PetscErrorCode setup(Simulation &) override { return 0; } // its options are the common ones
  PetscErrorCode solve_stage(Simulation &sim) override;
  bool supports(SolverFeature) const override { return true; }
  PetscErrorCode checkpoint_write(Simulation &sim, PetscViewer v, const char *group) override;
  PetscErrorCode checkpoint_read(Simulation &sim, PetscViewer v, const char *group,
                                 const std::string &file, PetscInt ranks) override;

private:
  RelaxationState st;
  PetscErrorCode StageStart(Simulation &sim, bool resume, Progress &pr);
  PetscErrorCode OpenHistory(Simulation &sim, bool fresh, FILE **hist);
  FireMix Fire(const Settings &s) const;
  PetscErrorCode LoadWork(Simulation &sim, const Load &load, const StepReport &rep);
  PetscErrorCode CheckStable(Simulation &sim, const StepReport &rep, PetscInt k, PetscInt ramp);
  PetscErrorCode Damp(Simulation &sim, const StepReport &rep);
  PetscErrorCode ProgressLine(Simulation &sim, Progress &pr, PetscInt k, PetscInt ramp,
                              const Load &load);
  PetscErrorCode Checkpoint(Simulation &sim, const Progress &pr, PetscInt k);
  PetscErrorCode StageEnd(Simulation &sim, const Progress &pr, double ratio_half);
};

PetscErrorCode RelaxationSolver::solve_stage(Simulation &sim) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  Load load;
  StepReport rep;
  Progress pr;
  FILE *hist = nullptr; // -relax_history, rank 0
  PetscFunctionBeginUser;
  for (int d = 0; d < DIM; ++d) load.gdir[d] = s.gdir[d];
  // A stage resumed from a checkpoint continues with the state the checkpoint restored (its
  // wave speed limit, step size, damping and energy budget); a new one starts them.
  const bool resume = sim.resume && sim.resume_in_stage;
  PetscCall(StageStart(sim, resume, pr));
  PetscCall(OpenHistory(sim, sim.stage == 0 && !resume, &hist));
  // Stage 0 ramps the loads; a later stage ramps its change (the shrinkage) at full load.
  const bool first = sim.stage == 0;
  const PetscInt ramp = first ? s.ramp_steps : sim.stage_ramp;
  PetscInt k = resume ? run.stage_step + 1 : 1;
  pr.step_last = k - 1;
  // the ratio at half the step cap, for the trend a capped stage reports (unknown, < 0, when the
  // stage resumed past it)
  double ratio_half = -1;
  for (; k <= s.max_steps; ++k) {
    run.stage_step = k;
    ++run.step;
    load.factor = first && ramp > 0 ? std::fmin(1.0, double(k) / ramp) : 1.0;
    load.shrink = !first && k <= ramp ? sim.stage_shrink / double(ramp) : 0.0;
    // the energy check's steps: G2P sums the particles' elastic energy if it can (one pass
    // over the particles less; the same sum)
    sim.step_energy = k % kEnergyEvery == 0;
    PetscCall(Step(sim, load, run.dt, Fire(s), rep));
    sim.step_energy = false;
    PetscCall(LoadWork(sim, load, rep)); // before a scene changes the loads in monitor
    run.time += run.dt;
    PetscCall(sim.scene->monitor(sim));
    run.kinetic = rep.g2p.kinetic;
    const double mean_ext = rep.grid.n_ext > 0 ? rep.grid.sum_ext / rep.grid.n_ext : 0.0;
    run.ratio = mean_ext > 0 ? rep.grid.max_unbalanced / mean_ext
                             : (rep.grid.max_unbalanced > 0 ? 1e300 : 0.0);
    PetscCall(CheckStable(sim, rep, k, ramp));
    PetscCall(Damp(sim, rep));
    if (s.output_every > 0 && run.step % s.output_every == 0) PetscCall(OutputSeriesFrame(sim));
    if (k == s.max_steps / 2) ratio_half = run.ratio;
    run.converged = !s.dynamic && k >= ramp && run.ratio <= s.tol;
    if (!s.relax_history.empty() &&
        (k % s.relax_history_every == 0 || run.converged || run.stop_stage || k == s.max_steps))
      PetscCall(HistoryRow(sim, st, hist, k));
    PetscCall(ProgressLine(sim, pr, k, ramp, load));
    if (run.converged || run.stop_stage) break;
    run.max_speed = rep.g2p.max_speed;
    run.dt = s.cfl * s.h / run.max_speed; // stable step from the current wave speeds
    PetscCall(Checkpoint(sim, pr, k));
  }
  if (hist) fclose(hist);
  if (k > s.max_steps) run.stage_step = s.max_steps;
  PetscCall(StageEnd(sim, pr, ratio_half));
  PetscFunctionReturn(0);
}

// A checkpoint between two steps of the stage every -checkpoint_every steps; one at the step that
// ends the stage is written by RunStages after the scene's end_stage.
PetscErrorCode RelaxationSolver::Checkpoint(Simulation &sim, const Progress &pr, PetscInt k) {
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  if (s.checkpoint_every > 0 && sim.run.step % s.checkpoint_every == 0 && k < s.max_steps) {
    sim.run.stage_seconds = MPI_Wtime() - pr.t_start;
    PetscCall(SheetsComplete(sim)); // each rank computed its own triangles
    PetscCall(CheckpointWrite(sim, true));
  }
  PetscFunctionReturn(0);
}

// A new stage starts the wave speed limit, the step size, the damping and the energy budget; a
// resumed one keeps the checkpoint's. The stage's progress lines start; stage 0 has a header.
PetscErrorCode RelaxationSolver::StageStart(Simulation &sim, bool resume, Progress &pr) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  PetscFunctionBeginUser;
  sim.resume = false;
  run.stop_stage = false;
  if (!resume) {
    PetscCall(InitialWaveSpeed(sim, &st.c0));
    run.max_speed = st.c0;
    run.dt = s.cfl * s.h / st.c0;
    st.kinetic_prev = 0;
    run.converged = false;
    st.ke_window = -1; // kinetic energy 100 steps ago, for the growth test
    st.fire_mix = s.fire_alpha;
    st.fire_steps = 0;
    st.fire_mv2 = st.fire_f2m = 0;
    PetscCall(EnergyBudgetInit(sim, st));
  }
  // FIRE's mixing turns each body's nodal velocity toward its own force, which the contact then
  // undoes: on the friction landfill (chain, mu = 0.3, h = 0.5 mm) it did not converge in
  // 100,000 steps and moved the settlement by 11 % and the peak strain by 86 %
  PetscCheck(s.damping != Damping::Fire || (sim.chains.empty() && !sim.iface_grid.active), sim.comm,
             PETSC_ERR_SUP,
             "-damping fire is not supported with membrane chains or an interface (it moved the "
             "friction landfill's answers); use -damping kinetic");
  // a resumed stage counts the seconds it ran before the checkpoint
  pr.t_start = MPI_Wtime() - (resume ? run.stage_seconds : 0.0);
  pr.t_last = MPI_Wtime();
  pr.log_ratio_last = resume ? std::log10(std::fmax(run.ratio, 1e-300)) : 0.0;
  if (sim.nstages > 0)
    snprintf(pr.tag, sizeof(pr.tag), "stage %d/%d  ", (int)sim.stage, (int)sim.nstages);
  if (!s.quiet && sim.stage == 0 && !resume)
    PetscCall(PetscPrintf(sim.comm,
                          "pmpm %s: %" PetscInt_FMT " x %" PetscInt_FMT " cells, h = %g m, "
                          "shape %s, dt = %.3e s (cfl %g), tolerance %g\n",
                          s.scene.c_str(), sim.model.ncell[0], sim.model.ncell[1], s.h,
                          ShapeKindNames[(int)s.shape], run.dt, s.cfl, s.tol));
  PetscFunctionReturn(0);
}

// -relax_history, rank 0: the first stage starts the file, later ones (and a restart) append.
PetscErrorCode RelaxationSolver::OpenHistory(Simulation &sim, bool fresh, FILE **hist) {
  const Settings &s = sim.set;
  PetscFunctionBeginUser;
  *hist = nullptr;
  if (s.relax_history.empty()) PetscFunctionReturn(0);
  int ok = 1;
  if (sim.rank == 0) {
    *hist = fopen(s.relax_history.c_str(), fresh ? "w" : "a");
    ok = *hist != nullptr;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, sim.comm));
  PetscCheck(ok, sim.comm, PETSC_ERR_FILE_OPEN, "-relax_history: cannot write %s",
             s.relax_history.c_str());
  // a new file has its header (also one a restart starts: it appends to what it finds)
  FILE *f = *hist;
  if (f && !fresh) fseek(f, 0, SEEK_END);
  if (f && (fresh || ftell(f) == 0))
    fprintf(f, "stage,step,ratio,kinetic,kinetic_resets,max_unbalanced,x,y\n");
  PetscFunctionReturn(0);
}

// -damping fire: the nodal velocities mixed toward the force.
FireMix RelaxationSolver::Fire(const Settings &s) const {
  FireMix mix;
  if (s.damping == Damping::Fire && !s.dynamic) {
    mix.on = true;
    mix.mix = st.fire_mix;
    mix.scale = st.fire_f2m > 0 ? std::sqrt(st.fire_mv2 / st.fire_f2m) : 0.0;
  }
  return mix;
}

// The work of this step's loads into the energy budget: weight and tractions, moving supports
// (transfers.hpp, PrescribedVelocity; this rank's nodes) and an imposed eigenstrain.
PetscErrorCode RelaxationSolver::LoadWork(Simulation &sim, const Load &load,
                                          const StepReport &rep) {
  PetscFunctionBeginUser;
  double pw = rep.g2p.weight_power;
  if (!sim.traction_idx.empty()) {
    ParticleView P;
    PetscCall(ParticlesGetView(sim.parts, P));
    pw += sim.parts.dim == 3 ? TractionPower(P, sim.model.loads3, sim.traction_idx)
                             : TractionPower(P, sim.model.loads, sim.traction_idx);
    PetscCall(ParticlesRestoreView(sim.parts, P));
  }
  st.budget_w_local += sim.run.dt * (load.factor * pw + rep.grid.support_power) + rep.eigen_power;
  PetscFunctionReturn(0);
}

// Instability: a non-finite ratio or step, particle speeds beyond the wave speed (an explicit
// step above the stable limit grows exponentially), sustained kinetic energy growth, or energy
// beyond the budget.
PetscErrorCode RelaxationSolver::CheckStable(Simulation &sim, const StepReport &rep, PetscInt k,
                                             PetscInt ramp) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  char why_buf[384];
  PetscFunctionBeginUser;
  const bool ramped = k >= ramp;
  const double vmax = rep.g2p.max_v;
  const char *why = nullptr;
  if (!std::isfinite(run.ratio) || !std::isfinite(rep.g2p.max_speed))
    why = "non-finite nodal force or wave speed";
  else if (vmax > st.c0)
    why = "particle speed exceeds the material wave speed";
  if (ramped && k % 100 == 0) {
    if (st.ke_window > 0 && run.kinetic > 1e8 * st.ke_window && !s.dynamic)
      why = "kinetic energy grew 1e8-fold in 100 steps after the load ramp";
    st.ke_window = run.kinetic;
  }
  if (!why && k % kEnergyEvery == 0) {
    double e[2] = {0, st.budget_w_local};
    if (rep.g2p.has_elastic) { // this rank's particles as G2P left them (before migrating)
      e[0] = rep.g2p.elastic + ChainsElasticEnergy(sim);
    } else {
      ParticleView P;
      PetscCall(ParticlesGetView(sim.parts, P));
      e[0] = ElasticEnergy(sim, P);
      PetscCall(ParticlesRestoreView(sim.parts, P));
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, e, 2, MPI_DOUBLE, MPI_SUM, sim.comm));
    const double held = run.kinetic + e[0], allowed = st.budget_e0 + e[1];
    if (!(held <= kEnergyFactor * allowed + st.budget_floor)) {
      double at[5] = {-1, 0, 0, 0, 0}; // id, x, y, z, |v|
      PetscCall(FastestParticle(sim, at));
      const bool d3 = sim.set.dim == 3;
      const char *unit = d3 ? "J" : "J/m"; // 2D: per metre of depth
      char where[96];
      if (d3)
        snprintf(where, sizeof(where), "(%g, %g, %g)", at[1], at[2], at[3]);
      else
        snprintf(where, sizeof(where), "(%g, %g)", at[1], at[2]);
      snprintf(why_buf, sizeof(why_buf),
               "kinetic + elastic energy %.3g %s exceeds %g x (initial kinetic energy + work "
               "of the loads) = %g x %.3g %s, energy created by the time integration; fastest "
               "particle %.0f at x = %s m, |v| = %.3g m/s",
               held, unit, kEnergyFactor, kEnergyFactor, allowed, unit, at[0], where, at[4]);
      why = why_buf;
    }
  }
  // Standard MPM's cell-crossing error also creates energy, whatever the step size.
  const char *hint = s.shape == ShapeKind::Linear
                         ? " With -shape mpm, particles crossing cell faces create energy too: "
                           "-shape pmpm avoids that."
                         : "";
  PetscCheck(!why, sim.comm, PETSC_ERR_NOT_CONVERGED,
             "Instability at step %" PetscInt_FMT " (t = %g s, dt = %g s): %s. Reduce -cfl "
             "(now %g; 0.5 is safe for both shapes) or raise -damping_alpha.%s",
             run.step, run.time, run.dt, why, s.cfl, hint);
  PetscFunctionReturn(0);
}

// FIRE, then kinetic damping (-damping), never under -dynamic.
PetscErrorCode RelaxationSolver::Damp(Simulation &sim, const StepReport &rep) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  PetscFunctionBeginUser;
  if (s.dynamic) PetscFunctionReturn(0);
  if (s.damping == Damping::Fire) {
    // FIRE (Bitzek et al. 2006): where the forces' power over the step turns negative the
    // motion has passed a minimum along its path: stop everything and mix afresh; while it
    // stays positive, the mixing decays after a delay and the motion gathers speed. The power
    // is the nodal forces' work, sum f . (v_old + v_new) / 2: energy taken by PIC, friction
    // or contact is not in it, so dissipation alone does not stop the motion (kinetic
    // damping's test, the kinetic energy falling, is met by that too).
    if (rep.grid.power < 0) {
      PetscCall(ZeroParticleVelocities(sim));
      st.fire_mix = s.fire_alpha;
      st.fire_steps = 0;
      st.fire_mv2 = 0; // the next step starts from rest
      ++st.kinetic_resets;
    } else {
      st.fire_mv2 = rep.grid.mv2;
      if (++st.fire_steps > s.fire_delay) st.fire_mix *= s.fire_decay;
    }
    st.fire_f2m = rep.grid.f2m;
  }
  if (s.damping == Damping::Kinetic || s.damping == Damping::Both) {
    if (run.kinetic < st.kinetic_prev) {
      PetscCall(ZeroParticleVelocities(sim));
      st.kinetic_prev = 0;
      ++st.kinetic_resets;
    } else {
      st.kinetic_prev = run.kinetic;
    }
  }
  PetscFunctionReturn(0);
}

// Progress on rank 0 at most every -progress_interval seconds, and at convergence.
PetscErrorCode RelaxationSolver::ProgressLine(Simulation &sim, Progress &pr, PetscInt k,
                                              PetscInt ramp, const Load &load) {
  const Settings &s = sim.set;
  const RunState &run = sim.run;
  PetscFunctionBeginUser;
  const double now = MPI_Wtime();
  if (s.quiet || !(now - pr.t_last >= s.progress_seconds || run.converged)) PetscFunctionReturn(0);
  const double lr = std::log10(std::fmax(run.ratio, 1e-300));
  const double per_step = (now - pr.t_last) / double(k - pr.step_last);
  // Steps left: the ramp, then the ratio's recent decay rate down to -tol (log scale);
  // unknown (?) until the ratio has fallen between two lines.
  double left = -1;
  if (k < ramp)
    left = double(ramp - k) * 2.0;
  else if (pr.step_last > 0 && lr < pr.log_ratio_last)
    left = (lr - std::log10(s.tol)) / ((pr.log_ratio_last - lr) / double(k - pr.step_last));
  if (left >= 0) left = std::fmin(left, double(s.max_steps - k));
  char eta[48];
  if (run.converged)
    snprintf(eta, sizeof(eta), "converged");
  else {
    FormatSeconds(left >= 0 ? left * per_step : -1, eta + 4, sizeof(eta) - 4);
    std::memcpy(eta, "ETA ", 4);
  }
  PetscCall(PetscPrintf(sim.comm,
                        "  %sstep %8" PetscInt_FMT "  t %.4e s  ratio %.3e  load %.2f  "
                        "KE %.3e  %s\n",
                        pr.tag, k, run.time, run.ratio, load.factor, run.kinetic, eta));
  pr.t_last = now;
  pr.step_last = k;
  pr.log_ratio_last = lr;
  PetscFunctionReturn(0);
}

// The stage's time, its last line (converged, ended by the scene, or where it stalled), and the
// paper interface's tension warning.
PetscErrorCode RelaxationSolver::StageEnd(Simulation &sim, const Progress &pr, double ratio_half) {
  const Settings &s = sim.set;
  RunState &run = sim.run;
  PetscFunctionBeginUser;
  run.stage_seconds = MPI_Wtime() - pr.t_start;
  run.wall_seconds += run.stage_seconds;
  if (!s.quiet) {
    if (s.dynamic)
      PetscCall(PetscPrintf(sim.comm, "dynamic run: %" PetscInt_FMT " steps, t = %g s, %.2f s\n",
                            run.step, run.time, run.stage_seconds));
    else if (run.stop_stage)
      PetscCall(PetscPrintf(sim.comm,
                            "%sended by the scene after %" PetscInt_FMT " steps (%.2f s), "
                            "unbalanced-force ratio %.3e\n",
                            pr.tag, run.stage_step, run.stage_seconds, run.ratio));
    else if (run.converged)
      PetscCall(PetscPrintf(sim.comm,
                            "%sconverged: unbalanced-force ratio %.3e <= %g after %" PetscInt_FMT
                            " steps (%.2f s)\n",
                            pr.tag, run.ratio, s.tol, run.stage_step, run.stage_seconds));
    else
      PetscCall(NotConverged(sim, pr.tag, ratio_half));
  }
  // The paper's interface keeps one normal velocity for both bodies, so it also holds them
  // together where they pull apart, and its friction counts compression only. That is sound
  // while the interface stays pressed (quasi-static loading); say so when it did not.
  const double *I = sim.iface_impulse;
  if (sim.model.iface.type == InterfaceType::Paper && I[0] > 0 && I[1] > kTensionWarn * I[0])
    PetscCall(PetscPrintf(sim.comm,
                          "warning: the paper interface carried tension (%.1f %% of its "
                          "compressive normal impulse): the common normal velocity held the "
                          "bodies together, and the friction may over-grip by about as much; "
                          "damp the ringing (-pic, -damping) or use -interface_type contact\n",
                          100 * I[1] / I[0]));
  PetscFunctionReturn(0);
}

PetscErrorCode RelaxationSolver::checkpoint_write(Simulation &sim, PetscViewer v,
                                                  const char *group) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, group));
  PetscCall(CheckpointWriteReal(v, "kinetic_prev", st.kinetic_prev));
  PetscCall(CheckpointWriteInt(v, "kinetic_resets", st.kinetic_resets));
  PetscCall(CheckpointWriteReal(v, "c0", st.c0));
  PetscCall(CheckpointWriteReal(v, "ke_window", st.ke_window));
  PetscCall(CheckpointWriteReal(v, "budget_e0", st.budget_e0));
  PetscCall(CheckpointWriteReal(v, "budget_floor", st.budget_floor));
  PetscCall(CheckpointWriteRankShare(sim.comm, v, "budget_w_local", st.budget_w_local));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

PetscErrorCode RelaxationSolver::checkpoint_read(Simulation &sim, PetscViewer v, const char *group,
                                                 const std::string &file, PetscInt ranks) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, group));
  PetscCall(CheckpointReadReal(v, "kinetic_prev", &st.kinetic_prev));
  PetscCall(CheckpointReadInt(v, "kinetic_resets", &st.kinetic_resets));
  PetscCall(CheckpointReadReal(v, "c0", &st.c0));
  PetscCall(CheckpointReadReal(v, "ke_window", &st.ke_window));
  PetscCall(CheckpointReadReal(v, "budget_e0", &st.budget_e0));
  PetscCall(CheckpointReadReal(v, "budget_floor", &st.budget_floor));
  // this rank's share of the loads' work on the same rank count; else all of it on rank 0
  PetscCall(
      CheckpointReadRankShare(sim.comm, v, "budget_w_local", file, ranks, &st.budget_w_local));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}
} // namespace

std::unique_ptr<EquilibriumSolver> make_relaxation_solver() {
  return std::make_unique<RelaxationSolver>();
}

} // namespace pmpm
