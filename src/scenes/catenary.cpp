// The elastic catenary (docs/method.md, section 6.1): one membrane chain alone, pinned at both ends
// at equal height, initially straight and unstressed, sagging under its own weight w = gamma t. The
// closed form (Irvine 1981, ch. 1) for span l = L0, stiffness J:
//   H L0 / J + (2 H / w) asinh(w L0 / (2 H)) = l,
//   sag = w L0^2 / (8 J) + (H / w) (sqrt(1 + (V / H)^2) - 1),  V = w L0 / 2,
//   T(s) = sqrt(H^2 + (w s - V)^2), strain T / J (largest at the supports).
// -catenary_offset dx,dy moves the whole chain by a fraction of a cell against the grid.
// -catenary_second adds a second, independent chain ("liner", material -mat_liner_*) hanging
// -catenary_second_drop below the first: several named chains per scene, each with its own
// material, checked against its own closed form.
// Under -geometry axisymmetric (x the radius) the chain is a circular membrane of radius
// -catenary_span, clamped at its rim and sagging under its own weight: the chain's point on the
// axis stays there, its rim is pinned. It reports the sag and the strains at the centre and the
// rim; its reference is the membrane of revolution solved as a boundary-value problem
// (tests/test_membrane_axisymmetric.py), not the catenary.
// Under -dim 3 -depth D the catenary is extruded: a strip of 3D sheet (sheet.hpp), a rectangle
// lattice of the chain's spacing (one point per cell) over the span and across the depth (its
// points at the cells' centres in z, so the strip is D - h wide), pinned along both supports and
// held in z along its two free edges (rollers: the plane strain of the 2D chain, b_z = 0, so that
// N_x = J b_x as the chain's T = J eps). Its answers are the 2D ones, per unit width.
#include "pmpm/contact/sheet.hpp"
#include "pmpm/util/options.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/contact/sheet_contact.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

namespace {
struct CatenaryExact {
  double H, V, sag, strain_mid, strain_support, tension_mid;
};
CatenaryExact SolveCatenary(double l, double L0, double w, double J) {
  auto g = [&](double H) { return H * L0 / J + 2 * H / w * std::asinh(w * L0 / (2 * H)) - l; };
  double lo = 1e-12 * w * L0, hi = 1e3 * (w * L0 + J); // g(lo) < 0 < g(hi)
  for (int it = 0; it < 300; ++it) {
    const double m = std::sqrt(lo * hi);
    (g(m) < 0 ? lo : hi) = m;
  }
  CatenaryExact e;
  e.H = std::sqrt(lo * hi);
  e.V = 0.5 * w * L0;
  e.sag = w * L0 * L0 / (8 * J) + e.H / w * (std::sqrt(1 + (e.V / e.H) * (e.V / e.H)) - 1);
  e.tension_mid = e.H;
  e.strain_mid = e.H / J;
  e.strain_support = std::hypot(e.H, e.V) / J;
  return e;
}
} // namespace

class CatenaryScene final : public Scene {
  double span_ = 10, t_ = 0.0015, off_[DIM] = {0, 0}, width_ = 0;
  int nx3_ = 0, nz3_ = 0; // -dim 3: the strip's lattice (sheet_rectangle)
  CatenaryExact ex_{}, ex2_{};
  double y0_ = 0, y2_ = 0, drop_ = 0;
  bool axi_ = false; // -geometry axisymmetric: a circular membrane
  PetscBool second_ = PETSC_FALSE;

public:
  bool extrudes() const override { return true; } // -dim 3: a strip of 3D sheet

