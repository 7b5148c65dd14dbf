// A smooth strip or circular footing on weightless soil (docs/method.md, section 2.6), loaded in
// pressure stages: the bearing capacity is bracketed between the largest pressure at which the
// soil finds equilibrium and the first at which it does not.
//
// Half the problem by symmetry: soil of half-width W and depth D, x = 0 the footing's centre line
// (roller), far side on rollers, base fixed. The footing is a uniform pressure q on the surface
// over 0 <= x < B/2 (a smooth, flexible strip: Prandtl's mechanism and limit load hold for it as
// for a smooth rigid one). Stage k loads q_k of -footing_pressures; a stage that settles past
// -footing_collapse_settlement x B, or reaches its step cap, before it finds equilibrium has
// collapsed, and the run stops there.
//
// -footing_shape circle: a uniform pressure on a disc of diameter B, run round by
// -geometry axisymmetric (x the radius) or in 3D (-dim 3 -depth W: a quarter of the problem, the
// symmetry planes x = 0 and z = 0 on rollers, the particles of the surface row whose centres lie
// inside the disc loaded: its staircase is a particle face fine). Its reference is Shield's exact
// limit pressure of a smooth rigid circular punch on a Tresca half-space, 5.69 k (Shield 1955,
// Proc. R. Soc. Lond. A 233, 267-287), an upper bound for the uniform pressure on von Mises soil
// with the same k: the punch's mechanism moves the loaded disc down as one, so a uniform pressure
// does the punch's work on it, and von Mises with k = sigma_y / sqrt(3) dissipates no more than
// Tresca with that k in any flow (its yield surface lies inside Tresca's). The load's edge gives a
// smaller upper bound: a Prandtl mechanism there, small beside B, is a plane-strain one and needs
// only (2 + pi) k. No exact value is known for the uniform load; the axisymmetric run is the 3D
// run's independent check (docs/method.md, section 2.6).
//
// Exact limit loads for a weightless half-space: von Mises in plane strain (Tresca with
// k = sigma_y / sqrt(3)) q_u = (2 + pi) k (Prandtl 1920); Drucker-Prager matched to Mohr-Coulomb
// in plane strain (-mat_soil_match plane_strain, which gives the same plane-strain collapse loads
// as Mohr-Coulomb for associated flow), q_u = c N_c with N_c = (N_q - 1) cot phi,
// N_q = e^(pi tan phi) tan^2(45 + phi/2) (Prandtl-Reissner).
//
// Linear cells lock under isochoric plastic flow: without -fbar the soil holds pressures above
// q_u (tests/test_footing.py shows by how much). Dilatant Drucker-Prager (psi > 0) needs
// -fbar_pressure cell with -fbar (antilock.hpp; options/footing_cphi.opts).
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/model/extrude.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/registry.hpp"
#include "pmpm/materials/von_mises.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace pmpm {

enum class FootingShape { Strip = 0, Circle = 1 };
constexpr const char *FootingShapeNames[] = {"strip", "circle", "FootingShape", "FOOTING_",
                                             nullptr};
// Shield's mean pressure over k under a smooth rigid circular punch on a Tresca half-space
constexpr double kShieldNc = 5.69;

class FootingScene final : public Scene {
  double B_ = 1.0, W_ = 0, D_ = 0;
  FootingShape shape_ = FootingShape::Strip;
  // -geometry axisymmetric: the pressure the load table carries now (its tractions carry each
  // particle's radius, geometry.hpp, so a new pressure rescales them)
  double q_table_ = 0;
  std::vector<double> q_; // stage pressures (Pa)
  PetscInt ramp_ = 0;     // steps over which a later stage raises the pressure
  double collapse_ = 0.2; // settlement (in B) past which a stage has collapsed
  // per stage: pressure, held (equilibrium), settlement (mean of the loaded particles), steps
  std::vector<double> held_q_, settle_;
  std::vector<int> held_;
  std::vector<PetscInt> steps_;
  bool collapsed_ = false;
  double q_prev_ = 0; // the previous stage's pressure: where this stage's ramp starts

