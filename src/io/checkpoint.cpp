// Checkpoint and restart (checkpoint.hpp). File layout (PetscViewerHDF5):
//   /run        attributes: format, the run's identity (scene, cell size, grid, particles at
//               setup, chains), the stage loop's position, RunState and the solver's state
//               (EquilibriumSolver::checkpoint_write); relaxation's dataset budget_w_local
//               (one entry per rank)
//   /particles  counts (one entry per rank) and one dataset per swarm field, the ranks' blocks in
//               rank order (integers stored as reals, exact)
//   /chains/<k> every chain's evolving point and segment arrays, and its scalars as attributes
//   /output     the time-series frames listed so far
//   /scene      the scene's own state (Scene::checkpoint_write)
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/io/parallel_h5.hpp"
#include "pmpm/core/particle_records.hpp"
#include "pmpm/model/extrude.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <petscviewerhdf5.h>
#include <sstream>
#include <type_traits>

namespace pmpm {

namespace {
constexpr const char *kFormat = "pmpm checkpoint 3";
std::string g_reading = "the checkpoint"; // the file CheckpointRead is reading (messages)
PetscLogEvent ev_write = 0, ev_read = 0;

PetscErrorCode RegisterEvents() {
  PetscFunctionBeginUser;
  if (!ev_write) {
    PetscClassId cls;
    PetscCall(PetscClassIdRegister("pmpm checkpoint", &cls));
    PetscCall(PetscLogEventRegister("CheckpointWrite", cls, &ev_write));
    PetscCall(PetscLogEventRegister("CheckpointRead", cls, &ev_read));
  }
  PetscFunctionReturn(0);
}

// The HDF5 attribute type of a number: double or PetscInt.
template <class T>
constexpr PetscDataType kNumberType = std::is_same_v<T, double> ? PETSC_REAL : PETSC_INT;
static_assert(std::is_same_v<PetscReal, double> && !std::is_same_v<PetscInt, double>);

// Attributes of an absolute group path.
template <class T>
PetscErrorCode PutNumber(PetscViewer v, const char *group, const char *name, T x) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, group, name, kNumberType<T>, &x));
  PetscFunctionReturn(0);
}
constexpr auto PutReal = PutNumber<double>;
constexpr auto PutInt = PutNumber<PetscInt>;
PetscErrorCode PutString(PetscViewer v, const char *group, const char *name, const std::string &x) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, group, name, PETSC_STRING, x.c_str()));
  PetscFunctionReturn(0);
}
// Reading: a missing attribute is a damaged checkpoint (the caller's file name in the message).
PetscErrorCode Need(PetscViewer v, const char *group, const char *name, const std::string &file) {
  PetscBool has = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasAttribute(v, group, name, &has));
  PetscCheck(has, PetscObjectComm((PetscObject)v), PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: not a complete pmpm checkpoint (%s/%s missing)", file.c_str(), group,
             name);
  PetscFunctionReturn(0);
}
template <class T>
PetscErrorCode GetNumber(PetscViewer v, const char *group, const char *name,
                         const std::string &file, T *x) {
  PetscFunctionBeginUser;
  PetscCall(Need(v, group, name, file));
  PetscCall(PetscViewerHDF5ReadAttribute(v, group, name, kNumberType<T>, nullptr, x));
  PetscFunctionReturn(0);
}
constexpr auto GetReal = GetNumber<double>;
constexpr auto GetInt = GetNumber<PetscInt>;
PetscErrorCode GetString(PetscViewer v, const char *group, const char *name,
                         const std::string &file, std::string &x) {
  char *s = nullptr;
  PetscFunctionBeginUser;
  PetscCall(Need(v, group, name, file));
  PetscCall(PetscViewerHDF5ReadAttribute(v, group, name, PETSC_STRING, nullptr, &s));
  x = s ? s : "";
  PetscCall(PetscFree(s));
  PetscFunctionReturn(0);
}

// One value per rank as a dataset of the current group, and back: the whole array on every rank.
PetscErrorCode WritePerRank(MPI_Comm comm, PetscViewer v, const char *name, double x) {
  Vec a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, 1, PETSC_DETERMINE, &a));
  PetscCall(PetscObjectSetName((PetscObject)a, name));
  double *p;
  PetscCall(VecGetArray(a, &p));
  p[0] = x;
  PetscCall(VecRestoreArray(a, &p));
  PetscCall(VecView(a, v));
  PetscCall(VecDestroy(&a));
  PetscFunctionReturn(0);
}

// A dataset of the current group read whole onto every rank.
PetscErrorCode ReadAll(MPI_Comm comm, PetscViewer v, const char *name, std::vector<double> &out) {
  Vec a, all;
  VecScatter sc;
  const double *p;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, &a));
  PetscCall(PetscObjectSetName((PetscObject)a, name));
  PetscCall(VecLoad(a, v));
  PetscCall(VecScatterCreateToAll(a, &sc, &all));
  PetscCall(VecScatterBegin(sc, a, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, a, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(all, &n));
  PetscCall(VecGetArrayRead(all, &p));
  out.assign(p, p + n);
  PetscCall(VecRestoreArrayRead(all, &p));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&a));
  PetscFunctionReturn(0);
}

// Does the current group hold this dataset? (a clear message instead of PETSc's)
PetscErrorCode NeedDataset(PetscViewer v, const char *name, const std::string &file) {
  PetscBool has = PETSC_FALSE;
  char *group = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(v, name, &has));
  PetscCall(PetscViewerHDF5GetGroup(v, nullptr, &group));
  const std::string g = group ? group : "";
  PetscCall(PetscFree(group));
  PetscCheck(has, PetscObjectComm((PetscObject)v), PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: not a complete pmpm checkpoint (dataset %s/%s missing)", file.c_str(),
             g.c_str(), name);
  PetscFunctionReturn(0);
}

