// The active trapdoor (docs/method.md, section 6.4): a layer of cohesionless Drucker-Prager soil of
// height H on a rough rigid base in which a strip of width B (the door) is lowered slowly. Its
// ground reaction curve, the pressure on the door over the initial overburden gamma H against the
// door's displacement over B, falls as the soil arches over the door and is read beside Terzaghi's
// arching with K = 1 and K = Ka.
//
// Half the problem by symmetry: soil of half-width W from the door's centre line x = 0 (roller),
// far side on rollers, top free. The grid reaches below the base (y < 0) by the largest door
// displacement and two cells, so soil that follows the door stays on the grid. Every node at or
// below the base is a support with an imposed velocity (transfers.hpp, PrescribedVelocity): fixed
// outside the door, (0, -V) under it, (0, -V/2) at the door's edge x = B/2 (the base's velocity
// then integrates to V B/2, a door of exactly half-width B/2 between grid lines). The door's force
// is the sum of the nodal forces its nodes hold, each weighted by its velocity share (1, 1/2 at
// the edge): the force conjugate to V. Stage 0 brings the soil to equilibrium under its weight
// with the door held (its pressure is gamma H); stage k lowers the door to the k-th entry of
// -trapdoor_displacements (x B) at a steady -trapdoor_rate (cells per step), holds it, and
// relaxes to equilibrium; end_stage records the door's displacement and pressure. Under -solver
// newton a stage imposes the door's displacement instead, in load steps (SupportMotion,
// docs/newton.md), and the door's force is the residual's on the same weighted dofs.
//
// The soil follows the door on the grid: the door is a region of nodes at the door's velocity, not
// a surface, so its top is resolved to a cell. For displacements below a cell (the minimum of the
// curve) that is the base itself. Under relaxation the curve depends on the door's rate as well as
// on the cell: a faster door drops soil onto itself and reads more pressure (docs/trapdoor.md);
// Newton's has no rate.
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/step/cycle.hpp"
#include "pmpm/scenes/giroud.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace pmpm {

namespace {
constexpr double kDeg = M_PI / 180.0;
} // namespace

class TrapdoorScene final : public Scene, public SupportMotion {
  double B_ = 1.0, H_ = 0, W_ = 0;
  std::vector<double> disp_; // door displacement of each stage, over B
  double rate_ = 1e-5;       // door displacement per step, over the cell size
  PetscInt ramp_ = 0;        // steps over which this stage lowers the door
  PetscInt base_j_ = 0;      // node row of the base (y = 0)
  // the door's motion: displacement so far (m, down), the stage's target, speed (m/s, down)
  double d_ = 0, target_ = 0, speed_ = 0;
  double d0_ = 0; // -solver newton: the door's displacement at the stage's start (m)
  // per stage: door displacement (m), pressure on the door (Pa), converged, steps
  std::vector<double> rec_d_, rec_p_;
  std::vector<int> rec_conv_;
  std::vector<PetscInt> rec_steps_;

  double gamma(const Simulation &sim) const { return sim.model.mats[0].gamma; }

  // The door's nodes move at speed_ (down); the rest of the base is fixed. (-dim 3: the keys of
  // the 3D grid's nodes, three dofs each.)
  void set_door_speed(Simulation &sim) {
    PrescribedVelocity &pv = sim.prescribed;
    const PetscInt D = sim.set.dim;
    for (size_t k = 0; k < pv.key.size(); ++k)
      if (pv.key[k] % D == 1) pv.v[k] = -speed_ * pv.weight[k];
  }

  // Terzaghi's arching pressure over gamma H for lateral stress ratio K (docs/method.md,
  // section 6.4).
  double terzaghi_ratio(const Simulation &sim, double K) const {
    const auto &dp = dynamic_cast<const DruckerPrager &>(*sim.model.mats[0].model).params();
    const double g = gamma(sim);
    return giroud::terzaghi_pressure(g, B_, H_, K * std::tan(dp.phi_deg * kDeg), dp.cohesion) /
           (g * H_);
  }
  double ka(const Simulation &sim) const {
    const auto &dp = dynamic_cast<const DruckerPrager &>(*sim.model.mats[0].model).params();
    const double s = std::sin(dp.phi_deg * kDeg);
    return (1 - s) / (1 + s);
  }

  // trapdoor.csv: one row per stage so far.
  PetscErrorCode write_csv(Simulation &sim) {
    PetscFunctionBeginUser;
    PetscCall(OutputPrepareDirectory(sim));
    if (sim.rank == 0) {
      const std::string path = sim.set.output_dir + "/trapdoor.csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      std::fprintf(f, "stage,displacement_over_B,pressure_over_gammaH,door_pressure,converged,"
                      "steps\n");
      const double gh = gamma(sim) * H_;
      for (size_t k = 0; k < rec_d_.size(); ++k)
        std::fprintf(f, "%d,%.8e,%.8e,%.8e,%d,%d\n", (int)k, rec_d_[k] / B_, rec_p_[k] / gh,
                     rec_p_[k], rec_conv_[k], (int)rec_steps_[k]);
      std::fclose(f);
    }
    PetscCall(OutputCommit(sim, "trapdoor.csv"));
    PetscFunctionReturn(0);
  }

