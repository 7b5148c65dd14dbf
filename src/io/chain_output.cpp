// Membrane chains' output: a profile CSV per chain, the chains as polylines in HDF5 + XDMF (drawn
// by ParaView over the particles), and their block of summary.json. Every rank holds every
// point, so rank 0 writes.
#include "pmpm/io/output.hpp"
#include <cmath>
#include <cstdio>
#include <petscviewerhdf5.h>

namespace pmpm {

namespace {
// Point values from the adjacent segments: mean strain and tension, slack if either is.
void point_segment_values(const Chain &c, int i, double &eps, double &T, bool &slack) {
  const int a = std::max(i - 1, 0), b = std::min(i, c.n - 2);
  eps = 0.5 * (c.eps[a] + c.eps[b]);
  T = 0.5 * (c.T[a] + c.T[b]);
  slack = c.slack[a] || c.slack[b];
}

PetscErrorCode WriteSeq(PetscViewer v, const char *name, int n, int bs, const double *data) {
  Vec x;
  double *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n * bs, &x));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecGetArray(x, &a));
  for (int i = 0; i < n * bs; ++i) a[i] = data[i];
  PetscCall(VecRestoreArray(x, &a));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode OutputChains(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.chains.empty()) PetscFunctionReturn(0);
  if (sim.rank == 0) {
    const std::string dir = sim.set.output_dir;
    for (const Chain &c : sim.chains) {
      const std::string path = dir + "/chain_" + c.name + ".csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      // under -geometry axisymmetric also the hoop strain and tension (chain.hpp)
      std::fprintf(f,
                   "s0,x0,y0,x,y,ux,uy,strain,tension,slack,slip_top,slip_bottom,"
                   "pressure_top,pressure_bottom%s\n",
                   c.axisymmetric ? ",strain_hoop,tension_hoop" : "");
      double s0 = 0;
      for (int i = 0; i < c.n; ++i) {
        if (i > 0) s0 += c.l0[i - 1];
        double eps, T;
        bool slack;
        point_segment_values(c, i, eps, T, slack);
        const double *x = &c.x[i * DIM], *x0 = &c.x0[i * DIM];
        std::fprintf(
            f, "%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%d,%.15g,%.15g,%.15g,%.15g",
            s0, x0[0], x0[1], x[0], x[1], x[0] - x0[0], x[1] - x0[1], eps, T, slack ? 1 : 0,
            c.slip_top[i], c.slip_bot[i], c.p_top[i], c.p_bot[i]);
        if (c.axisymmetric) {
          const int a = std::max(i - 1, 0), b = std::min(i, c.n - 2);
          std::fprintf(f, ",%.15g,%.15g", 0.5 * (c.eps_hoop[a] + c.eps_hoop[b]),
                       0.5 * (c.T_hoop[a] + c.T_hoop[b]));
        }
        std::fprintf(f, "\n");
      }
      std::fclose(f);
      PetscCheck(std::rename((path + ".tmp").c_str(), path.c_str()) == 0, PETSC_COMM_SELF,
                 PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", path.c_str());
    }
    // chains.h5: /chains/<name>/{position, position0, strain, tension, slip_top, slip_bottom}
    PetscViewer v;
    const std::string h5 = dir + "/chains.h5";
    PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, (h5 + ".tmp").c_str(), FILE_MODE_WRITE, &v));
    std::string xmf = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n  <Domain>\n";
    for (const Chain &c : sim.chains) {
      std::vector<double> eps(c.n), T(c.n), slack(c.n);
      for (int i = 0; i < c.n; ++i) {
        bool s;
        point_segment_values(c, i, eps[i], T[i], s);
        slack[i] = s;
      }
      PetscCall(PetscViewerHDF5PushGroup(v, ("/chains/" + c.name).c_str()));
      PetscCall(WriteSeq(v, "position", c.n, DIM, c.x.data()));
      PetscCall(WriteSeq(v, "position0", c.n, DIM, c.x0.data()));
      PetscCall(WriteSeq(v, "strain", c.n, 1, eps.data()));
      PetscCall(WriteSeq(v, "tension", c.n, 1, T.data()));
      PetscCall(WriteSeq(v, "slack", c.n, 1, slack.data()));
      PetscCall(WriteSeq(v, "slip_top", c.n, 1, c.slip_top.data()));
      PetscCall(WriteSeq(v, "slip_bottom", c.n, 1, c.slip_bot.data()));
      PetscCall(PetscViewerHDF5PopGroup(v));
      char buf[4096];
      const std::string g = "chains.h5:/chains/" + c.name + "/";
      snprintf(buf, sizeof(buf),
               "    <Grid Name=\"chain %s\" GridType=\"Uniform\">\n"
               "      <Time Value=\"%.9g\"/>\n"
               "      <Topology TopologyType=\"Polyline\" NodesPerElement=\"%d\" "
               "NumberOfElements=\"1\"/>\n"
               "      <Geometry GeometryType=\"XY\">\n"
               "        <DataItem Dimensions=\"%d 2\" NumberType=\"Float\" Precision=\"8\" "
               "Format=\"HDF\">%sposition</DataItem>\n      </Geometry>\n",
               c.name.c_str(), sim.run.time, c.n, c.n, g.c_str());
      xmf += buf;
      for (const char *a : {"strain", "tension", "slack", "slip_top", "slip_bottom"}) {
        snprintf(buf, sizeof(buf),
                 "      <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                 "        <DataItem Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" "
                 "Format=\"HDF\">%s%s</DataItem>\n      </Attribute>\n",
                 a, c.n, g.c_str(), a);
        xmf += buf;
      }
      xmf += "    </Grid>\n";
    }
    xmf += "  </Domain>\n</Xdmf>\n";
    PetscCall(PetscViewerDestroy(&v));
    PetscCheck(std::rename((h5 + ".tmp").c_str(), h5.c_str()) == 0, PETSC_COMM_SELF,
               PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", h5.c_str());
    FILE *f = std::fopen((dir + "/chains.xmf").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write chains.xmf");
    std::fprintf(f, "%s", xmf.c_str());
    std::fclose(f);
  }
  PetscCallMPI(MPI_Barrier(sim.comm));
  PetscFunctionReturn(0);
}

