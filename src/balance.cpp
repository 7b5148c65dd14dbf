#include "pmpm/balance.hpp"
#include "pmpm/output.hpp"
#include "pmpm/simulation.hpp"
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
  const PetscInt c = (PetscInt)std::floor((x[d] - sim.origin[d]) / sim.set.h);
  return std::min(std::max(c, (PetscInt)0), sim.ncell[d] - 1);
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
  PetscCall(PetscOptionsEnum("-balance",
                             "Partition: none (PETSc's even split of the nodes) or setup (split "
                             "the particles per cell column and row evenly, at setup)",
                             nullptr, BalanceModeNames, (PetscEnum)b.mode, (PetscEnum *)&b.mode,
                             nullptr));
  PetscCall(PetscOptionsReal("-balance_gain",
                             "Rebuild the grid only if it lowers the imbalance (max / mean "
                             "particles per rank) by more than this fraction, 0 <= g < 1",
                             nullptr, b.gain, &b.gain, nullptr));
  PetscOptionsEnd();
  PetscCheck(b.gain >= 0 && b.gain < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-balance_gain must be in [0, 1) (got %g)", b.gain);
  PetscFunctionReturn(0);
}

PetscErrorCode BalanceSetup(Simulation &sim, ParticleList &init) {
  Balance &b = sim.balance;
  PetscInt px, py;
  PetscFunctionBeginUser;
  if (!ev_balance) {
    PetscClassId cls;
    PetscCall(PetscClassIdRegister("pmpm balance", &cls));
    PetscCall(PetscLogEventRegister("Balance", cls, &ev_balance));
  }
  PetscCall(PetscLogEventBegin(ev_balance, 0, 0, 0, 0));
  const double t0 = MPI_Wtime();
  PetscCall(RankImbalance(sim.comm, (PetscInt)init.size(), &b.before));
  b.after = b.before;
  PetscCall(DMDAGetInfo(sim.grid.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  if (b.mode == BalanceMode::Setup && sim.size > 1) {
    // particles per cell column, then per cell row
    const PetscInt nx = sim.ncell[0], ny = sim.ncell[1];
    std::vector<double> cnt(nx + ny, 0.0);
    for (const auto &q : init) {
      cnt[CellOf(sim, q.x, 0)] += 1;
      cnt[nx + CellOf(sim, q.x, 1)] += 1;
    }
    PetscCallMPI(
        MPI_Allreduce(MPI_IN_PLACE, cnt.data(), (int)cnt.size(), MPI_DOUBLE, MPI_SUM, sim.comm));
    const std::vector<PetscInt> bx = SplitCounts(cnt.data(), nx, px),
                                by = SplitCounts(cnt.data() + nx, ny, py);
    if (!bx.empty() && !by.empty()) {
      // the imbalance that partition would have (every rank bins its particles)
      std::vector<double> blk(px * py, 0.0);
      for (const auto &q : init) {
        const PetscInt i =
            std::upper_bound(bx.begin(), bx.end(), CellOf(sim, q.x, 0)) - bx.begin() - 1;
        const PetscInt j =
            std::upper_bound(by.begin(), by.end(), CellOf(sim, q.x, 1)) - by.begin() - 1;
        blk[j * px + i] += 1;
      }
      PetscCallMPI(
          MPI_Allreduce(MPI_IN_PLACE, blk.data(), (int)blk.size(), MPI_DOUBLE, MPI_SUM, sim.comm));
      if (Imbalance(blk) < b.before * (1 - b.gain)) {
        const std::vector<PetscInt> lx = NodeCounts(bx), ly = NodeCounts(by);
        const bool iface = sim.iface_grid.active;
        const int extra = sim.grid.nd - sim.grid.nbody * GridDof::NDOF;
        PetscCall(ParticlesDestroy(sim.parts)); // the swarm holds a bare pointer to the DMDA
        PetscCall(InterfaceGridDestroy(sim.iface_grid));
        PetscCall(GridDestroy(sim.grid));
        PetscCall(GridCreate(sim.comm, sim.set.h, sim.origin, sim.ncell, sim.grid.nbody, extra,
                             sim.grid, px, py, lx.data(), ly.data()));
        if (iface) PetscCall(InterfaceGridCreate(sim.grid, sim.iface_grid));
        PetscCall(ParticlesCreate(sim.grid, sim.parts));
        init.clear();
        PetscCall(sim.scene->generate(sim, init));
        PetscCall(RankImbalance(sim.comm, (PetscInt)init.size(), &b.after));
        b.rebuilt = true;
      }
    }
  }
  double dt = MPI_Wtime() - t0;
  PetscCallMPI(MPI_Allreduce(&dt, &b.seconds, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
  PetscCall(PetscLogEventEnd(ev_balance, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode PartitionJson(Simulation &sim, std::string &json) {
  PetscInt px, py, n;
  const PetscInt *lx, *ly;
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(sim.grid.da, nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(sim.grid.da, &lx, &ly, nullptr));
  PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &n));
  std::vector<PetscInt> counts(sim.size);
  PetscCallMPI(MPI_Allgather(&n, 1, MPIU_INT, counts.data(), 1, MPIU_INT, sim.comm));
  const double imbalance = Imbalance(std::vector<double>(counts.begin(), counts.end()));
  const Balance &b = sim.balance;
  const char *sep = ",\n    ";
  json = "\"partition\": {\n    \"processes\": [" + std::to_string(px) + ", " + std::to_string(py) +
         "]" + sep + "\"origin\": [" + json_num(sim.origin[0]) + ", " + json_num(sim.origin[1]) +
         "]" + sep + "\"nodes_x\": " + json_array(std::vector<PetscInt>(lx, lx + px)) + sep +
         "\"nodes_y\": " + json_array(std::vector<PetscInt>(ly, ly + py)) + sep +
         "\"cell_bounds_x\": " + json_array(CellBounds(lx, px, sim.ncell[0])) + sep +
         "\"cell_bounds_y\": " + json_array(CellBounds(ly, py, sim.ncell[1])) + sep +
         "\"particles_per_rank\": " + json_array(counts) + sep + json_kv("imbalance", imbalance) +
         "\n  },\n  \"balance\": {\n    \"mode\": \"" + BalanceModeNames[(int)b.mode] + "\"" + sep +
         json_kv("gain", b.gain) + sep + json_kv("imbalance_before", b.before) + sep +
         json_kv("imbalance_after", b.after) + sep +
         json_kv("rebuilt", b.rebuilt ? "true" : "false") + sep + json_kv("seconds", b.seconds) +
         "\n  }";
  PetscFunctionReturn(0);
}

} // namespace pmpm
