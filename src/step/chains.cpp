// Membrane chains (chain.hpp) in the explicit step: their points' mass, momentum and forces into
// their own body's nodal block, the stacked bodies' contact at their nodes after the momentum
// balance, the points moved by the owner of their cell and shared by one allreduce, and their
// share of the step's report.
#include "pmpm/step/step_hooks.hpp"
#include <cmath>

namespace pmpm {

namespace {
bool Active(const Simulation &sim, const Load &) {
  return !sim.chains.empty();
}

// 1a. Their points' mass, momentum, axial and external forces into their own body's block, and
//     their geometry (normals, length) into their slots.
PetscErrorCode ParticlesToGrid(StepState &S) {
  Grid &g = S.sim.grid;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  PetscCall(GridWithLocal(g, false, [&](const GridView &G) {
    for (const Chain &c : S.sim.chains) p2g_chain(c, S.load, G, g);
  }));
  PetscFunctionReturn(0);
}

// 3a. Stacked bodies at the chains' nodes: no interpenetration, separation, friction per face.
//     The normal impulses, their ghosts, the friction capacity they give the sheet, then the
//     contact.
PetscErrorCode Contact(StepState &S) {
  Simulation &sim = S.sim;
  Grid &g = sim.grid;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.contact);
  ContactParams cp = sim.model.contact;
  cp.dt = S.dt;
  contact_bodies(S.G, sim.chains, cp, true, S.rep.contact);
  PetscCall(GridRestoreGlobal(g, S.G));
  PetscCall(GridGlobalToLocal(g));
  PetscCall(GridWithLocal(g, false, [&](const GridView &L) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(GridGetGlobal(g, S.G)); // the step's global view, again for the contact below
    chain_friction_capacity(L, S.G, sim.chains);
    PetscFunctionReturn(0);
  }));
  contact_bodies(S.G, sim.chains, cp, false, S.rep.contact);
  PetscFunctionReturn(0);
}

// 5a. The owner of each point's cell moves it; one allreduce shares them all.
PetscErrorCode GridToPoints(StepState &S) {
  Simulation &sim = S.sim;
  Grid &g = sim.grid;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  std::vector<double> &buf = sim.scratch.chain_buf, part;
  buf.clear();
  G2PParams pc = S.pp; // the points' own PIC fraction (-chain_pic)
  pc.pic = sim.set.chain_pic;
  PetscCall(GridWithLocal(g, false, [&](const GridView &G) {
    for (Chain &c : sim.chains) {
      g2p_chain(c, G, g, pc, sim.model.iface.tail_share);
      chain_pack(c, part);
      buf.insert(buf.end(), part.begin(), part.end());
    }
  }));
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
  PetscFunctionReturn(0);
}

// 7. Their contact sums over ranks; their kinetic energy, speeds and load power from the points
//    every rank holds (added once, not per rank).
PetscErrorCode Reductions(StepState &S) {
  Simulation &sim = S.sim;
  StepReport &rep = S.rep;
  ContactStats &cs = rep.contact;
  PetscFunctionBeginUser;
  cs.friction.resize(sim.chains.size(), 0.0);
  PetscCall(ReduceContact(sim, cs, cs.friction));
  for (size_t k = 0; k < sim.chains.size(); ++k) sim.chains[k].friction_force = cs.friction[k];
  double ke = 0, v2 = 0, c = 0, pw = 0;
  for (const Chain &ch : sim.chains) {
    c = std::fmax(c, ch.wave_speed());
    for (int i = 0; i < ch.n; ++i) {
      // per radian under -geometry axisymmetric (Chain::ring), as the grid's
      const double *v = &ch.v[i * DIM], s2 = v[0] * v[0] + v[1] * v[1], r = ch.ring(i);
      ke += 0.5 * ch.line_mass * ch.length[i] * r * s2;
      v2 = std::fmax(v2, s2);
      pw += ch.line_weight * ch.length[i] * r * (S.load.gdir[0] * v[0] + S.load.gdir[1] * v[1]);
    }
    const double *v = &ch.v[(ch.n - 1) * DIM];
    if (ch.axisymmetric)
      pw += ch.ring(ch.n - 1) * (ch.end_force[0] * v[0] + ch.end_force[1] * v[1]);
    else
      pw += ch.end_force[0] * v[0] + ch.end_force[1] * v[1];
  }
  report_points(rep, sim.rank, ke, c, v2, pw);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ReduceContact(Simulation &sim, ContactStats &cs, std::vector<double> &per) {
  PetscFunctionBeginUser;
  std::vector<double> sm = {cs.contact_nodes, cs.slip_nodes, cs.separated_nodes, cs.compression,
                            cs.tension};
  sm.insert(sm.end(), per.begin(), per.end());
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sm.data(), static_cast<int>(sm.size()), MPI_DOUBLE,
                             MPI_SUM, sim.comm));
  cs.contact_nodes = sm[0];
  cs.slip_nodes = sm[1];
  cs.separated_nodes = sm[2];
  cs.compression = sm[3];
  cs.tension = sm[4];
  per.assign(sm.begin() + 5, sm.end());
  sim.contact_stats = cs;
  sim.contact_impulse[0] += cs.compression;
  sim.contact_impulse[1] += cs.tension;
  PetscFunctionReturn(0);
}

extern const StepHook chain_hook = [] {
  StepHook h{};
  h.name = "chains";
  h.active = Active;
  h.phases.p2g = ParticlesToGrid;
  h.phases.grid_update = Contact;
  h.phases.after_g2p = GridToPoints;
  h.reduce = Reductions;
  return h;
}();

} // namespace pmpm
