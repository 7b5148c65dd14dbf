// 3D sheets (sheet.hpp) in the explicit step under -dim 3: their points' mass, momentum and
// forces into the grid's nodes, the points moved by the owner of their cell and sent to the
// ranks around it (ShareWithNeighbours), their forces from the new positions, and their share of
// the step's report. Every rank holds arrays for the whole sheet, current for the points of its
// own and its neighbours' cells (Sheet::here); each computes only the triangles at the points
// whose blocks reach its nodes (LocalTriangles), and SheetsComplete makes the sheet whole where
// it is read whole (a stage's record, the outputs, a checkpoint). An elastoplastic triangle that
// comes to a rank takes its plastic state from one that computed it (RefreshPlasticState). Points
// may be pinned, or held in some components (rollers: the extruded catenary's free edges). A
// sheet alone on the grid (the sheet and extruded catenary scenes) is the grid's only body; a
// sheet between bodies (an extruded scene's chain, extrude.cpp) is a body of its own, and the
// stacked bodies at its nodes are resolved after the momentum balance (sheet_contact.hpp).
#include "pmpm/contact/sheet_contact.hpp"
#include "pmpm/step/step_hooks.hpp"
#include <algorithm>
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

// Whether this rank owns the cell holding x (the rank that moves a point there).
bool OwnsPoint(const GridT<3> &g, const double *x) {
  PetscInt c[3];
  CellOf(g, x, c);
  return g.owns_cell(c);
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
  const int m_pts = s.mine_valid ? static_cast<int>(s.mine.size()) : s.n;
  for (int k0 = 0; k0 < m_pts; ++k0) {
    const int i = s.mine_valid ? s.mine[k0] : k0;
    // without mine (every point is current here then): the points in this rank's cells
    if (!s.mine_valid && !OwnsPoint(g, &s.x[3 * static_cast<size_t>(i)])) continue;
    if (s.pinned[i]) continue;
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

// The points this rank moves, from every point's position (after the set-up, a restart or
// SheetsComplete, when every point is current on every rank).
void EnsureMine(Sheet &s, const GridT<3> &g) {
  if (s.mine_valid) return;
  s.mine.clear();
  for (int i = 0; i < s.n; ++i)
    if (OwnsPoint(g, &s.x[3 * static_cast<size_t>(i)])) s.mine.push_back(i);
  s.mine_valid = true;
}

PetscErrorCode ParticlesToGrid(StepStateT<3> &S) {
  GridT<3> &g = S.sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  for (Sheet &s : S.sim.sheets) EnsureMine(s, g);
  PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &G) {
    for (const Sheet &s : S.sim.sheets) P2GSheet(s, S.load, g, G);
  }));
  PetscFunctionReturn(0);
}