  PetscErrorCode setup(Simulation &sim) override {
    PetscInt n = DIM;
    PetscBool drop_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "catenary_", "Catenary: one chain pinned at both ends", nullptr);
    PetscCall(PmpmOptionsReal("-span",
                              "Span l between the supports (m), > 0 (-geometry axisymmetric: the "
                              "circular membrane's radius)",
                              nullptr, span_, &span_, nullptr));
    PetscCall(PmpmOptionsRealArray("-offset",
                                   "Shift of the chain against the grid, dx,dy (m; a fraction "
                                   "of a cell tests grid independence)",
                                   nullptr, off_, &n, nullptr));
    PetscCall(PetscOptionsBool("-second",
                               "A second chain (\"liner\", material -mat_liner_*, thickness "
                               "-membrane_thickness) below the first",
                               nullptr, second_, &second_, nullptr));
    PetscCall(PmpmOptionsReal("-second_drop", "How far the second chain hangs below the first (m)",
                              nullptr, drop_, &drop_, &drop_set));
    PetscOptionsEnd();
    PetscCall(MembraneThicknessOption(sim.comm, "The membrane", &t_));
    PmpmCheckInput(span_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-catenary_span must be > 0 (got %g)", span_);
    PetscCall(CheckMembraneThickness(sim.comm, t_));
    const double h = sim.set.h;
    axi_ = sim.set.geometry == Geometry::Axisymmetric;
    PmpmCheckInput(!axi_ || (!second_ && off_[0] == 0), sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-geometry axisymmetric: the catenary is one circular membrane centred on the "
                   "axis (no -catenary_second, no x in -catenary_offset)");
    PmpmCheckInput(!second_ || sim.set.dim == 2, sim.comm, PETSC_ERR_SUP,
                   "-catenary_second: under -dim 3 the catenary is one strip of sheet");
    ChainSpec cs;
    cs.name = "membrane";
    cs.material = "membrane";
    cs.thickness = t_;
    cs.pin_start = cs.pin_end = true;
    // the closed form sizes the box: two cells beside the supports, the sag plus two cells below
    Chain probe;
    {
      ChainSpec ps = cs;
      ps.line = {0, 0, span_, 0};
      const PetscErrorCode err = ChainCreate(sim.comm, ps, span_, probe);
      if (err && ListingHelp()) { // -help: the sheet's unchecked defaults size no box
        sim.model.chain_specs.push_back(ps);
        PetscFunctionReturn(0);
      }
      PetscCall(err);
    }
    ex_ = SolveCatenary(span_, span_, probe.line_weight, probe.law.J);
    double depth = ex_.sag;
    if (second_) {
      Chain probe2;
      ChainSpec ps = cs;
      ps.name = ps.material = "liner";
      ps.line = {0, 0, span_, 0};
      PetscCall(ChainCreate(sim.comm, ps, span_, probe2));
      ex2_ = SolveCatenary(span_, span_, probe2.line_weight, probe2.law.J);
      PmpmCheckInput(!drop_set || drop_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-catenary_second_drop must be > 0 m (got %g; default below the first chain's "
                     "sag)",
                     drop_);
      if (drop_ <= 0) drop_ = 1.2 * ex_.sag + 2 * h; // below the first chain's sag
      depth = std::fmax(depth, drop_ + ex2_.sag);
    }
    if (axi_) // Foppl-Hencky's sag of a circular membrane, 0.653 a (q a / E t)^(1/3) at nu = 0.3
      depth = std::fmax(depth, 0.7 * span_ *
                                   std::cbrt(probe.line_weight * span_ /
                                             (probe.law.J * (1 - probe.nu * probe.nu))));
    sim.model.ncell[0] = static_cast<PetscInt>(std::ceil(span_ / h - 1e-9)) + (axi_ ? 2 : 4);
    sim.model.ncell[1] = static_cast<PetscInt>(std::ceil(1.2 * depth / h)) + 5;
    sim.model.origin[0] = axi_ ? 0.0 : -2 * h; // axisymmetric: the axis is the grid's x = 0
    if (axi_) cs.pin_start = false;
    sim.model.origin[1] = -(sim.model.ncell[1] - 3) * h;
    y0_ = 0.5 * h + off_[1];
    cs.line = {off_[0], y0_, off_[0] + span_, y0_};
    PmpmCheckInput(std::fabs(off_[0]) < h && std::fabs(off_[1]) < h, sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE,
                   "-catenary_offset must be within one cell (|d| < %g m)", h);
    if (second_) { // chains go bottom to top
      ChainSpec c2 = cs;
      c2.name = c2.material = "liner";
      y2_ = y0_ - drop_;
      c2.line = {off_[0], y2_, off_[0] + span_, y2_};
      sim.model.chain_specs.push_back(c2);
    }
    for (int f = 0; f < 2 * DIM; ++f) sim.model.face[f] = FaceBC::Free;
    if (sim.set.dim == 3) {
      PetscCall(StripSetup(sim, probe, cs));
      PetscFunctionReturn(0);
    }
    sim.model.chain_specs.push_back(cs);
    PetscFunctionReturn(0);
  }

  // -dim 3: the strip of sheet over the chain's line, across the depth.
  PetscErrorCode StripSetup(Simulation &sim, const Chain &probe, const ChainSpec &cs) {
    PetscFunctionBeginUser;
    const double h = sim.set.h;
    PmpmCheckInput(sim.set.depth >= 2 * h - 1e-9 * h, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-dim 3: -depth %g m is the catenary strip's width plus a cell: give at least "
                   "two cells (%g m)",
                   sim.set.depth, 2 * h);
    // uniaxial J = E t is the sheet's E t / (1 - nu^2) only when nu = 0
    PmpmCheckInput(probe.stiffness == StiffnessKind::PlaneStrain || probe.nu == 0, sim.comm,
                   PETSC_ERR_SUP,
                   "-mat_membrane_axial_stiffness uniaxial with -mat_membrane_nu %g: a 3D sheet "
                   "is biaxial (J = E t / (1 - nu^2)); use plane_strain, or nu = 0",
                   probe.nu);
    // one point per cell along the span (the shipped -chain_spacing 1), at the cells' centres
    // in z across the depth
    nx3_ = static_cast<int>(std::ceil(span_ / h - 1e-9)) + 1;
    nz3_ = static_cast<int>(std::llround(sim.set.depth / h));
    width_ = (nz3_ - 1) * h;
    Sheet st = SheetMaterialOf(probe);
    sheet_rectangle(cs.line[0], span_ / (nx3_ - 1), nx3_, 0.5 * h, h, nz3_, cs.line[1], st);
    st.held.assign(st.n, 0);
    for (int i = 0; i < nx3_; ++i)
      for (int j = 0; j < nz3_; ++j) {
        const int p = i * nz3_ + j;
        st.pinned[p] = i == 0 || i == nx3_ - 1;
        if (j == 0 || j == nz3_ - 1) st.held[p] = 1 << 2; // z held: a roller
      }
    sheet_normals(st);
    sim.sheets.push_back(std::move(st));
    PetscFunctionReturn(0);
  }

  // -dim 3: the strip's answers per unit width, read as the chain's (below): the mid-span
  // column(s) of points, the x strain of the triangles in the two columns of triangles around
  // mid-span and extrapolated from the first two at each support, the supports' reactions.
  PetscErrorCode StripResults(Simulation &sim, std::string &json) {
    PetscFunctionBeginUser;
    const Sheet &s = sim.sheets.front();
    const int nx = nx3_, nz = nz3_;
    const double ds = span_ / (nx - 1), ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
    auto column_y = [&](int i) {
      double y = 0;
      for (int j = 0; j < nz; ++j) y += s.x[3 * (i * nz + j) + 1];
      return y / nz;
    };
    const double ymid = 0.5 * (column_y((nx - 1) / 2) + column_y(nx / 2));
    // per column of triangles k (between point columns k and k + 1): mean x and z strains, N_x
    std::vector<double> ex_k(nx - 1, 0.0), ez_k(nx - 1, 0.0), N_k(nx - 1, 0.0), cnt(nx - 1, 0.0);
    for (int t = 0; t < s.nt; ++t) {
      double cx = 0;
      for (int a = 0; a < 3; ++a) cx += s.x0[3 * s.tri[3 * t + a]] / 3;
      const int k = std::clamp(static_cast<int>(std::floor((cx - s.x0[0]) / ds)), 0, nx - 2);
      const double bx = sheet_strain_along(s, t, ex), bz = sheet_strain_along(s, t, ez);
      ex_k[k] += bx;
      ez_k[k] += bz;
      N_k[k] += s.J * (bx + s.nu * bz);
      cnt[k] += 1;
    }
    for (int k = 0; k + 1 < nx; ++k) {
      ex_k[k] /= cnt[k];
      ez_k[k] /= cnt[k];
      N_k[k] /= cnt[k];
    }
    const int k0 = std::max(0, nx / 2 - 1), k1 = std::min(nx - 2, (nx - 1) / 2);
    const double eps_mid = 0.5 * (ex_k[k0] + ex_k[k1]), T_mid = 0.5 * (N_k[k0] + N_k[k1]);
    auto end = [&](int a, int b) { return 1.5 * ex_k[a] - 0.5 * ex_k[b]; };
    const double eps_sup = 0.5 * (end(0, 1) + end(nx - 2, nx - 3));
    double ez_max = 0;
    for (int k = 0; k + 1 < nx; ++k) ez_max = std::fmax(ez_max, std::fabs(ez_k[k]));
    // the support at the start: the sheet's pull on its pinned points and their own weight
    double Hs = 0, Vs = 0;
    for (int j = 0; j < nz; ++j) {
      Hs += s.f[3 * j];
      Vs += -s.f[3 * j + 1] + s.weight[j];
    }
    const char *sep = ",\n    ";
    json = json_kv("span", span_) + sep + json_kv("width", width_) + sep +
           json_kv("thickness", t_) + sep + json_kv("weight_per_length", s.area_weight) + sep +
           json_kv("axial_stiffness", s.J) + sep + json_kv("points", double(s.n)) + sep +
           json_kv("triangles", double(s.nt)) + sep + json_kv("sag", y0_ - ymid) + sep +
           json_kv("sag_exact", ex_.sag) + sep + json_kv("strain_mid", eps_mid) + sep +
           json_kv("strain_mid_exact", ex_.strain_mid) + sep + json_kv("strain_support", eps_sup) +
           sep + json_kv("strain_support_exact", ex_.strain_support) + sep +
           json_kv("tension_mid", T_mid) + sep + json_kv("tension_mid_exact", ex_.tension_mid) +
           sep + json_kv("horizontal_reaction", Hs / width_) + sep +
           json_kv("vertical_reaction", Vs / width_) + sep +
           json_kv("vertical_reaction_exact", ex_.V) + sep + json_kv("strain_across_max", ez_max);
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &, ParticleList &) override { return 0; }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    if (sim.set.dim == 3) {
      PetscCall(StripResults(sim, json));
      PetscFunctionReturn(0);
    }
    const Chain &c = sim.chains.back(); // the membrane (the liner, if any, is below it)
    if (axi_) {
      // the centre (point 0, on the axis; its segment's strain, isotropic there) and the rim
      // (the last two segments' strains extrapolated to the support, as below)
      const int m = c.n - 2;
      const char *sep = ",\n    ";
      json = json_kv("radius", span_) + sep + json_kv("thickness", t_) + sep +
             json_kv("weight_per_area", c.line_weight) + sep + json_kv("axial_stiffness", c.law.J) +
             sep + json_kv("poisson", c.nu) + sep + json_kv("points", double(c.n)) + sep +
             json_kv("sag", y0_ - c.x[1]) + sep + json_kv("strain_centre", c.eps[0]) + sep +
             json_kv("strain_hoop_centre", c.eps_hoop[0]) + sep +
             json_kv("strain_rim", 1.5 * c.eps[m] - 0.5 * c.eps[m - 1]) + sep +
             json_kv("tension_rim", 1.5 * c.T[m] - 0.5 * c.T[m - 1]) + sep +
             json_kv("tension_hoop_rim", 1.5 * c.T_hoop[m] - 0.5 * c.T_hoop[m - 1]) + sep +
             json_kv("vertical_reaction", c.reaction[1][1]) + sep +
             json_kv("weight", c.line_weight * 0.5 * span_ * span_);
      PetscFunctionReturn(0);
    }
    // mid-span: the point at s = L0 / 2 (the point count is odd for an even division) or the
    // mean of the two around it; strains: the segments there and at the supports
    const int im = (c.n - 1) / 2, jm = c.n / 2;
    const double ymid = 0.5 * (c.x[im * DIM + 1] + c.x[jm * DIM + 1]);
    const int k0 = std::max(0, c.n / 2 - 1), k1 = std::min(c.n - 2, (c.n - 1) / 2);
    const double eps_mid = 0.5 * (c.eps[k0] + c.eps[k1]), T_mid = 0.5 * (c.T[k0] + c.T[k1]);
    // support strain: extrapolate the first two segments' strains to s = 0 (they sit at s =
    // l0/2 and 3 l0/2) and likewise at the other end
    auto end = [&](int a, int b) { return 1.5 * c.eps[a] - 0.5 * c.eps[b]; };
    const double eps_sup = 0.5 * (end(0, 1) + end(c.n - 2, c.n - 3));
    const char *sep = ",\n    ";
    json = json_kv("span", span_) + sep + json_kv("thickness", t_) + sep +
           json_kv("weight_per_length", c.line_weight) + sep + json_kv("axial_stiffness", c.law.J) +
           sep + json_kv("points", double(c.n)) + sep + json_kv("sag", y0_ - ymid) + sep +
           json_kv("sag_exact", ex_.sag) + sep + json_kv("strain_mid", eps_mid) + sep +
           json_kv("strain_mid_exact", ex_.strain_mid) + sep + json_kv("strain_support", eps_sup) +
           sep + json_kv("strain_support_exact", ex_.strain_support) + sep +
           json_kv("tension_mid", T_mid) + sep + json_kv("tension_mid_exact", ex_.tension_mid) +
           sep + json_kv("horizontal_reaction", -c.reaction[0][0]) + sep +
           json_kv("vertical_reaction", c.reaction[0][1]) + sep +
           json_kv("vertical_reaction_exact", ex_.V);
    if (second_) {
      const Chain &l = sim.chains[0];
      const double yl = 0.5 * (l.x[((l.n - 1) / 2) * DIM + 1] + l.x[(l.n / 2) * DIM + 1]);
      json += std::string(sep) + json_kv("liner_sag", y2_ - yl) + sep +
              json_kv("liner_sag_exact", ex2_.sag) + sep +
              json_kv("liner_axial_stiffness", l.law.J);
    }
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_catenary_scene() {
  return std::make_unique<CatenaryScene>();
}

} // namespace pmpm