// The number of values in a dataset of the current group (collective: HDF5 metadata).
PetscErrorCode DatasetSize(PetscViewer v, const char *name, PetscInt *n) {
  hid_t fid, gid;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5OpenGroup(v, nullptr, &fid, &gid));
  const hid_t d = H5Dopen2(gid, name, H5P_DEFAULT);
  const hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  *n = sp >= 0 ? static_cast<PetscInt>(H5Sget_simple_extent_npoints(sp)) : -1;
  if (sp >= 0) H5Sclose(sp);
  if (d >= 0) H5Dclose(d);
  H5Gclose(gid);
  PetscFunctionReturn(0);
}

// The options that define the model a checkpoint holds: every option the run was given (command
// line and options files), by lower-case name, except run control, which a restart may change:
// output, partition, and how the relaxation seeks equilibrium (its damping, tolerance and history
// file; a stage stopped at its cap may be resumed with another scheme or a looser tolerance).
bool RunControl(const std::string &name) {
  static const char *const exact[] = {
      "restart",           "output_dir",   "max_steps",        "quiet",
      "progress_interval", "output_every", "checkpoint_every", "checkpoint_at_stage_end",
      "options_file",      "help",         "memory_limit",     "options_left"};
  // (no other option name starts with "tol")
  static const char *const prefix[] = {"balance", "da_processors_", "log",   "malloc",       "info",
                                       "tol",     "damping",        "fire_", "relax_history"};
  for (const char *e : exact)
    if (name == e) return true;
  for (const char *q : prefix)
    if (name.compare(0, std::strlen(q), q) == 0) return true;
  return false;
}

// lower-case name -> (the name as given, its value)
using OptionMap = std::map<std::string, std::pair<std::string, std::string>>;

std::string Lower(std::string s) {
  for (char &ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

PetscErrorCode ModelOptions(OptionMap &out) {
  char *all = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  std::istringstream in(all ? all : "");
  PetscCall(PetscFree(all));
  std::string tok, key;
  out.clear();
  while (in >> tok) {
    PetscBool valid = PETSC_FALSE;
    PetscCall(PetscOptionsValidKey(tok.c_str(), &valid));
    if (valid) {
      const std::string name = tok.substr(tok[1] == '-' ? 2 : 1);
      key = Lower(name);
      if (RunControl(key))
        key.clear();
      else
        out[key] = {name, ""};
    } else if (!key.empty()) {
      std::string &val = out[key].second;
      val += (val.empty() ? "" : " ") + tok;
    }
  }
  PetscFunctionReturn(0);
}

// one "name value" per line; names and values hold no blanks or newlines but between values
std::string Serialise(const OptionMap &m) {
  std::string s;
  for (const auto &kv : m) s += kv.second.first + " " + kv.second.second + "\n";
  return s;
}

OptionMap Deserialise(const std::string &s) {
  OptionMap m;
  std::istringstream in(s);
  std::string line;
  while (std::getline(in, line)) {
    const size_t sp = line.find(' ');
    if (sp != std::string::npos)
      m[Lower(line.substr(0, sp))] = {line.substr(0, sp), line.substr(sp + 1)};
  }
  return m;
}

// The same value: the same text, or the same numbers (2 and 2.0; 1e7 and 10e6).
bool SameValue(const std::string &a, const std::string &b) {
  if (a == b) return true;
  std::istringstream x(a), y(b);
  std::string ta, tb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(x, ta, ',')),
               gb = static_cast<bool>(std::getline(y, tb, ','));
    if (ga != gb) return false;
    if (!ga) return true;
    char *ea = nullptr, *eb = nullptr;
    const double va = std::strtod(ta.c_str(), &ea), vb = std::strtod(tb.c_str(), &eb);
    if (ta.empty() || tb.empty() || *ea || *eb || va != vb) return false;
  }
}

std::string CheckpointName(const Simulation &sim) {
  char name[64];
  snprintf(name, sizeof(name), "checkpoint_%d.h5", (int)sim.run.step);
  return name;
}