// 5a. The owner of each point's cell moves it (the grid's velocity and acceleration at the point,
//     FLIP / PIC as the chains', -chain_pic); rec gets a record per point it moves (s.mine): the
//     point's index, then x and v, and for a sheet between bodies the slip on each face and the
//     pressure on each face (PackWidth values).
int PackWidth(const Sheet &s) {
  return s.in_contact() ? 14 : 6;
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

void G2PSheet(const Sheet &s, const GridViewT<3> &G, double dt, double pic, double tail_share,
              std::vector<double> &rec) {
  Weights<UGIMPShape, 3> W;
  const int pw = PackWidth(s), body = s.body * G3::NDOF;
  rec.assign((1 + pw) * s.mine.size(), 0.0);
  for (size_t k0 = 0; k0 < s.mine.size(); ++k0) {
    const int i = s.mine[k0];
    const double *x = &s.x[3 * static_cast<size_t>(i)], *v = &s.v[3 * static_cast<size_t>(i)];
    rec[(1 + pw) * k0] = i;
    double *out = &rec[(1 + pw) * k0 + 1];
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
    if (s.in_contact()) FaceSlipsAndPressures(s, i, G, W, dt, tail_share, out + 6);
  }
}

// The triangles this rank computes, increasing: those with a corner whose block can reach its
// ghosted nodes. Those points' forces (P2GSheet: the points it owns) and normals (their blocks,
// sheet_point_weights: also sheet_friction_capacity's points in the ghost layers) are then
// exact. A block's first node is the point's cell c or c - 1 (its half-size is under half a cell)
// and it spans three nodes, so only cells gs <= c <= gs + gm - 2 reach the ghosted nodes; those
// cells are this rank's or its neighbours' (a rank's cells are at least a stencil wide), whose
// points it holds current (s.here). Also sets s.reach (those points) and s.mine (the points in
// its own cells). Returns whether a listed triangle has a corner this rank does not hold current
// (a triangle reaching past the neighbours: the step then shares every point).
bool LocalTriangles(Sheet &s, const GridT<3> &g, std::vector<char> &near, std::vector<int> &tris) {
  near.assign(s.n, 0);
  s.reach.clear();
  s.mine.clear();
  const bool all = s.here.empty();
  for (int i = 0; i < s.n; ++i) {
    if (!all && !s.here[i]) continue;
    PetscInt c[3];
    CellOf(g, &s.x[3 * static_cast<size_t>(i)], c);
    const bool own = g.owns_cell(c);
    bool in = true;
    for (int d = 0; d < 3; ++d) in = in && c[d] >= g.gs[d] && c[d] <= g.gs[d] + g.gm[d] - 2;
    near[i] = in || own;
    if (near[i]) s.reach.push_back(i);
    if (own) s.mine.push_back(i);
  }
  s.mine_valid = true;
  tris.clear();
  bool missing = false;
  for (int t = 0; t < s.nt; ++t) {
    const int *v = &s.tri[3 * static_cast<size_t>(t)];
    if (!(near[v[0]] || near[v[1]] || near[v[2]])) continue;
    tris.push_back(t);
    if (!all) missing = missing || !s.here[v[0]] || !s.here[v[1]] || !s.here[v[2]];
  }
  return missing;
}

// The ranks beside this one on the grid (DMDAGetNeighbors: the 26 around it, without itself and
// the box's outside), each once; and whether every rank is at least kWide nodes wide in each
// direction. The points a rank needs (those of its cells and of the cells within two of them,
// LocalTriangles) are then all moved by it or by a neighbour: a point moves less than a cell a
// step, and a rank two away has its cells at least kWide away. On a thinner split every rank
// takes every point (ShareWithAll), as before the points were shared with neighbours only.
constexpr PetscInt kWide = 4;
PetscErrorCode Neighbours(const GridT<3> &g, PetscMPIInt rank, std::vector<PetscMPIInt> &nb,
                          bool *wide) {
  const PetscMPIInt *r;
  const PetscInt *l[3];
  PetscInt p[3];
  PetscFunctionBeginUser;
  PetscCall(DMDAGetNeighbors(g.da, &r));
  nb.clear();
  for (int k = 0; k < 27; ++k)
    if (r[k] >= 0 && r[k] != rank && std::find(nb.begin(), nb.end(), r[k]) == nb.end())
      nb.push_back(r[k]);
  std::sort(nb.begin(), nb.end());
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da, &l[0], &l[1], &l[2]));
  *wide = true;
  for (int d = 0; d < 3; ++d)
    for (PetscInt q = 0; q < p[d] && p[d] > 1; ++q) *wide = *wide && l[d][q] >= kWide;
  PetscFunctionReturn(0);
}

// Records (G2PSheet's) into the sheet: positions, velocities and, between bodies, the slips and
// pressures; each point marked current. Returns the index of a point with a non-finite position
// or velocity, or -1.
int Unpack(Sheet &s, const double *rec, size_t nrec) {
  const int pw = PackWidth(s);
  int bad = -1;
  for (size_t k = 0; k < nrec; ++k) {
    const double *r = rec + (1 + pw) * k;
    const int i = static_cast<int>(r[0]);
    const double *b = r + 1;
    for (int d = 0; d < 3; ++d) {
      s.x[3 * i + d] = b[d];
      s.v[3 * i + d] = b[3 + d];
    }
    if (s.in_contact() && !s.pinned[i]) {
      for (int d = 0; d < 3; ++d) {
        s.slip_top[3 * i + d] = b[6 + d];
        s.slip_bot[3 * i + d] = b[9 + d];
      }
      s.p_top[i] = b[12];
      s.p_bot[i] = b[13];
    }
    if (!s.here.empty()) s.here[i] = 1;
    if (bad < 0 && !std::isfinite(b[0] + b[1] + b[2] + b[3] + b[4] + b[5])) bad = i;
  }
  return bad;
}

