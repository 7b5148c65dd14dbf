// One step of the partition MPM cycle, top to bottom: StepWith reads as the method, one short
// function per phase. Each phase is a plain kernel from transfers.cpp or the materials' batch
// update; PETSc appears only for the ghost exchanges and the migration. The optional physics
// (chains, the colour interface, F-bar, an imposed eigenstrain, cpGIMP's support check) attach to
// the phases as hooks (step_hooks.hpp, one file each in src/step/). The phases are templates on
// the dimension D: Step runs them in 2D, or in 3D under -dim 3 (extrude.hpp) with the hooks that
// have a 3D form.
#include "pmpm/step/cycle.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include "pmpm/step/step_hooks.hpp"
#include "pmpm/step/stress_update.hpp"
#include <cmath>

namespace pmpm {

StepEvents step_events;

namespace {
// Call a phase's member of every active hook that has it in dimension D (StepPhases3 has checked
// that each active hook has a 3D form of every phase it takes part in).
template <int D>
PetscErrorCode Hooks(const ActiveHooks &h,
                     PetscErrorCode (*HookPhasesT<D>::*member)(StepStateT<D> &), StepStateT<D> &S) {
  PetscFunctionBeginUser;
  for (int i = 0; i < h.n; ++i)
    if (const auto f = Phases<D>(*h.hook[i]).*member) PetscCall(f(S));
  PetscFunctionReturn(0);
}

// Whether a hook's 3D phases cover its 2D ones (a hook with no 3D form for one of its phases
// cannot run in 3D).
bool Has3DForm(const StepHook &k) {
  const HookPhasesT<2> &a = k.phases;
  const HookPhasesT<3> &b = k.phases3;
  const bool has2[] = {!!a.before_p2g,      !!a.p2g,         !!a.ghost_add,
                       !!a.after_ghost_add, !!a.grid_update, !!a.ghost_scatter,
                       !!a.before_g2p,      !!a.after_g2p,   !!a.stress};
  const bool has3[] = {!!b.before_p2g,      !!b.p2g,         !!b.ghost_add,
                       !!b.after_ghost_add, !!b.grid_update, !!b.ghost_scatter,
                       !!b.before_g2p,      !!b.after_g2p,   !!b.stress};
  for (int i = 0; i < 9; ++i)
    if (has2[i] && !has3[i]) return false;
  return true;
}

// 1. Particles to grid: mass, momentum, internal and external force (eq. 7-9, 14); then the
//    hooks' own nodal values (1a chains, 1b the interface's body).
template <class Shape, int D>
PetscErrorCode ParticlesToGrid(StepStateT<D> &S, const ActiveHooks &h) {
  Simulation &sim = S.sim;
  GridViewT<D> G;
  PetscFunctionBeginUser;
  {
    PmpmLogEventScope(step_events.p2g);
    PetscCall(GridGetLocal(sim.grid_of<D>(), true, G));
    p2g<Shape>(S.P, S.load, G, nullptr, 0, S.pshift);
    if (!sim.traction_idx.empty()) {
      if constexpr (D == 3) // -dim 3: the extruded table (extrude.hpp)
        p2g_traction<Shape>(S.P, sim.model.loads3, sim.traction_idx, S.load.factor, G);
      else
        p2g_traction<Shape>(S.P, sim.model.loads, sim.traction_idx, S.load.factor, G);
    }
    PetscCall(GridRestoreLocal(sim.grid_of<D>(), G));
  }
  PetscCall(Hooks(h, &HookPhasesT<D>::p2g, S));
  PetscFunctionReturn(0);
}

// 2. Sum the ghost contributions across ranks (2b: what the hooks need of the sums).
template <int D> PetscErrorCode GhostAdd(StepStateT<D> &S, const ActiveHooks &h) {
  PetscFunctionBeginUser;
  {
    PmpmLogEventScope(step_events.l2g);
    PetscCall(GridLocalToGlobalAdd(S.sim.template grid_of<D>()));
    PetscCall(Hooks(h, &HookPhasesT<D>::ghost_add, S));
  }
  PetscCall(Hooks(h, &HookPhasesT<D>::after_ghost_add, S));
  PetscFunctionReturn(0);
}

// 3. Nodal momentum balance with damping and boundary conditions (eq. 1-2); then the hooks' own
//    (3a the chains' contact, 3b the interface).
template <int D>
PetscErrorCode GridMomentum(StepStateT<D> &S, const FireMix &fire, const ActiveHooks &h) {
  Simulation &sim = S.sim;
  GridUpdateParamsT<D> &gp = S.gp;
  PetscFunctionBeginUser;
  gp.dt = S.dt;
  const bool local = sim.set.damping == Damping::Local || sim.set.damping == Damping::Both;
  gp.damping_alpha = local ? sim.set.damping_alpha : 0.0;
  for (int f = 0; f < 2 * D; ++f) gp.face[f] = sim.model.face[f];
  gp.prescribed = &sim.prescribed;
  if (fire.on) {
    gp.fire = true;
    gp.fire_mix = fire.mix;
    gp.fire_scale = fire.scale;
  }
  {
    PmpmLogEventScope(step_events.grid);
    PetscCall(GridGetGlobal(sim.grid_of<D>(), S.G));
    grid_update(S.G, gp, S.grid_stats);
  }
  PetscCall(Hooks(h, &HookPhasesT<D>::grid_update, S));
  PetscCall(GridRestoreGlobal(sim.grid_of<D>(), S.G));
  PetscFunctionReturn(0);
}

// 4. New nodal velocities and accelerations to the ghosts.
template <int D> PetscErrorCode GhostScatter(StepStateT<D> &S, const ActiveHooks &h) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.g2l);
  PetscCall(GridGlobalToLocal(S.sim.template grid_of<D>()));
  PetscCall(Hooks(h, &HookPhasesT<D>::ghost_scatter, S));
  PetscFunctionReturn(0);
}

