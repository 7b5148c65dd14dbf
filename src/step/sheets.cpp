// 3D sheets (sheet.hpp) in the explicit step under -dim 3: their points' mass, momentum and
// forces into the grid's nodes, the points moved by the owner of their cell and shared by one
// allreduce, their forces from the new positions, and their share of the step's report. Every
// rank holds the whole sheet's points; each computes only the triangles at the points whose
// blocks reach its nodes (LocalTriangles), so the triangles' cost divides among the ranks, and
// SheetsComplete makes them whole where the whole sheet is read (a stage's record, the outputs,
// a checkpoint). An elastoplastic triangle that comes to a rank takes its plastic state from one
// that computed it (RefreshPlasticState). Points
// may be pinned, or held in some components (rollers: the extruded catenary's free edges). A
// sheet alone on the grid (the sheet and extruded catenary scenes) is the grid's only body; a
// sheet between bodies (an extruded scene's chain, extrude.cpp) is a body of its own, and the
// stacked bodies at its nodes are resolved after the momentum balance (sheet_contact.hpp).
#include "pmpm/contact/sheet_contact.hpp"
#include "pmpm/step/step_hooks.hpp"
#include <cmath>
#include <limits>

namespace pmpm {

namespace {
using G3 = GridDofT<3>;
constexpr int NS = UGIMPShape::NS, NN = Weights<UGIMPShape, 3>::NN;

bool Active(const Simulation &sim, const Load &) {
  return !sim.sheets.empty();
}

// The cell holding x (may lie outside the box); a point on the box's upper face (an extruded
// strip's edge at z = depth) is in the last cell. G: the grid or a view of it.
template <class Grid> void CellOf(const Grid &G, const double *x, PetscInt c[3]) {
  for (int d = 0; d < 3; ++d) {
    c[d] = static_cast<PetscInt>(std::floor((x[d] - G.origin[d]) / G.h));
    if (c[d] == G.ncell[d] && x[d] == G.origin[d] + G.ncell[d] * G.h) c[d] = G.ncell[d] - 1;
  }
}

bool InContact(const Simulation &sim) {
  for (const Sheet &s : sim.sheets)
    if (s.in_contact()) return true;
  return false;
}
} // namespace

// Point i's uGIMP weights: a square patch of the sheet one cell wide in its tangent plane, thin
// across it (the chain's one-cell blocks, chain.cpp, with the axis extents of the patch), kept
// inside the box.
void sheet_point_weights(const Sheet &s, int i, const GridViewT<3> &G, Weights<UGIMPShape, 3> &W) {
  const double *x = &s.x[3 * static_cast<size_t>(i)], *n = &s.nrm[3 * static_cast<size_t>(i)];
  double lp[3];
  for (int d = 0; d < 3; ++d) {
    const double lo = x[d] - G.origin[d], hi = G.origin[d] + G.ncell[d] * G.h - x[d];
    const double l = std::fmax(1e-3 * G.h, 0.5 * G.h * std::sqrt(std::fmax(0.0, 1 - n[d] * n[d])));
    lp[d] = std::fmax(1e-6 * G.h, std::fmin(l, std::fmin(lo, hi)));
  }
  weights<UGIMPShape, 3>(x, lp, G.origin, G.h, W);
}

namespace {

// 1a. The points this rank owns (not pinned): mass, momentum, internal force and weight into the
//     grid's body block (the sheet's own block when it lies between bodies, with its normal and
//     area in its slots).
void P2GSheet(const Sheet &s, const LoadT<3> &load, const GridT<3> &g, const GridViewT<3> &G) {
  Weights<UGIMPShape, 3> W;
  const int body = s.body * G3::NDOF;
  for (int i = 0; i < s.n; ++i) {
    const double *x = &s.x[3 * static_cast<size_t>(i)];
    PetscInt c[3];
    CellOf(G, x, c);
    if (s.pinned[i] || !g.owns_cell(c)) continue;
    sheet_point_weights(s, i, G, W);
    const double m = s.mass[i], wt = load.factor * s.weight[i];
    // a held component's forces meet its support's reaction: none reach the grid
    double fext[3], fint[3];
    for (int d = 0; d < 3; ++d) {
      const bool hold = !s.held.empty() && (s.held[i] >> d & 1);
      fext[d] = hold ? 0.0 : wt * load.gdir[d];
      fint[d] = hold ? 0.0 : s.f[3 * i + d];
      if (!s.fend.empty() && !hold) fext[d] += load.factor * s.fend[3 * i + d];
    }
    const double *nrm = &s.nrm[3 * static_cast<size_t>(i)];
    for (int k = 0; k < NN; ++k) {
      const double w = W.w[k];
      if (w == 0.0) continue;
      double *node =
          G.node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS));
      double *nb = node + body;
      nb[G3::M] += w * m;
      for (int d = 0; d < 3; ++d) {
        nb[G3::P + d] += w * m * s.v[3 * i + d];
        nb[G3::F + d] += w * (fint[d] + fext[d]);
        nb[G3::FEXT + d] += w * fext[d];
      }
      if (!s.in_contact()) continue;
      double *ns = node + s.slot;
      for (int d = 0; d < 3; ++d) ns[SheetDof::NX + d] += w * m * s.up * nrm[d];
      ns[SheetDof::AREA] += w * s.area[i];
    }
  }
}