// The records of the points this rank moves (s.mine) as they are now (SheetsComplete).
void Pack(const Sheet &s, std::vector<double> &rec) {
  const int pw = PackWidth(s);
  rec.assign((1 + pw) * s.mine.size(), 0.0);
  for (size_t k = 0; k < s.mine.size(); ++k) {
    const int i = s.mine[k];
    double *r = &rec[(1 + pw) * k];
    r[0] = i;
    for (int d = 0; d < 3; ++d) {
      r[1 + d] = s.x[3 * i + d];
      r[4 + d] = s.v[3 * i + d];
    }
    if (!s.in_contact()) continue;
    for (int d = 0; d < 3; ++d) {
      r[7 + d] = s.slip_top[3 * i + d];
      r[10 + d] = s.slip_bot[3 * i + d];
    }
    r[13] = s.p_top[i];
    r[14] = s.p_bot[i];
  }
}

// Each rank's records to its neighbours and theirs to it (the points of the cells around its
// own), into `in`.
PetscErrorCode ShareWithNeighbours(const std::vector<PetscMPIInt> &nb,
                                   const std::vector<double> &rec, MPI_Comm comm,
                                   std::vector<std::vector<double>> &in) {
  const int nn = static_cast<int>(nb.size()), tag = 7301;
  std::vector<int> count(nn), mine(nn, static_cast<int>(rec.size()));
  std::vector<MPI_Request> rq(2 * static_cast<size_t>(nn));
  PetscFunctionBeginUser;
  for (int k = 0; k < nn; ++k) {
    PetscCallMPI(MPI_Irecv(&count[k], 1, MPI_INT, nb[k], tag, comm, &rq[k]));
    PetscCallMPI(MPI_Isend(&mine[k], 1, MPI_INT, nb[k], tag, comm, &rq[nn + k]));
  }
  PetscCallMPI(MPI_Waitall(2 * nn, rq.data(), MPI_STATUSES_IGNORE));
  in.resize(nn);
  for (int k = 0; k < nn; ++k) {
    in[k].resize(count[k]);
    PetscCallMPI(MPI_Irecv(in[k].data(), count[k], MPI_DOUBLE, nb[k], tag + 1, comm, &rq[k]));
    PetscCallMPI(MPI_Isend(rec.data(), mine[k], MPI_DOUBLE, nb[k], tag + 1, comm, &rq[nn + k]));
  }
  PetscCallMPI(MPI_Waitall(2 * nn, rq.data(), MPI_STATUSES_IGNORE));
  PetscFunctionReturn(0);
}

// Every rank's records to every rank (the step whose triangles reach past the neighbours, and
// SheetsComplete).
PetscErrorCode ShareWithAll(const std::vector<double> &rec, MPI_Comm comm,
                            std::vector<double> &all) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> count(size), displ(size + 1, 0);
  const int n = static_cast<int>(rec.size());
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, count.data(), 1, MPI_INT, comm));
  for (int r = 0; r < size; ++r) displ[r + 1] = displ[r] + count[r];
  all.resize(displ[size]);
  PetscCallMPI(MPI_Allgatherv(rec.data(), n, MPI_DOUBLE, all.data(), count.data(), displ.data(),
                              MPI_DOUBLE, comm));
  PetscFunctionReturn(0);
}

// A triangle's arrays (sheet.hpp) for SheetsComplete: strains, principal strains and tensions,
// the forces' tensor, P, the state, and an elastoplastic sheet's plastic state; f visits each.
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
// An elastoplastic triangle's plastic state alone.
constexpr int kPlasticRecord = 4;
template <class F> void PlasticRecord(Sheet &s, int t, F &&f) {
  for (int k = 0; k < 3; ++k) f(s.bp[3 * static_cast<size_t>(t) + k]);
  f(s.alpha[t]);
}