// MUSL: the updated particle momenta mapped back to the grid, and the kinematics taken from that
// remapped velocity.
template <class Shape, int D> PetscErrorCode MuslRemap(StepStateT<D> &S) {
  Simulation &sim = S.sim;
  GridT<D> &g = sim.grid_of<D>();
  GridViewT<D> G;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.musl);
  PetscCall(GridGetLocal(g, true, G));
  p2g_momentum<Shape>(S.P, G);
  PetscCall(GridRestoreLocal(g, G));
  PetscCall(GridLocalToGlobalAdd(g));
  PetscCall(GridGetGlobal(g, G));
  grid_velocity(G, sim.model.face, &sim.prescribed);
  PetscCall(GridRestoreGlobal(g, G));
  PetscCall(GridGlobalToLocal(g));
  PetscCall(GridGetLocal(g, false, G));
  g2p_kinematics<Shape, D>(S.P, G, S.G1, owned_cells(g), S.pp, sim.wave_modulus.data(),
                           sim.scratch.dudx.data(), S.g2p_stats);
  PetscCall(GridRestoreLocal(g, G));
  PetscFunctionReturn(0);
}

// 5. Grid to particles: velocity (eq. 4), position (eq. 5), velocity gradient (eq. 20), F,
//    volume; with `elastic` (the fused step 6) the stress too. USL reads one nodal field in one
//    pass; MUSL remaps first. Then the hooks (5' F-bar, 5a the chains' points).
template <class Shape, int D>
PetscErrorCode GridToParticles(StepStateT<D> &S, const ActiveHooks &h, const double *elastic) {
  Simulation &sim = S.sim;
  GridT<D> &g = sim.grid_of<D>();
  G2PParamsT<D> &pp = S.pp;
  GridViewT<D> G;
  std::vector<double> energy;
  PetscFunctionBeginUser;
  pp.dt = S.dt;
  pp.pic = sim.set.pic;
  for (int d = 0; d < D; ++d) pp.gdir[d] = S.load.gdir[d];
  pp.elastic = elastic;
  pp.hoop = sim.scratch.hoop.empty() ? nullptr : sim.scratch.hoop.data(); // -geometry axisymmetric
  if (elastic && sim.step_energy) { // relaxation's energy check: G2P sums the elastic energy
    for (const auto &m : sim.model.mats) energy.insert(energy.end(), {m.el.E, m.el.nu});
    pp.energy = energy.data();
  }
  PetscCall(Hooks(h, &HookPhasesT<D>::before_g2p, S));
  {
    PmpmLogEventScope(step_events.g2p);
    PetscCall(GridGetLocal(g, false, G));
    if (!sim.set.musl)
      g2p<Shape, D>(S.P, G, S.G1, owned_cells(g), pp, sim.wave_modulus.data(),
                    sim.scratch.dudx.data(), S.g2p_stats);
    else
      g2p_velocity<Shape>(S.P, G, S.G1, pp);
    PetscCall(GridRestoreLocal(g, G));
  }
  if (sim.set.musl) PetscCall(MuslRemap<Shape>(S));
  PetscCall(Hooks(h, &HookPhasesT<D>::after_g2p, S));
  PetscFunctionReturn(0);
}