// Rank 0 looks at the file before PetscViewerHDF5 does (whose HDF5 error stack would be the
// only message otherwise): it exists, is readable, is HDF5 whose end is where HDF5 recorded it
// (a truncated file is not), and is a pmpm checkpoint. The verdict goes to every rank.
PetscErrorCode CheckFile(MPI_Comm comm, PetscMPIInt rank, const std::string &file) {
  char why[256] = "";
  PetscFunctionBeginUser;
  if (rank == 0) {
    if (FILE *f = std::fopen(file.c_str(), "rb")) {
      unsigned char sig[8] = {0};
      const size_t got = std::fread(sig, 1, 8, f);
      std::fclose(f);
      const unsigned char h5[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
      if (got != 8 || std::memcmp(sig, h5, 8) != 0) {
        snprintf(why, sizeof(why), "not an HDF5 file");
      } else {
        H5E_auto2_t fn;
        void *data;
        H5Eget_auto2(H5E_DEFAULT, &fn, &data);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // our message, not HDF5's error stack
        const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        if (id < 0) {
          snprintf(why, sizeof(why), "an HDF5 file HDF5 cannot open (truncated or damaged)");
        } else {
          const htri_t ok = H5Aexists_by_name(id, "/run", "format", H5P_DEFAULT);
          if (ok <= 0) snprintf(why, sizeof(why), "an HDF5 file but not a pmpm checkpoint");
          H5Fclose(id);
        }
        H5Eset_auto2(H5E_DEFAULT, fn, data);
      }
    } else {
      snprintf(why, sizeof(why), "cannot open the file (no such file, or not readable)");
    }
  }
  PetscCallMPI(MPI_Bcast(why, sizeof(why), MPI_CHAR, 0, comm));
  PetscCheck(!why[0], comm, PETSC_ERR_FILE_OPEN, "-restart %s: %s", file.c_str(), why);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckpointWriteArray(PetscViewer v, const char *name, const std::vector<double> &a) {
  Vec x;
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // the length first, so an empty array is a dataset too
  PetscInt n = static_cast<PetscInt>(a.size()) + 1;
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm)); // rank 0's array (others may hold none)
  PetscCall(VecCreateMPI(comm, rank == 0 ? n : 0, n, &x));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  if (rank == 0) {
    double *p;
    PetscCall(VecGetArray(x, &p));
    p[0] = static_cast<double>(a.size());
    std::copy(a.begin(), a.end(), p + 1);
    PetscCall(VecRestoreArray(x, &p));
  }
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointReadArray(PetscViewer v, const char *name, std::vector<double> &a) {
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  std::vector<double> all;
  PetscFunctionBeginUser;
  PetscCall(NeedDataset(v, name, g_reading));
  PetscCall(ReadAll(comm, v, name, all));
  PetscCheck(!all.empty() && all[0] == double(all.size() - 1), comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: damaged checkpoint (array %s: its length does not match)",
             g_reading.c_str(), name);
  a.assign(all.begin() + 1, all.end());
  PetscFunctionReturn(0);
}

template <class T> PetscErrorCode CheckpointWriteNumber(PetscViewer v, const char *name, T x) {
  char *group = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetGroup(v, nullptr, &group));
  PetscCall(PutNumber(v, group, name, x));
  PetscCall(PetscFree(group));
  PetscFunctionReturn(0);
}

template <class T> PetscErrorCode CheckpointReadNumber(PetscViewer v, const char *name, T *x) {
  char *group = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetGroup(v, nullptr, &group));
  const std::string g = group ? group : "/";
  PetscCall(PetscFree(group));
  PetscCall(GetNumber(v, g.c_str(), name, g_reading, x));
  PetscFunctionReturn(0);
}

template PetscErrorCode CheckpointWriteNumber<double>(PetscViewer, const char *, double);
template PetscErrorCode CheckpointWriteNumber<PetscInt>(PetscViewer, const char *, PetscInt);
template PetscErrorCode CheckpointReadNumber<double>(PetscViewer, const char *, double *);
template PetscErrorCode CheckpointReadNumber<PetscInt>(PetscViewer, const char *, PetscInt *);