PetscErrorCode ParticlesToGrid(StepStateT<3> &S) {
  GridT<3> &g = S.sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &G) {
    for (const Sheet &s : S.sim.sheets) P2GSheet(s, S.load, g, G);
  }));
  PetscFunctionReturn(0);
}

// 5a. The owner of each point's cell moves it (the grid's velocity and acceleration at the point,
//     FLIP / PIC as the chains', -chain_pic); buf gets, for the points it owns, x, v and 1, and
//     for a sheet between bodies the slip on each face and the pressure on each face (PackWidth);
//     zeros for the others.
int PackWidth(const Sheet &s) {
  return s.in_contact() ? 15 : 7;
}

// Point i's slips and pressures from the bodies beside it (a sheet between bodies): the slip
// rate on a face is the mean over the stencil's nodes where that body holds more than a tail
// share of the node (tail: below it the body moves with the node's common acceleration, not
// its own: sheet_contact.hpp) of the sheet's velocity relative to it, its part in the sheet's
// plane; the pressure is the point's share of its nodes' normal impulses, w A_i / AREA of each,
// over A_i dt. (Counting every node with mass, as the 2D chain does, let a waste block's
// round-off mass of 1e-26 kg at a node of a sloped sheet's toe, its velocity 2e4 m/s, put 0.1 m
// of slip on the point in one step: the extruded side slope's geostatic stage reported 0.11 m
// of slip where the plane's chain has 7 mm.)
void FaceSlipsAndPressures(const Sheet &s, int i, const GridViewT<3> &G,
                           const Weights<UGIMPShape, 3> &W, double dt, double tail_share,
                           double *out) {
  constexpr int ND = G3::NDOF;
  const int body = s.body * ND, above = body + ND, below = body - ND;
  const double *n = &s.nrm[3 * static_cast<size_t>(i)];
  double va[3] = {0, 0, 0}, vb[3] = {0, 0, 0}, ma = 0, mb = 0, nt = 0, nbt = 0;
  for (int k = 0; k < NN; ++k) {
    const double w = W.w[k];
    if (w == 0.0) continue;
    const double *node =
        G.node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS));
    const double *nc = node + body, *na = node + above, *nb = node + below, *ns = node + s.slot;
    const double tail = tail_share * G.body_mass_sum(node);
    if (na[G3::M] > tail) {
      for (int d = 0; d < 3; ++d) va[d] += w * (nc[G3::P + d] - na[G3::P + d]);
      ma += w;
    }
    if (nb[G3::M] > tail) {
      for (int d = 0; d < 3; ++d) vb[d] += w * (nc[G3::P + d] - nb[G3::P + d]);
      mb += w;
    }
    const double share = ns[SheetDof::AREA] > 0 ? w / ns[SheetDof::AREA] : 0.0;
    nt += share * ns[SheetDof::NTOP];
    nbt += share * ns[SheetDof::NBOT];
  }
  const double *st = &s.slip_top[3 * static_cast<size_t>(i)],
               *sb = &s.slip_bot[3 * static_cast<size_t>(i)];
  const double an = ma > 0 ? (va[0] * n[0] + va[1] * n[1] + va[2] * n[2]) : 0.0,
               bn = mb > 0 ? (vb[0] * n[0] + vb[1] * n[1] + vb[2] * n[2]) : 0.0;
  for (int d = 0; d < 3; ++d) {
    out[d] = st[d] + (ma > 0 ? dt * (va[d] - an * n[d]) / ma : 0.0);
    out[3 + d] = sb[d] + (mb > 0 ? dt * (vb[d] - bn * n[d]) / mb : 0.0);
  }
  out[6] = nt / dt;
  out[7] = nbt / dt;
}

