// The paper's Figure 2 bar: plane strain, x = 0 on rollers, y = 0 on rollers (the symmetry line
// that pins u_y), traction t on the end x = L, no gravity. Static solution (REFERENCE.md 2.1):
// sigma_xx = t, u_x = t (1 - nu^2) x / E, u_y = -nu (1 + nu) t y / E.
#include "pmpm/cycle.hpp"
#include "pmpm/output.hpp"
#include "pmpm/scene_util.hpp"
#include <cmath>

namespace pmpm {

class BarScene final : public Scene {
  double L_ = 1.0, B_ = 0.25, t_ = 1e3, box_ = 0;
  PetscInt nL_ = 0;

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "bar_", "Bar under end traction (paper Figure 2)", nullptr);
    PetscCall(PetscOptionsReal("-length", "Bar length L (m)", nullptr, L_, &L_, nullptr));
    PetscCall(PetscOptionsReal("-height", "Bar height B (m)", nullptr, B_, &B_, nullptr));
    PetscCall(PetscOptionsReal("-traction", "End traction t (Pa, tension > 0)", nullptr, t_, &t_,
                               nullptr));
    PetscCall(PetscOptionsReal("-box_length", "Grid length in x (m), >= L + 2 cells; default 1.5 L",
                               nullptr, box_, &box_, nullptr));
    PetscOptionsEnd();
    PetscInt nB, nbox;
    PetscCall(CheckCells(sim.comm, "-bar_length", L_, sim.set.h, &nL_));
    PetscCall(CheckCells(sim.comm, "-bar_height", B_, sim.set.h, &nB));
    if (box_ <= 0) box_ = sim.set.h * std::ceil(1.5 * L_ / sim.set.h);
    PetscCall(CheckCells(sim.comm, "-bar_box_length", box_, sim.set.h, &nbox));
    PetscCheck(nbox >= nL_ + 2, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-bar_box_length %g m leaves no room for the bar to stretch: the grid is too small "
               "for the particles (need >= L + 2 cells = %g m)",
               box_, (nL_ + 2) * sim.set.h);
    PetscCheck(t_ != 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE, "-bar_traction must be non-zero");
    sim.origin[0] = sim.origin[1] = 0;
    sim.ncell[0] = nbox;
    sim.ncell[1] = nB + 1;
    sim.face[XMIN] = FaceBC::Roller;
    sim.face[YMIN] = FaceBC::Roller;
    sim.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "bar", sim.mats[0]));
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, std::vector<ParticleInit> &out) override {
    PetscFunctionBeginUser;
    const double L = L_, B = B_;
    FillRegular(
        sim, [L, B](const double x[DIM]) { return x[0] < L && x[1] < B ? 0 : -1; }, out);
    for (auto &q : out) {
      if (q.x[0] + q.lp[0] > L - 1e-9 * L) { // the loaded end face
        q.traction[0] = t_ * 2.0 * q.lp[1];
        q.tface[0] = q.lp[0];
      }
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    ParticleView P;
    PetscFunctionBeginUser;
    const ElasticConstants &c = sim.mats[0].el;
    // [sum ux at tip, sum x0 at tip, count at tip]; and max stress error
    double s[3] = {0, 0, 0}, err = 0;
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p) {
      err = std::fmax(err, std::fabs(P.stress[p * NSTRESS] - t_) / std::fabs(t_));
      if (P.traction[p * DIM] != 0.0) {
        s[0] += P.x[p * DIM] - P.x0[p * DIM];
        s[1] += P.x0[p * DIM];
        s[2] += 1;
      }
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, s, 3));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_DOUBLE, MPI_MAX, sim.comm));
    double res_mpm, res_pmpm;
    PetscCall(StaticResidual(sim, ShapeKind::Linear, &res_mpm));
    PetscCall(StaticResidual(sim, ShapeKind::UGIMP, &res_pmpm));
    const double tip = s[0] / s[2];
    const double tip_exact = t_ * (1 - c.nu * c.nu) * (s[1] / s[2]) / c.E;
    json =
        json_kv("traction", t_) + ",\n    " + json_kv("tip_displacement", tip) + ",\n    " +
        json_kv("tip_displacement_exact", tip_exact) + ",\n    " +
        json_kv("tip_displacement_error_rel", std::fabs(tip - tip_exact) / std::fabs(tip_exact)) +
        ",\n    " + json_kv("stress_error_rel", err) + ",\n    " +
        json_kv("force_residual", sim.run.ratio) + ",\n    " +
        json_kv("force_residual_mpm", res_mpm) + ",\n    " +
        json_kv("force_residual_pmpm", res_pmpm);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_bar_scene() {
  return std::make_unique<BarScene>();
}

} // namespace pmpm
