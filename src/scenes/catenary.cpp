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
#include "pmpm/util/options.hpp"
#include "pmpm/io/output.hpp"
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
  double span_ = 10, t_ = 0.0015, off_[DIM] = {0, 0};
  CatenaryExact ex_{}, ex2_{};
  double y0_ = 0, y2_ = 0, drop_ = 0;
  bool axi_ = false; // -geometry axisymmetric: a circular membrane
  PetscBool second_ = PETSC_FALSE;

public:
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
    PetscOptionsBegin(sim.comm, "membrane_", "The membrane", nullptr);
    PetscCall(
        PmpmOptionsReal("-thickness", "Membrane thickness t (m), > 0", nullptr, t_, &t_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(span_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-catenary_span must be > 0 (got %g)", span_);
    PmpmCheckInput(t_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-membrane_thickness must be > 0 (got %g)", t_);
    const double h = sim.set.h;
    axi_ = sim.set.geometry == Geometry::Axisymmetric;
    PmpmCheckInput(!axi_ || (!second_ && off_[0] == 0), sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-geometry axisymmetric: the catenary is one circular membrane centred on the "
                   "axis (no -catenary_second, no x in -catenary_offset)");
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
    sim.model.chain_specs.push_back(cs);
    for (int f = 0; f < 2 * DIM; ++f) sim.model.face[f] = FaceBC::Free;
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &, ParticleList &) override { return 0; }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
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
