// A free elastic block in a larger empty box (no gravity, free faces, nothing held): a test of
// particle migration between ranks and of the conservation of mass and momentum. The block
// starts with a rigid motion, v = v0 + omega e_z x (x - x_c), set before the first step:
//   -block_velocity vx,vy   translation v0
//   -block_omega w          rotation about the block's centre x_c (rad/s, counter-clockwise)
//   -block_period T         > 0: the translation oscillates, v(t) = v0 cos(2 pi t / T), driven by
//                           a uniform body acceleration a(t) = dv/dt applied as the particles'
//                           weight along v0 (a body force proportional to mass moves the block
//                           rigidly); the block's centre then swings by v0 T / (2 pi) either side.
// The particle momentum changes exactly by the impulse of the applied forces, sum dt F (internal
// forces sum to zero by the partition of unity, and P2G / G2P carry momentum unchanged), so the
// scene records that impulse and reports the mismatch, which is round-off. Use -dynamic.
// With -transfer apic the particles' spin m_p (B_yx - B_xy) is part of the angular momentum
// (affine.hpp), and the initial rigid rotation gives each particle its affine part,
// B_p = C D_p with C = omega [0 -1; 1 0], so that the block starts as one rigid body.
#include "pmpm/util/options.hpp"
#include "pmpm/core/affine.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

class BlockScene final : public Scene {
  double Lb_ = 0.25, Hb_ = 0.25, box_[DIM] = {1.0, 0.5}, xc_[DIM] = {-1, -1};
  double v0_[DIM] = {0, 0}, omega_ = 0, period_ = 0;
  // rank 0: history and bookkeeping
  double mass0_ = 0, n0_ = 0, L0_ = 0; // initial mass, count, angular momentum
  double impulse_[DIM] = {0, 0}, P0_[DIM] = {0, 0};
  double force_[DIM] = {0, 0};                  // total applied force during the next step
  double split_ = -1;                           // x of the first rank boundary (-1: one rank)
  double max_dP_ = 0, max_dM_ = 0, max_dN_ = 0; // largest relative mismatches over the run
  double min_dL_ = 0, max_dL_ = 0;              // angular momentum drift range (relative)
  int side_ = 0; // which side of the rank boundary the centre is on (-1, 1; 0: within h/4 of it)
  PetscInt crossings_ = 0, min_local_ = -1, max_local_ = 0;