public:
  // -dim 3: the strip door extruded between rollers (the support table on every node plane)
  bool extrudes() const override { return true; }

  PetscErrorCode setup(Simulation &sim) override {
    PetscInt n = 64;
    PetscBool set = PETSC_FALSE, hset = PETSC_FALSE, wset = PETSC_FALSE;
    PetscFunctionBeginUser;
    disp_.assign(n, 0.0);
    PetscOptionsBegin(sim.comm, "trapdoor_", "Active trapdoor under a cohesionless soil layer",
                      nullptr);
    PetscCall(PmpmOptionsReal("-width", "Door width B (m), > 0; B/2 a whole number of cells",
                              nullptr, B_, &B_, nullptr));
    PetscCall(PmpmOptionsReal("-height", "Soil height H (m), > 0, whole cells; default 2 B",
                              nullptr, H_, &H_, &hset));
    PetscCall(PmpmOptionsReal("-soil_width",
                              "Soil half-width W from the door's centre line (m), >= B, whole "
                              "cells; default B/2 + max(B, 1.5 H)",
                              nullptr, W_, &W_, &wset));
    PetscCall(PmpmOptionsRealArray("-displacements",
                                   "Door displacement of each stage over B, increasing, in "
                                   "(0, 0.5]",
                                   nullptr, disp_.data(), &n, &set));
    PetscCall(PmpmOptionsReal("-rate",
                              "Door displacement per step over the cell size, in (0, 0.01]: a "
                              "stage lowers the door at this steady rate, then holds it",
                              nullptr, rate_, &rate_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(
        set && n >= 1, sim.comm, PETSC_ERR_USER_INPUT,
        "-trapdoor_displacements is required: the door displacement of each stage over B");
    disp_.resize(n);
    for (PetscInt k = 0; k < n; ++k)
      PmpmCheckInput(disp_[k] > 0 && disp_[k] <= 0.5 && (k == 0 || disp_[k] > disp_[k - 1]),
                     sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-trapdoor_displacements must be increasing and in (0, 0.5] (entry %d is %g)",
                     (int)k, disp_[k]);
    PmpmCheckInput(B_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trapdoor_width must be > 0 (got %g)", B_);
    PmpmCheckInput(rate_ > 0 && rate_ <= 0.01, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trapdoor_rate must be in (0, 0.01] cells per step (got %g)", rate_);
    // given, they must be > 0 (0 is not "the default")
    PmpmCheckInput(!hset || H_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trapdoor_height must be > 0 m, whole cells (got %g; default 2 B)", H_);
    PmpmCheckInput(!wset || W_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trapdoor_soil_width must be > 0 m, >= B, whole cells (got %g; default B/2 + "
                   "max(B, 1.5 H))",
                   W_);
    if (H_ <= 0) H_ = 2 * B_;
    if (W_ <= 0) W_ = 0.5 * B_ + std::max(B_, 1.5 * H_);
    PetscInt nb, nw, nh;
    PetscCall(CheckCells(sim.comm, "-trapdoor_width / 2", 0.5 * B_, sim.set.h, &nb));
    PetscCall(CheckCells(sim.comm, "-trapdoor_height", H_, sim.set.h, &nh));
    PetscCall(CheckCells(sim.comm, "-trapdoor_soil_width", W_, sim.set.h, &nw));
    PmpmCheckInput(W_ >= B_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trapdoor_soil_width (%g m) must be at least the door width %g m", W_, B_);
    // room below the base for the soil that follows the door: its largest displacement + 2 cells
    base_j_ = static_cast<PetscInt>(std::ceil(disp_.back() * B_ / sim.set.h - 1e-9)) + 2;
    sim.model.origin[0] = 0;
    sim.model.origin[1] = -base_j_ * sim.set.h;
    sim.model.ncell[0] = nw;
    sim.model.ncell[1] =
        base_j_ + nh + 1; // a cell above the surface for the top particles' support
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.face[YMAX] = FaceBC::Free;
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "soil", sim.model.mats[0]));
    const auto *dp = dynamic_cast<const DruckerPrager *>(sim.model.mats[0].model.get());
    PmpmCheckInput(dp && dp->params().phi_deg > 0, sim.comm, PETSC_ERR_USER_INPUT,
                   "-mat_soil_model must be drucker_prager with -mat_soil_friction_angle > 0 (the "
                   "soil arches by friction)");
    PmpmCheckInput(sim.model.mats[0].gamma > 0, sim.comm, PETSC_ERR_USER_INPUT,
                   "-mat_soil_gamma must be > 0: the soil's weight is the door's load");
    // the supports: every node at or below the base; the door's (i <= nb) move, share 1 (1/2 at
    // the edge) of the door's speed, and weigh the door's force by that share
    // -dim 3: the same on every node plane along z (the door a strip across the depth)
    PrescribedVelocity &pv = sim.prescribed;
    pv = PrescribedVelocity{};
    const int D = static_cast<int>(sim.set.dim);
    const PetscInt nz = D == 3 ? static_cast<PetscInt>(std::llround(sim.set.depth / sim.set.h)) : 0;
    const PetscInt ncell[3] = {sim.model.ncell[0], sim.model.ncell[1], nz};
    for (PetscInt k = 0; k <= nz; ++k)
      for (PetscInt j = 0; j <= base_j_; ++j)
        for (PetscInt i = 0; i <= nw; ++i) {
          const double share = i < nb ? 1.0 : (i == nb ? 0.5 : 0.0);
          const PetscInt n[3] = {i, j, k};
          for (int d = 0; d < D; ++d) {
            pv.key.push_back(D == 3 ? PrescribedKey<3>(n, d, ncell)
                                    : PrescribedKey(i, j, d, sim.model.ncell));
            pv.v.push_back(0.0);
            pv.weight.push_back(share);
          }
        }
    PrescribedVelocitySort(pv);
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double W = W_, H = H_;
    FillRegular(
        sim, [W, H](const double x[DIM]) { return x[0] < W && x[1] > 0 && x[1] < H ? 0 : -1; },
        out);
    PetscFunctionReturn(0);
  }

  PetscInt stages() const override { return static_cast<PetscInt>(disp_.size()); }

  PetscErrorCode begin_stage(Simulation &sim, PetscInt k) override {
    PetscFunctionBeginUser;
    speed_ = 0;
    if (k > 0) {
      // a steady speed that reaches the target in ramp_ steps of the stage's first step size
      // (Relax's: cfl h / wave speed); monitor corrects it step by step with the actual sizes
      double c = 0;
      PetscCall(InitialWaveSpeed(sim, &c));
      target_ = disp_[k - 1] * B_;
      ramp_ = std::max<PetscInt>(
          1, static_cast<PetscInt>(std::ceil((target_ - d_) / (rate_ * sim.set.h))));
      speed_ = (target_ - d_) / (ramp_ * sim.set.cfl * sim.set.h / c);
      sim.stage_ramp = ramp_; // no convergence while the door moves
    }
    set_door_speed(sim);
    PetscFunctionReturn(0);
  }

  // After each step of a lowering stage: the door's displacement so far (exact: the speed of the
  // step just taken times its size), and the speed that reaches the target at the ramp's end.
  PetscErrorCode monitor(Simulation &sim) override {
    PetscFunctionBeginUser;
    const PetscInt k = sim.run.stage_step;
    if (sim.stage == 0 || k < 1 || speed_ == 0) PetscFunctionReturn(0);
    d_ += speed_ * sim.run.dt;
    speed_ = k < ramp_ ? std::fmax(0.0, target_ - d_) / (double(ramp_ - k) * sim.run.dt) : 0.0;
    set_door_speed(sim);
    PetscFunctionReturn(0);
  }

  PetscErrorCode end_stage(Simulation &sim, PetscInt k) override {
    PetscFunctionBeginUser;
    // the force the soil puts on the door (down), over the half-door (-dim 3: and the depth)
    const double p = -sim.support_force[1] / (0.5 * B_ * (sim.set.dim == 3 ? sim.set.depth : 1.0));
    rec_d_.push_back(d_);
    rec_p_.push_back(p);
    rec_conv_.push_back(sim.run.converged ? 1 : 0);
    rec_steps_.push_back(sim.run.stage_step);
    PetscCall(write_csv(sim));
    if (!sim.set.quiet)
      PetscCall(PetscPrintf(sim.comm,
                            "trapdoor: stage %d, door displacement %.4g B, pressure %.4g gamma H "
                            "(%s)\n",
                            (int)k, d_ / B_, p / (gamma(sim) * H_),
                            sim.run.converged ? "equilibrium" : "NOT converged"));
    PetscFunctionReturn(0);
  }

  // -solver newton (solver.hpp): a lowering stage imposes the door's displacement over its load
  // steps, (0, -(target - d) share) on each door dof, the base's other dofs held; the door's
  // velocity stays 0, so monitor leaves it alone.
  bool moves_supports(PetscInt k) const override { return k >= 1; }
  PetscErrorCode support_displacement(Simulation &sim, PetscInt, std::vector<double> &du) override {
    PetscFunctionBeginUser;
    const PrescribedVelocity &pv = sim.prescribed;
    const PetscInt D = sim.set.dim; // y is dof 1 of D per node (-dim 3: three)
    du.assign(pv.key.size(), 0.0);
    for (size_t k = 0; k < pv.key.size(); ++k)
      if (pv.key[k] % D == 1) du[k] = -(target_ - d_) * pv.weight[k];
    d0_ = d_;
    speed_ = 0;
    set_door_speed(sim);
    PetscFunctionReturn(0);
  }
  PetscErrorCode supports_moved(Simulation &, double t) override {
    PetscFunctionBeginUser;
    d_ = t >= 1.0 ? target_ : d0_ + t * (target_ - d0_);
    PetscFunctionReturn(0);
  }

  // The stage record and the door's motion (checkpoint.hpp).
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    const std::vector<double> conv(rec_conv_.begin(), rec_conv_.end()),
        steps(rec_steps_.begin(), rec_steps_.end());
    PetscCall(CheckpointWriteArray(v, "displacement", rec_d_));
    PetscCall(CheckpointWriteArray(v, "pressure", rec_p_));
    PetscCall(CheckpointWriteArray(v, "converged", conv));
    PetscCall(CheckpointWriteArray(v, "steps", steps));
    PetscCall(CheckpointWriteReal(v, "door_displacement", d_));
    PetscCall(CheckpointWriteReal(v, "door_target", target_));
    PetscCall(CheckpointWriteReal(v, "door_speed", speed_));
    PetscCall(CheckpointWriteReal(v, "door_ramp", double(ramp_)));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &sim, PetscViewer v) override {
    std::vector<double> conv, steps;
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "displacement", rec_d_));
    PetscCall(CheckpointReadArray(v, "pressure", rec_p_));
    PetscCall(CheckpointReadArray(v, "converged", conv));
    PetscCall(CheckpointReadArray(v, "steps", steps));
    PetscCall(CheckpointReadReal(v, "door_displacement", &d_));
    PetscCall(CheckpointReadReal(v, "door_target", &target_));
    PetscCall(CheckpointReadReal(v, "door_speed", &speed_));
    double ramp = 0;
    PetscCall(CheckpointReadReal(v, "door_ramp", &ramp));
    ramp_ = static_cast<PetscInt>(ramp);
    rec_conv_.assign(conv.begin(), conv.end());
    rec_steps_.assign(steps.begin(), steps.end());
    set_door_speed(sim);
    PetscFunctionReturn(0);
  }

  // The curve's minimum (after stage 0) and where, its last value, and Terzaghi's bracket.
  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const double gh = gamma(sim) * H_;
    size_t kmin = 0;
    for (size_t k = 1; k < rec_p_.size(); ++k)
      if (kmin == 0 || rec_p_[k] < rec_p_[kmin]) kmin = k;
    const char *sep = ",\n    ";
    const auto &dp = dynamic_cast<const DruckerPrager &>(*sim.model.mats[0].model).params();
    json = json_kv("door_width", B_) + sep + json_kv("height", H_) + sep +
           json_kv("soil_half_width", W_) + sep + json_kv("gamma", gamma(sim)) + sep +
           json_kv("phi", dp.phi_deg) + sep + json_kv("cohesion", dp.cohesion) + sep +
           json_kv("Ka", ka(sim)) + sep + json_kv("terzaghi_K1", terzaghi_ratio(sim, 1.0)) + sep +
           json_kv("terzaghi_Ka", terzaghi_ratio(sim, ka(sim))) + sep +
           json_kv("fbar", sim.set.fbar ? 1.0 : 0.0);
    if (!rec_p_.empty()) json += sep + json_kv("initial_ratio", rec_p_[0] / gh);
    if (kmin > 0)
      json += sep + json_kv("min_ratio", rec_p_[kmin] / gh) + sep +
              json_kv("min_displacement_over_B", rec_d_[kmin] / B_) + sep +
              json_kv("final_ratio", rec_p_.back() / gh) + sep +
              json_kv("final_displacement_over_B", rec_d_.back() / B_);
    json += std::string(sep) + "\"stages\": [";
    for (size_t k = 0; k < rec_p_.size(); ++k) {
      char row[200];
      std::snprintf(row, sizeof(row),
                    "%s{\"displacement_over_B\": %.9g, \"ratio\": %.9g, \"converged\": %s, "
                    "\"steps\": %d}",
                    k ? ", " : "", rec_d_[k] / B_, rec_p_[k] / gh, rec_conv_[k] ? "true" : "false",
                    (int)rec_steps_[k]);
      json += row;
    }
    json += "]";
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_trapdoor_scene() {
  return std::make_unique<TrapdoorScene>();
}

} // namespace pmpm