std::string ChainSummaryJson(const Simulation &sim) {
  if (sim.chains.empty()) return "";
  std::string s = "\"chains\": {\n";
  const char *sep = ",\n      ";
  for (size_t k = 0; k < sim.chains.size(); ++k) {
    const Chain &c = sim.chains[k];
    int ipk = 0, itk = 0;
    double slack_len = 0, smin = 1e300, stop = 0, sbot = 0;
    for (int j = 0; j + 1 < c.n; ++j) {
      if (c.eps[j] > c.eps[ipk]) ipk = j;
      if (c.T[j] > c.T[itk]) itk = j;
      smin = std::fmin(smin, c.eps[j]);
      if (c.slack[j]) slack_len += c.l0[j];
    }
    for (int i = 0; i < c.n; ++i) {
      stop = std::fmax(stop, std::fabs(c.slip_top[i]));
      sbot = std::fmax(sbot, std::fabs(c.slip_bot[i]));
    }
    auto mid = [&](int j, int d) { return 0.5 * (c.x[j * DIM + d] + c.x[(j + 1) * DIM + d]); };
    s += "    \"" + c.name + "\": {\n      \"law\": \"" + MembraneLawNames[c.law.kind] + "\"" +
         sep + "\"axial_stiffness_kind\": \"" + StiffnessKindNames[(int)c.stiffness] + "\"" + sep +
         json_kv("axial_stiffness", c.law.J) + sep + json_kv("thickness", c.thickness) + sep +
         json_kv("points", double(c.n)) + sep + json_kv("line_mass", c.line_mass) + sep +
         json_kv("line_weight", c.line_weight) + sep + "\"interface\": \"" +
         FaceTypeNames[(int)c.top.type] + "\"" + sep + json_kv("mu_top", c.top.mu) + sep +
         json_kv("mu_bottom", c.bottom.mu) + sep + json_kv("adhesion_top", c.top.adhesion) + sep +
         json_kv("adhesion_bottom", c.bottom.adhesion) + sep + json_kv("peak_strain", c.eps[ipk]) +
         sep + json_kv("peak_strain_x", mid(ipk, 0)) + sep + json_kv("peak_strain_y", mid(ipk, 1)) +
         sep + json_kv("min_strain", smin) + sep + json_kv("peak_tension", c.T[itk]) + sep +
         json_kv("peak_tension_x", mid(itk, 0)) + sep + json_kv("slack_length", slack_len) + sep +
         json_kv("max_slip_top", stop) + sep + json_kv("max_slip_bottom", sbot) + sep +
         json_kv("friction_force", c.friction_force) + sep + "\"reaction_start\": [" +
         json_num(c.reaction[0][0]) + ", " + json_num(c.reaction[0][1]) + "]" + sep +
         "\"reaction_end\": [" + json_num(c.reaction[1][0]) + ", " + json_num(c.reaction[1][1]) +
         "]\n    }";
    s += k + 1 < sim.chains.size() ? ",\n" : "\n";
  }
  const ContactStats &cs = sim.contact_stats;
  const double *I = sim.contact_impulse;
  s += "  },\n  \"contact\": {\n    " + json_kv("contact_nodes", cs.contact_nodes) + ",\n    " +
       json_kv("slip_nodes", cs.slip_nodes) + ",\n    " +
       json_kv("separated_nodes", cs.separated_nodes) + ",\n    " +
       json_kv("normal_impulse_compression", I[0]) + ",\n    " +
       json_kv("normal_impulse_tension", I[1]) + "\n  },\n  ";
  return s;
}

} // namespace pmpm
