#include "pmpm/output.hpp"
#include "pmpm/balance.hpp"
#include <cmath>
#include <cstdio>
#include <petscviewerhdf5.h>
#include <sys/stat.h>
#include <vector>

namespace pmpm {

namespace {
PetscLogEvent ev_output = 0;

PetscErrorCode MakeDirs(const std::string &path) {
  PetscFunctionBeginUser;
  std::string cur;
  for (size_t i = 0; i <= path.size(); ++i) {
    if (i == path.size() || path[i] == '/') {
      if (!cur.empty()) {
        struct stat st;
        if (stat(cur.c_str(), &st) != 0)
          PetscCheck(mkdir(cur.c_str(), 0755) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN,
                     "cannot create output directory %s (from -output_dir)", cur.c_str());
      }
    }
    if (i < path.size()) cur += path[i];
  }
  PetscFunctionReturn(0);
}

// Write one particle field (bs values per particle) as a named dataset.
PetscErrorCode WriteField(MPI_Comm comm, PetscViewer v, const char *name, PetscInt n, int bs,
                          const double *data) {
  Vec x;
  double *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, n * bs, PETSC_DETERMINE, &x));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt i = 0; i < n * bs; ++i) a[i] = data[i];
  PetscCall(VecRestoreArray(x, &a));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

std::string XdmfText(const std::string &h5, PetscInt n, double time) {
  char buf[4096];
  const std::string f = h5 + ":/particles/";
  auto attr = [&](const char *name, const char *type, int bs) {
    char a[512];
    if (bs == 1)
      snprintf(a, sizeof(a),
               "      <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n"
               "        <DataItem Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" "
               "Format=\"HDF\">%s%s</DataItem>\n      </Attribute>\n",
               name, (int)n, f.c_str(), name);
    else
      snprintf(a, sizeof(a),
               "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n"
               "        <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" "
               "Format=\"HDF\">%s%s</DataItem>\n      </Attribute>\n",
               name, type, (int)n, bs, f.c_str(), name);
    return std::string(a);
  };
  snprintf(buf, sizeof(buf),
           "    <Grid Name=\"particles\" GridType=\"Uniform\">\n"
           "      <Time Value=\"%.9g\"/>\n"
           "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\"/>\n"
           "      <Geometry GeometryType=\"XY\">\n"
           "        <DataItem Dimensions=\"%d 2\" NumberType=\"Float\" Precision=\"8\" "
           "Format=\"HDF\">%sposition</DataItem>\n      </Geometry>\n",
           time, (int)n, (int)n, f.c_str());
  std::string s = buf;
  s += attr("displacement", "Vector", 2);
  s += attr("velocity", "Vector", 2);
  s += attr("stress", "Matrix", 4);
  s += attr("volume", "Scalar", 1);
  s += attr("material", "Scalar", 1);
  s += attr("eps_p", "Scalar", 1);
  s += attr("id", "Scalar", 1);
  s += "    </Grid>\n";
  return s;
}

std::vector<std::string> g_series; // XDMF grids of the time-series frames (rank 0)
} // namespace

std::string json_num(double v) {
  if (!std::isfinite(v)) return "null";
  char b[64];
  snprintf(b, sizeof(b), "%.17g", v);
  return b;
}
std::string json_kv(const std::string &k, double v) {
  return "\"" + k + "\": " + json_num(v);
}
std::string json_kv(const std::string &k, const std::string &raw) {
  return "\"" + k + "\": " + raw;
}

