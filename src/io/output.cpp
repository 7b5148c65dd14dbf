#include "pmpm/io/output.hpp"
#include "pmpm/model/balance.hpp"
#include "pmpm/io/parallel_h5.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include <algorithm>
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

// dim: the particles' dimension (2: XY; 3: XYZ and the six stress components).
std::string XdmfText(const std::string &h5, PetscInt n, double time, int dim) {
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
           "      <Geometry GeometryType=\"%s\">\n"
           "        <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" "
           "Format=\"HDF\">%sposition</DataItem>\n      </Geometry>\n",
           time, (int)n, dim == 3 ? "XYZ" : "XY", (int)n, dim, f.c_str());
  std::string s = buf;
  s += attr("displacement", "Vector", dim);
  s += attr("velocity", "Vector", dim);
  s += attr("stress", "Matrix", dim == 3 ? NStress<3> : NStress<2>);
  s += attr("volume", "Scalar", 1);
  s += attr("material", "Scalar", 1);
  s += attr("eps_p", "Scalar", 1);
  s += attr("id", "Scalar", 1);
  s += "    </Grid>\n";
  return s;
}

std::vector<std::string> g_series; // XDMF grids of the time-series frames (rank 0)
bool g_series_first = true;        // this run's first frame (a restarted run's may come later)
} // namespace

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
  const int D = sim.parts.dim, NS = D == 3 ? NStress<3> : NStress<2>;
  const std::string path = sim.set.output_dir + "/" + h5name;
  PetscCall(ParticlesGetView(sim.parts, P));
  const PetscInt n = P.n;
  // The fields that are not stored go through the step's scratch (L dt per particle between G2P
  // and the stress update, free between steps): no new memory.
  std::vector<double> &derived = sim.scratch.dudx;
  derived.resize(std::max(derived.size(), static_cast<size_t>(n * D)));
  PetscCall(PetscViewerHDF5Open(sim.comm, (path + ".tmp").c_str(), FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/particles"));
  hid_t fid, gid;
  PetscCall(PetscViewerHDF5OpenGroup(v, nullptr, &fid, &gid));
  // every rank writes its own particles' rows of each dataset, in one collective MPI-IO call (a
  // parallel file system's fast path): nothing is gathered on one rank (parallel_h5.hpp)

  PetscCall(WriteRowsCollective(sim.comm, gid, "position", n, D, P.x));
  PetscCall(WriteRowsCollective(sim.comm, gid, "position0", n, D, P.x0));
  for (PetscInt i = 0; i < n * D; ++i) derived[i] = P.x[i] - P.x0[i];
  PetscCall(WriteRowsCollective(sim.comm, gid, "displacement", n, D, derived.data()));
  PetscCall(WriteRowsCollective(sim.comm, gid, "velocity", n, D, P.v));
  PetscCall(WriteRowsCollective(sim.comm, gid, "stress", n, NS, P.stress));
  PetscCall(WriteRowsCollective(sim.comm, gid, "F", n, D * D, P.F));
  PetscCall(WriteRowsCollective(sim.comm, gid, "volume", n, 1, P.vol));
  PetscCall(WriteRowsCollective(sim.comm, gid, "volume0", n, 1, P.vol0));
  if (sim.set.shape == ShapeKind::CPGIMP) { // the block the weights see: cpGIMP's deformed one
    for (PetscInt p = 0; p < n; ++p)
      if (D == 3)
        CPGIMPShape::half<3>(P.lp + p * D, P.F + p * D * D, &derived[p * D]);
      else
        CPGIMPShape::half<2>(P.lp + p * D, P.F + p * D * D, &derived[p * D]);
    PetscCall(WriteRowsCollective(sim.comm, gid, "halfsize", n, D, derived.data()));
  } else
    PetscCall(WriteRowsCollective(sim.comm, gid, "halfsize", n, D, P.lp));
  PetscCall(WriteRowsCollective(sim.comm, gid, "mass", n, 1, P.mass));
  PetscCall(WriteRowsCollective(sim.comm, gid, "eps_p", n, 1, P.eps_p));
  PetscCall(WriteRowsCollective(sim.comm, gid, "colour", n, 1, P.colour));
  for (PetscInt p = 0; p < n; ++p) derived[p] = P.mat[p];
  PetscCall(WriteRowsCollective(sim.comm, gid, "material", n, 1, derived.data()));
  for (PetscInt p = 0; p < n; ++p) derived[p] = P.pid[p];
  PetscCall(WriteRowsCollective(sim.comm, gid, "id", n, 1, derived.data()));
  H5Gclose(gid);
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  H5garbage_collect(); // HDF5's free lists hand their blocks back
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
                 XdmfText(base, ntot, sim.run.time, D).c_str());
    std::fclose(f);
    if (h5name.rfind("series/", 0) == 0) g_series.push_back(XdmfText(base, ntot, sim.run.time, D));
  }
  PetscCall(PetscLogEventEnd(ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputSeriesFrame(Simulation &sim) {
  char name[64];
  PetscFunctionBeginUser;
  if (g_series_first) PetscCall(OutputPrepareDirectory(sim));
  g_series_first = false;
  snprintf(name, sizeof(name), "series/particles_%08d.h5", (int)sim.run.step);
  PetscCall(OutputParticles(sim, name));
  PetscFunctionReturn(0);
}

void OutputSeriesReset() {
  g_series.clear();
  g_series_first = true;
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

PetscErrorCode OutputSummary(Simulation &sim, const std::string &results,
                             const std::string &design) {
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
    if (sim.model.iface.type != InterfaceType::Bonded) {
      const double *I = sim.iface_impulse;
      const char *sep = ",\n    ";
      iface = std::string("\"interface\": {\n    \"type\": \"") +
              InterfaceTypeNames[(int)sim.model.iface.type] + "\"" + sep + "\"normals\": \"" +
              InterfaceNormalsNames[(int)sim.model.iface.normals] + "\"" + sep +
              json_kv("mu_top", sim.model.iface.mu_top) + sep +
              json_kv("mu_bottom", sim.model.iface.mu_bottom) + sep +
              json_kv("normal_impulse_compression", I[0]) + sep +
              json_kv("normal_impulse_tension", I[1]) + sep +
              json_kv("tension_ratio", I[0] > 0 ? I[1] / I[0] : 0.0) + "\n  },\n  ";
    }
    iface += ChainSummaryJson(sim);
    // the equilibrium solver, and its own report (Newton: load steps, nonlinear and linear
    // iterations)
    std::string solver = "\"solver\": \"" + s.solver + "\",\n  " + sim.solver->report();
    iface = solver + iface;
    std::string cells =
        std::to_string(sim.model.ncell[0]) + ", " + std::to_string(sim.model.ncell[1]);
    if (s.dim == 3) cells += ", " + std::to_string(sim.grid3.ncell[2]); // -depth's cells
    std::fprintf(
        f,
        "{\n  \"scene\": \"%s\",\n  \"ranks\": %d,\n  \"particles\": %d,\n"
        "  \"cells\": [%s],\n  %s,\n  \"ppc\": %d,\n  \"shape\": \"%s\",\n"
        "  \"cfl\": %s,\n  \"steps\": %d,\n  \"time\": %s,\n  %s,\n"
        "  \"converged\": %s,\n  %s,\n  \"tolerance\": %s,\n  \"migrations\": %d,\n"
        "  %s,\n  %s%s,\n  \"results\": {\n    %s\n  }\n}\n",
        s.scene.c_str(), sim.size, (int)n, cells.c_str(), json_kv("h", s.h).c_str(), (int)s.ppc,
        ShapeKindNames[(int)s.shape], json_num(s.cfl).c_str(), (int)sim.run.step,
        json_num(sim.run.time).c_str(), json_kv("wall_seconds", sim.run.wall_seconds).c_str(),
        sim.run.converged ? "true" : "false",
        json_kv("unbalanced_force_ratio", sim.run.ratio).c_str(), json_num(s.tol).c_str(),
        (int)sim.run.migrations, partition.c_str(), iface.c_str(), design.c_str(), results.c_str());
    std::fclose(f);
  }
  PetscCall(OutputCommit(sim, "summary.json"));
  PetscFunctionReturn(0);
}

} // namespace pmpm