// Each triangle this rank did not compute at the last step (not fresh) takes the `width` values
// `record` visits from the lowest rank that did: one allreduce of an int per triangle, one of
// `width` doubles per triangle. Every triangle was computed by some rank (every point has an
// owner). Collective.
template <class Record>
PetscErrorCode TakeFromLowestFresh(Sheet &s, MPI_Comm comm, int width, Record &&record) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<int> from(s.nt);
  for (int t = 0; t < s.nt; ++t) from[t] = s.fresh[t] ? rank : std::numeric_limits<int>::max();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, from.data(), s.nt, MPI_INT, MPI_MIN, comm));
  std::vector<double> buf(width * static_cast<size_t>(s.nt), 0.0);
  for (int t = 0; t < s.nt; ++t) {
    PetscCheck(from[t] != std::numeric_limits<int>::max(), comm, PETSC_ERR_PLIB,
               "sheet %s: triangle %d was computed by no rank at the last step", s.name.c_str(), t);
    if (from[t] != rank) continue;
    double *b = &buf[width * static_cast<size_t>(t)];
    record(s, t, [&](double &v) { *b++ = v; });
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE,
                             MPI_SUM, comm));
  for (int t = 0; t < s.nt; ++t) {
    if (s.fresh[t]) continue;
    const double *b = &buf[width * static_cast<size_t>(t)];
    record(s, t, [&](double &v) { v = *b++; });
  }
  PetscFunctionReturn(0);
}

// An elastoplastic triangle's plastic state is history: a rank that computes a triangle it did
// not compute at the last step (a point crossed into its cells) takes the state from a rank that
// did, before the step's update; the state taken is the last step's. Only at the steps where
// some rank's set changes.
PetscErrorCode RefreshPlasticState(Sheet &s, const std::vector<int> &tris, MPI_Comm comm) {
  PetscFunctionBeginUser;
  int stale = 0;
  for (const int t : tris) stale |= !s.fresh[t];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_INT, MPI_LOR, comm));
  if (!stale) PetscFunctionReturn(0);
  PetscCall(PetscInfo(nullptr, "sheet %s: plastic state shared (a rank's triangles changed)\n",
                      s.name.c_str()));
  PetscCall(TakeFromLowestFresh(s, comm, kPlasticRecord,
                                [](Sheet &sh, int t, auto &&f) { PlasticRecord(sh, t, f); }));
  PetscFunctionReturn(0);
}