void G2PSheet(const Sheet &s, const GridT<3> &g, const GridViewT<3> &G, double dt, double pic,
              double tail_share, std::vector<double> &buf) {
  Weights<UGIMPShape, 3> W;
  const int pw = PackWidth(s), body = s.body * G3::NDOF;
  buf.assign(pw * static_cast<size_t>(s.n), 0.0);
  for (int i = 0; i < s.n; ++i) {
    const double *x = &s.x[3 * static_cast<size_t>(i)], *v = &s.v[3 * static_cast<size_t>(i)];
    PetscInt c[3];
    CellOf(G, x, c);
    if (!g.owns_cell(c)) continue;
    double *out = &buf[pw * static_cast<size_t>(i)];
    out[6] = 1.0;
    if (s.pinned[i]) {
      for (int d = 0; d < 3; ++d) out[d] = x[d];
      continue;
    }
    sheet_point_weights(s, i, G, W);
    double vg[3] = {0, 0, 0}, ag[3] = {0, 0, 0};
    for (int k = 0; k < NN; ++k) {
      const double w = W.w[k];
      if (w == 0.0) continue;
      const double *nb =
          G.node(W.base[0] + k % NS, W.base[1] + (k / NS) % NS, W.base[2] + k / (NS * NS)) + body;
      for (int d = 0; d < 3; ++d) {
        vg[d] += w * nb[G3::P + d];
        ag[d] += w * nb[G3::F + d];
      }
    }
    for (int d = 0; d < 3; ++d) {
      out[d] = x[d] + dt * vg[d];
      out[3 + d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
      if (!s.held.empty() && (s.held[i] >> d & 1)) { // a roller: this component stays
        out[d] = x[d];
        out[3 + d] = 0.0;
      }
    }
    if (s.in_contact()) FaceSlipsAndPressures(s, i, G, W, dt, tail_share, out + 7);
  }
}

// The triangles this rank computes, increasing: those with a corner whose block can reach its
// ghosted nodes. Those points' forces (P2GSheet: the points it owns) and normals (their blocks,
// sheet_point_weights: also sheet_friction_capacity's points in the ghost layers) are then
// exact. A block's first node is the point's cell c or c - 1 (its half-size is under half a cell)
// and it spans three nodes, so only cells gs <= c <= gs + gm - 2 reach the ghosted nodes.
void LocalTriangles(Sheet &s, const GridT<3> &g, std::vector<char> &near, std::vector<int> &tris) {
  near.assign(s.n, 0);
  s.reach.clear();
  for (int i = 0; i < s.n; ++i) {
    PetscInt c[3];
    CellOf(g, &s.x[3 * static_cast<size_t>(i)], c);
    bool in = true;
    for (int d = 0; d < 3; ++d) in = in && c[d] >= g.gs[d] && c[d] <= g.gs[d] + g.gm[d] - 2;
    near[i] = in || g.owns_cell(c);
    if (near[i]) s.reach.push_back(i);
  }
  tris.clear();
  for (int t = 0; t < s.nt; ++t) {
    const int *v = &s.tri[3 * static_cast<size_t>(t)];
    if (near[v[0]] || near[v[1]] || near[v[2]]) tris.push_back(t);
  }
}

// An elastoplastic triangle's plastic state is history: a rank that computes a triangle it did
// not compute at the last step (a point crossed into its cells) takes the state from a rank that
// did (the lowest), before the step's update. Every triangle was computed by some rank (every
// point has an owner), so the state taken is the last step's. Two allreduces over the triangles,
// only at the steps where some rank's set changes.
PetscErrorCode RefreshPlasticState(Sheet &s, const std::vector<int> &tris, MPI_Comm comm) {
  PetscFunctionBeginUser;
  int stale = 0;
  for (const int t : tris) stale |= !s.fresh[t];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_INT, MPI_LOR, comm));
  if (!stale) PetscFunctionReturn(0);
  PetscCall(PetscInfo(nullptr, "sheet %s: plastic state shared (a rank's triangles changed)\n",
                      s.name.c_str()));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<int> from(s.nt);
  for (int t = 0; t < s.nt; ++t) from[t] = s.fresh[t] ? rank : std::numeric_limits<int>::max();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, from.data(), s.nt, MPI_INT, MPI_MIN, comm));
  std::vector<double> state(4 * static_cast<size_t>(s.nt), 0.0);
  for (int t = 0; t < s.nt; ++t) {
    PetscCheck(from[t] != std::numeric_limits<int>::max(), comm, PETSC_ERR_PLIB,
               "sheet %s: triangle %d was computed by no rank at the last step", s.name.c_str(), t);
    if (from[t] != rank) continue;
    for (int k = 0; k < 3; ++k) state[4 * static_cast<size_t>(t) + k] = s.bp[3 * t + k];
    state[4 * static_cast<size_t>(t) + 3] = s.alpha[t];
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, state.data(), static_cast<int>(state.size()), MPI_DOUBLE,
                             MPI_SUM, comm));
  for (int t = 0; t < s.nt; ++t) {
    for (int k = 0; k < 3; ++k) s.bp[3 * t + k] = state[4 * static_cast<size_t>(t) + k];
    s.alpha[t] = state[4 * static_cast<size_t>(t) + 3];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode GridToPoints(StepStateT<3> &S) {
  Simulation &sim = S.sim;
  GridT<3> &g = sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  const double pic = sim.set.chain_pic < 0 ? S.pp.pic : sim.set.chain_pic;
  std::vector<double> &buf = sim.scratch.chain_buf;
  for (Sheet &s : sim.sheets) {
    PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &G) {
      G2PSheet(s, g, G, S.dt, pic, sim.model.iface.tail_share, buf);
    }));
    {
      PmpmLogEventScope(step_events.sheet_share);
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE,
                                 MPI_SUM, sim.comm));
    }
    const int pw = PackWidth(s);
    int owners = 0;
    for (int i = 0; i < s.n; ++i) {
      const double *b = &buf[pw * static_cast<size_t>(i)];
      owners += b[6] == 1.0;
      for (int d = 0; d < 3; ++d) {
        s.x[3 * i + d] = b[d];
        s.v[3 * i + d] = b[3 + d];
      }
      if (s.in_contact() && !s.pinned[i]) {
        for (int d = 0; d < 3; ++d) {
          s.slip_top[3 * i + d] = b[7 + d];
          s.slip_bot[3 * i + d] = b[10 + d];
        }
        s.p_top[i] = b[13];
        s.p_bot[i] = b[14];
      }
      PetscCheck(std::isfinite(b[0] + b[1] + b[2] + b[3] + b[4] + b[5]), sim.comm,
                 PETSC_ERR_NOT_CONVERGED,
                 "Instability at step %" PetscInt_FMT ": sheet point %d (initially at (%g, %g, %g) "
                 "m) has a non-finite position or velocity. Reduce -cfl (now %g) or raise "
                 "-damping_alpha.",
                 sim.run.step, i, s.x0[3 * i], s.x0[3 * i + 1], s.x0[3 * i + 2], sim.set.cfl);
    }
    PetscCheck(owners == s.n, sim.comm, PETSC_ERR_NOT_CONVERGED,
               "Instability at step %" PetscInt_FMT ": the sheet has %d of its %d points off the "
               "grid. Enlarge the grid or reduce -cfl (now %g).",
               sim.run.step, s.n - owners, s.n, sim.set.cfl);
    PmpmLogEventScope(step_events.sheet_forces);
    if (sim.size == 1) {
      sheet_update_forces(s);
      sheet_normals(s);
      continue;
    }
    std::vector<int> &tris = sim.scratch.sheet_tris;
    LocalTriangles(s, g, sim.scratch.sheet_near, tris);
    if (s.law == SheetLaw::Elastoplastic) PetscCall(RefreshPlasticState(s, tris, sim.comm));
    sheet_update_forces(s, tris);
    sheet_normals(s, tris);
  }
  PetscFunctionReturn(0);
}