PetscErrorCode CheckpointWriteRankShare(MPI_Comm comm, PetscViewer v, const char *name, double x) {
  PetscFunctionBeginUser;
  PetscCall(WritePerRank(comm, v, name, x));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointReadRankShare(MPI_Comm comm, PetscViewer v, const char *name,
                                       const std::string &file, PetscInt ranks, double *x) {
  std::vector<double> w;
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(NeedDataset(v, name, file));
  PetscCall(ReadAll(comm, v, name, w));
  PetscCheck((PetscInt)w.size() == ranks, comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: damaged checkpoint (/run/%s)", file.c_str(), name);
  double sum = 0;
  for (double y : w) sum += y;
  *x = ranks == size ? w[rank] : (rank == 0 ? sum : 0.0);
  PetscFunctionReturn(0);
}

namespace {

// The two ends of the structs' checkpoint_fields visitors: each field an attribute of `group`,
// written (bool as 0/1, an enum as its number) ...
struct AttrWriter {
  PetscViewer v;
  const char *group;
  PetscErrorCode operator()(const char *name, double &x) const {
    return PutReal(v, group, name, x);
  }
  PetscErrorCode operator()(const char *name, PetscInt &x) const {
    return PutInt(v, group, name, x);
  }
  PetscErrorCode operator()(const char *name, bool &x) const {
    return PutInt(v, group, name, x ? 1 : 0);
  }
  template <class E, std::enable_if_t<std::is_enum<E>::value, int> = 0>
  PetscErrorCode operator()(const char *name, E &x) const {
    return PutInt(v, group, name, static_cast<PetscInt>(x));
  }
};
// ... and read back (a missing one is a damaged checkpoint).
struct AttrReader {
  PetscViewer v;
  const char *group;
  const std::string &file;
  PetscErrorCode operator()(const char *name, double &x) const {
    return GetReal(v, group, name, file, &x);
  }
  PetscErrorCode operator()(const char *name, PetscInt &x) const {
    return GetInt(v, group, name, file, &x);
  }
  PetscErrorCode operator()(const char *name, bool &x) const {
    PetscInt i = 0;
    PetscFunctionBeginUser;
    PetscCall(GetInt(v, group, name, file, &i));
    x = i != 0;
    PetscFunctionReturn(0);
  }
  template <class E, std::enable_if_t<std::is_enum<E>::value, int> = 0>
  PetscErrorCode operator()(const char *name, E &x) const {
    PetscInt i = 0;
    PetscFunctionBeginUser;
    PetscCall(GetInt(v, group, name, file, &i));
    x = static_cast<E>(i);
    PetscFunctionReturn(0);
  }
};

// The two ends of Chain::checkpoint_arrays and Sheet::checkpoint_arrays: each array a dataset of
// the current group (slack flags as 0/1, the reactions as 4 values), written ...
struct PointArrayWriter {
  PetscViewer v;
  PetscErrorCode operator()(const char *name, std::vector<double> &a) const {
    return CheckpointWriteArray(v, name, a);
  }
  PetscErrorCode operator()(const char *name, std::vector<char> &a) const {
    return CheckpointWriteArray(v, name, std::vector<double>(a.begin(), a.end()));
  }
  PetscErrorCode operator()(const char *name, double (&r)[2][DIM]) const {
    return CheckpointWriteArray(v, name, {r[0][0], r[0][1], r[1][0], r[1][1]});
  }
};
// ... and read back, each of the length this run's chain or sheet has (else a damaged checkpoint).
struct PointArrayReader {
  PetscViewer v;
  const std::string &who; // "chain <name>", "sheet <name>"
  const std::string &file;
  PetscErrorCode read(const char *name, size_t n, std::vector<double> &src) const {
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, name, src));
    PetscCheck(src.size() == n, PetscObjectComm((PetscObject)v), PETSC_ERR_FILE_UNEXPECTED,
               "-restart %s: damaged checkpoint (%s, %s: %d values for %d)", file.c_str(),
               who.c_str(), name, (int)src.size(), (int)n);
    PetscFunctionReturn(0);
  }
  PetscErrorCode operator()(const char *name, std::vector<double> &a) const {
    return read(name, a.size(), a);
  }
  PetscErrorCode operator()(const char *name, std::vector<char> &a) const {
    std::vector<double> src;
    PetscFunctionBeginUser;
    PetscCall(read(name, a.size(), src));
    for (size_t i = 0; i < src.size(); ++i) a[i] = src[i] != 0;
    PetscFunctionReturn(0);
  }
  PetscErrorCode operator()(const char *name, double (&r)[2][DIM]) const {
    std::vector<double> src;
    PetscFunctionBeginUser;
    PetscCall(read(name, 2 * DIM, src));
    for (int e = 0; e < 2; ++e)
      for (int d = 0; d < DIM; ++d) r[e][d] = src[e * DIM + d];
    PetscFunctionReturn(0);
  }
};

constexpr const char *kRun = "/run";

// /run: the run's identity, the stage loop's position, the checkpointed scalars (the structs'
// checkpoint_fields) and the solver's state.
PetscErrorCode WriteRun(Simulation &sim, PetscViewer v, bool in_stage) {
  const char *R = kRun;
  PetscFunctionBeginUser;
  PetscCall(PutString(v, R, "format", kFormat));
  PetscCall(PutString(v, R, "scene", sim.set.scene));
  OptionMap model;
  PetscCall(ModelOptions(model));
  PetscCall(PutString(v, R, "model_options", Serialise(model)));
  PetscCall(PutReal(v, R, "cell_size", sim.set.h));
  PetscCall(PutInt(v, R, "ncell_x", sim.model.ncell[0]));
  PetscCall(PutInt(v, R, "ncell_y", sim.model.ncell[1]));
  PetscCall(PutInt(v, R, "particles_setup", sim.particles_setup));
  PetscCall(PutInt(v, R, "chains", static_cast<PetscInt>(sim.chains.size())));
  PetscCall(PutInt(v, R, "ranks", sim.size));
  PetscCall(PutInt(v, R, "stage", in_stage ? sim.stage : sim.stage + 1));
  PetscCall(PutInt(v, R, "in_stage", in_stage ? 1 : 0));
  const AttrWriter put{v, R};
  PetscCall(sim.checkpoint_fields(put));
  PetscCall(sim.solver->checkpoint_write(sim, v, R)); // relaxation's damping and energy budget
  PetscCall(sim.checkpoint_totals(put));
  PetscFunctionReturn(0);
}

// /run's arrays: the last step's stats, the capped stages, the loads, the partition.
PetscErrorCode WriteRunArrays(Simulation &sim, PetscViewer v) {
  const InterfaceStats &is = sim.iface_stats;
  const ContactStats &cs = sim.contact_stats;
  const RunState &r = sim.run;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, kRun));
  PetscCall(CheckpointWriteArray(v, "iface_stats",
                                 {is.contact_nodes, is.slip_nodes, is.compression, is.tension}));
  std::vector<double> c = {cs.contact_nodes, cs.slip_nodes, cs.separated_nodes, cs.compression,
                           cs.tension};
  c.insert(c.end(), cs.friction.begin(), cs.friction.end());
  PetscCall(CheckpointWriteArray(v, "contact_stats", c));
  PetscCall(CheckpointWriteArray(
      v, "capped_stages", std::vector<double>(r.capped_stages.begin(), r.capped_stages.end())));
  // the surface loads (every rank holds them alike; a scene may have changed them)
  std::vector<double> loads;
  for (const ParticleLoad &L : sim.model.loads)
    for (const double *a : {L.traction, L.tface, L.lp}) loads.insert(loads.end(), a, a + DIM);
  PetscCall(CheckpointWriteArray(v, "loads", loads));
  // the partition the particles' blocks belong to (-balance run may have moved it)
  std::vector<PetscInt> part;
  PetscCall(BalancePartition(sim, part));
  PetscCall(CheckpointWriteArray(v, "partition", std::vector<double>(part.begin(), part.end())));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

// /particles: each field as the ranks' blocks in rank order, and the block sizes.
PetscErrorCode WriteParticles(Simulation &sim, PetscViewer v) {
  PetscInt n;
  hid_t fid, gid;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &n));
  PetscCall(PetscViewerHDF5PushGroup(v, "/particles"));
  PetscCall(WritePerRank(sim.comm, v, "counts", static_cast<double>(n)));
  PetscCall(PetscViewerHDF5OpenGroup(v, nullptr, &fid, &gid));
  for (const ParticleFieldInfo &f : ParticlesFieldList(sim.parts)) {
    void *data;
    PetscInt bs;
    PetscDataType type;
    PetscCall(DMSwarmGetField(sim.parts.sw, f.name, &bs, &type, &data));
    // real fields are written from the swarm's own arrays; integers through the step's scratch
    // (free between steps), so a checkpoint costs no memory per particle (parallel_h5.hpp)
    const double *a = static_cast<const double *>(data);
    if (f.integer) {
      sim.scratch.dudx.resize(std::max(sim.scratch.dudx.size(), static_cast<size_t>(n * bs)));
      for (PetscInt i = 0; i < n * bs; ++i)
        sim.scratch.dudx[i] = static_cast<double>(static_cast<PetscInt *>(data)[i]);
      a = sim.scratch.dudx.data();
    }
    PetscCall(WriteRowsCollective(sim.comm, gid, f.name, n, bs, a, true));
    PetscCall(DMSwarmRestoreField(sim.parts.sw, f.name, &bs, &type, &data));
  }
  H5Gclose(gid);
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

