// One step of the partition MPM cycle, top to bottom. Each phase is a plain kernel from
// transfers.cpp or a material's batch update; PETSc appears only for the ghost exchanges and the
// migration.
#include "pmpm/cycle.hpp"
#include "pmpm/log_event.hpp"
#include "pmpm/antilock.hpp"
#include "pmpm/degradation.hpp"
#include "pmpm/shape_cpgimp.hpp"
#include <cmath>

namespace pmpm {

namespace {
PetscLogEvent ev_p2g, ev_l2g, ev_grid, ev_g2l, ev_g2p, ev_musl, ev_stress, ev_migrate, ev_iface,
    ev_chain, ev_contact, ev_fbar, ev_support;

template <class Shape>
PetscErrorCode StepWith(Simulation &sim, const Load &load, double dt, StepReport &rep) {
  Grid &g = sim.grid;
  GridView G;
  ParticleView P;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));

  // 0. F-bar: the cells the particles start the step in (this rank owns them all), and with
  //    -fbar_pressure cell the internal force's pressure averaged over them, conjugate to the
  //    volume change averaged over them in step 5'.
  const double *pshift = nullptr;
  if (sim.set.fbar) {
    PmpmLogEventScope(ev_fbar);
    fbar_groups(P, g.origin, g.h, g.cell_lo, g.cell_hi, g.nbody, sim.fbar_group);
    if (sim.set.fbar_pressure == FbarPressure::Cell) {
      fbar_pressure_shift(P, sim.fbar_group, sim.fbar_sums, sim.fbar_shift);
      pshift = sim.fbar_shift.data();
    }
  }

  // 1. Particles to grid: mass, momentum, internal and external force (eq. 7-9, 14).
  {
    PmpmLogEventScope(ev_p2g);
    PetscCall(GridGetLocal(g, true, G));
    p2g<Shape>(P, load, G, nullptr, 0, pshift);
    if (!sim.traction_idx.empty())
      p2g_traction<Shape>(P, sim.loads, sim.traction_idx, load.factor, G);
    PetscCall(GridRestoreLocal(g, G));
  }
  // 1a. Membrane chains: their points' mass, momentum, axial and external forces into their own
  //     body's block, and their geometry (normals, length) into their slots.
  if (!sim.chains.empty()) {
    PmpmLogEventScope(ev_chain);
    PetscCall(GridGetLocal(g, false, G));
    for (const Chain &c : sim.chains) p2g_chain(c, load, G, g);
    PetscCall(GridRestoreLocal(g, G));
  }
  // 1b. Interface: body 1's own mass, momentum, force, and its colour gradient (the normals).
  Grid &gb = sim.iface_grid.body;
  const bool iface = sim.iface_grid.active;
  if (iface) {
    PmpmLogEventScope(ev_iface);
    const PetscInt nb = static_cast<PetscInt>(sim.iface_idx.size());
    PetscCall(GridGetLocal(gb, true, G));
    p2g<Shape>(P, load, G, sim.iface_idx.data(), nb, pshift);
    if (sim.iface.normals == InterfaceNormals::Cells)
      p2g_cell_colour(P, G); // all particles
    else
      p2g_colour_gradient<Shape>(P, sim.iface_idx.data(), nb, G); // in FEXT slots
    PetscCall(GridRestoreLocal(gb, G));
  }

  // 2. Sum the ghost contributions across ranks.
  {
    PmpmLogEventScope(ev_l2g);
    PetscCall(GridLocalToGlobalAdd(g));
    if (iface) PetscCall(GridLocalToGlobalAdd(gb));
  }
  // 2b. The paper's normals: central differences of the cell-average colour need the
  //     neighbouring cells' sums, one more ghost exchange of the body grid.
  if (iface && sim.iface.normals == InterfaceNormals::Cells) {
    PmpmLogEventScope(ev_iface);
    GridView C, B;
    PetscCall(GridGlobalToLocal(gb));
    PetscCall(GridGetLocal(gb, false, C));
    PetscCall(GridGetGlobal(gb, B));
    cell_colour_normals(C, B);
    PetscCall(GridRestoreGlobal(gb, B));
    PetscCall(GridRestoreLocal(gb, C));
  }