PetscErrorCode OutputPrepareDirectory(Simulation &sim) {
  PetscFunctionBeginUser;
  if (!ev_output) {
    PetscClassId cls;
    PetscCall(PetscClassIdRegister("pmpm output", &cls));
    PetscCall(PetscLogEventRegister("Output", cls, &ev_output));
  }
  PetscErrorCode ierr = 0;
  if (sim.rank == 0)
    ierr =
        MakeDirs(sim.set.output_dir + (sim.set.output_every || sim.nstages > 0 ? "/series" : ""));
  PetscCallMPI(MPI_Bcast(&ierr, 1, MPI_INT, 0, sim.comm));
  PetscCheck(!ierr, sim.comm, PETSC_ERR_FILE_OPEN, "cannot create -output_dir %s",
             sim.set.output_dir.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode OutputCommit(Simulation &sim, const std::string &name) {
  PetscFunctionBeginUser;
  if (sim.rank == 0) {
    const std::string dst = sim.set.output_dir + "/" + name;
    PetscCheck(std::rename((dst + ".tmp").c_str(), dst.c_str()) == 0, PETSC_COMM_SELF,
               PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", dst.c_str());
  }
  PetscCallMPI(MPI_Barrier(sim.comm));
  PetscFunctionReturn(0);
}

// Writes DIR/<h5name> (via .tmp) and DIR/<stem>.xmf beside it.
PetscErrorCode OutputParticles(Simulation &sim, const std::string &h5name) {
  ParticleView P;
  PetscViewer v;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_output, 0, 0, 0, 0));
  const std::string path = sim.set.output_dir + "/" + h5name;
  PetscCall(ParticlesGetView(sim.parts, P));
  const PetscInt n = P.n;
  std::vector<double> disp(n * DIM), mat(n), id(n);
  for (PetscInt p = 0; p < n; ++p) {
    for (int d = 0; d < DIM; ++d) disp[p * DIM + d] = P.x[p * DIM + d] - P.x0[p * DIM + d];
    mat[p] = P.mat[p];
    id[p] = P.pid[p];
  }
  PetscCall(PetscViewerHDF5Open(sim.comm, (path + ".tmp").c_str(), FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/particles"));
  PetscCall(WriteField(sim.comm, v, "position", n, DIM, P.x));
  PetscCall(WriteField(sim.comm, v, "position0", n, DIM, P.x0));
  PetscCall(WriteField(sim.comm, v, "displacement", n, DIM, disp.data()));
  PetscCall(WriteField(sim.comm, v, "velocity", n, DIM, P.v));
  PetscCall(WriteField(sim.comm, v, "stress", n, NSTRESS, P.stress));
  PetscCall(WriteField(sim.comm, v, "F", n, DIM * DIM, P.F));
  PetscCall(WriteField(sim.comm, v, "volume", n, 1, P.vol));
  PetscCall(WriteField(sim.comm, v, "volume0", n, 1, P.vol0));
  PetscCall(WriteField(sim.comm, v, "halfsize", n, DIM, P.lp));
  PetscCall(WriteField(sim.comm, v, "mass", n, 1, P.mass));
  PetscCall(WriteField(sim.comm, v, "eps_p", n, 1, P.eps_p));
  PetscCall(WriteField(sim.comm, v, "colour", n, 1, P.colour));
  PetscCall(WriteField(sim.comm, v, "material", n, 1, mat.data()));
  PetscCall(WriteField(sim.comm, v, "id", n, 1, id.data()));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(ParticlesRestoreView(sim.parts, P));
  PetscCall(OutputCommit(sim, h5name));

  PetscInt ntot;
  PetscCall(ParticlesGlobalCount(sim.parts, &ntot));
  if (sim.rank == 0) {
    const std::string stem = h5name.substr(0, h5name.size() - 3);
    const std::string base = h5name.substr(h5name.find_last_of('/') + 1);
    FILE *f = std::fopen((sim.set.output_dir + "/" + stem + ".xmf").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s.xmf", stem.c_str());
    std::fprintf(f,
                 "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n  <Domain>\n%s"
                 "  </Domain>\n</Xdmf>\n",
                 XdmfText(base, ntot, sim.run.time).c_str());
    std::fclose(f);
    if (h5name.rfind("series/", 0) == 0) g_series.push_back(XdmfText(base, ntot, sim.run.time));
  }
  PetscCall(PetscLogEventEnd(ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputSeriesFrame(Simulation &sim) {
  char name[64];
  PetscFunctionBeginUser;
  static bool first = true; // this process's first frame (a restarted run's may come later)
  if (first) PetscCall(OutputPrepareDirectory(sim));
  first = false;
  snprintf(name, sizeof(name), "series/particles_%08d.h5", (int)sim.run.step);
  PetscCall(OutputParticles(sim, name));
  PetscFunctionReturn(0);
}

std::vector<std::string> &OutputSeriesFrames() {
  return g_series;
}

PetscErrorCode OutputSeriesFinish(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.rank == 0 && !g_series.empty()) {
    FILE *f = std::fopen((sim.set.output_dir + "/series/particles_series.xmf").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write the series .xmf");
    std::fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n  <Domain>\n"
                    "  <Grid Name=\"series\" GridType=\"Collection\" "
                    "CollectionType=\"Temporal\">\n");
    for (const auto &g : g_series) std::fprintf(f, "%s", g.c_str());
    std::fprintf(f, "  </Grid>\n  </Domain>\n</Xdmf>\n");
    std::fclose(f);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OutputSummary(Simulation &sim, const std::string &results) {
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(ParticlesGlobalCount(sim.parts, &n));
  std::string partition;
  PetscCall(PartitionJson(sim, partition));
  if (sim.rank == 0) {
    const std::string path = sim.set.output_dir + "/summary.json";
    FILE *f = std::fopen((path + ".tmp").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
    const Settings &s = sim.set;
    std::string iface;
    if (sim.iface.type != InterfaceType::Bonded) {
      const double *I = sim.iface_impulse;
      const char *sep = ",\n    ";
      iface = std::string("\"interface\": {\n    \"type\": \"") +
              InterfaceTypeNames[(int)sim.iface.type] + "\"" + sep + "\"normals\": \"" +
              InterfaceNormalsNames[(int)sim.iface.normals] + "\"" + sep +
              json_kv("mu_top", sim.iface.mu_top) + sep +
              json_kv("mu_bottom", sim.iface.mu_bottom) + sep +
              json_kv("normal_impulse_compression", I[0]) + sep +
              json_kv("normal_impulse_tension", I[1]) + sep +
              json_kv("tension_ratio", I[0] > 0 ? I[1] / I[0] : 0.0) + "\n  },\n  ";
    }
    iface += ChainSummaryJson(sim);
    // the equilibrium solver, and Newton's work (load steps, nonlinear and linear iterations)
    std::string solver = std::string("\"solver\": \"") + SolverNames[(int)s.solver] + "\",\n  ";
    if (s.solver == Solver::Newton)
      solver += "\"newton\": {\"load_steps\": " + std::to_string(sim.run.load_steps) +
                ", \"nonlinear_iterations\": " + std::to_string(sim.run.newton_its) +
                ", \"linear_iterations\": " + std::to_string(sim.run.linear_its) + "},\n  ";
    iface = solver + iface;
    std::fprintf(f,
                 "{\n  \"scene\": \"%s\",\n  \"ranks\": %d,\n  \"particles\": %d,\n"
                 "  \"cells\": [%d, %d],\n  %s,\n  \"ppc\": %d,\n  \"shape\": \"%s\",\n"
                 "  \"cfl\": %s,\n  \"steps\": %d,\n  \"time\": %s,\n  %s,\n"
                 "  \"converged\": %s,\n  %s,\n  \"tolerance\": %s,\n  \"migrations\": %d,\n"
                 "  %s,\n  %s\"results\": {\n    %s\n  }\n}\n",
                 s.scene.c_str(), sim.size, (int)n, (int)sim.ncell[0], (int)sim.ncell[1],
                 json_kv("h", s.h).c_str(), (int)s.ppc, ShapeKindNames[(int)s.shape],
                 json_num(s.cfl).c_str(), (int)sim.run.step, json_num(sim.run.time).c_str(),
                 json_kv("wall_seconds", sim.run.wall_seconds).c_str(),
                 sim.run.converged ? "true" : "false",
                 json_kv("unbalanced_force_ratio", sim.run.ratio).c_str(), json_num(s.tol).c_str(),
                 (int)sim.run.migrations, partition.c_str(), iface.c_str(), results.c_str());
    std::fclose(f);
  }
  PetscCall(OutputCommit(sim, "summary.json"));
  PetscFunctionReturn(0);
}

} // namespace pmpm