// A chain's or a sheet's group, /<kind>/<k> (kind "chains" or "sheets").
std::string PointSetGroup(const char *kind, size_t k) {
  return std::string("/") + kind + "/" + std::to_string(k);
}

// Its identity, the name and the point count, written ...
PetscErrorCode PutPointSetIdentity(PetscViewer v, const char *g, const std::string &name, int n) {
  PetscFunctionBeginUser;
  PetscCall(PutString(v, g, "name", name));
  PetscCall(PutInt(v, g, "points", n));
  PetscFunctionReturn(0);
}

// ... and read back: the checkpoint's k-th chain or sheet (kind "chain" or "sheet") must be this
// run's, the same name with as many points.
PetscErrorCode CheckPointSetIdentity(Simulation &sim, PetscViewer v, const std::string &file,
                                     const char *kind, size_t k, const char *g,
                                     const std::string &name, int n) {
  std::string stored;
  PetscInt npts;
  PetscFunctionBeginUser;
  PetscCall(GetString(v, g, "name", file, stored));
  PetscCall(GetInt(v, g, "points", file, &npts));
  PetscCheck(stored == name && npts == n, sim.comm, PETSC_ERR_USER_INPUT,
             "-restart %s: the checkpoint's %s %d is %s with %d points, this run's %s with "
             "%d (restart with the options files of the run that wrote it)",
             file.c_str(), kind, (int)k, stored.c_str(), (int)npts, name.c_str(), n);
  PetscFunctionReturn(0);
}

// /chains/<k> (every rank holds them alike: rank 0's are written).
PetscErrorCode WriteChains(Simulation &sim, PetscViewer v) {
  PetscFunctionBeginUser;
  for (size_t k = 0; k < sim.chains.size(); ++k) {
    Chain &ch = sim.chains[k];
    const std::string g = PointSetGroup("chains", k);
    PetscCall(PutPointSetIdentity(v, g.c_str(), ch.name, ch.n));
    PetscCall(ch.checkpoint_fields(AttrWriter{v, g.c_str()}));
    PetscCall(PetscViewerHDF5PushGroup(v, g.c_str()));
    PetscCall(ch.checkpoint_arrays(PointArrayWriter{v}));
    PetscCall(PetscViewerHDF5PopGroup(v));
  }
  PetscFunctionReturn(0);
}

// /sheets/<k>: their positions and velocities (every rank holds them alike).
PetscErrorCode WriteSheets(Simulation &sim, PetscViewer v) {
  PetscFunctionBeginUser;
  for (size_t k = 0; k < sim.sheets.size(); ++k) {
    Sheet &sh = sim.sheets[k];
    const std::string g = PointSetGroup("sheets", k);
    PetscCall(PutPointSetIdentity(v, g.c_str(), sh.name, sh.n));
    PetscCall(PetscViewerHDF5PushGroup(v, g.c_str()));
    PetscCall(sh.checkpoint_arrays(PointArrayWriter{v}));
    PetscCall(PetscViewerHDF5PopGroup(v));
  }
  PetscFunctionReturn(0);
}

// /output: the time series listed so far (rank 0's list; one attribute per frame).
PetscErrorCode WriteFrames(Simulation &sim, PetscViewer v) {
  std::vector<std::string> &frames = OutputSeriesFrames();
  PetscFunctionBeginUser;
  PetscInt nf = sim.rank == 0 ? static_cast<PetscInt>(frames.size()) : 0;
  PetscCallMPI(MPI_Bcast(&nf, 1, MPIU_INT, 0, sim.comm));
  PetscCall(PutInt(v, "/output", "series_frames", nf));
  for (PetscInt i = 0; i < nf; ++i) {
    std::string s = sim.rank == 0 ? frames[i] : std::string();
    int len = static_cast<int>(s.size());
    PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, sim.comm));
    s.resize(static_cast<size_t>(len));
    PetscCallMPI(MPI_Bcast(&s[0], len, MPI_CHAR, 0, sim.comm));
    char a[32];
    snprintf(a, sizeof(a), "frame_%d", (int)i);
    PetscCall(PutString(v, "/output", a, s));
  }
  PetscFunctionReturn(0);
}

// The checkpoint's identity: format, scene, and the presence of the run's size attributes; the
// rank count that wrote it.
PetscErrorCode ReadIdentity(Simulation &sim, PetscViewer v, const std::string &file,
                            PetscInt *ranks) {
  const char *R = kRun, *F = file.c_str();
  std::string fmt, scene;
  double h;
  PetscInt nx, ny, np0, nch;
  PetscFunctionBeginUser;
  PetscCall(GetString(v, R, "format", file, fmt));
  PetscCheck(fmt == kFormat, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: checkpoint format \"%s\", this pmpm reads \"%s\"", F, fmt.c_str(),
             kFormat);
  PetscCall(GetString(v, R, "scene", file, scene));
  PetscCall(GetReal(v, R, "cell_size", file, &h));
  PetscCall(GetInt(v, R, "ncell_x", file, &nx));
  PetscCall(GetInt(v, R, "ncell_y", file, &ny));
  PetscCall(GetInt(v, R, "particles_setup", file, &np0));
  PetscCall(GetInt(v, R, "chains", file, &nch));
  PetscCall(GetInt(v, R, "ranks", file, ranks));
  PetscCheck(scene == sim.set.scene, sim.comm, PETSC_ERR_USER_INPUT,
             "-restart %s: the checkpoint is of scene %s, this run is scene %s (restart with the "
             "options files of the run that wrote it)",
             F, scene.c_str(), sim.set.scene.c_str());
  PetscFunctionReturn(0);
}