// 3a. Stacked bodies at the nodes of the sheets between bodies: the normal impulses, their
//     ghosts, the friction capacity they give each face, then the contact (chains.cpp's Contact).
PetscErrorCode Contact(StepStateT<3> &S) {
  Simulation &sim = S.sim;
  GridT<3> &g = sim.grid3;
  PetscFunctionBeginUser;
  if (!InContact(sim)) PetscFunctionReturn(0);
  PmpmLogEventScope(step_events.contact);
  SheetContactParams cp;
  cp.dt = S.dt;
  cp.tail_share = sim.model.iface.tail_share;
  cp.chain_tail_share = sim.model.contact.chain_tail_share;
  for (int f = 0; f < 6; ++f) cp.face[f] = sim.model.face[f];
  contact_sheets(S.G, sim.sheets, cp, true, S.rep.contact);
  PetscCall(GridRestoreGlobal(g, S.G));
  PetscCall(GridGlobalToLocal(g));
  PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &L) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(GridGetGlobal(g, S.G)); // the step's global view, again for the contact below
    sheet_friction_capacity(L, S.G, sim.sheets);
    PetscFunctionReturn(0);
  }));
  contact_sheets(S.G, sim.sheets, cp, false, S.rep.contact);
  PetscFunctionReturn(0);
}

