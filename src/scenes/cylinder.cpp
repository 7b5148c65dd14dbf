// A thick-walled cylinder under internal and external pressure (Lame), axisymmetric
// (-geometry axisymmetric; docs/method.md, section 9): inner radius a (0: a solid cylinder, its
// inner face the axis), outer radius b, height H between rollers on z = 0 and z = H (the grid ends
// there), so that u_z = 0 and the cylinder is in plane strain along its axis. The grid starts at
// r = a (the inner pressure is the xmin face's traction) and runs two cells beyond b (the outer
// pressure is the xmax face's, on the body's outer particles). Exact (Timoshenko & Goodier 1970,
// section 28; tension positive, pressures p_i, p_o compressive):
//   sigma_rr = A - B / r^2,  sigma_thth = A + B / r^2,  sigma_zz = 2 nu A,
//   A = (p_i a^2 - p_o b^2) / (b^2 - a^2),  B = (p_i - p_o) a^2 b^2 / (b^2 - a^2),
//   u_r = r eps_thth = (1 + nu) r ((1 - 2 nu) A + B / r^2) / E.
// With a = 0 (solid) B = 0: the stress is uniform, sigma_rr = sigma_thth = -p_o, and u_r is linear
// in r; the discrete equations hold that state exactly (no discretisation error), which makes it
// the test of the axis. Small strain: the particles are compared at their initial radius.
#include "pmpm/util/options.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

class CylinderScene final : public Scene {
  double a_ = 1.0, b_ = 2.0, H_ = 0, pi_ = 1e4, po_ = 0;