  // 3. Nodal momentum balance with damping and boundary conditions (eq. 1-2).
  GridUpdateParams gp;
  gp.dt = dt;
  gp.damping_alpha = (sim.set.damping == Damping::Local || sim.set.damping == Damping::Both)
                         ? sim.set.damping_alpha
                         : 0.0;
  for (int f = 0; f < 2 * DIM; ++f) gp.face[f] = sim.face[f];
  gp.prescribed = &sim.prescribed;
  if (sim.set.damping == Damping::Fire && !sim.set.dynamic) {
    const RunState &r = sim.run;
    gp.fire = true;
    gp.fire_mix = r.fire_mix;
    gp.fire_scale = r.fire_f2m > 0 ? std::sqrt(r.fire_mv2 / r.fire_f2m) : 0.0;
  }
  {
    PmpmLogEventScope(ev_grid);
    PetscCall(GridGetGlobal(g, G));
    grid_update(G, gp, rep.grid);
  }
  // 3a. Stacked bodies at the chains' nodes: no interpenetration, separation, friction per face.
  if (!sim.chains.empty()) {
    PmpmLogEventScope(ev_contact);
    ContactParams cp = sim.contact;
    cp.dt = dt;
    // normal impulses, their ghosts, the friction capacity they give the sheet, then the contact
    contact_bodies(G, sim.chains, cp, true, rep.contact);
    PetscCall(GridRestoreGlobal(g, G));
    PetscCall(GridGlobalToLocal(g));
    GridView L;
    PetscCall(GridGetLocal(g, false, L));
    PetscCall(GridGetGlobal(g, G));
    chain_friction_capacity(L, G, sim.chains);
    PetscCall(GridRestoreLocal(g, L));
    contact_bodies(G, sim.chains, cp, false, rep.contact);
  }
  // 3b. Interface: friction-limited velocities of body 1 and body 2 where they meet.
  if (iface) {
    PmpmLogEventScope(ev_iface);
    GridView B;
    InterfaceParams ip = sim.iface;
    ip.dt = dt;
    ip.damping_alpha = gp.damping_alpha;
    PetscCall(GridGetGlobal(gb, B));
    interface_update(G, B, ip, rep.iface);
    PetscCall(GridRestoreGlobal(gb, B));
  }
  PetscCall(GridRestoreGlobal(g, G));

  // 4. New nodal velocities and accelerations to the ghosts.
  {
    PmpmLogEventScope(ev_g2l);
    PetscCall(GridGlobalToLocal(g));
    if (iface) PetscCall(GridGlobalToLocal(gb));
  }
  GridView Gb;
  if (iface) PetscCall(GridGetLocal(gb, false, Gb));
  const GridView *G1 = iface ? &Gb : nullptr;