// 7. Their contact sums over ranks (sheets between bodies); their kinetic energy, speeds and
//    load power from the points every rank holds (added once).
PetscErrorCode Reductions(StepState &S) {
  Simulation &sim = S.sim;
  StepReport &rep = S.rep;
  PetscFunctionBeginUser;
  if (InContact(sim)) {
    rep.contact.friction3.resize(3 * sim.sheets.size(), 0.0);
    PetscCall(ReduceContact(sim, rep.contact, rep.contact.friction3));
  }
  double ke = 0, v2 = 0, c = 0, pw = 0;
  const double gz = sim.set.gdir_z;
  for (const Sheet &s : sim.sheets) {
    c = std::fmax(c, s.wave_speed());
    for (int i = 0; i < s.n; ++i) {
      const double *v = &s.v[3 * static_cast<size_t>(i)];
      const double s2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      ke += 0.5 * s.mass[i] * s2;
      v2 = std::fmax(v2, s2);
      // at full weight: the budget multiplies by the load factor (relaxation.cpp, LoadWork)
      pw += s.weight[i] * (S.load.gdir[0] * v[0] + S.load.gdir[1] * v[1] + gz * v[2]);
      if (!s.fend.empty())
        pw += s.fend[3 * i] * v[0] + s.fend[3 * i + 1] * v[1] + s.fend[3 * i + 2] * v[2];
    }
  }
  report_points(rep, sim.rank, ke, c, v2, pw);
  PetscFunctionReturn(0);
}
} // namespace