// The model it resumes: the same options but run control (RunControl).
PetscErrorCode CheckModelOptions(Simulation &sim, PetscViewer v, const std::string &file) {
  const char *F = file.c_str();
  std::string stored;
  OptionMap now;
  PetscFunctionBeginUser;
  PetscCall(GetString(v, kRun, "model_options", file, stored));
  const OptionMap was = Deserialise(stored);
  PetscCall(ModelOptions(now));
  const char *allowed = "a restart resumes the checkpoint's model; only run control (-max_steps, "
                        "-output_*, -checkpoint_*, -progress_interval, -quiet, -memory_limit, "
                        "-balance*, -da_processors_*, -tol, -damping*, -fire_*, "
                        "-relax_history*) may differ";
  auto shown = [](const std::pair<std::string, std::string> &o) {
    return "-" + o.first + (o.second.empty() ? "" : " " + o.second);
  };
  for (const auto &kv : now) {
    const auto it = was.find(kv.first);
    PetscCheck(it != was.end(), sim.comm, PETSC_ERR_USER_INPUT,
               "-restart %s: %s is given here, not to the run that wrote the checkpoint; %s", F,
               shown(kv.second).c_str(), allowed);
    PetscCheck(SameValue(kv.second.second, it->second.second), sim.comm, PETSC_ERR_USER_INPUT,
               "-restart %s: -%s changed from %s (the run that wrote the checkpoint) to %s; %s", F,
               kv.second.first.c_str(), it->second.second.c_str(), kv.second.second.c_str(),
               allowed);
  }
  for (const auto &kv : was) // (a checkpoint may predate an option's counting as run control)
    PetscCheck(now.count(kv.first) || RunControl(kv.first), sim.comm, PETSC_ERR_USER_INPUT,
               "-restart %s: %s was given to the run that wrote the checkpoint, not here; %s", F,
               shown(kv.second).c_str(), allowed);
  PetscFunctionReturn(0);
}

// /run's stage loop position, the checkpointed scalars and the solver's state.
PetscErrorCode ReadRun(Simulation &sim, PetscViewer v, const std::string &file, PetscInt ranks,
                       PetscInt *stage, PetscInt *in_stage) {
  const char *R = kRun;
  PetscFunctionBeginUser;
  PetscCall(GetInt(v, R, "stage", file, stage));
  PetscCall(GetInt(v, R, "in_stage", file, in_stage));
  const PetscInt nstages = sim.scene->stages();
  PetscCheck(*stage >= 0 && *stage <= nstages + 1, sim.comm, PETSC_ERR_USER_INPUT,
             "-restart %s: the checkpoint is at stage %d, this run has stages 0..%d (restart with "
             "the options files of the run that wrote it)",
             file.c_str(), (int)*stage, (int)nstages);
  const AttrReader get{v, R, file};
  PetscCall(sim.checkpoint_fields(get));
  PetscCall(sim.solver->checkpoint_read(sim, v, R, file, ranks));
  PetscCall(sim.checkpoint_totals(get));
  PetscFunctionReturn(0);
}

// /run's arrays: the last step's stats, the capped stages and the loads.
PetscErrorCode ReadStatsLoads(Simulation &sim, PetscViewer v, const std::string &file) {
  const char *F = file.c_str();
  std::vector<double> is, cs, capped, loads;
  PetscFunctionBeginUser;
  PetscCall(CheckpointReadArray(v, "iface_stats", is));
  PetscCall(CheckpointReadArray(v, "contact_stats", cs));
  PetscCall(CheckpointReadArray(v, "capped_stages", capped));
  sim.run.capped_stages.assign(capped.begin(), capped.end());
  PetscCall(CheckpointReadArray(v, "loads", loads));
  PetscCheck(loads.size() == 3 * DIM * sim.model.loads.size(), sim.comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint has %d loaded particles, these options give %d", F,
             (int)(loads.size() / (3 * DIM)), (int)sim.model.loads.size());
  for (size_t k = 0; k < sim.model.loads.size(); ++k)
    for (int d = 0; d < DIM; ++d) {
      sim.model.loads[k].traction[d] = loads[3 * DIM * k + d];
      sim.model.loads[k].tface[d] = loads[3 * DIM * k + DIM + d];
      sim.model.loads[k].lp[d] = loads[3 * DIM * k + 2 * DIM + d];
    }
  PetscCheck(is.size() == 4 && cs.size() == 5 + sim.chains.size(), sim.comm,
             PETSC_ERR_FILE_UNEXPECTED, "-restart %s: damaged checkpoint (/run stats)", F);
  sim.iface_stats = InterfaceStats{is[0], is[1], is[2], is[3]};
  ContactStats &c = sim.contact_stats;
  c.contact_nodes = cs[0];
  c.slip_nodes = cs[1];
  c.separated_nodes = cs[2];
  c.compression = cs[3];
  c.tension = cs[4];
  c.friction.assign(cs.begin() + 5, cs.end());
  PetscFunctionReturn(0);
}