PetscErrorCode GridToPoints(StepStateT<3> &S) {
  Simulation &sim = S.sim;
  GridT<3> &g = sim.grid3;
  PetscFunctionBeginUser;
  PmpmLogEventScope(step_events.chain);
  const double pic = sim.set.chain_pic < 0 ? S.pp.pic : sim.set.chain_pic;
  std::vector<double> &rec = sim.scratch.chain_buf;
  for (Sheet &s : sim.sheets) {
    PetscCall(GridWithLocal(g, false, [&](const GridViewT<3> &G) {
      G2PSheet(s, G, S.dt, pic, sim.model.iface.tail_share, rec);
    }));
    const int pw = PackWidth(s);
    const size_t nrec = rec.size() / (1 + pw);
    int bad = Unpack(s, rec.data(), nrec);
    int check[3] = {static_cast<int>(nrec), 0, bad >= 0 ? bad + 1 : 0};
    std::vector<int> &tris = sim.scratch.sheet_tris;
    if (sim.size > 1) {
      // the points of the cells around this rank's, from its neighbours
      std::vector<std::vector<double>> in(1);
      bool wide = false;
      {
        PmpmLogEventScope(step_events.sheet_share);
        std::vector<PetscMPIInt> nb;
        PetscCall(Neighbours(g, sim.rank, nb, &wide));
        if (wide)
          PetscCall(ShareWithNeighbours(nb, rec, sim.comm, in));
        else
          PetscCall(ShareWithAll(rec, sim.comm, in[0]));
      }
      if (wide) {
        s.here.assign(s.n, 0);
        for (const int i : s.mine) s.here[i] = 1; // the records' points (the last step's mine)
      } else {
        s.here.clear();
      }
      for (const std::vector<double> &r : in) {
        const int b2 = Unpack(s, r.data(), r.size() / (1 + pw));
        if (check[2] == 0 && b2 >= 0) check[2] = b2 + 1;
      }
      check[1] = LocalTriangles(s, g, sim.scratch.sheet_near, tris);
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, check, 2, MPI_INT, MPI_SUM, sim.comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, check + 2, 1, MPI_INT, MPI_MAX, sim.comm));
    if (check[2] > 0) {
      const int i = check[2] - 1;
      SETERRQ(sim.comm, PETSC_ERR_NOT_CONVERGED,
              "Instability at step %" PetscInt_FMT ": sheet point %d (initially at (%g, %g, %g) "
              "m) has a non-finite position or velocity. Reduce -cfl (now %g) or raise "
              "-damping_alpha.",
              sim.run.step, i, s.x0[3 * i], s.x0[3 * i + 1], s.x0[3 * i + 2], sim.set.cfl);
    }
    PetscCheck(check[0] == s.n, sim.comm, PETSC_ERR_NOT_CONVERGED,
               "Instability at step %" PetscInt_FMT ": the sheet has %d of its %d points off the "
               "grid. Enlarge the grid or reduce -cfl (now %g).",
               sim.run.step, s.n - check[0], s.n, sim.set.cfl);
    if (check[1] > 0) { // a triangle reaches past the neighbours: every point, this step
      PetscCall(PetscInfo(nullptr,
                          "sheet %s: a triangle reaches past a rank's neighbours at step "
                          "%" PetscInt_FMT ": every point shared\n",
                          s.name.c_str(), sim.run.step));
      std::vector<double> all;
      PetscCall(ShareWithAll(rec, sim.comm, all));
      Unpack(s, all.data(), all.size() / (1 + pw));
      s.here.clear();
      LocalTriangles(s, g, sim.scratch.sheet_near, tris);
    }
    PmpmLogEventScope(step_events.sheet_forces);
    if (sim.size == 1) {
      sheet_update_forces(s);
      sheet_normals(s);
      s.mine_valid = false; // from the new positions at the next P2G
      continue;
    }
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
  // one rank: every point; under MPI the points each rank moves (the others' velocities may be
  // a step old here), summed over the ranks
  const bool split = sim.size > 1;
  for (const Sheet &s : sim.sheets) {
    c = std::fmax(c, s.wave_speed());
    const int m = split ? static_cast<int>(s.mine.size()) : s.n;
    for (int k = 0; k < m; ++k) {
      const int i = split ? s.mine[k] : k;
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
  if (split) {
    double sum[2] = {ke, pw};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, sim.comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v2, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
    ke = sum[0];
    pw = sum[1];
  }
  report_points(rep, sim.rank, ke, c, v2, pw);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode SheetsComplete(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.size == 1) PetscFunctionReturn(0);
  for (Sheet &s : sim.sheets) {
    // every point from the rank that moves it
    int partial = 0;
    for (size_t i = 0; i < s.here.size(); ++i) partial |= !s.here[i];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &partial, 1, MPI_INT, MPI_LOR, sim.comm));
    if (partial) {
      std::vector<double> rec, all;
      Pack(s, rec);
      PetscCall(ShareWithAll(rec, sim.comm, all));
      Unpack(s, all.data(), all.size() / (1 + PackWidth(s)));
    }
    s.here.clear();
    int stale = 0;
    for (int t = 0; t < s.nt; ++t) stale |= !s.fresh[t];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_INT, MPI_LOR, sim.comm));
    if (!stale) continue;
    // each triangle's arrays from the lowest rank that computed it at the last step
    PetscCall(TakeFromLowestFresh(s, sim.comm, kRecord,
                                  [](Sheet &sh, int t, auto &&f) { TriangleRecord(sh, t, f); }));
    sheet_sum_forces(s);
    sheet_normals(s);
  }
  // the next step may run on another partition (-balance run): every point, until it computes
  // its own lists again
  for (Sheet &s : sim.sheets) {
    s.reach.clear();
    s.mine_valid = false;
  }
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