  // The pressure the loads carry now: every loaded particle's traction is q times its face
  // length (its block's width). Every rank sets the whole table alike.
  PetscErrorCode set_pressure(Simulation &sim, double q) {
    PetscFunctionBeginUser;
    if (sim.set.geometry == Geometry::Axisymmetric) {
      for (ParticleLoad &L : sim.model.loads) L.traction[1] *= q / q_table_;
      q_table_ = q;
      PetscFunctionReturn(0);
    }
    for (ParticleLoad &L : sim.model.loads) L.traction[1] = -q * 2.0 * L.lp[0];
    if (sim.set.dim == 3) PetscCall(ExtrudeLoads(sim)); // the step reads the extruded table
    PetscFunctionReturn(0);
  }

  // Mean vertical displacement of the loaded particles (the footing's settlement, positive down);
  // -geometry axisymmetric: weighted by their loads (their faces' areas).
  PetscErrorCode settlement(Simulation &sim, double *s) {
    ParticleView P;
    double v[2] = {0, 0};
    const int D = sim.parts.dim; // -dim 3: extruded
    const bool axi = sim.set.geometry == Geometry::Axisymmetric;
    PetscFunctionBeginUser;
    PetscCall(ParticlesGetView(sim.parts, P));
    for (const PetscInt p : sim.traction_idx) {
      const double w = axi ? -sim.model.loads[P.load[p]].traction[1] : 1.0;
      v[0] += w * (P.x0[p * D + 1] - P.x[p * D + 1]);
      v[1] += w;
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, v, 2));
    *s = v[1] > 0 ? v[0] / v[1] : 0;
    PetscFunctionReturn(0);
  }

  // Friction angle of the Mohr-Coulomb soil the exact solution is for (0 for von Mises).
  double phi_rad(const Simulation &sim) const {
    if (const auto *dp = dynamic_cast<const DruckerPrager *>(sim.model.mats[0].model.get()))
      return dp->params().phi_deg * M_PI / 180.0;
    return 0;
  }

  // How far Prandtl's mechanism reaches from the centre line: the active wedge under the strip
  // (r0 = (B/2) / cos(45 + phi/2)), the log-spiral fan (r1 = r0 e^((pi/2) tan phi)) and the
  // passive wedge, whose surface is 2 r1 cos(45 - phi/2) long. 1.5 B for phi = 0.
  double mechanism_reach(const Simulation &sim) const {
    const double phi = phi_rad(sim), r0 = 0.5 * B_ / std::cos(M_PI / 4 + phi / 2);
    const double r1 = r0 * std::exp(0.5 * M_PI * std::tan(phi));
    return 0.5 * B_ + 2 * r1 * std::cos(M_PI / 4 - phi / 2);
  }

  // The strip's exact limit pressure; the circle's reference (Shield's, for phi = 0; 0: none).
  double exact(const Simulation &sim) const {
    const Material &m = *sim.model.mats[0].model;
    if (shape_ == FootingShape::Circle) {
      if (const auto *vm = dynamic_cast<const VonMises *>(&m))
        return kShieldNc * vm->params().sigma_y0 / std::sqrt(3.0);
      if (const auto *dp = dynamic_cast<const DruckerPrager *>(&m))
        return phi_rad(sim) <= 0 ? kShieldNc * dp->params().cohesion : 0.0;
      return 0;
    }
    if (const auto *vm = dynamic_cast<const VonMises *>(&m))
      return (2.0 + M_PI) * vm->params().sigma_y0 / std::sqrt(3.0);
    if (const auto *dp = dynamic_cast<const DruckerPrager *>(&m)) {
      const double phi = phi_rad(sim), c = dp->params().cohesion;
      if (phi <= 0) return (2.0 + M_PI) * c;
      const double t = std::tan(M_PI / 4 + phi / 2);
      const double Nq = std::exp(M_PI * std::tan(phi)) * t * t;
      return c * (Nq - 1.0) / std::tan(phi);
    }
    return 0;
  }

