// A block on an incline (docs/method.md, section 2.5): the interface verified on its own. The plane
// stays horizontal and gravity is rotated by theta: g = |g| (sin theta, -cos theta). The block
// (colour 0) rests on a base slab (colour 1) whose bottom is fixed. Coulomb friction mu
// (-interface_mu_top, the base's upper face):
//   tan theta <= mu: the block sticks (a = 0);  otherwise a = g (sin theta - mu cos theta).
// Undamped dynamics; the block's acceleration is the least-squares slope of its centre-of-mass
// velocity over the second half of the run (after the start-up transient).
//
// -incline_chain: a membrane chain ("membrane", -mat_membrane_*, -membrane_thickness) lies on the
// base's top surface from one cell inside its left end to one cell inside its right end (a chain
// point's one-cell block must stay on the grid), and the block rests on it. The particles below
// the chain (the base) are body 0, those above (the block) body 2; contact_stack resolves them
// at the nodes with the chain's normals (exactly the surface's normal: no corner normals, so no
// colour is needed). Friction between block and sheet is the chain's upper face
// (-interface_mu_top, or -chain_membrane_mu_top); its lower face (-interface_mu_bottom) should
// be rough enough to hold the sheet on the base, so the exact solution is the block sliding on a
// fixed sheet, as above with mu the upper face's. The ends are free (-incline_chain_pin pins both,
// as supports); results add the sheet's largest displacement.
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>

