#include "pmpm/balance.hpp"
#include "pmpm/output.hpp"
#include <algorithm>
#include <vector>

namespace pmpm {

namespace {
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
} // namespace

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
  double total = 0, most = 0;
  for (PetscInt c : counts) {
    total += c;
    most = std::max(most, (double)c);
  }
  const double imbalance = total > 0 ? most / (total / sim.size) : 1.0;
  const char *sep = ",\n    ";
  json = "\"partition\": {\n    \"processes\": [" + std::to_string(px) + ", " + std::to_string(py) +
         "]" + sep + "\"origin\": [" + json_num(sim.origin[0]) + ", " + json_num(sim.origin[1]) +
         "]" + sep + "\"nodes_x\": " + json_array(std::vector<PetscInt>(lx, lx + px)) + sep +
         "\"nodes_y\": " + json_array(std::vector<PetscInt>(ly, ly + py)) + sep +
         "\"cell_bounds_x\": " + json_array(CellBounds(lx, px, sim.ncell[0])) + sep +
         "\"cell_bounds_y\": " + json_array(CellBounds(ly, py, sim.ncell[1])) + sep +
         "\"particles_per_rank\": " + json_array(counts) + sep + json_kv("imbalance", imbalance) +
         "\n  }";
  PetscFunctionReturn(0);
}

} // namespace pmpm