  // 5. Grid to particles: velocity (eq. 4), position (eq. 5), velocity gradient (eq. 20), F,
  //    volume. USL reads one nodal field in one pass; MUSL first maps the updated particle
  //    momenta back to the grid and takes the kinematics from that remapped velocity.
  G2PParams pp;
  pp.dt = dt;
  pp.pic = sim.set.pic;
  for (int d = 0; d < DIM; ++d) pp.gdir[d] = load.gdir[d];
  // 6 fused into 5 when every material is linear elastic in rate form and nothing reads the
  // velocity gradient in between (F-bar) or subtracts from it (an eigenstrain)
  const bool eigen = load.shrink != 0;
  std::vector<double> elastic(2 * sim.mats.size());
  bool fuse = !sim.set.fbar && !eigen;
  for (size_t m = 0; fuse && m < sim.mats.size(); ++m)
    fuse = sim.mats[m].model->linear_elastic_rate(elastic[2 * m], elastic[2 * m + 1]);
  if (fuse) pp.elastic = elastic.data();
  pp.hoop = sim.hoop.empty() ? nullptr : sim.hoop.data(); // -geometry axisymmetric
  std::vector<double> energy;
  if (fuse && sim.step_energy) {
    for (const auto &m : sim.mats) energy.insert(energy.end(), {m.el.E, m.el.nu});
    pp.energy = energy.data();
  }
  {
    PmpmLogEventScope(ev_g2p);
    PetscCall(GridGetLocal(g, false, G));
    if (!sim.set.musl)
      g2p<Shape>(P, G, G1, g, pp, sim.wave_modulus.data(), sim.dudx.data(), rep.g2p);
    else
      g2p_velocity<Shape>(P, G, G1, pp);
    PetscCall(GridRestoreLocal(g, G));
  }
  if (sim.set.musl) {
    PmpmLogEventScope(ev_musl);
    PetscCall(GridGetLocal(g, true, G));
    p2g_momentum<Shape>(P, G);
    PetscCall(GridRestoreLocal(g, G));
    PetscCall(GridLocalToGlobalAdd(g));
    PetscCall(GridGetGlobal(g, G));
    grid_velocity(G, sim.face, &sim.prescribed);
    PetscCall(GridRestoreGlobal(g, G));
    PetscCall(GridGlobalToLocal(g));
    PetscCall(GridGetLocal(g, false, G));
    g2p_kinematics<Shape>(P, G, G1, g, pp, sim.wave_modulus.data(), sim.dudx.data(), rep.g2p);
    PetscCall(GridRestoreLocal(g, G));
  }
  if (iface) PetscCall(GridRestoreLocal(gb, Gb));
  // 5'. F-bar: each particle's volume change over the step replaced by its cell's.
  if (sim.set.fbar) {
    PmpmLogEventScope(ev_fbar);
    fbar_apply(P, sim.fbar_group, sim.fbar_sums, sim.dudx.data());
  }
  // 5a. Chain points: the owner of each point's cell moves it; one allreduce shares them all.
  if (!sim.chains.empty()) {
    PmpmLogEventScope(ev_chain);
    PetscCall(GridGetLocal(g, false, G));
    std::vector<double> &buf = sim.chain_buf, part;
    buf.clear();
    G2PParams pc = pp; // the points' own PIC fraction (-chain_pic)
    pc.pic = sim.set.chain_pic;
    for (Chain &c : sim.chains) {
      g2p_chain(c, G, g, pc);
      chain_pack(c, part);
      buf.insert(buf.end(), part.begin(), part.end());
    }
    PetscCall(GridRestoreLocal(g, G));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE,
                               MPI_SUM, sim.comm));
    size_t off = 0;
    for (Chain &c : sim.chains) {
      const size_t w = static_cast<size_t>(c.n) * (2 * DIM + 5);
      part.assign(buf.begin() + off, buf.begin() + off + w);
      off += w;
      const int owners = chain_owner_count(part, c.n);
      PetscCheck(owners == c.n, sim.comm, PETSC_ERR_NOT_CONVERGED,
                 "Instability at step %" PetscInt_FMT ": chain %s has %d of its %d points off the "
                 "grid. Enlarge the grid or reduce -cfl (now %g).",
                 sim.run.step, c.name.c_str(), c.n - owners, c.n, sim.set.cfl);
      chain_unpack(c, part);
      for (int i = 0; i < c.n; ++i) {
        const double *x = &c.x[i * DIM], *v = &c.v[i * DIM];
        PetscCheck(std::isfinite(x[0] + x[1] + v[0] + v[1]), sim.comm, PETSC_ERR_NOT_CONVERGED,
                   "Instability at step %" PetscInt_FMT ": chain %s point %d (initially at x = "
                   "(%g, %g) m) has a non-finite position or velocity. Reduce -cfl (now %g) or "
                   "raise -damping_alpha.",
                   sim.run.step, c.name.c_str(), i, c.x0[i * DIM], c.x0[i * DIM + 1], sim.set.cfl);
      }
      chain_update_tension(c);
    }
  }

  // 6. Stress update, one batch per material (eq. 6), less any imposed eigenstrain.
  //    (Done in step 5 when fused: the event then stays empty, G2P holds the time.)
  {
    PmpmLogEventScope(ev_stress);
    if (eigen) rep.eigen_power = shrinkage_increment(P, sim.shrink, load.shrink, sim.eigen);
    for (size_t m = 0; !fuse && m < sim.mats.size(); ++m) {
      StressBatch b;
      b.n = static_cast<int>(sim.mat_idx[m].size());
      if (b.n == 0) continue;
      b.idx = sim.mat_idx[m].data();
      b.dudx = sim.dudx.data();
      b.F = P.F;
      b.stress = P.stress;
      b.eps_p = P.eps_p;
      if (eigen) b.eigen = sim.eigen.data();
      b.hoop = pp.hoop;
      sim.mats[m].model->update_stress(b);
    }
  }
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscFunctionReturn(0);
}
// The chains' share of the step's report: their contact sums over ranks; their kinetic energy,
// speeds and load power from the points every rank holds (added once, not per rank).
PetscErrorCode ChainReductions(Simulation &sim, const Load &load, StepReport &rep) {
  ContactStats &cs = rep.contact;
  PetscFunctionBeginUser;
  std::vector<double> sm = {cs.contact_nodes, cs.slip_nodes, cs.separated_nodes, cs.compression,
                            cs.tension};
  cs.friction.resize(sim.chains.size(), 0.0);
  sm.insert(sm.end(), cs.friction.begin(), cs.friction.end());
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sm.data(), static_cast<int>(sm.size()), MPI_DOUBLE,
                             MPI_SUM, sim.comm));
  cs.contact_nodes = sm[0];
  cs.slip_nodes = sm[1];
  cs.separated_nodes = sm[2];
  cs.compression = sm[3];
  cs.tension = sm[4];
  for (size_t k = 0; k < sim.chains.size(); ++k) {
    cs.friction[k] = sm[5 + k];
    sim.chains[k].friction_force = sm[5 + k];
  }
  sim.contact_stats = cs;
  sim.contact_impulse[0] += cs.compression;
  sim.contact_impulse[1] += cs.tension;
  double ke = 0, v2 = 0, c = 0, pw = 0;
  for (const Chain &ch : sim.chains) {
    c = std::fmax(c, ch.wave_speed());
    for (int i = 0; i < ch.n; ++i) {
      const double *v = &ch.v[i * DIM], s2 = v[0] * v[0] + v[1] * v[1];
      ke += 0.5 * ch.line_mass * ch.length[i] * s2;
      v2 = std::fmax(v2, s2);
      pw += ch.line_weight * ch.length[i] * (load.gdir[0] * v[0] + load.gdir[1] * v[1]);
    }
    const double *v = &ch.v[(ch.n - 1) * DIM];
    pw += ch.end_force[0] * v[0] + ch.end_force[1] * v[1];
  }
  rep.g2p.kinetic += ke;
  rep.g2p.max_c = std::fmax(rep.g2p.max_c, c);
  rep.g2p.max_v = std::fmax(rep.g2p.max_v, std::sqrt(v2));
  rep.g2p.max_speed = rep.g2p.max_c + rep.g2p.max_v;
  if (sim.rank == 0) rep.g2p.weight_power += pw; // the budget sums its local parts over ranks
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode LogRegister() {
  PetscClassId cls;
  PetscFunctionBeginUser;
  PetscCall(PetscClassIdRegister("pmpm", &cls));
  PetscCall(PetscLogEventRegister("P2G", cls, &ev_p2g));
  PetscCall(PetscLogEventRegister("GhostAdd", cls, &ev_l2g));
  PetscCall(PetscLogEventRegister("GridUpdate", cls, &ev_grid));
  PetscCall(PetscLogEventRegister("GhostScatter", cls, &ev_g2l));
  PetscCall(PetscLogEventRegister("G2P", cls, &ev_g2p));
  PetscCall(PetscLogEventRegister("MUSLRemap", cls, &ev_musl));
  PetscCall(PetscLogEventRegister("Interface", cls, &ev_iface));
  PetscCall(PetscLogEventRegister("Chain", cls, &ev_chain));
  PetscCall(PetscLogEventRegister("Contact", cls, &ev_contact));
  PetscCall(PetscLogEventRegister("FBar", cls, &ev_fbar));
  PetscCall(PetscLogEventRegister("CpgimpSupport", cls, &ev_support));
  PetscCall(PetscLogEventRegister("StressUpdate", cls, &ev_stress));
  PetscCall(PetscLogEventRegister("Migrate", cls, &ev_migrate));
  PetscFunctionReturn(0);
}