// 6 is fused into 5 when every material is linear elastic in rate form and no hook reads the
// velocity gradient in between (F-bar) or subtracts from it (an eigenstrain): the materials'
// (E, nu) pairs for G2P, or false. Plane strain only (elastic_rate_update, transfers.cpp).
bool FusedStress(const Simulation &sim, const ActiveHooks &h, std::vector<double> &elastic) {
  elastic.resize(2 * sim.model.mats.size());
  bool fuse = !h.reads_gradient && sim.set.dim == 2;
  for (size_t m = 0; fuse && m < sim.model.mats.size(); ++m)
    fuse = sim.model.mats[m].model->linear_elastic_rate(elastic[2 * m], elastic[2 * m + 1]);
  return fuse;
}

// 6. Stress update, one batch per material (eq. 6), less any imposed eigenstrain (its hook).
//    (Done in step 5 when fused: the event then stays empty, G2P holds the time.)
template <int D> PetscErrorCode StressUpdate(StepStateT<D> &S, const ActiveHooks &h, bool fused) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.stress);
  PetscCall(Hooks(h, &HookPhasesT<D>::stress, S));
  if (!fused)
    UpdateStresses(S.sim, S.sim.scratch.dudx.data(), S.P.F, S.P.stress, S.P.eps_p, S.eigen);
  PetscFunctionReturn(0);
}

template <class Shape, int D>
PetscErrorCode StepWith(StepStateT<D> &S, const FireMix &fire, const ActiveHooks &h) {
  std::vector<double> elastic;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(S.sim.parts, S.P));
  PetscCall(Hooks(h, &HookPhasesT<D>::before_p2g, S)); // 0. (F-bar's groups)
  PetscCall(ParticlesToGrid<Shape>(S, h));             // 1.
  PetscCall(GhostAdd(S, h));                           // 2.
  PetscCall(GridMomentum(S, fire, h));                 // 3.
  PetscCall(GhostScatter(S, h));                       // 4.
  const bool fused = FusedStress(S.sim, h, elastic);
  PetscCall(GridToParticles<Shape>(S, h, fused ? elastic.data() : nullptr)); // 5.
  PetscCall(StressUpdate(S, h, fused));                                      // 6.
  PetscCall(ParticlesRestoreView(S.sim.parts, S.P));
  PetscFunctionReturn(0);
}

