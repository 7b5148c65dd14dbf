// 3D sheets' output (sheet.hpp): a point table per sheet (sheet_<name>.csv) and the sheets as
// triangulated surfaces in HDF5 + XDMF (sheets.h5, sheets.xmf: ParaView draws them over the
// particles), with principal strains and tensions per point (the area-weighted means of
// sheet_point_principal) and per triangle, each triangle's state and major direction. Every rank
// holds every point, so rank 0 writes, under temporary names renamed when complete.
#include "pmpm/io/output.hpp"
#include <cstdio>
#include <hdf5.h>

namespace pmpm {

namespace {
// A (rows, cols) dataset of `type` (cols == 1: shape (rows)) under loc; true on failure.
bool WriteDataset(hid_t loc, const char *name, int rows, int cols, hid_t type, const void *data) {
  const hsize_t dims[2] = {static_cast<hsize_t>(rows), static_cast<hsize_t>(cols)};
  const hid_t space = H5Screate_simple(cols > 1 ? 2 : 1, dims, nullptr);
  const hid_t d = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool bad = d < 0 || H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0;
  if (d >= 0) bad |= H5Dclose(d) < 0;
  return bad | (H5Sclose(space) < 0);
}
bool WriteDoubles(hid_t loc, const char *name, int rows, int cols, const double *data) {
  return WriteDataset(loc, name, rows, cols, H5T_NATIVE_DOUBLE, data);
}

// One sheet's values for the files: per point (2 per point, major first) and per triangle.
struct SheetFields {
  std::vector<double> strain, tension;                  // per point
  std::vector<double> u, pinned;                        // per point: displacement, held
  std::vector<double> e1, e2, n1, n2, state, direction; // per triangle
};

SheetFields Fields(const Sheet &s) {
  SheetFields F;
  sheet_point_principal(s, F.strain, F.tension);
  F.u.resize(s.x.size());
  for (size_t k = 0; k < s.x.size(); ++k) F.u[k] = s.x[k] - s.x0[k];
  F.pinned.assign(s.pinned.begin(), s.pinned.end());
  F.direction.resize(3 * static_cast<size_t>(s.nt));
  for (int t = 0; t < s.nt; ++t) {
    F.e1.push_back(s.b[2 * t]);
    F.e2.push_back(s.b[2 * t + 1]);
    F.n1.push_back(s.N[2 * t]);
    F.n2.push_back(s.N[2 * t + 1]);
    F.state.push_back(static_cast<double>(s.state[t]));
    sheet_major_direction(s, t, &F.direction[3 * static_cast<size_t>(t)]);
  }
  return F;
}

// Column k of a (n, 2) array.
std::vector<double> Column(const std::vector<double> &a, int k) {
  std::vector<double> c(a.size() / 2);
  for (size_t i = 0; i < c.size(); ++i) c[i] = a[2 * i + k];
  return c;
}

PetscErrorCode WriteCsv(const std::string &path, const Sheet &s, const SheetFields &F) {
  PetscFunctionBeginUser;
  FILE *f = std::fopen((path + ".tmp").c_str(), "w");
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
  std::fprintf(f,
               "x0,y0,z0,x,y,z,ux,uy,uz,strain_major,strain_minor,tension_major,"
               "tension_minor,pinned%s\n",
               s.in_contact() ? ",slip_top_x,slip_top_y,slip_top_z,slip_bottom_x,slip_bottom_y,"
                                "slip_bottom_z,pressure_top,pressure_bottom"
                              : "");
  for (int i = 0; i < s.n; ++i) {
    const double *x = &s.x[3 * static_cast<size_t>(i)], *x0 = &s.x0[3 * static_cast<size_t>(i)];
    std::fprintf(f,
                 "%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,"
                 "%.15g,%d",
                 x0[0], x0[1], x0[2], x[0], x[1], x[2], x[0] - x0[0], x[1] - x0[1], x[2] - x0[2],
                 F.strain[2 * i], F.strain[2 * i + 1], F.tension[2 * i], F.tension[2 * i + 1],
                 s.pinned[i] ? 1 : 0);
    if (s.in_contact()) {
      const double *a = &s.slip_top[3 * static_cast<size_t>(i)],
                   *b = &s.slip_bot[3 * static_cast<size_t>(i)];
      std::fprintf(f, ",%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g,%.15g", a[0], a[1], a[2], b[0],
                   b[1], b[2], s.p_top[i], s.p_bot[i]);
    }
    std::fprintf(f, "\n");
  }
  std::fclose(f);
  PetscCheck(std::rename((path + ".tmp").c_str(), path.c_str()) == 0, PETSC_COMM_SELF,
             PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", path.c_str());
  PetscFunctionReturn(0);
}

// The XDMF grid of one sheet (its datasets in sheets.h5 under /sheets/<name>/).
std::string XdmfSheet(const Sheet &s, const std::string &name, double time) {
  const std::string g = "sheets.h5:/sheets/" + name + "/";
  char buf[1024];
  snprintf(buf, sizeof(buf),
           "    <Grid Name=\"sheet %s\" GridType=\"Uniform\">\n"
           "      <Time Value=\"%.9g\"/>\n"
           "      <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n"
           "        <DataItem Dimensions=\"%d 3\" NumberType=\"Int\" Precision=\"4\" "
           "Format=\"HDF\">%striangles</DataItem>\n      </Topology>\n"
           "      <Geometry GeometryType=\"XYZ\">\n"
           "        <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" Precision=\"8\" "
           "Format=\"HDF\">%sposition</DataItem>\n      </Geometry>\n",
           name.c_str(), time, s.nt, s.nt, g.c_str(), s.n, g.c_str());
  std::string x = buf;
  struct Attr {
    const char *name, *centre;
    int n, comps;
  };
  const Attr attrs[] = {{"displacement", "Node", s.n, 3},
                        {"strain_major", "Node", s.n, 1},
                        {"strain_minor", "Node", s.n, 1},
                        {"tension_major", "Node", s.n, 1},
                        {"tension_minor", "Node", s.n, 1},
                        {"pinned", "Node", s.n, 1},
                        {"triangle_strain_major", "Cell", s.nt, 1},
                        {"triangle_strain_minor", "Cell", s.nt, 1},
                        {"triangle_tension_major", "Cell", s.nt, 1},
                        {"triangle_tension_minor", "Cell", s.nt, 1},
                        {"triangle_state", "Cell", s.nt, 1},
                        {"triangle_direction_major", "Cell", s.nt, 3},
                        {"triangle_plastic_strain", "Cell", s.nt, 1},
                        {"slip_top", "Node", s.n, 3},
                        {"slip_bottom", "Node", s.n, 3},
                        {"pressure_top", "Node", s.n, 1},
                        {"pressure_bottom", "Node", s.n, 1}};
  for (const Attr &a : attrs) {
    if (a.name == std::string("triangle_plastic_strain") && s.law != SheetLaw::Elastoplastic)
      continue;
    if ((a.name == std::string("slip_top") || a.name == std::string("slip_bottom") ||
         a.name == std::string("pressure_top") || a.name == std::string("pressure_bottom")) &&
        !s.in_contact())
      continue;
    char dims[64];
    snprintf(dims, sizeof(dims), a.comps > 1 ? "%d %d" : "%d", a.n, a.comps);
    snprintf(buf, sizeof(buf),
             "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n"
             "        <DataItem Dimensions=\"%s\" NumberType=\"Float\" Precision=\"8\" "
             "Format=\"HDF\">%s%s</DataItem>\n      </Attribute>\n",
             a.name, a.comps > 1 ? "Vector" : "Scalar", a.centre, dims, g.c_str(), a.name);
    x += buf;
  }
  return x + "    </Grid>\n";
}
} // namespace

PetscErrorCode OutputSheets(Simulation &sim) {
  PetscFunctionBeginUser;
  if (sim.sheets.empty()) PetscFunctionReturn(0);
  if (sim.rank == 0) {
    const std::string dir = sim.set.output_dir, h5 = dir + "/sheets.h5";
    // HDF5's own error stack stays quiet: one line of ours below
    H5E_auto2_t efn;
    void *edata;
    H5Eget_auto2(H5E_DEFAULT, &efn, &edata);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const hid_t file = H5Fcreate((h5 + ".tmp").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    bool err = file < 0;
    const hid_t top =
        file < 0 ? -1 : H5Gcreate2(file, "sheets", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::string xmf = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n  <Domain>\n";
    std::vector<SheetFields> fields;
    for (const Sheet &s : sim.sheets) fields.push_back(Fields(s));
    for (size_t k = 0; k < sim.sheets.size() && top >= 0; ++k) {
      const Sheet &s = sim.sheets[k];
      const SheetFields &F = fields[k];
      const std::string &name = s.name;
      const hid_t g = H5Gcreate2(top, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      err |= g < 0;
      if (g < 0) break;
      err |= WriteDataset(g, "triangles", s.nt, 3, H5T_NATIVE_INT, s.tri.data());
      err |= WriteDoubles(g, "position", s.n, 3, s.x.data());
      err |= WriteDoubles(g, "position0", s.n, 3, s.x0.data());
      err |= WriteDoubles(g, "displacement", s.n, 3, F.u.data());
      err |= WriteDoubles(g, "strain_major", s.n, 1, Column(F.strain, 0).data());
      err |= WriteDoubles(g, "strain_minor", s.n, 1, Column(F.strain, 1).data());
      err |= WriteDoubles(g, "tension_major", s.n, 1, Column(F.tension, 0).data());
      err |= WriteDoubles(g, "tension_minor", s.n, 1, Column(F.tension, 1).data());
      err |= WriteDoubles(g, "pinned", s.n, 1, F.pinned.data());
      err |= WriteDoubles(g, "triangle_strain_major", s.nt, 1, F.e1.data());
      err |= WriteDoubles(g, "triangle_strain_minor", s.nt, 1, F.e2.data());
      err |= WriteDoubles(g, "triangle_tension_major", s.nt, 1, F.n1.data());
      err |= WriteDoubles(g, "triangle_tension_minor", s.nt, 1, F.n2.data());
      err |= WriteDoubles(g, "triangle_state", s.nt, 1, F.state.data());
      err |= WriteDoubles(g, "triangle_direction_major", s.nt, 3, F.direction.data());
      if (s.law == SheetLaw::Elastoplastic)
        err |= WriteDoubles(g, "triangle_plastic_strain", s.nt, 1, s.alpha.data());
      if (s.in_contact()) { // a sheet between bodies: each face's slip (m) and pressure (Pa)
        err |= WriteDoubles(g, "slip_top", s.n, 3, s.slip_top.data());
        err |= WriteDoubles(g, "slip_bottom", s.n, 3, s.slip_bot.data());
        err |= WriteDoubles(g, "pressure_top", s.n, 1, s.p_top.data());
        err |= WriteDoubles(g, "pressure_bottom", s.n, 1, s.p_bot.data());
      }
      err |= H5Gclose(g) < 0;
      xmf += XdmfSheet(s, name, sim.run.time);
    }
    if (top >= 0) err |= H5Gclose(top) < 0;
    if (file >= 0) err |= H5Fclose(file) < 0;
    H5Eset_auto2(H5E_DEFAULT, efn, edata);
    PetscCheck(!err && top >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write %s",
               h5.c_str());
    PetscCheck(std::rename((h5 + ".tmp").c_str(), h5.c_str()) == 0, PETSC_COMM_SELF,
               PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", h5.c_str());
    for (size_t k = 0; k < sim.sheets.size(); ++k)
      PetscCall(WriteCsv(dir + "/sheet_" + sim.sheets[k].name + ".csv", sim.sheets[k], fields[k]));
    FILE *f = std::fopen((dir + "/sheets.xmf").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s/sheets.xmf", dir.c_str());
    std::fprintf(f, "%s  </Domain>\n</Xdmf>\n", xmf.c_str());
    std::fclose(f);
  }
  PetscCallMPI(MPI_Barrier(sim.comm));
  PetscFunctionReturn(0);
}

} // namespace pmpm