namespace {
// cpGIMP: every block must fit the 4-node support for the next step (half-size <= one cell);
// otherwise stop with the particle, its stretch and what to change.
PetscErrorCode CheckSupport(Simulation &sim) {
  ParticleView P;
  PetscFunctionBeginUser;
  PmpmLogEventScope(ev_support); // to the end: the error's broadcast too, only when it fails
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

PetscErrorCode Step(Simulation &sim, const Load &load, double dt, StepReport &rep) {
  PetscFunctionBeginUser;
  rep = StepReport{};
  switch (sim.set.shape) {
  case ShapeKind::Linear:
    PetscCall(StepWith<LinearShape>(sim, load, dt, rep));
    break;
  case ShapeKind::UGIMP:
    PetscCall(StepWith<UGIMPShape>(sim, load, dt, rep));
    break;
  case ShapeKind::CPGIMP:
    PetscCall(StepWith<CPGIMPShape>(sim, load, dt, rep));
    break;
  }

  // 7. Reductions: unbalanced force, loads, energy, wave speed, escapes (two allreduces). This
  //    rank's largest unbalanced force and where it is are kept for a stage that stalls.
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

  if (!sim.chains.empty()) PetscCall(ChainReductions(sim, load, rep));

  // A particle off the grid, with J <= 0, or non-finite: stop with where, when and what to do.
  if (mx[3] > 0) {
    const int who = static_cast<int>(mx[3]) - 1;
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

  // 8. Migrate only when a particle left its rank's cells.
  if (sm[3] > 0) {
    PmpmLogEventScope(ev_migrate);
    PetscCall(ParticlesMigrate(sim.parts));
    PetscCall(SimulationIndexParticles(sim));
    ++sim.run.migrations;
  }
  if (sim.set.shape == ShapeKind::CPGIMP) PetscCall(CheckSupport(sim));
  PetscFunctionReturn(0);
}

PetscErrorCode StaticResidual(Simulation &sim, ShapeKind shape, double *ratio) {
  Grid &g = sim.grid;
  GridView G;
  ParticleView P;
  Load load;
  GridStats st;
  GridUpdateParams gp; // dt = 0, no damping: only the force sums are wanted
  PetscFunctionBeginUser;
  for (int d = 0; d < DIM; ++d) load.gdir[d] = sim.set.gdir[d];
  for (int f = 0; f < 2 * DIM; ++f) gp.face[f] = sim.face[f];
  gp.prescribed = &sim.prescribed;
  PetscCall(ParticlesGetView(sim.parts, P));
  PetscCall(GridGetLocal(g, true, G));
  const bool tr = !sim.traction_idx.empty();
  switch (shape) {
  case ShapeKind::Linear:
    p2g<LinearShape>(P, load, G);
    if (tr) p2g_traction<LinearShape>(P, sim.loads, sim.traction_idx, load.factor, G);
    break;
  case ShapeKind::UGIMP:
    p2g<UGIMPShape>(P, load, G);
    if (tr) p2g_traction<UGIMPShape>(P, sim.loads, sim.traction_idx, load.factor, G);
    break;
  case ShapeKind::CPGIMP:
    p2g<CPGIMPShape>(P, load, G);
    if (tr) p2g_traction<CPGIMPShape>(P, sim.loads, sim.traction_idx, load.factor, G);
    break;
  }
  // the chains' tension, weight and end loads (grid_update sums a node's bodies)
  for (const Chain &c : sim.chains) p2g_chain(c, load, G, g);
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

PetscErrorCode InitialWaveSpeed(Simulation &sim, double *max_speed) {
  ParticleView P;
  double c = 0;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGetView(sim.parts, P));
  for (PetscInt p = 0; p < P.n; ++p)
    c = std::fmax(c, std::sqrt(sim.wave_modulus[P.mat[p]] * P.vol[p] / P.mass[p]));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  for (const Chain &ch : sim.chains) c = std::fmax(c, ch.wave_speed());
  PetscCallMPI(MPI_Allreduce(&c, max_speed, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscFunctionReturn(0);
}

} // namespace pmpm