// On the same rank count each rank takes back its own block of particles: the grid must be
// partitioned as when the checkpoint was written (-balance run may have moved it since setup).
// -dim 3 (no rebuild there: the partition is PETSc's or -da_processors_x/y/z): *moved says the
// particles must be sent to their cells' owners, as on another rank count.
PetscErrorCode ReadPartition(Simulation &sim, PetscViewer v, const std::string &file,
                             PetscInt ranks, bool *moved) {
  std::vector<double> saved;
  std::vector<PetscInt> part;
  PetscFunctionBeginUser;
  PetscCall(CheckpointReadArray(v, "partition", saved));
  PetscCall(BalancePartition(sim, part));
  const std::vector<PetscInt> want(saved.begin(), saved.end());
  *moved = ranks != sim.size || (sim.set.dim == 3 && want != part);
  if (ranks == sim.size && want != part && sim.set.dim == 2) {
    PetscCheck(want.size() >= 2 && (PetscInt)want.size() == 2 + want[0] + want[1] &&
                   want[0] * want[1] == sim.size,
               sim.comm, PETSC_ERR_FILE_UNEXPECTED,
               "-restart %s: damaged checkpoint (/run/partition)", file.c_str());
    PetscCall(BalanceRebuildGrid(
        sim, want[0], want[1], std::vector<PetscInt>(want.begin() + 2, want.begin() + 2 + want[0]),
        std::vector<PetscInt>(want.begin() + 2 + want[0], want.end())));
  }
  PetscFunctionReturn(0);
}