namespace pmpm {

class InclineScene final : public Scene {
  double theta_ = 30, Lb_ = 0.2, Hb_ = 0.1, Lbase_ = 1.0, Hbase_ = 0.1, x0_ = 0.1;
  // -dim 3: the slope's fall line turned by phi about the base's normal (y), and the block's z
  // extent [z0, z0 + width) (width 0: the whole depth, the extruded plane-strain block)
  double phi_ = 0, z0_ = 0, Wb_ = 0;
  PetscBool chain_ = PETSC_FALSE, pin_ = PETSC_FALSE; // a membrane chain under the block
  double thickness_ = 0.0015;                         // its thickness (m)
  std::vector<double> t_, v_, s_; // rank 0: time, block velocity and displacement along x
  double sz_ = 0;                 // -dim 3: the block's mean displacement along z (last monitor)

public:
  // -dim 3: extruded; with -incline_azimuth the block slides down a fall line in x-z
  bool extrudes() const override { return true; }
  bool keeps_extruded(const double x[3]) const override {
    const bool block = x[1] >= Hbase_;
    return !block || Wb_ <= 0 || (x[2] > z0_ && x[2] < z0_ + Wb_);
  }

  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "incline_", "Block on an incline (rotated gravity)", nullptr);
    PetscCall(PmpmOptionsReal("-angle",
                              "Incline angle theta (degrees), 0..80; sets the gravity "
                              "direction",
                              nullptr, theta_, &theta_, nullptr));
    PetscCall(PmpmOptionsReal("-block_length", "Block length (m)", nullptr, Lb_, &Lb_, nullptr));
    PetscCall(PmpmOptionsReal("-block_height", "Block height (m)", nullptr, Hb_, &Hb_, nullptr));
    PetscCall(
        PmpmOptionsReal("-base_length", "Base slab length (m)", nullptr, Lbase_, &Lbase_, nullptr));
    PetscCall(
        PmpmOptionsReal("-base_height", "Base slab height (m)", nullptr, Hbase_, &Hbase_, nullptr));
    PetscCall(PmpmOptionsReal("-block_x", "Block's left end at the start (m)", nullptr, x0_, &x0_,
                              nullptr));
    PetscCall(
        PetscOptionsBool("-chain",
                         "A membrane chain (-mat_membrane_*, -membrane_thickness) on the "
                         "base's top surface, under the block: friction on its upper face "
                         "(-interface_mu_top), its lower face (-interface_mu_bottom) holds it",
                         nullptr, chain_, &chain_, nullptr));
    PetscCall(PetscOptionsBool("-chain_pin", "Pin both ends of the membrane chain (supports)",
                               nullptr, pin_, &pin_, nullptr));
    PetscCall(PmpmOptionsReal("-azimuth",
                              "-dim 3: the fall line turned by this angle (degrees, 0..90) from x "
                              "towards z about the base's normal; gravity (sin t cos a, -cos t, "
                              "sin t sin a)",
                              nullptr, phi_, &phi_, nullptr));
    PetscCall(PmpmOptionsReal("-block_z", "-dim 3: the block's start along z (m), >= 0", nullptr,
                              z0_, &z0_, nullptr));
    PetscCall(PmpmOptionsReal("-block_width",
                              "-dim 3: the block's extent along z (m); 0: the whole depth", nullptr,
                              Wb_, &Wb_, nullptr));
    PetscOptionsEnd();
    PetscCall(MembraneThicknessOption(sim.comm, "The membrane (with -incline_chain)", &thickness_));
    PmpmCheckInput(theta_ >= 0 && theta_ <= 80, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-incline_angle must be in [0, 80] degrees (got %g)", theta_);
    PetscInt n;
    PetscCall(CheckCells(sim.comm, "-incline_base_length", Lbase_, sim.set.h, &sim.model.ncell[0]));
    PetscCall(CheckCells(sim.comm, "-incline_base_height", Hbase_, sim.set.h, &n));
    PetscCall(CheckCells(sim.comm, "-incline_block_height", Hb_, sim.set.h, &sim.model.ncell[1]));
    sim.model.ncell[1] += n + 2;
    PetscCall(CheckCells(sim.comm, "-incline_block_length", Lb_, sim.set.h, &n));
    PmpmCheckInput(x0_ >= 0 && x0_ + Lb_ <= Lbase_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-incline_block_x: the block must start on the base");
    PmpmCheckInput(phi_ >= 0 && phi_ <= 90, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-incline_azimuth must be in [0, 90] degrees (got %g)", phi_);
    PmpmCheckInput(sim.set.dim == 3 || (phi_ == 0 && z0_ == 0 && Wb_ == 0), sim.comm,
                   PETSC_ERR_ARG_INCOMP,
                   "-incline_azimuth, -incline_block_z and -incline_block_width need -dim 3");
    PmpmCheckInput(z0_ >= 0 && Wb_ >= 0 && z0_ + Wb_ <= sim.set.depth * (1 + 1e-12), sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE,
                   "-incline_block_z %g and -incline_block_width %g m: the block must lie within "
                   "-depth %g m",
                   z0_, Wb_, sim.set.depth);
    PmpmCheckInput(phi_ == 0 || Wb_ > 0, sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-incline_azimuth %g needs -incline_block_width > 0: a block over the whole "
                   "depth cannot slide along z",
                   phi_);
    const double th = theta_ * M_PI / 180, ph = phi_ * M_PI / 180;
    sim.set.gdir[0] = std::sin(th) * std::cos(ph);
    sim.set.gdir[1] = -std::cos(th);
    sim.set.gdir_z = std::sin(th) * std::sin(ph);
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.mats.resize(2);
    PetscCall(MaterialFromOptions(sim.comm, "block", sim.model.mats[0]));
    PetscCall(MaterialFromOptions(sim.comm, "base", sim.model.mats[1]));
    PmpmCheckInput(sim.set.inertia == InertiaScaling::None, sim.comm, PETSC_ERR_USER_INPUT,
                   "the incline is dynamic: use -inertia_scaling none and give -mat_block_density");
    if (chain_) {
      const double h = sim.set.h;
      PmpmCheckInput(
          x0_ >= h - 1e-9 * h && x0_ + Lb_ <= Lbase_ - h + 1e-9 * h, sim.comm,
          PETSC_ERR_ARG_OUTOFRANGE,
          "-incline_block_x: with -incline_chain the block must start on the chain, which "
          "ends one cell (%g m) inside each end of the base",
          h);
      ChainSpec cs;
      cs.name = "membrane";
      cs.material = "membrane";
      PetscCall(CheckMembraneThickness(sim.comm, thickness_));
      cs.thickness = thickness_;
      cs.pin_start = cs.pin_end = pin_;
      cs.line = {h, Hbase_, Lbase_ - h, Hbase_};
      sim.model.chain_specs.push_back(cs);
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double Hbase = Hbase_, Hb = Hb_, Lbase = Lbase_, x0 = x0_, Lb = Lb_;
    FillRegular(
        sim,
        [=](const double x[DIM]) {
          if (x[1] < Hbase && x[0] < Lbase) return 1;
          if (x[1] < Hbase + Hb && x[0] > x0 && x[0] < x0 + Lb) return 0;
          return -1;
        },
        out);
    // The base carries colour 1: its top is flat across the whole contact, so the colour-gradient
    // normals there are exact; a coloured block would give 45-degree normals at its corners,
    // whose normal constraint locks the sliding. Friction acts on the base's upper face.
    // With the chain the bodies come from the chain's line and its normals: no colour.
    for (auto &q : out) q.colour = q.mat == 1 && !chain_ ? 1.0 : 0.0;
    PetscFunctionReturn(0);
  }

  // checkpoint.hpp: the block's time history so far
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointWriteArray(v, "history_t", t_));
    PetscCall(CheckpointWriteArray(v, "history_v", v_));
    PetscCall(CheckpointWriteArray(v, "history_s", s_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "history_t", t_));
    PetscCall(CheckpointReadArray(v, "history_v", v_));
    PetscCall(CheckpointReadArray(v, "history_s", s_));
    PetscFunctionReturn(0);
  }

  PetscErrorCode monitor(Simulation &sim) override {
    ParticleView P;
    // block mass, momentum and mass * displacement along the fall line (x, or -dim 3's x-z
    // direction (cos a, sin a)), mass * displacement along z
    double s[4] = {0, 0, 0, 0};
    PetscFunctionBeginUser;
    const int D = sim.parts.dim;
    const double ph = phi_ * M_PI / 180, e[3] = {std::cos(ph), 0.0, std::sin(ph)};
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p)
      if (P.mat[p] == 0) {
        const double *v = P.v + p * D, *x = P.x + p * D, *x0 = P.x0 + p * D;
        double vs = v[0] * e[0], us = (x[0] - x0[0]) * e[0];
        if (D == 3) {
          vs += v[2] * e[2];
          us += (x[2] - x0[2]) * e[2];
          s[3] += P.mass[p] * (x[2] - x0[2]);
        }
        s[0] += P.mass[p];
        s[1] += P.mass[p] * vs;
        s[2] += P.mass[p] * us;
      }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCall(SumAll(sim.comm, s, 4));
    t_.push_back(sim.run.time);
    v_.push_back(s[1] / s[0]);
    s_.push_back(s[2] / s[0]);
    sz_ = s[3] / s[0];
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const MaterialEntry &b = sim.model.mats[0];
    const double g = b.gamma / b.density, th = theta_ * M_PI / 180;
    // with the chain: its upper face (the -interface_* defaults or -chain_membrane_* overrides)
    const Chain *c = sim.chains.empty() ? nullptr : &sim.chains[0];
    const double mu = c ? c->top.mu : sim.model.iface.mu_top;
    const bool bonded =
        c ? c->top.type == FaceType::Bonded : sim.model.iface.type == InterfaceType::Bonded;
    const bool sticks = bonded || std::tan(th) <= mu;
    const double a_exact = sticks ? 0.0 : g * (std::sin(th) - mu * std::cos(th));
    // least-squares slope of v(t) over the second half of the run
    double st = 0, sv = 0, stt = 0, stv = 0, n = 0;
    const double T = t_.empty() ? 0 : t_.back();
    for (size_t k = 0; k < t_.size(); ++k)
      if (t_[k] >= 0.5 * T) {
        st += t_[k], sv += v_[k], stt += t_[k] * t_[k], stv += t_[k] * v_[k], n += 1;
      }
    const double a = n > 1 ? (n * stv - st * sv) / (n * stt - st * st) : 0.0;
    const char *sep = ",\n    ";
    json = json_kv("angle_deg", theta_) + sep + json_kv("mu", bonded ? -1.0 : mu) + sep +
           json_kv("gravity", g) + sep + json_kv("duration", T) + sep + json_kv("acceleration", a) +
           sep + json_kv("acceleration_exact", a_exact) + sep +
           json_kv("acceleration_free_slip", g * std::sin(th)) + sep +
           json_kv("displacement", s_.empty() ? 0.0 : s_.back()) + sep +
           json_kv("azimuth_deg", phi_) + sep + json_kv("displacement_z", sz_) + sep +
           json_kv("displacement_exact", 0.5 * a_exact * T * T) + sep +
           "\"sticks_exact\": " + (sticks ? "true" : "false") + sep +
           json_kv("contact_nodes",
                   c ? sim.contact_stats.contact_nodes : sim.iface_stats.contact_nodes) +
           sep +
           json_kv("slip_nodes", c ? sim.contact_stats.slip_nodes : sim.iface_stats.slip_nodes);
    if (c) { // the sheet should stay where it was laid: its largest displacement along x and y
      double ux = 0, uy = 0;
      for (int i = 0; i < c->n; ++i) {
        ux = std::fmax(ux, std::fabs(c->x[i * DIM] - c->x0[i * DIM]));
        uy = std::fmax(uy, std::fabs(c->x[i * DIM + 1] - c->x0[i * DIM + 1]));
      }
      json += sep + json_kv("sheet_max_displacement_x", ux) + sep +
              json_kv("sheet_max_displacement_y", uy);
    }
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_incline_scene() {
  return std::make_unique<InclineScene>();
}

} // namespace pmpm