namespace {
// A triangle's arrays (sheet.hpp), packed for SheetsComplete: strains, principal strains and
// tensions, the forces' tensor, P, the state, and an elastoplastic sheet's plastic state.
constexpr int kRecord = 3 + 2 + 2 + 3 + 6 + 1 + 4;
template <class F> void TriangleRecord(Sheet &s, int t, F &&f) {
  const size_t T = static_cast<size_t>(t);
  for (int k = 0; k < 3; ++k) f(s.biot[3 * T + k]);
  for (int k = 0; k < 2; ++k) f(s.b[2 * T + k]);
  for (int k = 0; k < 2; ++k) f(s.N[2 * T + k]);
  for (int k = 0; k < 3; ++k) f(s.tens[3 * T + k]);
  for (int k = 0; k < 6; ++k) f(s.P[6 * T + k]);
  double state = static_cast<double>(s.state[t]);
  f(state);
  s.state[t] = static_cast<SheetState>(static_cast<int>(state));
  double none = 0;
  const bool plastic = s.law == SheetLaw::Elastoplastic;
  for (int k = 0; k < 3; ++k) f(plastic ? s.bp[3 * T + k] : none);
  f(plastic ? s.alpha[t] : none);
}
} // namespace

PetscErrorCode SheetsComplete(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.size == 1) PetscFunctionReturn(0);
  for (Sheet &s : sim.sheets) {
    int stale = 0;
    for (int t = 0; t < s.nt; ++t) stale |= !s.fresh[t];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_INT, MPI_LOR, sim.comm));
    if (!stale) continue;
    // each triangle's arrays from the lowest rank that computed it at the last step
    std::vector<int> from(s.nt);
    for (int t = 0; t < s.nt; ++t)
      from[t] = s.fresh[t] ? sim.rank : std::numeric_limits<int>::max();
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, from.data(), s.nt, MPI_INT, MPI_MIN, sim.comm));
    std::vector<double> buf(kRecord * static_cast<size_t>(s.nt), 0.0);
    for (int t = 0; t < s.nt; ++t) {
      if (from[t] != sim.rank) continue;
      double *b = &buf[kRecord * static_cast<size_t>(t)];
      TriangleRecord(s, t, [&](double &v) { *b++ = v; });
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE,
                               MPI_SUM, sim.comm));
    for (int t = 0; t < s.nt; ++t) {
      if (s.fresh[t]) continue;
      const double *b = &buf[kRecord * static_cast<size_t>(t)];
      TriangleRecord(s, t, [&](double &v) { v = *b++; });
    }
    sheet_sum_forces(s);
    sheet_normals(s);
  }
  // the next step may run on another partition (-balance run): every point, until it computes
  // its own list again
  for (Sheet &s : sim.sheets) s.reach.clear();
  PetscFunctionReturn(0);
}

// The sheets' forces and weight on the 3D grid, for the static residual (cycle.cpp).
void p2g_sheets(const Simulation &sim, const LoadT<3> &load, const GridViewT<3> &G) {
  for (const Sheet &s : sim.sheets) P2GSheet(s, load, sim.grid3, G);
}

extern const StepHook sheet_hook = [] {
  StepHook h{};
  h.name = "sheets";
  h.active = Active;
  h.phases3.p2g = ParticlesToGrid;
  h.phases3.grid_update = Contact;
  h.phases3.after_g2p = GridToPoints;
  h.reduce = Reductions;
  return h;
}();

} // namespace pmpm