// 7. Reductions: unbalanced force, loads, energy, wave speed, escapes (two allreduces). This
//    rank's largest unbalanced force and where it is are kept for a stage that stalls. Returns
//    the rank (+1) of a particle that went bad, and whether one left its rank's cells.
PetscErrorCode Reduce(Simulation &sim, StepReport &rep, int *bad_rank, bool *left) {
  PetscFunctionBeginUser;
  sim.run.local_unbalanced = rep.grid.max_unbalanced;
  for (int d = 0; d < DIM; ++d) sim.run.local_unbalanced_at[d] = rep.grid.max_at[d];
  double mx[4] = {rep.grid.max_unbalanced, rep.g2p.max_c, rep.g2p.max_v,
                  static_cast<double>(rep.g2p.bad > 0 ? sim.rank + 1 : 0)};
  double sm[13] = {rep.grid.sum_ext,
                   rep.grid.n_ext,
                   rep.g2p.kinetic,
                   static_cast<double>(rep.g2p.left_rank),
                   rep.iface.contact_nodes,
                   rep.iface.slip_nodes,
                   rep.iface.compression,
                   rep.iface.tension,
                   rep.grid.support_force[0],
                   rep.grid.support_force[1],
                   rep.grid.power,
                   rep.grid.mv2,
                   rep.grid.f2m};
  // FIRE's sums ride along only when asked for (the other runs reduce what they always did)
  const int nsm = sim.set.damping == Damping::Fire ? 13 : 10;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mx, 4, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sm, nsm, MPI_DOUBLE, MPI_SUM, sim.comm));
  if (nsm == 13) {
    rep.grid.power = sm[10];
    rep.grid.mv2 = sm[11];
    rep.grid.f2m = sm[12];
  }
  for (int d = 0; d < DIM; ++d) rep.grid.support_force[d] = sim.support_force[d] = sm[8 + d];
  rep.iface.contact_nodes = sm[4];
  rep.iface.slip_nodes = sm[5];
  rep.iface.compression = sm[6];
  rep.iface.tension = sm[7];
  sim.iface_stats = rep.iface;
  sim.iface_impulse[0] += sm[6];
  sim.iface_impulse[1] += sm[7];
  rep.grid.max_unbalanced = mx[0];
  rep.g2p.max_c = mx[1];
  rep.g2p.max_v = mx[2];
  rep.g2p.max_speed = mx[1] + mx[2];
  rep.grid.sum_ext = sm[0];
  rep.grid.n_ext = sm[1];
  rep.g2p.kinetic = sm[2];
  *bad_rank = static_cast<int>(mx[3]);
  *left = sm[3] > 0;
  PetscFunctionReturn(0);
}

// A particle off the grid, with J <= 0, or non-finite: stop with where, when and what to do.
PetscErrorCode BadParticle(Simulation &sim, const StepReport &rep, int who) {
  PetscFunctionBeginUser;
  double info[3] = {static_cast<double>(rep.g2p.bad_pid), rep.g2p.bad_x[0], rep.g2p.bad_x[1]};
  PetscCallMPI(MPI_Bcast(info, 3, MPI_DOUBLE, who, sim.comm));
  char what[96] = "";
  if (sim.rank == who) PetscCall(PetscStrncpy(what, rep.g2p.bad_what, sizeof(what)));
  PetscCallMPI(MPI_Bcast(what, sizeof(what), MPI_CHAR, who, sim.comm));
  SETERRQ(sim.comm, PETSC_ERR_NOT_CONVERGED,
          "Instability at step %" PetscInt_FMT ": %s (particle %.0f at x = (%g, %g) m). "
          "Reduce -cfl (now %g; measured stable up to about 0.6), raise -damping_alpha, enlarge "
          "the grid if the body moves off it%s.",
          sim.run.step, what, info[0], info[1], info[2], sim.set.cfl,
          sim.set.shape == ShapeKind::Linear
              ? ", or use -shape pmpm (standard MPM inverts particles that cross into "
                "nearly empty cells, at any step size)"
              : "");
}

// Phases 0-6 in dimension D, the shape chosen at compile time.
template <int D>
PetscErrorCode StepPhases(StepStateT<D> &S, const FireMix &fire, const ActiveHooks &h) {
  PetscFunctionBeginUser;
  switch (S.sim.set.shape) {
  case ShapeKind::Linear:
    PetscCall(StepWith<LinearShape>(S, fire, h));
    break;
  case ShapeKind::UGIMP:
    PetscCall(StepWith<UGIMPShape>(S, fire, h));
    break;
  case ShapeKind::CPGIMP:
    PetscCall(StepWith<CPGIMPShape>(S, fire, h));
    break;
  }
  PetscFunctionReturn(0);
}

