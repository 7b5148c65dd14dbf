// A column under self-weight (docs/method.md, section 2.2): height H, base fixed, sides on rollers,
// top free or loaded by a surcharge q (-bc_ymax_traction 0,-q), which adds -q to the stress below.
// Uniaxial strain, so the Cauchy stress at initial height Y is exactly -gamma (H - Y) at any
// deformation (the weight above is conserved). Each model's law then gives J(Y), and
// y(Y) = int_0^Y J dY:
//   linear elastic (Jaumann rate): sigma_yy = M ln J          -> J = exp(sigma / M)
//   neo-Hookean:   sigma_yy = (lambda ln J + mu (J^2 - 1)) / J (solved by Newton)
// For small strain both reduce to u_y = -(gamma / M)(H Y - Y^2 / 2).
//
// -column_round (-dim 3): a round column, the quarter of a cylinder of radius W = -column_width
// about the axis x = z = 0 (the planes x = 0 and z = 0 are its symmetry planes: rollers), its
// curved side free (-bc_xmax free -bc_zmax free, -depth >= W). Base fixed, sides free: no closed
// form, but the same body under -geometry axisymmetric (x the radius, -bc_xmax free) is an
// independent solution of it (tests/test_round3d.py). With a free side the results say there is
// no closed form ("closed_form"), as they do for the axisymmetric column.
#include "pmpm/util/options.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>
#include <algorithm>
#include <vector>

namespace pmpm {

class ColumnScene final : public Scene {
  double H_ = 1.0, W_ = 0;
  PetscBool round_ = PETSC_FALSE;

  // Exact y(Y) = int_0^Y J dY tabulated once (Simpson per panel, 4096 panels), then read by
  // cubic Hermite interpolation with dy/dY = J: error far below 1e-10 of the settlement.
  static constexpr int kPanels = 4096;
  std::vector<double> ytab_, jtab_;
  void tabulate(const MaterialEntry &m) {
    const double dY = H_ / kPanels;
    ytab_.assign(kPanels + 1, 0.0);
    jtab_.assign(kPanels + 1, 0.0);
    for (int k = 0; k <= kPanels; ++k) jtab_[k] = UniaxialStrainJ(m, sigma_exact(k * dY));
    for (int k = 0; k < kPanels; ++k) {
      const double jm = UniaxialStrainJ(m, sigma_exact((k + 0.5) * dY));
      ytab_[k + 1] = ytab_[k] + dY / 6.0 * (jtab_[k] + 4.0 * jm + jtab_[k + 1]);
    }
  }
  // sigma_yy at initial height Y: the weight above plus a surcharge q on the top face
  // (-bc_ymax_traction 0,-q), both conserved at any deformation.
  double gamma_ = 0, q_ = 0;
  double sigma_exact(double Y) const { return -gamma_ * (H_ - Y) - q_; }
  double u_exact(double Y) const {
    const double dY = H_ / kPanels;
    const int k = std::min(kPanels - 1, std::max(0, static_cast<int>(Y / dY)));
    const double t = (Y - k * dY) / dY, t2 = t * t, t3 = t2 * t;
    const double y = (2 * t3 - 3 * t2 + 1) * ytab_[k] + (t3 - 2 * t2 + t) * dY * jtab_[k] +
                     (-2 * t3 + 3 * t2) * ytab_[k + 1] + (t3 - t2) * dY * jtab_[k + 1];
    return y - Y;
  }

  // The closed form holds with every side on rollers (the axis is one under -geometry
  // axisymmetric) and a prism's body.
  bool UniaxialStrain(const Simulation &sim) const {
    const FaceBC *f = sim.model.face;
    const bool z = sim.set.dim == 2 || (f[ZMIN] == FaceBC::Roller && f[ZMAX] == FaceBC::Roller);
    return !round_ && f[XMIN] == FaceBC::Roller && f[XMAX] == FaceBC::Roller && z;
  }

public:
  bool extrudes() const override { return true; } // CompareVertical reads any dimension
  bool keeps_extruded(const double x[3]) const override {
    return !round_ || x[0] * x[0] + x[2] * x[2] < W_ * W_;
  }
  PetscErrorCode setup(Simulation &sim) override {
    PetscBool w_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "column_", "Column under self-weight", nullptr);
    PetscCall(PmpmOptionsReal("-height", "Column height H (m)", nullptr, H_, &H_, nullptr));
    PetscCall(
        PmpmOptionsReal("-width", "Column width (m); default 4 cells", nullptr, W_, &W_, &w_set));
    PetscCall(PetscOptionsBool("-round",
                               "-dim 3: a round column, the quarter cylinder of radius "
                               "-column_width about x = z = 0 (needs -depth >= the width and "
                               "-bc_xmax free -bc_zmax free)",
                               nullptr, round_, &round_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(!w_set || W_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-column_width must be > 0 m (got %g; default 4 cells)", W_);
    if (W_ <= 0) W_ = 4 * sim.set.h;
    PmpmCheckInput(!round_ || sim.set.dim == 3, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-column_round needs -dim 3 (in 2D, -geometry axisymmetric makes the column "
                   "round)");
    PmpmCheckInput(!round_ || sim.set.depth >= W_ * (1 - 1e-12), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-column_round needs -depth >= -column_width %g m (got %g): the quarter "
                   "cylinder must fit the box",
                   W_, sim.set.depth);
    PetscInt nH, nW;
    PetscCall(CheckCells(sim.comm, "-column_height", H_, sim.set.h, &nH));
    PetscCall(CheckCells(sim.comm, "-column_width", W_, sim.set.h, &nW));
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nW;
    sim.model.ncell[1] = nH + 2;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "column", sim.model.mats[0]));
    PmpmCheckInput(sim.model.mats[0].gamma > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-mat_column_gamma must be > 0 for a column under self-weight");
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double H = H_, W = W_;
    FillRegular(
        sim, [H, W](const double x[DIM]) { return x[0] < W && x[1] < H ? 0 : -1; }, out);
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const MaterialEntry &m = sim.model.mats[0];
    gamma_ = m.gamma;
    q_ = -sim.model.face_traction[YMAX][1];
    tabulate(m);
    VerticalComparison c;
    PetscCall(CompareVertical(
        sim, [this](double Y) { return sigma_exact(Y); }, [this](double Y) { return u_exact(Y); },
        {H_}, c));
    const double small = (m.gamma * H_ * H_ / 2 + q_ * H_) / m.el.M();
    json = json_kv("top_settlement", -c.row_u[0]) + ",\n    " +
           json_kv("top_settlement_exact", -c.row_u_exact[0]) + ",\n    " +
           json_kv("top_surface_settlement_small_strain", small) + ",\n    " +
           json_kv("stress_l2_error_rel", c.stress_l2) + ",\n    " +
           json_kv("displacement_l2_error_rel", c.displacement_l2) + ",\n    " +
           json_kv("surcharge", q_) + ",\n    " + "\"model\": \"" + m.model->model() + "\"" +
           ",\n    \"closed_form\": \"" +
           (UniaxialStrain(sim) ? "uniaxial strain"
                                : "none: a side is not a roller (the errors above compare with "
                                  "uniaxial strain)") +
           "\"";
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_column_scene() {
  return std::make_unique<ColumnScene>();
}

} // namespace pmpm
