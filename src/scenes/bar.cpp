// The paper's Figure 2 bar: plane strain, x = 0 on rollers, y = 0 on rollers (the symmetry line
// that pins u_y), traction t on the end x = L, no gravity. Static solution (docs/method.md,
// section 2.1): sigma_xx = t, u_x = t (1 - nu^2) x / E, u_y = -nu (1 + nu) t y / E. Extruded
// (-dim 3) between free z faces (-bc_zmin free -bc_zmax free) it is a bar in uniaxial stress:
// u_x = t x / E, u_y = -nu t y / E, u_z = -nu t (z - z_0) / E; also with one z face on rollers
// (a symmetry plane, z_0 there: -bc_zmin roller -bc_zmax free), which holds the rigid z
// translation an implicit solve cannot leave free.
//
// Vibrating bar (docs/method.md, section 2.4), with -bar_initial_velocity v0 (and -bar_traction 0,
// nu = 0, -bar_top_roller, -dynamic): fixed-free, v(x, 0) = v0 sin(beta x), beta = pi / (2L); exact
// v = v0 cos(omega t) sin(beta x), omega = beta sqrt(E / rho), centre-of-mass velocity
// (2 v0 / pi) cos(omega t), energy rho v0^2 L B / 4 constant. The period is measured from the
// zero crossings of the centre-of-mass velocity; the energy is kinetic + elastic
// (V sigma : C^-1 : sigma / 2) at every step. With -transfer apic the particles start with the
// field's gradient as their affine part (B_p = C D_p) and the kinetic energy includes it
// (affine_kinetic, at the particles' current D_p). Extruded (-dim 3) the energy is the depth's:
// energy_exact is times -depth; between free z faces with nu > 0 the bar is in a mixed state
// (sigma_zz = 0, eps_yy = 0 under -bar_top_roller), whose modulus E / (1 - nu^2) sets omega
// (tests/test_dim3.py computes that period; the results' omega_exact is nu = 0's).
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/step/cycle.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

class BarScene final : public Scene {
  double L_ = 1.0, B_ = 0.25, t_ = 1e3, box_ = 0, v0_ = 0;
  PetscInt nL_ = 0;
  PetscBool top_roller_ = PETSC_FALSE;
  std::vector<double> hist_t_, hist_v_, hist_e_; // rank 0: time, centre-of-mass v_x, energy

  double beta() const { return M_PI / (2 * L_); }

public:
  // both bars extrude (-dim 3): the results and the vibrating bar's monitor read any dimension
  bool extrudes() const override { return true; }
  PetscErrorCode setup(Simulation &sim) override {
    PetscBool box_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "bar_", "Bar under end traction (paper Figure 2)", nullptr);
    PetscCall(PmpmOptionsReal("-length", "Bar length L (m)", nullptr, L_, &L_, nullptr));
    PetscCall(PmpmOptionsReal("-height", "Bar height B (m)", nullptr, B_, &B_, nullptr));
    PetscCall(PmpmOptionsReal("-traction", "End traction t (Pa, tension > 0)", nullptr, t_, &t_,
                              nullptr));
    PetscCall(PmpmOptionsReal("-box_length", "Grid length in x (m), >= L + 2 cells; default 1.5 L",
                              nullptr, box_, &box_, &box_set));
    PetscCall(PmpmOptionsReal("-initial_velocity",
                              "Vibrating bar: initial v_x = v0 sin(pi x / 2L) (m/s); 0: static bar",
                              nullptr, v0_, &v0_, nullptr));
    PetscCall(PetscOptionsBool("-top_roller",
                               "Roller on the bar's top face y = B (the grid ends there): with "
                               "nu = 0 the bar is one-dimensional",
                               nullptr, top_roller_, &top_roller_, nullptr));
    PetscOptionsEnd();
    PetscInt nB, nbox;
    PetscCall(CheckCells(sim.comm, "-bar_length", L_, sim.set.h, &nL_));
    PetscCall(CheckCells(sim.comm, "-bar_height", B_, sim.set.h, &nB));
    PmpmCheckInput(!box_set || box_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-bar_box_length must be > 0 m (got %g; default 1.5 L)", box_);
    if (box_ <= 0) box_ = sim.set.h * std::ceil(1.5 * L_ / sim.set.h);
    PetscCall(CheckCells(sim.comm, "-bar_box_length", box_, sim.set.h, &nbox));
    PmpmCheckInput(
        nbox >= nL_ + 2, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-bar_box_length %g m leaves no room for the bar to stretch: the grid is too small "
        "for the particles (need >= L + 2 cells = %g m)",
        box_, (nL_ + 2) * sim.set.h);
    PmpmCheckInput(
        t_ != 0 || v0_ != 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-bar_traction must be non-zero (or give -bar_initial_velocity for a vibrating bar)");
    PmpmCheckInput(v0_ == 0 || t_ == 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-bar_initial_velocity needs -bar_traction 0 (free vibration)");
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nbox;
    sim.model.ncell[1] = top_roller_ ? nB : nB + 1;
    sim.model.face[XMIN] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Roller;
    if (top_roller_) sim.model.face[YMAX] = FaceBC::Roller;
    sim.model.face_traction[XMAX][0] = t_; // on the bar's end, the body's face toward x max
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "bar", sim.model.mats[0]));
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double L = L_, B = B_;
    FillRegular(
        sim, [L, B](const double x[DIM]) { return x[0] < L && x[1] < B ? 0 : -1; }, out);
    PetscFunctionReturn(0); // the end traction is the xmax face traction (SimulationSetup)
  }