// -dim 3: the step in 3D, its statistics handed on in the report's 2D form (the z of the node of
// the largest unbalanced force is kept in the run state; the reduction and the messages read x
// and y).
PetscErrorCode StepPhases3(Simulation &sim, const Load &load, double dt, const FireMix &fire,
                           const ActiveHooks &h, StepReport &rep) {
  LoadT<3> load3;
  GridStatsT<3> gs;
  G2PStatsT<3> ps;
  PetscFunctionBeginUser;
  load3.factor = load.factor;
  load3.shrink = load.shrink;
  for (int d = 0; d < DIM; ++d) load3.gdir[d] = load.gdir[d];
  load3.gdir[2] = sim.set.gdir_z; // the 2D scene's gravity, in its plane unless turned
  for (int i = 0; i < h.n; ++i)   // the backstop: ExtrusionCheck refuses these before the run
    PetscCheck(Has3DForm(*h.hook[i]), sim.comm, PETSC_ERR_SUP,
               "-dim 3 does not run %s yet (step %" PetscInt_FMT ")", h.hook[i]->name,
               sim.run.step);
  StepStateT<3> S(sim, load3, dt, rep, gs, ps);
  PetscCall(StepPhases(S, fire, h));
  static_cast<GridSums &>(rep.grid) = gs; // the scalars whole, the vectors' x and y
  static_cast<G2PSums &>(rep.g2p) = ps;
  for (int d = 0; d < DIM; ++d) {
    rep.grid.max_at[d] = gs.max_at[d];
    rep.grid.support_force[d] = gs.support_force[d];
    rep.g2p.bad_x[d] = ps.bad_x[d];
  }
  sim.run.local_unbalanced_at[2] = gs.max_at[2];
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode LogRegister() {
  StepEvents &e = step_events;
  PetscClassId cls;
  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("pmpm", &cls));
  PetscCall(PetscLogEventRegister("P2G", cls, &e.p2g));
  PetscCall(PetscLogEventRegister("GhostAdd", cls, &e.l2g));
  PetscCall(PetscLogEventRegister("GridUpdate", cls, &e.grid));
  PetscCall(PetscLogEventRegister("GhostScatter", cls, &e.g2l));
  PetscCall(PetscLogEventRegister("G2P", cls, &e.g2p));
  PetscCall(PetscLogEventRegister("MUSLRemap", cls, &e.musl));
  PetscCall(PetscLogEventRegister("Interface", cls, &e.iface));
  PetscCall(PetscLogEventRegister("Chain", cls, &e.chain));
  PetscCall(PetscLogEventRegister("SheetShare", cls, &e.sheet_share));
  PetscCall(PetscLogEventRegister("SheetForces", cls, &e.sheet_forces));
  PetscCall(PetscLogEventRegister("Contact", cls, &e.contact));
  PetscCall(PetscLogEventRegister("FBar", cls, &e.fbar));
  PetscCall(PetscLogEventRegister("CpgimpSupport", cls, &e.support));
  PetscCall(PetscLogEventRegister("StressUpdate", cls, &e.stress));
  PetscCall(PetscLogEventRegister("Migrate", cls, &e.migrate));
  PetscFunctionReturn(0);
}

