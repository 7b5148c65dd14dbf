#include "pmpm/util/options.hpp"
#include "pmpm/model/prerun.hpp"
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace pmpm {

namespace {
constexpr double kGiB = 1073741824.0;
// per node besides the nodal vectors: coordinates (2 doubles, global and local) and the
// local-to-global map and scatter indices
constexpr double kGridBytesPerNode = 2 * DIM * 8 + 16;
// per particle: pmpm's swarm fields (particles.cpp: 22 doubles and 4 PetscInt) and DMSwarm's own
// (coordinates' id, rank, cell: 16 B), 208 B; and the setup's transient at its peak, the rest of
// the generated list and the swarm's reallocation copies while it grows (96 B, measured: the
// column's 340 B marginal peak at 1-4 M particles less its 41 B of grid and the swarm). The run's
// scratch (velocity gradient, material index: 36 B) comes after and is smaller. The estimate
// is 4-9 % above the measured peaks (docs/benchmarks/memory.md). -transfer apic adds B.
constexpr double kParticleBytes = 22 * 8 + 4 * sizeof(PetscInt) + 16 + 96;

// per rank: the libraries, MPI's buffers and PETSc's objects (the resident size of a 1-rank run
// of options/bar.opts, 47 MB)
constexpr double kRankBaseBytes = 48.0 * 1048576;

// Bytes this node can still use: MemAvailable, or the cgroup's remaining limit if lower.
double NodeAvailable() {
  double avail = -1;
  std::ifstream mi("/proc/meminfo");
  std::string key;
  double kb;
  std::string unit;
  while (mi >> key >> kb) {
    std::getline(mi, unit);
    if (key == "MemAvailable:") avail = kb * 1024;
  }
  std::ifstream mx("/sys/fs/cgroup/memory.max"), cur("/sys/fs/cgroup/memory.current");
  double lim, used;
  if (mx >> lim && cur >> used && lim - used < avail) avail = lim - used; // "max": no number
  return avail;
}

// Compare each node's need (the sum over its ranks of `need`) with what it has; fail with the
// worst node's numbers.
PetscErrorCode CompareWithNodes(Simulation &sim, const MemoryCheck &m, double need,
                                const char *what) {
  MPI_Comm node;
  PetscMPIInt node_rank, node_size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_split_type(sim.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &node_rank));
  PetscCallMPI(MPI_Comm_size(node, &node_size));
  double v[3] = {need, 0, (double)node_size}; // node's need, its available bytes, its ranks
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 1, MPI_DOUBLE, MPI_SUM, node));
  if (node_rank == 0) v[1] = m.limit_gib > 0 ? m.limit_gib * kGiB : NodeAvailable();
  PetscCallMPI(MPI_Bcast(&v[1], 1, MPI_DOUBLE, 0, node));
  PetscCallMPI(MPI_Comm_free(&node));
  struct {
    double ratio;
    int rank;
  } loc = {v[1] > 0 ? v[0] / v[1] : 0.0, sim.rank}, worst;
  PetscCallMPI(MPI_Allreduce(&loc, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, sim.comm));
  PetscCallMPI(MPI_Bcast(v, 3, MPI_DOUBLE, worst.rank, sim.comm));
  if (worst.ratio > 1) {
    // memory goes as 1 / h^dim: the cell size that fits (with 10 % to spare)
    const double h = sim.set.h * std::pow(1.1 * worst.ratio, 1.0 / sim.set.dim);
    // bad input (exit code 1), refused before any allocation: not PETSC_ERR_MEM
    SETERRQ(sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
            "-cell_size %g needs about %.3g GiB (%s) on a node running %d rank%s, which has "
            "%.3g GiB available%s: use -cell_size %.3g or more, or more nodes",
            sim.set.h, v[0] / kGiB, what, (int)v[2], v[2] > 1 ? "s" : "", v[1] / kGiB,
            m.limit_gib > 0 ? " (-memory_limit)" : " (MemAvailable)", h);
  }
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode CheckOutputDir(MPI_Comm comm, const std::string &dir) {
  PetscMPIInt rank;
  char msg[PETSC_MAX_PATH_LEN + 128] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    struct stat st;
    std::string probe_in; // the directory to probe for writing
    if (stat(dir.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode))
        snprintf(msg, sizeof(msg), "-output_dir %s exists and is not a directory", dir.c_str());
      else
        probe_in = dir;
    } else {
      // the nearest existing ancestor (the directories below it will be created)
      std::string up = dir;
      while (!up.empty() && up.back() == '/') up.pop_back();
      for (;;) {
        const size_t k = up.find_last_of('/');
        up = k == std::string::npos ? "." : (k == 0 ? "/" : up.substr(0, k));
        if (stat(up.c_str(), &st) == 0 || up == "." || up == "/") break;
      }
      if (stat(up.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        snprintf(msg, sizeof(msg), "-output_dir %s cannot be created: %s is not a directory",
                 dir.c_str(), up.c_str());
      else
        probe_in = up;
    }
    if (!msg[0]) { // root ignores permissions: try it
      std::string tmpl = probe_in + "/.pmpm_probe_XXXXXX";
      if (char *made = mkdtemp(&tmpl[0]))
        rmdir(made);
      else
        snprintf(msg, sizeof(msg), "-output_dir %s cannot be %s: %s (in %s)", dir.c_str(),
                 probe_in == dir ? "written" : "created", std::strerror(errno), probe_in.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!msg[0], comm, PETSC_ERR_FILE_OPEN, "%s", msg);
  PetscFunctionReturn(0);
}

PetscErrorCode MemoryFromOptions(MPI_Comm comm, MemoryCheck &m) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Memory check before the run", nullptr);
  PetscCall(PmpmOptionsReal("-memory_limit",
                            "Memory per node the run may use (GiB), > 0; default: the node's "
                            "available memory (MemAvailable, or the cgroup's limit if lower)",
                            nullptr, m.limit_gib, &m.limit_gib, nullptr));
  PetscOptionsEnd();
  PetscCheck(m.limit_gib >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-memory_limit must be > 0 GiB, or 0 for the node's available memory (got %g)",
             m.limit_gib);
  PetscFunctionReturn(0);
}

namespace {
double GridBytesPerNode(int nd, bool iface) {
  return 2.0 * 8 * nd + kGridBytesPerNode + (iface ? 2.0 * 8 * GridDof::NDOF : 0.0);
}

// -solver newton on a rank with `owned` and `ghosted` nodes of the D-dimensional grid: per owned
// node the matrix (D rows of D (2w + 1)^D entries, a value and a column index each; w the stencil
// width, newton.cpp's CreateGrid) and the default preconditioner in multiples of it: MUMPS's LU in
// 2D (9x) and BoomerAMG in 3D (2x); per ghosted node the particles' stiffness gathered per node
// pair before insertion ((2w + 1)^D blocks of D^2 doubles). Measured against relaxation's peak
// RSS: the footing at B/16 and B/64 (2,009 and 31,073 nodes) 11.6 and 13.4 KB per node, estimated
// 12.8; the quarter circular footing at B/8 (3,757 owned, 7,497 ghosted nodes) 59 KB per owned
// node, estimated 58.5. Another -pc_type changes the preconditioner's term (a 3D LU fills in:
// 162 KB per node measured there).
double NewtonBytes(const Simulation &sim, int D, double owned, double ghosted) {
  if (sim.set.solver != "newton") return 0.0;
  const int w = !sim.model.chain_specs.empty() ? 3 : sim.set.shape == ShapeKind::Linear ? 1 : 2;
  const double nb =
      D == 3 ? (2.0 * w + 1) * (2 * w + 1) * (2 * w + 1) : (2.0 * w + 1) * (2 * w + 1);
  const double matrix = D * (D * nb) * (8.0 + sizeof(PetscInt));
  const double blocks = nb * D * D * 8.0;
  return owned * matrix * (D == 3 ? 3.0 : 10.0) + ghosted * blocks;
}
const char *NewtonWhat(const Simulation &sim, const char *what, const char *with) {
  return sim.set.solver == "newton" ? with : what;
}
} // namespace

PetscErrorCode CheckMemoryGrid(Simulation &sim, const MemoryCheck &m, int nd, bool iface) {
  PetscFunctionBeginUser;
  const double nodes = (double)(sim.model.ncell[0] + 1) * (double)(sim.model.ncell[1] + 1);
  const double mine = nodes / sim.size, per_node = GridBytesPerNode(nd, iface);
  PetscCall(CompareWithNodes(sim, m,
                             kRankBaseBytes + mine * per_node + NewtonBytes(sim, 2, mine, mine),
                             NewtonWhat(sim, "the grid alone", "the grid and Newton's matrix")));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckMemoryParticles(Simulation &sim, const MemoryCheck &m, PetscInt nlocal) {
  PetscFunctionBeginUser;
  const double nodes = (double)sim.grid.gm[0] * sim.grid.gm[1];
  const double need = kRankBaseBytes +
                      nodes * GridBytesPerNode(sim.grid.nd, sim.iface_grid.active) +
                      NewtonBytes(sim, 2, (double)sim.grid.m[0] * sim.grid.m[1], nodes) +
                      (double)nlocal * (kParticleBytes + (sim.parts.affine ? DIM * DIM * 8 : 0));
  PetscCall(CompareWithNodes(
      sim, m, need, NewtonWhat(sim, "grid and particles", "grid, particles and Newton's matrix")));
  PetscFunctionReturn(0);
}

namespace {
// -dim 3 (extrude.hpp): per node, the coordinates (3 doubles, global and local) and the maps; per
// particle the swarm's fields (33 doubles: x x0 v lp 12, mass vol vol0 weight 4, stress 6, F 9,
// eps_p colour 2; 4 PetscInt; DMSwarm's 16 B) and the setup's transient (the extruded list while
// the swarm grows: at most one copy of it beside the swarm).
constexpr double kGridBytesPerNode3 = 2 * 3 * 8 + 16;
constexpr double kParticleBytes3 = 33 * 8 + 4 * sizeof(PetscInt) + 16 + sizeof(ParticleInitT<3>);
} // namespace

PetscErrorCode CheckMemoryExtruded(Simulation &sim, const MemoryCheck &m, PetscInt nz,
                                   PetscInt nlocal) {
  PetscFunctionBeginUser;
  // the colour interface's body grid (local and global vectors) doubles the nodal values
  const bool iface = sim.model.iface.type != InterfaceType::Bonded;
  const double per_node = (iface ? 4.0 : 2.0) * 8 * GridDofT<3>::NDOF + kGridBytesPerNode3;
  if (nlocal == 0) {
    const double nodes =
        (double)(sim.model.ncell[0] + 1) * (double)(sim.model.ncell[1] + 1) * (double)(nz + 1);
    PetscCall(CompareWithNodes(
        sim, m,
        kRankBaseBytes + nodes / sim.size * per_node +
            NewtonBytes(sim, 3, nodes / sim.size, nodes / sim.size),
        NewtonWhat(sim, "the 3D grid alone", "the 3D grid and Newton's matrix alone")));
  } else {
    const GridT<3> &g = sim.grid3;
    const double nodes = (double)g.gm[0] * g.gm[1] * g.gm[2];
    PetscCall(CompareWithNodes(sim, m,
                               kRankBaseBytes + nodes * per_node +
                                   (double)nlocal * kParticleBytes3 +
                                   NewtonBytes(sim, 3, (double)g.m[0] * g.m[1] * g.m[2], nodes),
                               NewtonWhat(sim, "the 3D grid and particles",
                                          "the 3D grid, particles and Newton's matrix")));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckProcessGrid(Simulation &sim, int D, const PetscInt *ncell) {
  const char *names[3] = {"-da_processors_x", "-da_processors_y", "-da_processors_z"};
  PetscInt np[3] = {0, 0, 0};
  PetscBool set[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
  PetscFunctionBeginUser;
  for (int d = 0; d < D; ++d) {
    PetscCall(PetscOptionsGetInt(nullptr, nullptr, names[d], &np[d], &set[d]));
    if (!set[d]) continue;
    // the stencil width, 2: a rank needs at least two node columns (rows)
    const PetscInt nodes = ncell[d] + 1, most = nodes / 2;
    PetscCheck(np[d] >= 1 && np[d] <= most, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "%s %" PetscInt_FMT " must be in 1..%" PetscInt_FMT ": the grid has %" PetscInt_FMT
               " nodes in %c and each rank needs at least 2",
               names[d], np[d], most, nodes, "xyz"[d]);
    PetscCheck(sim.size % np[d] == 0, sim.comm, PETSC_ERR_ARG_INCOMP,
               "%s %" PetscInt_FMT " does not divide the %d ranks", names[d], np[d], sim.size);
  }
  PetscInt given = 0, product = 1, missing = -1;
  for (int d = 0; d < D; ++d) {
    if (set[d]) {
      ++given;
      product *= np[d];
    } else
      missing = d;
  }
  if (D == 2)
    PetscCheck(!set[0] || !set[1] || np[0] * np[1] == sim.size, sim.comm, PETSC_ERR_ARG_INCOMP,
               "-da_processors_x %" PetscInt_FMT " times -da_processors_y %" PetscInt_FMT
               " must be the %d ranks",
               np[0], np[1], sim.size);
  else
    PetscCheck(given < D ? sim.size % product == 0 : product == sim.size, sim.comm,
               PETSC_ERR_ARG_INCOMP,
               "-da_processors_x/y/z (%" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT
               ", 0: not given) must multiply to the %d ranks",
               np[0], np[1], np[2], sim.size);
  if (given == D - 1) { // the other direction then takes the remaining ranks
    const PetscInt other = sim.size / product, nodes = ncell[missing] + 1;
    for (int d = 0; d < D; ++d)
      if (set[d])
        PetscCheck(other <= nodes / 2, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "%s %" PetscInt_FMT " leaves %" PetscInt_FMT " ranks in %c, where the grid has "
                   "%" PetscInt_FMT " nodes and each rank needs at least 2",
                   names[d], np[d], other, "xyz"[missing], nodes);
  }
  PetscFunctionReturn(0);
}

} // namespace pmpm