  double coef_a() const { return (pi_ * a_ * a_ - po_ * b_ * b_) / (b_ * b_ - a_ * a_); }
  double coef_b() const { return (pi_ - po_) * a_ * a_ * b_ * b_ / (b_ * b_ - a_ * a_); }

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscBool h_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "cylinder_", "Thick-walled cylinder under pressure (Lame)",
                      nullptr);
    PetscCall(PmpmOptionsReal("-inner_radius", "Inner radius a (m), >= 0 (0: a solid cylinder)",
                              nullptr, a_, &a_, nullptr));
    PetscCall(
        PmpmOptionsReal("-outer_radius", "Outer radius b (m), > a", nullptr, b_, &b_, nullptr));
    PetscCall(PmpmOptionsReal("-height", "Height H between the rollers (m); default 4 cells",
                              nullptr, H_, &H_, &h_set));
    PetscCall(PmpmOptionsReal("-inner_pressure", "Pressure on r = a (Pa, compressive > 0)", nullptr,
                              pi_, &pi_, nullptr));
    PetscCall(PmpmOptionsReal("-outer_pressure", "Pressure on r = b (Pa, compressive > 0)", nullptr,
                              po_, &po_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(sim.set.geometry == Geometry::Axisymmetric, sim.comm, PETSC_ERR_USER_INPUT,
                   "-scene cylinder needs -geometry axisymmetric (its exact solution is the "
                   "cylinder's)");
    PmpmCheckInput(a_ >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cylinder_inner_radius must be >= 0 m (got %g)", a_);
    PmpmCheckInput(b_ > a_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cylinder_outer_radius must be > -cylinder_inner_radius %g m (got %g)", a_, b_);
    PmpmCheckInput(a_ > 0 || pi_ == 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cylinder_inner_pressure needs -cylinder_inner_radius > 0 (a solid cylinder "
                   "has no inner face)");
    PmpmCheckInput(!h_set || H_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cylinder_height must be > 0 m (got %g; default 4 cells)", H_);
    if (H_ <= 0) H_ = 4 * sim.set.h;
    PetscInt nw, nH;
    PetscCall(
        CheckCells(sim.comm, "-cylinder_outer_radius - inner_radius", b_ - a_, sim.set.h, &nw));
    PetscCall(CheckCells(sim.comm, "-cylinder_height", H_, sim.set.h, &nH));
    sim.model.origin[0] = a_;
    sim.model.origin[1] = 0;
    sim.model.ncell[0] = nw + 2;
    sim.model.ncell[1] = nH;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Free; // r = 0: a roller (GeometryCheck)
    sim.model.face[YMIN] = sim.model.face[YMAX] = FaceBC::Roller;
    sim.model.face_traction[XMIN][0] = pi_;  // pushes along +r
    sim.model.face_traction[XMAX][0] = -po_; // pushes along -r
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "cylinder", sim.model.mats[0]));
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double b = b_;
    FillRegular(
        sim, [b](const double x[DIM]) { return x[0] < b ? 0 : -1; }, out);
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    ParticleView P;
    PetscFunctionBeginUser;
    const ElasticConstants &el = sim.model.mats[0].el;
    const double A = coef_a(), B = coef_b(), E = el.E, nu = el.nu;
    // sums over the particles (weights V, per radian): err^2 and exact^2 of u_r, sigma_rr,
    // sigma_thth, sigma_zz; then |u_z|^2 V (relative to u_r's norm); then max |err| of u_r and of
    // the stresses
    double s[11] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p) {
      const double r = P.x0[p * DIM], V = P.vol0[p], *sg = P.stress + p * NSTRESS;
      const double srr = A - B / (r * r), stt = A + B / (r * r), szz = 2 * nu * A;
      const double ur = (1 + nu) * r * ((1 - 2 * nu) * A + B / (r * r)) / E;
      const double got[4] = {P.x[p * DIM] - r, sg[0], sg[2], sg[1]}, ex[4] = {ur, srr, stt, szz};
      for (int k = 0; k < 4; ++k) {
        s[2 * k] += V * (got[k] - ex[k]) * (got[k] - ex[k]);
        s[2 * k + 1] += V * ex[k] * ex[k];
      }
      const double uz = P.x[p * DIM + 1] - P.x0[p * DIM + 1];
      s[8] += V * uz * uz;
      s[9] = std::fmax(s[9], std::fabs(got[0] - ex[0]));
      for (int k = 1; k < 4; ++k) s[10] = std::fmax(s[10], std::fabs(got[k] - ex[k]));
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, s, 9));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s + 9, 2, MPI_DOUBLE, MPI_MAX, sim.comm));
    // the scales: the largest exact |u_r| (at r = a, or r = b when solid) and |stress|
    const double rs = a_ > 0 ? a_ : b_;
    const double u_scale = std::fabs((1 + nu) * rs * ((1 - 2 * nu) * A + B / (rs * rs)) / E);
    const double s_scale = std::fmax(std::fabs(pi_), std::fabs(po_));
    const double ur_l2 = std::sqrt(s[0] / s[1]);
    // the stress error over the three normal components, relative to their exact norm
    const double st_l2 = std::sqrt((s[2] + s[4] + s[6]) / (s[3] + s[5] + s[7]));
    json = json_kv("u_r_l2_error_rel", ur_l2) + ",\n    " +
           json_kv("u_r_max_error_rel", s[9] / u_scale) + ",\n    " +
           json_kv("stress_l2_error_rel", st_l2) + ",\n    " +
           json_kv("sigma_rr_l2_error_rel", std::sqrt(s[2] / s[3])) + ",\n    " +
           json_kv("sigma_thth_l2_error_rel", std::sqrt(s[4] / s[5])) + ",\n    " +
           json_kv("sigma_zz_l2_error_rel", s[7] > 0 ? std::sqrt(s[6] / s[7]) : 0.0) + ",\n    " +
           json_kv("stress_max_error_rel", s[10] / s_scale) + ",\n    " +
           json_kv("u_z_l2_rel", std::sqrt(s[8] / s[1])) + ",\n    " +
           json_kv("u_r_scale", u_scale);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_cylinder_scene() {
  return std::make_unique<CylinderScene>();
}

} // namespace pmpm
