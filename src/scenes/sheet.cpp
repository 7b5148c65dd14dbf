// The sheet scene (-dim 3): a flat circular geomembrane of radius a clamped at its rim, sagging
// under its own weight q = gamma t, alone on the 3D grid: the first check of the 3D sheet
// (sheet.hpp) through the grid. For nu = 0.3 and small slopes its centre deflection is
// Foppl-Hencky's w0 = 0.653 a (q a / E t)^(1/3) (Hencky 1915; Fichter 1997); at any slope it is
// the membrane of revolution that the axisymmetric catenary solves (-scene catenary -geometry
// axisymmetric; tests/test_membrane_axisymmetric.py), which has the same law. Reports the sag at
// the centre, the centre strain and the rim's radial strain (sheet_disc_strains), the peak
// principal strains (sheet_peak_principal), and writes the sheet as a surface (sheet_output.cpp).
#include "pmpm/io/output.hpp"
#include "pmpm/contact/sheet_contact.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include "pmpm/util/options.hpp"
#include <cmath>

namespace pmpm {

class SheetScene final : public Scene {
  double radius_ = 10, t_ = 0.01, y0_ = 0, centre_[3] = {0, 0, 0}, dr_ = 0;

public:
  bool extrudes() const override { return true; } // a 3D scene: -dim 3 only

  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "sheet_", "Sheet: a circular membrane clamped at its rim (-dim 3)",
                      nullptr);
    PetscCall(PmpmOptionsReal("-radius", "Radius a of the sheet (m), > 0", nullptr, radius_,
                              &radius_, nullptr));
    PetscOptionsEnd();
    PetscCall(MembraneThicknessOption(sim.comm, "The membrane", &t_));
    PmpmCheckInput(radius_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-sheet_radius must be > 0 (got %g)", radius_);
    PetscCall(CheckMembraneThickness(sim.comm, t_));
    // the material as a chain's (-mat_membrane_*): E, nu, gamma, density, law
    ChainSpec cs;
    cs.name = cs.material = "membrane";
    cs.thickness = t_;
    cs.line = {0, 0, radius_, 0};
    Chain probe;
    {
      const PetscErrorCode err = ChainCreate(sim.comm, cs, radius_, probe);
      if (err && ListingHelp()) PetscFunctionReturn(0);
      PetscCall(err);
    }
    if (ListingHelp()) PetscFunctionReturn(0);
    PmpmCheckInput(sim.set.dim == 3, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-scene sheet is three-dimensional: add -dim 3 (it sizes its box itself)");
    PmpmCheckInput(sim.set.depth == 0, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-depth %g: -scene sheet sizes its box's depth itself (leave -depth out)",
                   sim.set.depth);
    PmpmCheckInput(probe.stiffness == StiffnessKind::PlaneStrain, sim.comm, PETSC_ERR_SUP,
                   "-mat_membrane_axial_stiffness uniaxial: a 3D sheet is biaxial (J = E t / (1 - "
                   "nu^2)); leave it at plane_strain");
    const double h = sim.set.h;
    // the box: two cells beyond the rim in x and z, the sheet half a cell above y = 0, below it
    // the Foppl-Hencky sag (0.7 a (q a / E t)^(1/3)) plus a fifth and five cells
    const PetscInt half = static_cast<PetscInt>(std::ceil(radius_ / h - 1e-9)) + 2;
    const double Et = probe.law.J * (1 - probe.nu * probe.nu);
    const double sag = 0.7 * radius_ * std::cbrt(probe.line_weight * radius_ / Et);
    sim.model.ncell[0] = 2 * half;
    sim.model.origin[0] = -half * h;
    sim.model.ncell[1] = static_cast<PetscInt>(std::ceil(1.2 * sag / h)) + 5;
    sim.model.origin[1] = -(sim.model.ncell[1] - 3) * h;
    sim.set.depth = 2 * half * h;
    for (int f = 0; f < 2 * DIM; ++f) sim.model.face[f] = FaceBC::Free;
    y0_ = 0.5 * h;
    centre_[0] = 0;
    centre_[1] = y0_;
    centre_[2] = half * h;
    Sheet s = SheetMaterialOf(probe);
    sheet_disc(radius_, h, centre_, s);
    dr_ = radius_ / std::ceil(radius_ / h - 1e-9); // the lattice's ring gap (sheet_disc's K)
    sheet_normals(s);
    sim.sheets.push_back(std::move(s));
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &, ParticleList &) override { return 0; }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const Sheet &s = sim.sheets.front();
    const SheetDiscStrains e = sheet_disc_strains(s, centre_, radius_, dr_);
    const double Et = s.J * (1 - s.nu * s.nu);
    int wrinkled = 0;
    for (SheetState st : s.state) wrinkled += st != SheetState::Taut;
    const PeakPrincipal p = sheet_peak_principal(s);
    const char *sep = ",\n    ";
    json = json_kv("radius", radius_) + sep + json_kv("thickness", t_) + sep +
           json_kv("weight_per_area", s.area_weight) + sep + json_kv("axial_stiffness", s.J) + sep +
           json_kv("poisson", s.nu) + sep + json_kv("points", double(s.n)) + sep +
           json_kv("triangles", double(s.nt)) + sep + json_kv("sag", y0_ - s.x[1]) + sep +
           json_kv("sag_foppl_hencky_nu03",
                   0.653 * radius_ * std::cbrt(s.area_weight * radius_ / Et)) +
           sep + json_kv("strain_centre", e.centre) + sep + json_kv("strain_rim", e.rim) + sep +
           json_kv("triangles_not_taut", double(wrinkled)) + sep +
           // the design answer's form (sheet_peak_principal): the largest major principal strain
           // of a point, the minor strain there (the biaxial state), the tensions and where; the
           // largest of a single triangle
           json_kv("peak_strain_major", p.strain1) + sep + json_kv("peak_strain_minor", p.strain2) +
           sep + json_kv("peak_tension_major", p.tension1) + sep +
           json_kv("peak_tension_minor", p.tension2) + sep + "\"peak_at\": [" + json_num(p.x[0]) +
           ", " + json_num(p.x[1]) + ", " + json_num(p.x[2]) + "]" + sep +
           json_kv("peak_strain_triangle", p.triangle_strain1);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_sheet_scene() {
  return std::make_unique<SheetScene>();
}

} // namespace pmpm
