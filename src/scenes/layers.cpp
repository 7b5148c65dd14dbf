// Two bonded elastic layers under self-weight: a stiffness and unit-weight contrast test for the
// relaxation. A column of width W: the bottom layer (material "bottom", 0 <= Y < Hb) under the
// top layer (material "top", Hb <= Y < Hb + Ht); base fixed, sides on rollers, top free.
// Uniaxial strain, so at initial height Y the Cauchy stress is exactly minus the weight above
// (conserved under deformation):
//   sigma_yy(Y) = -gamma_t (H - Y)                     Hb <= Y <= H = Hb + Ht
//   sigma_yy(Y) = -gamma_t Ht - gamma_b (Hb - Y)        0 <= Y <= Hb
// and each layer's law gives J(Y) (linear elastic, Jaumann rate: sigma = M ln J; neo-Hookean:
// sigma = (lambda ln J + mu (J^2 - 1)) / J), u_y(Y) = int_0^Y (J - 1) dY, piecewise per layer
// (docs/method.md, section 2.2 for one layer). Small strain: u_y = int sigma / M.
#include "pmpm/util/options.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

class LayersScene final : public Scene {
  double Hb_ = 0.5, Ht_ = 0.5, W_ = 0;

  double stress_exact(const Simulation &sim, double Y) const {
    const double gb = sim.model.mats[0].gamma, gt = sim.model.mats[1].gamma, H = Hb_ + Ht_;
    return Y >= Hb_ ? -gt * (H - Y) : -gt * Ht_ - gb * (Hb_ - Y);
  }
  // int_a^b (J(sigma(Y)) - 1) dY inside one layer (Simpson, 400 intervals).
  double integrate(const Simulation &sim, const MaterialEntry &m, double a, double b) const {
    const int n = 400;
    const double dY = (b - a) / n;
    double s = 0;
    for (int k = 0; k <= n; ++k) {
      const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
      s += w * (UniaxialStrainJ(m, stress_exact(sim, a + k * dY)) - 1.0);
    }
    return s * dY / 3.0;
  }
  double u_exact(const Simulation &sim, double Y) const {
    if (Y <= Hb_) return integrate(sim, sim.model.mats[0], 0.0, Y);
    return integrate(sim, sim.model.mats[0], 0.0, Hb_) + integrate(sim, sim.model.mats[1], Hb_, Y);
  }

public:
  bool extrudes() const override { return true; } // CompareVertical reads any dimension
  PetscErrorCode setup(Simulation &sim) override {
    PetscBool w_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "layers_", "Two bonded layers under self-weight", nullptr);
    PetscCall(PmpmOptionsReal("-bottom_height", "Bottom layer height Hb (m)", nullptr, Hb_, &Hb_,
                              nullptr));
    PetscCall(
        PmpmOptionsReal("-top_height", "Top layer height Ht (m)", nullptr, Ht_, &Ht_, nullptr));
    PetscCall(
        PmpmOptionsReal("-width", "Column width (m); default 4 cells", nullptr, W_, &W_, &w_set));
    PetscOptionsEnd();
    PmpmCheckInput(!w_set || W_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-layers_width must be > 0 m (got %g; default 4 cells)", W_);
    if (W_ <= 0) W_ = 4 * sim.set.h;
    PetscInt nb, nt, nW;
    PetscCall(CheckCells(sim.comm, "-layers_bottom_height", Hb_, sim.set.h, &nb));
    PetscCall(CheckCells(sim.comm, "-layers_top_height", Ht_, sim.set.h, &nt));
    PetscCall(CheckCells(sim.comm, "-layers_width", W_, sim.set.h, &nW));
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nW;
    sim.model.ncell[1] = nb + nt + 2;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.mats.resize(2);
    PetscCall(MaterialFromOptions(sim.comm, "bottom", sim.model.mats[0]));
    PetscCall(MaterialFromOptions(sim.comm, "top", sim.model.mats[1]));
    PmpmCheckInput(sim.model.mats[0].gamma > 0 && sim.model.mats[1].gamma > 0, sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE,
                   "-mat_bottom_gamma and -mat_top_gamma must be > 0 for layers under self-weight");
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double Hb = Hb_, H = Hb_ + Ht_, W = W_;
    FillRegular(
        sim,
        [=](const double x[DIM]) {
          if (x[0] >= W || x[1] >= H) return -1;
          return x[1] < Hb ? 0 : 1;
        },
        out);
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const double H = Hb_ + Ht_;
    VerticalComparison c; // rows: the top face and the bottom layer's upper face
    PetscCall(CompareVertical(
        sim, [&](double Y) { return stress_exact(sim, Y); },
        [&](double Y) { return u_exact(sim, Y); }, {H, Hb_}, c));
    const double top = -c.row_u[0], top_ex = -c.row_u_exact[0];
    const double mid = -c.row_u[1], mid_ex = -c.row_u_exact[1];
    const MaterialEntry &b = sim.model.mats[0], &t = sim.model.mats[1];
    const char *sep = ",\n    ";
    json = json_kv("stiffness_ratio", t.el.E / b.el.E) + sep +
           json_kv("unit_weight_ratio", t.gamma / b.gamma) + sep + json_kv("top_settlement", top) +
           sep + json_kv("top_settlement_exact", top_ex) + sep +
           json_kv("top_settlement_error_rel", std::fabs(top - top_ex) / std::fabs(top_ex)) + sep +
           json_kv("interface_settlement", mid) + sep +
           json_kv("interface_settlement_exact", mid_ex) + sep +
           json_kv("interface_settlement_error_rel", std::fabs(mid - mid_ex) / std::fabs(mid_ex)) +
           sep + json_kv("stress_l2_error_rel", c.stress_l2) + sep +
           json_kv("displacement_l2_error_rel", c.displacement_l2);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_layers_scene() {
  return std::make_unique<LayersScene>();
}

} // namespace pmpm