PetscErrorCode Step(Simulation &sim, const Load &load, double dt, const FireMix &fire,
                    StepReport &rep) {
  int bad = 0;
  bool left = false;
  PetscFunctionBeginUser;
  rep = StepReport{};
  const ActiveHooks h = ActiveStepHooks(sim, load);
  StepState S(sim, load, dt, rep, rep.grid, rep.g2p);
  if (sim.set.dim == 3)
    PetscCall(StepPhases3(sim, load, dt, fire, h, rep)); // 0-6.
  else
    PetscCall(StepPhases(S, fire, h));      // 0-6.
  PetscCall(Reduce(sim, rep, &bad, &left)); // 7.
  PetscCall(RunHooks(h, &StepHook::reduce, S));
  if (bad > 0) PetscCall(BadParticle(sim, rep, bad - 1));
  if (left) PetscCall(Migrate(sim)); // 8.
  PetscCall(RunHooks(h, &StepHook::after_step, S));
  PetscFunctionReturn(0);
}

namespace {
template <int D> PetscErrorCode StaticResidualIn(Simulation &sim, ShapeKind shape, double *ratio) {
  GridT<D> &g = sim.grid_of<D>();
  GridViewT<D> G;
  ParticleView P;
  LoadT<D> load;
  GridStatsT<D> st;
  GridUpdateParamsT<D> gp; // dt = 0, no damping: only the force sums are wanted
  PetscFunctionBeginUser;
  GravityDirection<D>(sim, load.gdir);
  for (int f = 0; f < 2 * D; ++f) gp.face[f] = sim.model.face[f];
  gp.prescribed = &sim.prescribed;
  PetscCall(ParticlesGetView(sim.parts, P));
  PetscCall(GridGetLocal(g, true, G));
  switch (shape) {
  case ShapeKind::Linear:
    StaticForces<LinearShape>(sim, P, load, G);
    break;
  case ShapeKind::UGIMP:
    StaticForces<UGIMPShape>(sim, P, load, G);
    break;
  case ShapeKind::CPGIMP:
    StaticForces<CPGIMPShape>(sim, P, load, G);
    break;
  }
  // the chains' tension, weight and end loads (grid_update sums a node's bodies)
  if constexpr (D == DIM)
    for (const Chain &c : sim.chains) p2g_chain(c, load, G, g);
  else
    p2g_sheets(sim, load, G); // the 3D sheets' (step_hooks.hpp)
  PetscCall(GridRestoreLocal(g, G));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscCall(GridLocalToGlobalAdd(g));
  PetscCall(GridGetGlobal(g, G));
  grid_update(G, gp, st);
  PetscCall(GridRestoreGlobal(g, G));
  double mx = st.max_unbalanced, sm[2] = {st.sum_ext, st.n_ext};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sm, 2, MPI_DOUBLE, MPI_SUM, sim.comm));
  PetscCheck(sm[1] > 0, sim.comm, PETSC_ERR_ARG_WRONGSTATE,
             "no node carries an external load: the residual ratio is undefined");
  *ratio = mx / (sm[0] / sm[1]);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode StaticResidual(Simulation &sim, ShapeKind shape, double *ratio) {
  return sim.set.dim == 3 ? StaticResidualIn<3>(sim, shape, ratio)
                          : StaticResidualIn<DIM>(sim, shape, ratio);
}

PetscErrorCode InitialWaveSpeed(Simulation &sim, double *max_speed) {
  ParticleView P;
  double c = 0;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  for (PetscInt p = 0; p < P.n; ++p)
    c = std::fmax(c, std::sqrt(sim.wave_modulus[P.mat[p]] * P.vol[p] / P.mass[p]));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  for (const Chain &ch : sim.chains) c = std::fmax(c, ch.wave_speed());
  for (const Sheet &s : sim.sheets) c = std::fmax(c, s.wave_speed());
  PetscCallMPI(MPI_Allreduce(&c, max_speed, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscFunctionReturn(0);
}

// 8. Migrate only when a particle left its rank's cells (cycle.hpp).
PetscErrorCode Migrate(Simulation &sim) {
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.migrate);
  if (sim.set.dim == 3)
    PetscCall(ParticlesMigrate(sim.parts, sim.grid3));
  else
    PetscCall(ParticlesMigrate(sim.parts));
  PetscCall(SimulationIndexParticles(sim));
  ++sim.run.migrations;
  PetscFunctionReturn(0);
}

} // namespace pmpm