public:
  // -dim 3: the strip extruded between rollers (plane strain; with -fbar, 3D F-bar), or the
  // circle's quarter; its settlement and pressure read in any dimension
  bool extrudes() const override { return true; }
  bool extruded_loaded(const double x[3]) const override {
    return shape_ == FootingShape::Strip || x[0] * x[0] + x[2] * x[2] < 0.25 * B_ * B_;
  }

  PetscErrorCode setup(Simulation &sim) override {
    PetscInt n = 64;
    PetscBool set = PETSC_FALSE;
    PetscBool w_set = PETSC_FALSE, d_set = PETSC_FALSE;
    PetscFunctionBeginUser;
    q_.assign(n, 0.0);
    ramp_ = sim.set.ramp_steps;
    PetscOptionsBegin(sim.comm, "footing_", "Strip or circular footing on weightless soil",
                      nullptr);
    PetscCall(PmpmOptionsReal("-width", "Footing width B (m; a circle's diameter), > 0", nullptr,
                              B_, &B_, nullptr));
    PetscCall(PmpmOptionsEnum("-shape",
                              "strip (plane strain, or extruded by -dim 3) or circle (-geometry "
                              "axisymmetric, or -dim 3 with -depth the soil width)",
                              nullptr, FootingShapeNames, (PetscEnum)shape_, (PetscEnum *)&shape_,
                              nullptr));
    PetscCall(PmpmOptionsReal("-soil_width",
                              "Soil half-width W from the centre line (m); default 3 B", nullptr,
                              W_, &W_, &w_set));
    PetscCall(
        PmpmOptionsReal("-soil_depth", "Soil depth D (m); default 2 B", nullptr, D_, &D_, &d_set));
    PetscCall(PmpmOptionsRealArray("-pressures",
                                   "Footing pressure of each stage (Pa), increasing, > 0", nullptr,
                                   q_.data(), &n, &set));
    PetscCall(PmpmOptionsReal("-collapse_settlement",
                              "Settlement over B past which a stage has collapsed (the soil "
                              "flows on; the stage ends there), > 0",
                              nullptr, collapse_, &collapse_, nullptr));
    PetscCall(PmpmOptionsInt("-stage_ramp",
                             "Steps over which a later stage raises the pressure (default "
                             "-ramp_steps)",
                             nullptr, ramp_, &ramp_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(set && n >= 1, sim.comm, PETSC_ERR_USER_INPUT,
                   "-footing_pressures is required: the footing pressure of each stage (Pa)");
    q_.resize(n);
    for (PetscInt k = 0; k < n; ++k)
      PmpmCheckInput(q_[k] > 0 && (k == 0 || q_[k] > q_[k - 1]), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-footing_pressures must be positive and increasing (entry %d is %g Pa)",
                     (int)k, q_[k]);
    PmpmCheckInput(collapse_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-footing_collapse_settlement must be > 0 (got %g)", collapse_);
    PmpmCheckInput(ramp_ >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-footing_stage_ramp must be >= 0");
    PmpmCheckInput(!w_set || W_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-footing_soil_width must be > 0 m (got %g; default 3 B)", W_);
    PmpmCheckInput(!d_set || D_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-footing_soil_depth must be > 0 m (got %g; default 2 B)", D_);
    const bool axi = sim.set.geometry == Geometry::Axisymmetric;
    PmpmCheckInput(shape_ == FootingShape::Circle || !axi, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-footing_shape strip is plane: under -geometry axisymmetric use "
                   "-footing_shape circle");
    PmpmCheckInput(shape_ == FootingShape::Strip || axi || sim.set.dim == 3, sim.comm,
                   PETSC_ERR_ARG_INCOMP,
                   "-footing_shape circle needs -geometry axisymmetric or -dim 3 (a plane "
                   "section has no circle)");
    if (W_ <= 0) W_ = 3 * B_; // reach 3.03 B at phi = 20 deg: set it for such soils
    if (D_ <= 0) D_ = 2 * B_;
    PetscInt nb, nw, nd;
    PetscCall(CheckCells(sim.comm, "-footing_width / 2", 0.5 * B_, sim.set.h, &nb));
    PetscCall(CheckCells(sim.comm, "-footing_soil_width", W_, sim.set.h, &nw));
    PetscCall(CheckCells(sim.comm, "-footing_soil_depth", D_, sim.set.h, &nd));
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nw;
    // room above the surface for the heave beside a collapsing footing
    sim.model.ncell[1] =
        nd + std::max<PetscInt>(2, static_cast<PetscInt>(std::ceil(0.5 * B_ / sim.set.h)));
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "soil", sim.model.mats[0]));
    PmpmCheckInput(sim.model.mats[0].model->plastic(), sim.comm, PETSC_ERR_USER_INPUT,
                   "-mat_soil_model must be a plastic law (%s): a footing has a bearing "
                   "capacity only in a soil that yields",
                   MaterialLawList(&MaterialLaw::plastic).c_str());
    const double reach = mechanism_reach(sim);
    PmpmCheckInput(
        W_ >= reach, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-footing_soil_width (%g m) must be at least %g m: Prandtl's mechanism reaches "
        "%.2f B from the centre line for this soil (1.5 B for phi = 0, 3.03 B for 20 deg), "
        "and a side closer than that raises the capacity",
        W_, reach, reach / B_);
    PmpmCheckInput(shape_ == FootingShape::Strip || sim.set.dim == 2 || sim.set.depth >= reach,
                   sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-depth (%g m) must be at least %g m for -footing_shape circle: the "
                   "quarter's z side must lie beyond the mechanism's reach, as its x side does",
                   sim.set.depth, reach);
    q_table_ = q_[0];
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double W = W_, D = D_, half = 0.5 * B_;
    FillRegular(
        sim, [W, D](const double x[DIM]) { return x[0] < W && x[1] < D ? 0 : -1; }, out);
    // the surface row under the footing carries its pressure (stage 0's, ramped by the relaxation)
    for (auto &q : out)
      if (q.x[1] + q.lp[1] > D - 1e-9 * sim.set.h && q.x[0] < half) {
        q.traction[1] = -q_[0] * 2.0 * q.lp[0];
        q.tface[1] = q.lp[1];
      }
    PetscFunctionReturn(0);
  }

  PetscInt stages() const override { return static_cast<PetscInt>(q_.size()) - 1; }

  bool finished() const override { return collapsed_; }

  PetscErrorCode begin_stage(Simulation &sim, PetscInt k) override {
    PetscFunctionBeginUser;
    sim.stage_ramp = ramp_; // no convergence before the new pressure is fully on
    q_prev_ = k == 0 ? 0 : q_[k - 1];
    PetscFunctionReturn(0);
  }

  // Later stages raise the pressure linearly over the stage ramp (the traction field keeps it
  // after that, and a checkpoint keeps the field); a footing that has sunk past
  // the collapse settlement ends its stage (checked every 50 steps: one reduction).
  PetscErrorCode monitor(Simulation &sim) override {
    PetscFunctionBeginUser;
    const PetscInt k = sim.run.stage_step;
    if (sim.stage > 0 && k >= 1 && k <= std::max<PetscInt>(ramp_, 1)) {
      const double r = ramp_ > 0 ? std::fmin(1.0, double(k) / ramp_) : 1.0;
      PetscCall(set_pressure(sim, q_prev_ + r * (q_[sim.stage] - q_prev_)));
    }
    if (k > 0 && k % 50 == 0) {
      double s = 0;
      PetscCall(settlement(sim, &s));
      if (s > collapse_ * B_) sim.run.stop_stage = true;
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode end_stage(Simulation &sim, PetscInt k) override {
    double s = 0;
    PetscFunctionBeginUser;
    PetscCall(settlement(sim, &s));
    held_q_.push_back(q_[k]);
    held_.push_back(sim.run.converged ? 1 : 0);
    settle_.push_back(s);
    steps_.push_back(sim.run.stage_step);
    collapsed_ = !sim.run.converged;
    if (!sim.set.quiet)
      PetscCall(PetscPrintf(sim.comm, "footing: q = %.6g Pa (%.4f of %s) %s, settlement %.4g m\n",
                            q_[k], q_[k] / exact(sim),
                            shape_ == FootingShape::Strip ? "q_u" : "Shield's 5.69 k",
                            collapsed_ ? "collapsed" : "holds", s));
    PetscFunctionReturn(0);
  }

  // The circle's loaded area over the disc's (quarter of it in 3D, per radian under
  // -geometry axisymmetric): the faces of the loaded particles, as the pressure acts on them.
  PetscErrorCode loaded_area_ratio(Simulation &sim, double *ratio) {
    ParticleView P;
    double A = 0;
    const double a = 0.5 * B_;
    PetscFunctionBeginUser;
    PetscCall(ParticlesGetView(sim.parts, P));
    for (const PetscInt p : sim.traction_idx) {
      if (sim.parts.dim == 3) {
        const ParticleLoadT<3> &L = sim.model.loads3[P.load[p]];
        A += 4.0 * L.lp[0] * L.lp[2];
      } else
        A += -sim.model.loads[P.load[p]].traction[1] / q_table_;
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, &A, 1));
    *ratio = A / (sim.parts.dim == 3 ? 0.25 * M_PI * a * a : 0.5 * a * a);
    PetscFunctionReturn(0);
  }

  // The stage record and the pressure ramp's ends (checkpoint.hpp).
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    const std::vector<double> held(held_.begin(), held_.end()), steps(steps_.begin(), steps_.end());
    PetscCall(CheckpointWriteArray(v, "pressure", held_q_));
    PetscCall(CheckpointWriteArray(v, "holds", held));
    PetscCall(CheckpointWriteArray(v, "settlement", settle_));
    PetscCall(CheckpointWriteArray(v, "steps", steps));
    PetscCall(CheckpointWriteReal(v, "q_prev", q_prev_));
    PetscCall(CheckpointWriteReal(v, "q_table", q_table_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &, PetscViewer v) override {
    std::vector<double> held, steps;
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "pressure", held_q_));
    PetscCall(CheckpointReadArray(v, "holds", held));
    PetscCall(CheckpointReadArray(v, "settlement", settle_));
    PetscCall(CheckpointReadArray(v, "steps", steps));
    PetscCall(CheckpointReadReal(v, "q_prev", &q_prev_));
    PetscCall(CheckpointReadReal(v, "q_table", &q_table_));
    held_.assign(held.begin(), held.end());
    steps_.assign(steps.begin(), steps.end());
    collapsed_ = false; // a checkpoint is never written after a collapse
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    double lower = 0, upper = -1;
    for (size_t k = 0; k < held_.size(); ++k) {
      if (held_[k]) lower = held_q_[k];
      if (!held_[k] && upper < 0) upper = held_q_[k];
    }
    const double qu = exact(sim);
    json = json_kv("footing_width", B_) + ",\n    " + json_kv("bearing_capacity", lower) +
           ",\n    " +
           (upper > 0 ? json_kv("bearing_capacity_upper", upper)
                      : std::string("\"bearing_capacity_upper\": null")) +
           ",\n    ";
    if (shape_ == FootingShape::Strip) {
      json += json_kv("bearing_capacity_exact", qu) + ",\n    ";
    } else {
      double area = 0;
      PetscCall(loaded_area_ratio(sim, &area));
      json += std::string("\"footing_shape\": \"circle\",\n    ") +
              (qu > 0 ? json_kv("bearing_capacity_shield", qu)
                      : std::string("\"bearing_capacity_shield\": null")) +
              ",\n    " + json_kv("loaded_area_ratio", area) + ",\n    ";
    }
    json += json_kv("fbar", sim.set.fbar ? 1.0 : 0.0) + ",\n    \"stages\": [";
    for (size_t k = 0; k < held_.size(); ++k) {
      char row[200];
      std::snprintf(row, sizeof(row),
                    "%s{\"pressure\": %.9g, \"holds\": %s, \"settlement\": %.9g, \"steps\": %d}",
                    k ? ", " : "", held_q_[k], held_[k] ? "true" : "false", settle_[k],
                    (int)steps_[k]);
      json += row;
    }
    json += "]";
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_footing_scene() {
  return std::make_unique<FootingScene>();
}

} // namespace pmpm