  // Sums over the block: mass, count, momentum, mass * position, angular momentum about the origin
  // (with APIC the particles' spin too).
  PetscErrorCode sums(Simulation &sim, double s[7]) {
    ParticleView P;
    PetscFunctionBeginUser;
    for (int k = 0; k < 7; ++k) s[k] = 0;
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p) {
      const double m = P.mass[p], *x = P.x + p * DIM, *v = P.v + p * DIM;
      s[0] += m;
      s[1] += 1;
      s[2] += m * v[0];
      s[3] += m * v[1];
      s[4] += m * x[0];
      s[5] += m * x[1];
      s[6] += m * (x[0] * v[1] - x[1] * v[0]);
      if (P.B) s[6] += affine_spin(m, P.B + p * DIM * DIM);
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, s, 7));
    PetscFunctionReturn(0);
  }

  // Body acceleration magnitude along v0 during the step that starts at t (mid-step value).
  double accel(double t, double dt) const {
    if (period_ <= 0) return 0.0;
    const double w = 2 * M_PI / period_, v = std::hypot(v0_[0], v0_[1]);
    return -v * w * std::sin(w * (t + 0.5 * dt));
  }

  // Set every particle's weight to m a (the load is weight * gravity direction, gdir = v0/|v0|).
  PetscErrorCode apply_force(Simulation &sim, double a) {
    ParticleView P;
    PetscFunctionBeginUser;
    PetscCall(ParticlesGetView(sim.parts, P));
    double f = 0;
    for (PetscInt p = 0; p < P.n; ++p) {
      P.weight[p] = P.mass[p] * a;
      f += P.weight[p];
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, &f, 1));
    for (int d = 0; d < DIM; ++d) force_[d] = f * sim.set.gdir[d];
    PetscFunctionReturn(0);
  }

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscInt n = DIM;
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "block_", "Free elastic block in an empty box (migration test)",
                      nullptr);
    PetscCall(PmpmOptionsReal("-length", "Block length (m)", nullptr, Lb_, &Lb_, nullptr));
    PetscCall(PmpmOptionsReal("-height", "Block height (m)", nullptr, Hb_, &Hb_, nullptr));
    PetscCall(PmpmOptionsRealArray("-box", "Box size Lx,Ly (m)", nullptr, box_, &n, nullptr));
    n = DIM;
    PetscCall(PmpmOptionsRealArray("-centre",
                                   "Block centre at the start x,y (m); default: the box "
                                   "centre",
                                   nullptr, xc_, &n, nullptr));
    n = DIM;
    PetscCall(PmpmOptionsRealArray("-velocity", "Initial translation velocity vx,vy (m/s)", nullptr,
                                   v0_, &n, nullptr));
    PetscCall(PmpmOptionsReal("-omega", "Initial rigid rotation rate about the centre (rad/s)",
                              nullptr, omega_, &omega_, nullptr));
    PetscCall(PmpmOptionsReal("-period",
                              "Period of an oscillating translation v0 cos(2 pi t / T) (s); 0: "
                              "constant velocity",
                              nullptr, period_, &period_, nullptr));
    PetscOptionsEnd();
    PetscInt nx, ny;
    PetscCall(CheckCells(sim.comm, "-block_box (x)", box_[0], sim.set.h, &sim.model.ncell[0]));
    PetscCall(CheckCells(sim.comm, "-block_box (y)", box_[1], sim.set.h, &sim.model.ncell[1]));
    PetscCall(CheckCells(sim.comm, "-block_length", Lb_, sim.set.h, &nx));
    PetscCall(CheckCells(sim.comm, "-block_height", Hb_, sim.set.h, &ny));
    if (xc_[0] < 0) xc_[0] = 0.5 * box_[0];
    if (xc_[1] < 0) xc_[1] = 0.5 * box_[1];
    PmpmCheckInput(period_ >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE, "-block_period must be >= 0");
    PmpmCheckInput(period_ == 0 || std::hypot(v0_[0], v0_[1]) > 0, sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE, "-block_period needs a non-zero -block_velocity");
    // The block must start a cell clear of the box faces (its support stays on the grid).
    const double h = sim.set.h;
    PmpmCheckInput(xc_[0] - 0.5 * Lb_ >= h && xc_[0] + 0.5 * Lb_ <= box_[0] - h &&
                       xc_[1] - 0.5 * Hb_ >= h && xc_[1] + 0.5 * Hb_ <= box_[1] - h,
                   sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-block_centre: the block must start at least one cell inside -block_box");
    sim.model.origin[0] = sim.model.origin[1] = 0;
    for (int f = 0; f < 2 * DIM; ++f) sim.model.face[f] = FaceBC::Free;
    if (period_ > 0) { // the driving force acts along v0
      const double v = std::hypot(v0_[0], v0_[1]);
      for (int d = 0; d < DIM; ++d) sim.set.gdir[d] = v0_[d] / v;
    }
    sim.set.ramp_steps = 0;
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "block", sim.model.mats[0]));
    PmpmCheckInput(sim.model.mats[0].gamma == 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-mat_block_gamma must be 0: the block floats in an empty box (no gravity)");
    PmpmCheckInput(sim.set.dynamic, sim.comm, PETSC_ERR_USER_INPUT,
                   "the block scene is undamped dynamics: add -dynamic");
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double x0 = xc_[0] - 0.5 * Lb_, x1 = xc_[0] + 0.5 * Lb_;
    const double y0 = xc_[1] - 0.5 * Hb_, y1 = xc_[1] + 0.5 * Hb_;
    FillRegular(
        sim,
        [=](const double x[DIM]) {
          return x[0] > x0 && x[0] < x1 && x[1] > y0 && x[1] < y1 ? 0 : -1;
        },
        out);
    PetscFunctionReturn(0);
  }

  // checkpoint.hpp: the step-0 references, the running impulse and mismatches, the next step's
  // force (the particles' weights carry it too), the rank-boundary bookkeeping. The boundary
  // itself (split_) and the particle counts per rank are this run's layout's: kept from the
  // restarted run's setup when the rank count changed.
  PetscErrorCode checkpoint_write(Simulation &sim, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointWriteArray(v, "state",
                                   {mass0_,
                                    n0_,
                                    L0_,
                                    impulse_[0],
                                    impulse_[1],
                                    P0_[0],
                                    P0_[1],
                                    force_[0],
                                    force_[1],
                                    max_dP_,
                                    max_dM_,
                                    max_dN_,
                                    min_dL_,
                                    max_dL_,
                                    double(crossings_),
                                    double(side_),
                                    split_,
                                    double(min_local_),
                                    double(max_local_),
                                    double(sim.size)}));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &sim, PetscViewer v) override {
    std::vector<double> s;
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "state", s));
    PetscCheck(s.size() == 20, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
               "-restart %s: damaged checkpoint (the block's state)", sim.set.restart.c_str());
    mass0_ = s[0], n0_ = s[1], L0_ = s[2];
    impulse_[0] = s[3], impulse_[1] = s[4], P0_[0] = s[5], P0_[1] = s[6];
    force_[0] = s[7], force_[1] = s[8];
    max_dP_ = s[9], max_dM_ = s[10], max_dN_ = s[11], min_dL_ = s[12], max_dL_ = s[13];
    crossings_ = static_cast<PetscInt>(s[14]);
    if (s[19] == double(sim.size)) {
      side_ = static_cast<int>(s[15]);
      split_ = s[16];
      min_local_ = static_cast<PetscInt>(s[17]);
      max_local_ = static_cast<PetscInt>(s[18]);
    } else {
      side_ = 0;
      min_local_ = -1;
      max_local_ = 0;
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode monitor(Simulation &sim) override {
    double s[7];
    PetscFunctionBeginUser;
    if (sim.run.step == 0) { // initial rigid motion, the driving force, the rank boundary
      ParticleView P;
      PetscCall(ParticlesGetView(sim.parts, P));
      for (PetscInt p = 0; p < P.n; ++p) {
        const double *x = P.x + p * DIM;
        P.v[p * DIM + 0] = v0_[0] - omega_ * (x[1] - xc_[1]);
        P.v[p * DIM + 1] = v0_[1] + omega_ * (x[0] - xc_[0]);
        if (P.B) { // B = C D for the rigid rotation's gradient C
          double D[DIM], *B = P.B + p * DIM * DIM;
          affine_inertia(sim.set.shape, x, P.lp + p * DIM, P.F + p * DIM * DIM, sim.model.origin,
                         sim.set.h, D);
          B[0] = B[3] = 0;
          B[1] = -omega_ * D[1];
          B[2] = omega_ * D[0];
        }
      }
      PetscCall(ParticlesRestoreView(sim.parts, P));
      double lo = sim.grid.cell_lo[0] > 0 ? (double)sim.grid.cell_lo[0] : 1e300;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, sim.comm));
      split_ = lo < 1e300 ? sim.model.origin[0] + lo * sim.set.h : -1;
      PetscCall(sums(sim, s));
      mass0_ = s[0];
      n0_ = s[1];
      P0_[0] = s[2];
      P0_[1] = s[3];
      L0_ = s[6] - (s[4] * s[3] - s[5] * s[2]) / s[0]; // about the centre of mass
      side_ = 0;
      PetscCall(apply_force(sim, accel(0.0, 0.0)));
      PetscFunctionReturn(0);
    }
    // The impulse of the step just taken (force_ was set before it), then the next step's force.
    for (int d = 0; d < DIM; ++d) impulse_[d] += sim.run.dt * force_[d];
    PetscCall(sums(sim, s));
    const double pscale =
        mass0_ * (std::hypot(v0_[0], v0_[1]) + std::fabs(omega_) * 0.5 * std::hypot(Lb_, Hb_));
    const double dP = std::hypot(s[2] - P0_[0] - impulse_[0], s[3] - P0_[1] - impulse_[1]);
    max_dP_ = std::fmax(max_dP_, dP / pscale);
    max_dM_ = std::fmax(max_dM_, std::fabs(s[0] - mass0_) / mass0_);
    max_dN_ = std::fmax(max_dN_, std::fabs(s[1] - n0_));
    if (omega_ != 0) {
      const double L = s[6] - (s[4] * s[3] - s[5] * s[2]) / s[0];
      min_dL_ = std::fmin(min_dL_, L / L0_ - 1);
      max_dL_ = std::fmax(max_dL_, L / L0_ - 1);
    }
    // The centre crossing the rank boundary (a quarter-cell dead band: a centre that stays on
    // the line, as in the rotation, does not count).
    const double off = s[4] / s[0] - split_;
    const int side = std::fabs(off) < 0.25 * sim.set.h ? 0 : (off > 0 ? 1 : -1);
    if (split_ > 0 && side != 0) {
      if (side_ != 0 && side != side_) ++crossings_;
      side_ = side;
    }
    // How many particles this rank holds (the block moving between ranks), rank 0's view.
    PetscInt nl;
    PetscCall(DMSwarmGetLocalSize(sim.parts.sw, &nl));
    min_local_ = min_local_ < 0 ? nl : std::min(min_local_, nl);
    max_local_ = std::max(max_local_, nl);
    PetscCall(apply_force(sim, accel(sim.run.time, sim.run.dt)));
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    double s[7];
    PetscFunctionBeginUser;
    PetscCall(sums(sim, s));
    const char *sep = ",\n    ";
    json = json_kv("particles_initial", n0_) + sep + json_kv("mass_initial", mass0_) + sep +
           json_kv("mass_final", s[0]) + sep + json_kv("mass_error_rel_max", max_dM_) + sep +
           json_kv("count_error_max", max_dN_) + sep + json_kv("momentum_x", s[2]) + sep +
           json_kv("momentum_y", s[3]) + sep +
           json_kv("momentum_expected_x", P0_[0] + impulse_[0]) + sep +
           json_kv("momentum_expected_y", P0_[1] + impulse_[1]) + sep +
           json_kv("momentum_error_rel_max", max_dP_) + sep +
           json_kv("angular_momentum_initial", L0_) + sep +
           json_kv("angular_momentum_drift_min", min_dL_) + sep +
           json_kv("angular_momentum_drift_max", max_dL_) + sep +
           json_kv("centre_x_final", s[4] / s[0]) + sep + json_kv("centre_y_final", s[5] / s[0]) +
           sep + json_kv("rank_split_x", split_) + sep +
           json_kv("split_crossings", (double)crossings_) + sep +
           json_kv("rank0_particles_min", (double)min_local_) + sep +
           json_kv("rank0_particles_max", (double)max_local_);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_block_scene() {
  return std::make_unique<BlockScene>();
}

} // namespace pmpm