  // checkpoint.hpp: the time history so far
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointWriteArray(v, "history_t", hist_t_));
    PetscCall(CheckpointWriteArray(v, "history_v", hist_v_));
    PetscCall(CheckpointWriteArray(v, "history_e", hist_e_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "history_t", hist_t_));
    PetscCall(CheckpointReadArray(v, "history_v", hist_v_));
    PetscCall(CheckpointReadArray(v, "history_e", hist_e_));
    PetscFunctionReturn(0);
  }

  // Step 0: the initial velocity field; every step: s += [mass, x-momentum, kinetic + elastic
  // energy] of this rank's particles, in dimension D (-dim 3: stride 3, six stresses).
  template <int D>
  void MonitorSums(Simulation &sim, const ParticleView &P, const double *origin, double s[3]) {
    const ElasticConstants &c = sim.model.mats[0].el;
    constexpr int NS = NStress<D>;
    for (PetscInt p = 0; p < P.n; ++p) {
      double *v = P.v + p * D;
      double Dp[D] = {}, *B = P.B ? P.B + p * D * D : nullptr;
      if (B)
        affine_inertia<D>(sim.set.shape, P.x + p * D, P.lp + p * D, P.F + p * D * D, origin,
                          sim.set.h, Dp);
      if (sim.run.step == 0) {
        v[0] = v0_ * std::sin(beta() * P.x0[p * D]);
        if (B) B[0] = v0_ * beta() * std::cos(beta() * P.x0[p * D]) * Dp[0]; // C D, C = dv/dx
      }
      const double *q = P.stress + p * NS;
      const double sq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
      const double cross = q[0] * q[1] + q[1] * q[2] + q[2] * q[0];
      double shear2 = q[3] * q[3]; // xy (3D: + yz, xz)
      for (int k = 4; k < NS; ++k) shear2 += q[k] * q[k];
      double v2 = 0.0;
      for (int d = 0; d < D; ++d) v2 += v[d] * v[d];
      s[0] += P.mass[p];
      s[1] += P.mass[p] * v[0];
      s[2] += 0.5 * P.mass[p] * v2 +
              P.vol[p] * (sq - 2 * c.nu * cross + 2 * (1 + c.nu) * shear2) / (2 * c.E);
      if (B) s[2] += affine_kinetic<D>(P.mass[p], B, Dp); // APIC: the affine part (affine.hpp)
    }
  }

  PetscErrorCode monitor(Simulation &sim) override {
    ParticleView P;
    double s[3] = {0, 0, 0}; // mass, x-momentum, kinetic + elastic energy
    PetscFunctionBeginUser;
    if (v0_ == 0) PetscFunctionReturn(0);
    PetscCall(ParticlesGetView(sim.parts, P));
    if (sim.set.dim == 3)
      MonitorSums<3>(sim, P, sim.grid3.origin, s);
    else
      MonitorSums<DIM>(sim, P, sim.model.origin, s);
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, s, 3));
    hist_t_.push_back(sim.run.time);
    hist_v_.push_back(s[1] / s[0]);
    hist_e_.push_back(s[2]);
    PetscFunctionReturn(0);
  }

  // Period from the zero crossings of the centre-of-mass velocity; energy drift.
  PetscErrorCode vibration_results(Simulation &sim, std::string &json) {
    PetscFunctionBeginUser;
    const MaterialEntry &m = sim.model.mats[0];
    const double omega = beta() * std::sqrt(m.el.E / m.density), T_exact = 2 * M_PI / omega;
    std::vector<double> tc; // crossing times (linear interpolation)
    for (size_t k = 1; k < hist_v_.size(); ++k) {
      const double a = hist_v_[k - 1], b = hist_v_[k];
      if ((a > 0 && b <= 0) || (a < 0 && b >= 0))
        tc.push_back(hist_t_[k - 1] + (hist_t_[k] - hist_t_[k - 1]) * a / (a - b));
    }
    const double T = tc.size() >= 2 ? 2 * (tc.back() - tc.front()) / double(tc.size() - 1) : 0;
    // Energy: the whole-run range, and the drift of its mean over the first and the last
    // measured period (the kinetic and elastic parts are half a step apart, so the sum
    // oscillates by O(omega dt) within a period; its mean does not).
    double e0 = hist_e_.empty() ? 0 : hist_e_.front(), emin = e0, emax = e0;
    for (double e : hist_e_) emin = std::fmin(emin, e), emax = std::fmax(emax, e);
    auto mean_over = [&](double t0, double t1) {
      double s = 0, n = 0;
      for (size_t k = 0; k < hist_t_.size(); ++k)
        if (hist_t_[k] >= t0 && hist_t_[k] < t1) s += hist_e_[k], n += 1;
      return n > 0 ? s / n : 0.0;
    };
    const double tend = hist_t_.empty() ? 0 : hist_t_.back();
    const double Tm = T > 0 ? T : T_exact;
    const double e_first = mean_over(0, Tm), e_last = mean_over(tend - Tm, tend + 1);
    double vmax = 0;
    for (double v : hist_v_) vmax = std::fmax(vmax, std::fabs(v));
    const char *sep = ",\n    ";
    json =
        json_kv("initial_velocity", v0_) + sep + json_kv("omega_exact", omega) + sep +
        json_kv("period", T) + sep + json_kv("period_exact", T_exact) + sep +
        json_kv("period_error_rel", std::fabs(T - T_exact) / T_exact) + sep +
        json_kv("zero_crossings", (double)tc.size()) + sep + json_kv("vcm_amplitude", vmax) + sep +
        json_kv("vcm_amplitude_exact", 2 * v0_ / M_PI) + sep + json_kv("energy_initial", e0) + sep +
        json_kv("energy_exact",
                m.density * v0_ * v0_ * L_ * B_ / 4 * (sim.set.dim == 3 ? sim.set.depth : 1.0)) +
        sep + json_kv("energy_final", hist_e_.empty() ? 0 : hist_e_.back()) + sep +
        json_kv("energy_range_rel", (emax - emin) / e0) + sep +
        json_kv("energy_drift_rel", (e_last - e_first) / e_first) + sep + json_kv("duration", tend);
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    ParticleView P;
    PetscFunctionBeginUser;
    if (v0_ != 0) {
      PetscCall(vibration_results(sim, json));
      PetscFunctionReturn(0);
    }
    const ElasticConstants &c = sim.model.mats[0].el;
    // [sum ux at tip, sum x0 at tip, count at tip]; and max stress error
    double s[3] = {0, 0, 0}, err = 0;
    PetscCall(ParticlesGetView(sim.parts, P));
    const int D = sim.parts.dim, NS = D == 3 ? NStress<3> : NSTRESS; // -dim 3: extruded
    for (PetscInt p = 0; p < P.n; ++p) {
      err = std::fmax(err, std::fabs(P.stress[p * NS] - t_) / std::fabs(t_));
      if (P.load[p] >= 0) {
        s[0] += P.x[p * D] - P.x0[p * D];
        s[1] += P.x0[p * D];
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
    // -dim 3 with both z faces free, or one free and one on rollers: uniaxial stress,
    // u_x = t x / E (plane strain: t (1 - nu^2) x / E, also when extruded between rollers)
    const FaceBC zlo = sim.model.face[ZMIN], zhi = sim.model.face[ZMAX];
    const bool uniaxial = sim.set.dim == 3 && (zlo == FaceBC::Free || zhi == FaceBC::Free) &&
                          zlo != FaceBC::Fixed && zhi != FaceBC::Fixed;
    const double tip_exact = t_ * (uniaxial ? 1.0 : 1 - c.nu * c.nu) * (s[1] / s[2]) / c.E;
    json =
        (sim.set.dim == 3 ? std::string("\"state\": \"") +
                                (uniaxial ? "uniaxial stress" : "plane strain") + "\",\n    "
                          : std::string()) +
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