// One swarm field of /particles into columns [off, off + bs) of this rank's nloc records of
// width w.
PetscErrorCode ReadParticleField(Simulation &sim, PetscViewer v, const std::string &file,
                                 const ParticleFieldInfo &f, PetscInt total, PetscInt nloc,
                                 PetscInt w, PetscInt off, std::vector<double> &rec) {
  const char *F = file.c_str();
  Vec x;
  const double *a;
  PetscInt N;
  PetscFunctionBeginUser;
  PetscCall(NeedDataset(v, f.name, file));
  PetscCall(DatasetSize(v, f.name, &N));
  PetscCheck(N == total * f.bs, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: damaged checkpoint (/particles/%s holds %d values, its counts say "
             "%d particles of %d)",
             F, f.name, (int)N, (int)total, f.bs);
  PetscCall(VecCreate(sim.comm, &x));
  PetscCall(PetscObjectSetName((PetscObject)x, f.name));
  PetscCall(VecSetSizes(x, nloc * f.bs, PETSC_DETERMINE));
  PetscCall(VecSetType(x, VECSTANDARD));
  PetscCall(VecLoad(x, v)); // PETSc checks the dataset's size against the counts
  PetscCall(VecGetSize(x, &N));
  PetscCheck(N == total * f.bs, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: damaged checkpoint (/particles/%s)", F, f.name);
  PetscCall(VecGetArrayRead(x, &a));
  for (PetscInt p = 0; p < nloc; ++p)
    for (PetscInt b = 0; b < f.bs; ++b) rec[p * w + off + b] = a[p * f.bs + b];
  PetscCall(VecRestoreArrayRead(x, &a));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

// /particles: this rank's own block on the same rank count (bit for bit), else an even split
// sent on to the ranks owning the particles' cells.
PetscErrorCode ReadParticles(Simulation &sim, PetscViewer v, const std::string &file,
                             PetscInt ranks, bool moved) {
  const char *F = file.c_str();
  std::vector<double> counts;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, "/particles"));
  PetscCall(NeedDataset(v, "counts", file));
  PetscCall(ReadAll(sim.comm, v, "counts", counts));
  PetscCheck((PetscInt)counts.size() == ranks, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: damaged checkpoint (/particles/counts)", F);
  PetscInt total = 0;
  for (double c : counts) total += static_cast<PetscInt>(c);
  PetscInt nloc = 0;
  if (ranks == sim.size)
    nloc = static_cast<PetscInt>(counts[sim.rank]);
  else
    nloc = total / sim.size + (sim.rank < total % sim.size ? 1 : 0);
  const std::vector<ParticleFieldInfo> fields = ParticlesFieldList(sim.parts);
  PetscBool affine; // the APIC matrix: saved exactly when the run had -transfer apic
  PetscCall(PetscViewerHDF5HasDataset(v, kAffineField, &affine));
  PetscCheck(bool(affine) == sim.parts.affine, sim.comm, PETSC_ERR_USER_INPUT,
             "-restart %s: the checkpoint was written with -transfer %s, this run has -transfer "
             "%s: restart with the same -transfer",
             F, affine ? "apic" : "flip", sim.parts.affine ? "apic" : "flip");
  PetscInt w = 0;
  for (const auto &f : fields) w += f.bs;
  std::vector<double> rec(static_cast<size_t>(nloc * w)); // records: every field of a particle
  PetscInt off = 0;
  for (const auto &f : fields) {
    PetscCall(ReadParticleField(sim, v, file, f, total, nloc, w, off, rec));
    off += f.bs;
  }
  if (moved) {
    if (sim.set.dim == 3)
      PetscCall(RecordsRedistribute(sim.comm, sim.grid3, w, rec));
    else
      PetscCall(RecordsRedistribute(sim.comm, sim.grid, w, rec));
  }
  PetscCall(ParticlesUnpack(sim.parts, rec));
  PetscCall(SimulationIndexParticles(sim));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

// /chains/<k>: the same chain (name, points), its scalars and its arrays.
PetscErrorCode ReadChain(Simulation &sim, PetscViewer v, const std::string &file, size_t k) {
  Chain &ch = sim.chains[k];
  const std::string g = PointSetGroup("chains", k);
  PetscFunctionBeginUser;
  PetscCall(CheckPointSetIdentity(sim, v, file, "chain", k, g.c_str(), ch.name, ch.n));
  PetscCall(ch.checkpoint_fields(AttrReader{v, g.c_str(), file}));
  PetscCall(PetscViewerHDF5PushGroup(v, g.c_str()));
  PetscCall(ch.checkpoint_arrays(PointArrayReader{v, "chain " + ch.name, file}));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

// /sheets/<k>: the same sheet (name, points), its positions and velocities; its forces, strains
// and normals recomputed from them (as after a step).
PetscErrorCode ReadSheet(Simulation &sim, PetscViewer v, const std::string &file, size_t k) {
  Sheet &sh = sim.sheets[k];
  const std::string g = PointSetGroup("sheets", k);
  PetscFunctionBeginUser;
  PetscCall(CheckPointSetIdentity(sim, v, file, "sheet", k, g.c_str(), sh.name, sh.n));
  PetscCall(PetscViewerHDF5PushGroup(v, g.c_str()));
  PetscCall(sh.checkpoint_arrays(PointArrayReader{v, "sheet " + sh.name, file}));
  PetscCall(PetscViewerHDF5PopGroup(v));
  if (sh.in_contact()) { // its reference as laid (x0, checkpointed), its plastic state kept
    const std::vector<double> bp = sh.bp, alpha = sh.alpha;
    sheet_reference(sh);
    sh.bp = bp;
    sh.alpha = alpha;
  }
  sheet_update_forces(sh);
  sheet_normals(sh);
  PetscFunctionReturn(0);
}

// /output: the time-series frames listed so far.
PetscErrorCode ReadFrames(Simulation &sim, PetscViewer v, const std::string &file) {
  PetscInt nf;
  PetscFunctionBeginUser;
  PetscCall(GetInt(v, "/output", "series_frames", file, &nf));
  std::vector<std::string> &frames = OutputSeriesFrames();
  frames.clear();
  for (PetscInt i = 0; i < nf; ++i) {
    char a[32];
    std::string s;
    snprintf(a, sizeof(a), "frame_%d", (int)i);
    PetscCall(GetString(v, "/output", a, file, s));
    if (sim.rank == 0) frames.push_back(s);
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckpointWrite(Simulation &sim, bool in_stage) {
  PetscViewer v;
  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PetscLogEventBegin(ev_write, 0, 0, 0, 0));
  PetscCall(OutputPrepareDirectory(sim));
  const std::string name = CheckpointName(sim), path = sim.set.output_dir + "/" + name;
  PetscCall(PetscViewerHDF5Open(sim.comm, (path + ".tmp").c_str(), FILE_MODE_WRITE, &v));
  PetscCall(WriteRun(sim, v, in_stage));
  PetscCall(WriteRunArrays(sim, v));
  PetscCall(WriteParticles(sim, v));
  PetscCall(WriteChains(sim, v));
  PetscCall(WriteSheets(sim, v));
  PetscCall(WriteFrames(sim, v));
  // the scene's own state
  PetscCall(PutString(v, "/scene", "name", sim.set.scene));
  PetscCall(PetscViewerHDF5PushGroup(v, "/scene"));
  PetscCall(sim.scene->checkpoint_write(sim, v));
  PetscCall(PetscViewerHDF5PopGroup(v));

  PetscCall(PetscViewerDestroy(&v));
  PetscCallMPI(MPI_Barrier(sim.comm)); // every rank's part is on disk before the rename
  PetscCall(OutputCommit(sim, name));
  if (!sim.set.quiet)
    PetscCall(PetscPrintf(sim.comm, "checkpoint %s (stage %d, step %d)\n", path.c_str(),
                          (int)sim.stage, (int)sim.run.step));
  PetscCall(PetscLogEventEnd(ev_write, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointRead(Simulation &sim, const std::string &file) {
  PetscViewer v;
  PetscInt ranks, stage, in_stage;
  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PetscLogEventBegin(ev_read, 0, 0, 0, 0));
  PetscCall(CheckFile(sim.comm, sim.rank, file));
  g_reading = file;
  PetscCall(PetscViewerHDF5Open(sim.comm, file.c_str(), FILE_MODE_READ, &v));
  PetscCall(ReadIdentity(sim, v, file, &ranks));
  PetscCall(CheckModelOptions(sim, v, file));
  PetscCall(ReadRun(sim, v, file, ranks, &stage, &in_stage));
  PetscCall(PetscViewerHDF5PushGroup(v, kRun));
  PetscCall(ReadStatsLoads(sim, v, file));
  bool moved = false;
  PetscCall(ReadPartition(sim, v, file, ranks, &moved));
  PetscCall(PetscViewerHDF5PopGroup(v));
  if (sim.set.dim == 3) PetscCall(ExtrudeLoads(sim)); // the table just read, per z spacing
  PetscCall(ReadParticles(sim, v, file, ranks, moved));
  for (size_t k = 0; k < sim.chains.size(); ++k) PetscCall(ReadChain(sim, v, file, k));
  for (size_t k = 0; k < sim.sheets.size(); ++k) PetscCall(ReadSheet(sim, v, file, k));
  PetscCall(ReadFrames(sim, v, file));
  // the scene's own state
  PetscCall(PetscViewerHDF5PushGroup(v, "/scene"));
  PetscCall(sim.scene->checkpoint_read(sim, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));

  sim.stage = stage;
  sim.resume = true;
  sim.resume_in_stage = in_stage != 0;
  if (!sim.set.quiet)
    PetscCall(PetscPrintf(sim.comm, "restart from %s: stage %d, step %d (written on %d rank%s)\n",
                          file.c_str(), (int)stage, (int)sim.run.step, (int)ranks,
                          ranks > 1 ? "s" : ""));
  PetscCall(PetscLogEventEnd(ev_read, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace pmpm
