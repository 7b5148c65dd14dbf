#include "pmpm/util/options.hpp"
#include "pmpm/model/balance.hpp"
#include "pmpm/util/json.hpp"
#include "pmpm/core/particle_records.hpp"
#include "pmpm/model/simulation.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

namespace {
PetscLogEvent ev_balance = 0;

std::string json_array(const std::vector<PetscInt> &a) {
  std::string s = "[";
  for (size_t k = 0; k < a.size(); ++k) s += (k ? ", " : "") + std::to_string(a[k]);
  return s + "]";
}

// Cell bounds of the rank columns (rows): column i owns cells [b[i], b[i+1]). A particle centred
// in cell c belongs to the rank owning node c + 1 (Grid::owns_cell), so a column owning nodes
// [s, s + l) owns cells [s - 1, s + l - 1), the first from 0 and the last to ncell.
std::vector<PetscInt> CellBounds(const PetscInt *l, PetscInt np, PetscInt ncell) {
  std::vector<PetscInt> b(np + 1, 0);
  PetscInt s = 0;
  for (PetscInt i = 0; i + 1 < np; ++i) {
    s += l[i];
    b[i + 1] = s - 1;
  }
  b[np] = ncell;
  return b;
}

// The inverse: node counts per column from cell bounds.
std::vector<PetscInt> NodeCounts(const std::vector<PetscInt> &b) {
  const size_t np = b.size() - 1;
  std::vector<PetscInt> l(np);
  for (size_t i = 0; i < np; ++i)
    l[i] = (i + 1 < np ? b[i + 1] + 1 : b[np] + 1) - (i == 0 ? 0 : b[i] + 1);
  return l;
}

// Cut per-cell counts into np parts of near-equal sums at the cumulative quantiles. Every part is
// at least kMinCells wide, so every rank owns at least two nodes (DMDA's minimum for stencil
// width 2); among cuts equally close to a quantile (a run of empty cells) the one nearest the
// even split of cells. Empty if the cells are too few.
constexpr PetscInt kMinCells = 2;
std::vector<PetscInt> SplitCounts(const double *cnt, PetscInt ncell, PetscInt np) {
  std::vector<double> cum(ncell + 1, 0.0);
  for (PetscInt c = 0; c < ncell; ++c) cum[c + 1] = cum[c] + cnt[c];
  std::vector<PetscInt> b(np + 1, 0);
  b[np] = ncell;
  for (PetscInt i = 1; i < np; ++i) {
    const PetscInt lo = b[i - 1] + kMinCells, hi = ncell - kMinCells * (np - i);
    if (lo > hi) return {};
    const double target = cum[ncell] * i / np, even = (double)ncell * i / np;
    PetscInt best = lo;
    for (PetscInt k = lo; k <= hi; ++k) {
      const double dk = std::fabs(cum[k] - target), db = std::fabs(cum[best] - target);
      if (dk < db || (dk == db && std::fabs(k - even) < std::fabs(best - even))) best = k;
    }
    b[i] = best;
  }
  return b;
}

// The cell of a particle centre (as the scenes place it), clamped to the grid.
PetscInt CellOf(const Simulation &sim, const double *x, int d) {
  const PetscInt c = (PetscInt)std::floor((x[d] - sim.model.origin[d]) / sim.set.h);
  return std::min(std::max(c, (PetscInt)0), sim.model.ncell[d] - 1);
}

// max / mean of per-rank counts.
double Imbalance(const std::vector<double> &counts) {
  double total = 0, most = 0;
  for (double c : counts) {
    total += c;
    most = std::max(most, c);
  }
  return total > 0 ? most / (total / counts.size()) : 1.0;
}

// The particle-balanced partition of px x py ranks for the particles items[k] (positions by
// pos(item)): cell bounds per rank column and row (empty if the cells are too few) and the
// imbalance it would have. Every rank bins its own particles. -dim 3: g3 is the 3D grid, whose z
// slabs stay (bz, its cell bounds) while the x and y cuts follow the particles.
template <class Items, class Pos>
PetscErrorCode Plan(const Simulation &sim, PetscInt px, PetscInt py, const Items &items, Pos pos,
                    std::vector<PetscInt> &bx, std::vector<PetscInt> &by, double *predicted,
                    const GridT<3> *g3 = nullptr, const std::vector<PetscInt> &bz = {}) {
  PetscFunctionBeginUser;
  // particles per cell column, then per cell row
  const PetscInt nx = sim.model.ncell[0], ny = sim.model.ncell[1];
  std::vector<double> cnt(nx + ny, 0.0);
  for (const auto &q : items) {
    cnt[CellOf(sim, pos(q), 0)] += 1;
    cnt[nx + CellOf(sim, pos(q), 1)] += 1;
  }
  PetscCallMPI(
      MPI_Allreduce(MPI_IN_PLACE, cnt.data(), (int)cnt.size(), MPI_DOUBLE, MPI_SUM, sim.comm));
  bx = SplitCounts(cnt.data(), nx, px);
  by = SplitCounts(cnt.data() + nx, ny, py);
  *predicted = 1e300;
  if (bx.empty() || by.empty()) {
    bx.clear();
    PetscFunctionReturn(0);
  }
  const PetscInt pz = g3 ? static_cast<PetscInt>(bz.size()) - 1 : 1;
  std::vector<double> blk(px * py * pz, 0.0);
  for (const auto &q : items) {
    const PetscInt i =
        std::upper_bound(bx.begin(), bx.end(), CellOf(sim, pos(q), 0)) - bx.begin() - 1;
    const PetscInt j =
        std::upper_bound(by.begin(), by.end(), CellOf(sim, pos(q), 1)) - by.begin() - 1;
    PetscInt k = 0;
    if (g3) {
      PetscInt cz = static_cast<PetscInt>(std::floor((pos(q)[2] - g3->origin[2]) / g3->h));
      cz = std::min(std::max(cz, PetscInt(0)), g3->ncell[2] - 1);
      k = std::upper_bound(bz.begin(), bz.end(), cz) - bz.begin() - 1;
    }
    blk[(k * py + j) * px + i] += 1;
  }
  PetscCallMPI(
      MPI_Allreduce(MPI_IN_PLACE, blk.data(), (int)blk.size(), MPI_DOUBLE, MPI_SUM, sim.comm));
  *predicted = Imbalance(blk);
  PetscFunctionReturn(0);
}

// The Balance event of -log_view (registered on first use), begun.
PetscErrorCode BalanceEventBegin() {
  PetscFunctionBeginUser;
  if (!ev_balance) {
    PetscClassId cls;
    PetscCall(PetscClassIdRegister("pmpm balance", &cls));
    PetscCall(PetscLogEventRegister("Balance", cls, &ev_balance));
  }
  PetscCall(PetscLogEventBegin(ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode RankImbalance(MPI_Comm comm, PetscInt n, double *imb) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<double> counts(size);
  double local = (double)n;
  PetscCallMPI(MPI_Allgather(&local, 1, MPI_DOUBLE, counts.data(), 1, MPI_DOUBLE, comm));
  *imb = Imbalance(counts);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode BalanceFromOptions(MPI_Comm comm, Balance &b) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Load balance (particles per rank)", nullptr);
  PetscCall(PmpmOptionsEnum("-balance",
                            "Partition: none (PETSc's even split of the nodes), setup (split "
                            "the particles per cell column and row evenly, at setup) or run "
                            "(setup, and again at a stage's end when -balance_threshold is "
                            "passed)",
                            nullptr, BalanceModeNames, (PetscEnum)b.mode, (PetscEnum *)&b.mode,
                            nullptr));
  PetscCall(PmpmOptionsReal("-balance_gain",
                            "Rebuild the grid only if it lowers the imbalance (max / mean "
                            "particles per rank) by more than this fraction, 0 <= g < 1",
                            nullptr, b.gain, &b.gain, nullptr));
  PetscCall(PmpmOptionsReal("-balance_threshold",
                            "-balance run: rebalance at a stage's end when max / mean particles "
                            "per rank exceeds this, >= 1",
                            nullptr, b.threshold, &b.threshold, nullptr));
  PetscOptionsEnd();
  PetscCheck(b.gain >= 0 && b.gain < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-balance_gain must be in [0, 1) (got %g)", b.gain);
  PetscCheck(b.threshold >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-balance_threshold must be >= 1 (got %g)", b.threshold);
  PetscFunctionReturn(0);
}

PetscErrorCode BalanceSetup(Simulation &sim, ParticleList &init) {
  Balance &b = sim.balance;
  PetscInt px, py;
  PetscFunctionBeginUser;
  PetscCall(BalanceEventBegin());
  const double t0 = MPI_Wtime();
  PetscCall(RankImbalance(sim.comm, (PetscInt)init.size(), &b.before));
  b.after = b.before;
  PetscCall(DMDAGetInfo(sim.grid.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  if (b.mode != BalanceMode::None && sim.size > 1) {
    std::vector<PetscInt> bx, by;
    double predicted = 1e300;
    PetscCall(Plan(
        sim, px, py, init, [](const ParticleInit &q) { return q.x; }, bx, by, &predicted));
    if (!bx.empty() && predicted < b.before * (1 - b.gain)) {
      PetscCall(BalanceRebuildGrid(sim, px, py, NodeCounts(bx), NodeCounts(by)));
      init.clear();
      PetscCall(sim.scene->generate(sim, init));
      PetscCall(RankImbalance(sim.comm, (PetscInt)init.size(), &b.after));
      b.rebuilt = true;
    }
  }
  double dt = MPI_Wtime() - t0;
  PetscCallMPI(MPI_Allreduce(&dt, &b.seconds, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCall(PetscLogEventEnd(ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

namespace {
// -dim 3: the grid (and the interface's body grid, if there is one) rebuilt with the x and y cuts
// bx, by (cell bounds) on the same process grid, its z slabs kept; the swarm recreated empty.
PetscErrorCode RebuildGrid3(Simulation &sim, const std::vector<PetscInt> &bx,
                            const std::vector<PetscInt> &by) {
  GridT<3> &g = sim.grid3;
  PetscInt p[3];
  const PetscInt *l[3];
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da, &l[0], &l[1], &l[2]));
  const std::vector<PetscInt> lx = NodeCounts(bx), ly = NodeCounts(by), lz(l[2], l[2] + p[2]);
  const bool iface = sim.iface_grid.active;
  const double h = g.h, origin[3] = {g.origin[0], g.origin[1], g.origin[2]};
  const PetscInt ncell[3] = {g.ncell[0], g.ncell[1], g.ncell[2]};
  const int nbody = g.nbody, extra = g.nd - g.nbody * GridDofT<3>::NDOF;
  PetscCall(ParticlesDestroy(sim.parts)); // the swarm holds a bare pointer to the DMDA
  PetscCall(InterfaceGridDestroy(sim.iface_grid));
  PetscCall(GridDestroy(g));
  PetscCall(GridCreate<3>(sim.comm, h, origin, ncell, nbody, extra, g, p[0], p[1], lx.data(),
                          ly.data(), p[2], lz.data()));
  if (iface) PetscCall(InterfaceGridCreate(g, sim.iface_grid));
  PetscCall(ParticlesCreate(g, sim.parts));
  PetscFunctionReturn(0);
}
// -dim 3: max / mean particles per rank of the extruded plane on the partition with cell bounds
// bx, by, bz: the plane's particles in each column-row block times the block's z cells x ppc.
double ExtrudedImbalance(const Simulation &sim, const ParticleList &plane,
                         const std::vector<PetscInt> &bx, const std::vector<PetscInt> &by,
                         const std::vector<PetscInt> &bz) {
  const size_t px = bx.size() - 1, py = by.size() - 1, pz = bz.size() - 1;
  std::vector<double> blk2(px * py, 0.0), blk(px * py * pz);
  for (const ParticleInit &q : plane) {
    const size_t i = std::upper_bound(bx.begin(), bx.end(), CellOf(sim, q.x, 0)) - bx.begin() - 1;
    const size_t j = std::upper_bound(by.begin(), by.end(), CellOf(sim, q.x, 1)) - by.begin() - 1;
    blk2[j * px + i] += 1;
  }
  for (size_t k = 0; k < pz; ++k)
    for (size_t ij = 0; ij < px * py; ++ij)
      blk[k * px * py + ij] = blk2[ij] * (double)((bz[k + 1] - bz[k]) * sim.set.ppc);
  return Imbalance(blk);
}
} // namespace

PetscErrorCode BalanceSetupExtruded(Simulation &sim, const ParticleList &plane) {
  Balance &b = sim.balance;
  PetscInt p[3];
  const PetscInt *l[3];
  PetscFunctionBeginUser;
  PetscCall(BalanceEventBegin());
  const double t0 = MPI_Wtime();
  GridT<3> &g = sim.grid3;
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da, &l[0], &l[1], &l[2]));
  std::vector<PetscInt> b0[3];
  for (int d = 0; d < 3; ++d) b0[d] = CellBounds(l[d], p[d], g.ncell[d]);
  b.before = b.after = ExtrudedImbalance(sim, plane, b0[0], b0[1], b0[2]);
  if (b.mode != BalanceMode::None && sim.size > 1) {
    // the plane's particles per cell column, then per cell row (every rank has the whole plane)
    const PetscInt nx = g.ncell[0], ny = g.ncell[1];
    std::vector<double> cnt(nx + ny, 0.0);
    for (const ParticleInit &q : plane) {
      cnt[CellOf(sim, q.x, 0)] += 1;
      cnt[nx + CellOf(sim, q.x, 1)] += 1;
    }
    const std::vector<PetscInt> bx = SplitCounts(cnt.data(), nx, p[0]),
                                by = SplitCounts(cnt.data() + nx, ny, p[1]);
    const double predicted =
        bx.empty() || by.empty() ? 1e300 : ExtrudedImbalance(sim, plane, bx, by, b0[2]);
    if (predicted < b.before * (1 - b.gain)) {
      PetscCall(RebuildGrid3(sim, bx, by));
      b.after = predicted;
      b.rebuilt = true;
    }
  }
  double dt = MPI_Wtime() - t0;
  PetscCallMPI(MPI_Allreduce(&dt, &b.seconds, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCall(PetscLogEventEnd(ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode BalanceRebuildGrid(Simulation &sim, PetscInt px, PetscInt py,
                                  const std::vector<PetscInt> &lx,
                                  const std::vector<PetscInt> &ly) {
  PetscFunctionBeginUser;
  const bool iface = sim.iface_grid.active;
  const int nbody = sim.grid.nbody, extra = sim.grid.nd - nbody * GridDof::NDOF;
  PetscCall(ParticlesDestroy(sim.parts)); // the swarm holds a bare pointer to the DMDA
  PetscCall(InterfaceGridDestroy(sim.iface_grid));
  PetscCall(GridDestroy(sim.grid));
  PetscCall(GridCreate(sim.comm, sim.set.h, sim.model.origin, sim.model.ncell, nbody, extra,
                       sim.grid, px, py, lx.data(), ly.data()));
  if (iface) PetscCall(InterfaceGridCreate(sim.grid, sim.iface_grid));
  PetscCall(ParticlesCreate(sim.grid, sim.parts));
  PetscFunctionReturn(0);
}

PetscErrorCode BalancePartition(Simulation &sim, std::vector<PetscInt> &part) {
  PetscInt px, py;
  const PetscInt *lx, *ly;
  PetscFunctionBeginUser;
  if (sim.set.dim == 3) { // -dim 3: px, py, pz, then the node counts per direction
    PetscInt p[3];
    const PetscInt *l[3];
    PetscCall(DMDAGetInfo(sim.grid3.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2],
                          nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
    PetscCall(DMDAGetOwnershipRanges(sim.grid3.da, &l[0], &l[1], &l[2]));
    part = {p[0], p[1], p[2]};
    for (int d = 0; d < 3; ++d) part.insert(part.end(), l[d], l[d] + p[d]);
    PetscFunctionReturn(0);
  }
  PetscCall(DMDAGetInfo(sim.grid.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(sim.grid.da, &lx, &ly, nullptr));
  part = {px, py};
  part.insert(part.end(), lx, lx + px);
  part.insert(part.end(), ly, ly + py);
  PetscFunctionReturn(0);
}

namespace {
// -balance run's plan from the swarm: the x and y cuts that balance the particles' cell columns
// and rows on the run's process grid (-dim 3: the z slabs kept, as at setup: an extruded scene's
// particles stay uniform along z), and the imbalance they would give.
PetscErrorCode PlanFromSwarm(Simulation &sim, std::vector<PetscInt> &bx, std::vector<PetscInt> &by,
                             double *predicted) {
  const int D = static_cast<int>(sim.set.dim);
  PetscInt p[3] = {1, 1, 1};
  const PetscInt *l[3] = {nullptr, nullptr, nullptr};
  PetscFunctionBeginUser;
  DM da = D == 3 ? sim.grid3.da : sim.grid.da;
  PetscCall(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  std::vector<PetscInt> bz;
  if (D == 3) {
    PetscCall(DMDAGetOwnershipRanges(da, &l[0], &l[1], &l[2]));
    bz = CellBounds(l[2], p[2], sim.grid3.ncell[2]);
  }
  ParticleView P;
  PetscCall(ParticlesGetView(sim.parts, P));
  std::vector<PetscInt> idx(P.n);
  for (PetscInt q = 0; q < P.n; ++q) idx[q] = q;
  const double *x = P.x;
  PetscCall(Plan(
      sim, p[0], p[1], idx, [x, D](PetscInt q) { return x + q * D; }, bx, by, predicted,
      D == 3 ? &sim.grid3 : nullptr, bz));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode BalanceRun(Simulation &sim) {
  Balance &b = sim.balance;
  PetscInt n;
  PetscFunctionBeginUser;
  if (b.mode != BalanceMode::Run || sim.size == 1) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(ev_balance, 0, 0, 0, 0));
  const double t0 = MPI_Wtime();
  PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &n));
  double now;
  PetscCall(RankImbalance(sim.comm, n, &now));
  if (now > b.threshold) {
    std::vector<PetscInt> bx, by;
    double predicted = 1e300;
    PetscCall(PlanFromSwarm(sim, bx, by, &predicted));
    if (!bx.empty() && predicted < now * (1 - b.gain)) {
      const bool d3 = sim.set.dim == 3;
      std::vector<double> rec;
      PetscCall(ParticlesPack(sim.parts, rec));
      if (d3) {
        PetscCall(RebuildGrid3(sim, bx, by));
        PetscCall(RecordsRedistribute(sim.comm, sim.grid3, ParticleRecordWidth(sim.parts), rec));
      } else {
        PetscInt px, py;
        PetscCall(DMDAGetInfo(sim.grid.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr,
                              nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
        PetscCall(BalanceRebuildGrid(sim, px, py, NodeCounts(bx), NodeCounts(by)));
        PetscCall(RecordsRedistribute(sim.comm, sim.grid, ParticleRecordWidth(sim.parts), rec));
      }
      PetscCall(ParticlesUnpack(sim.parts, rec));
      PetscCall(SimulationIndexParticles(sim));
      PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &n));
      b.last_before = now;
      PetscCall(RankImbalance(sim.comm, n, &b.last_after));
      ++b.rebalances;
      if (!sim.set.quiet)
        PetscCall(PetscPrintf(
            sim.comm, "stage %d: rebalanced%s, particles per rank max/mean %.3f -> %.3f\n",
            (int)sim.stage, d3 ? " (the x and y cuts of the 3D process grid)" : "", b.last_before,
            b.last_after));
    }
  }
  double dt = MPI_Wtime() - t0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  b.run_seconds += dt;
  PetscCall(PetscLogEventEnd(ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode PartitionJson(Simulation &sim, std::string &json) {
  PetscInt p[3] = {1, 1, 1}, n;
  const PetscInt *l[3] = {nullptr, nullptr, nullptr};
  PetscFunctionBeginUser;
  const int D = static_cast<int>(sim.set.dim); // -dim 3: the 3D grid's partition
  DM da = D == 3 ? sim.grid3.da : sim.grid.da;
  const PetscInt *ncell = D == 3 ? sim.grid3.ncell : sim.model.ncell;
  PetscCall(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(da, &l[0], &l[1], D == 3 ? &l[2] : nullptr));
  PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &n));
  std::vector<PetscInt> counts(sim.size);
  PetscCallMPI(MPI_Allgather(&n, 1, MPIU_INT, counts.data(), 1, MPIU_INT, sim.comm));
  const double imbalance = Imbalance(std::vector<double>(counts.begin(), counts.end()));
  const Balance &b = sim.balance;
  const char *sep = ",\n    ";
  const char *axis[3] = {"x", "y", "z"};
  std::string procs, origin, ranges;
  for (int d = 0; d < D; ++d) {
    procs += (d ? ", " : "") + std::to_string(p[d]);
    origin += (d ? ", " : "") + json_num(d < DIM ? sim.model.origin[d] : sim.grid3.origin[d]);
    ranges += std::string("\"nodes_") + axis[d] +
              "\": " + json_array(std::vector<PetscInt>(l[d], l[d] + p[d])) + sep;
  }
  for (int d = 0; d < D; ++d)
    ranges += std::string("\"cell_bounds_") + axis[d] +
              "\": " + json_array(CellBounds(l[d], p[d], ncell[d])) + sep;
  json = "\"partition\": {\n    \"processes\": [" + procs + "]" + sep + "\"origin\": [" + origin +
         "]" + sep + ranges + "\"particles_per_rank\": " + json_array(counts) + sep +
         json_kv("imbalance", imbalance) + "\n  },\n  \"balance\": {\n    \"mode\": \"" +
         BalanceModeNames[(int)b.mode] + "\"" + sep + json_kv("gain", b.gain) + sep +
         json_kv("imbalance_before", b.before) + sep + json_kv("imbalance_after", b.after) + sep +
         json_kv("rebuilt", b.rebuilt ? "true" : "false") + sep + json_kv("seconds", b.seconds) +
         sep + json_kv("threshold", b.threshold) + sep +
         json_kv("rebalances", static_cast<double>(b.rebalances)) + sep +
         json_kv("last_imbalance_before", b.last_before) + sep +
         json_kv("last_imbalance_after", b.last_after) + sep +
         json_kv("run_seconds", b.run_seconds) + "\n  }";
  PetscFunctionReturn(0);
}

} // namespace pmpm
