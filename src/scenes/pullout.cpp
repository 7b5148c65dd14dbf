// Pull-out of an anchored sheet (docs/method.md, section 6.2): a membrane chain between two stiff
// elastic blocks under normal stress p (a traction on the upper block's top face), pulled at its
// right end by a dead load P (N/m, the chain's end force), both ramped together over -ramp_steps.
// Friction mu_t on the sheet's upper face, mu_b on its lower face (-interface_mu_top/_bottom or
// -chain_membrane_mu_top/_bottom). With m = (mu_t + mu_b) p, below the capacity m L:
//   T(x) = P - m x  for x < x_a = P / m,  0 beyond;   end displacement u0 = P^2 / (2 m J).
// Proportional loading (P and p ramped together) keeps x_a = P / m throughout the ramp and the
// slip zone sliding one way, so the rigid-plastic answer does not depend on the path.
//
// Geometry. The box is margin + L + margin wide and 2 H tall (H = -pullout_block_height, each
// block). The sheet lies at mid-height from x = margin to margin + L (+ -pullout_offset): the
// whole anchored length is inside the blocks, and the blocks go on for the margin (>= 2 cells)
// beyond both ends, bonded to each other where the sheet does not reach. The pulled end is the
// sheet's right end: x in the closed form is measured from its initial position, x = X_end - X
// (the force enters the anchorage at that point; the grid smears the entry over about one cell,
// an O(h) effect the tests measure). 2 H must be an odd number of cells: the sheet then lies at a
// cell centre, where the blocks' particles on either side reach exactly the two node rows its
// points reach, so every node that carries the sheet carries the pressure through it (with the
// sheet on a grid line, a quarter of its mass would sit on nodes with one neighbour only and no
// normal force: no friction holds it there). Base fixed, sides on rollers (they hold both blocks
// horizontally, so the friction cannot drag the upper block), top free under the pressure.
//
// Results (summary.json): end_displacement (u_x of the pulled point) and its exact value;
// anchored_length, measured as the base of the tension triangle, 2 (sum_k T_k l0_k) / P (it
// uses every segment and no threshold), and its exact value P / m; friction_force, the friction
// on the sheet resisting the pull (N/m, positive against P) at the last step, and its mean over
// the last quarter of the steps after the ramp (friction_force_mean); the tension at the pulled
// end (the last segment); the contact pressure on each face, length-weighted over the points
// two cells or more from the sheet's ends; J (the chain's law: E t with
// -mat_membrane_axial_stiffness uniaxial); capacity m L and pulled_out (P > m L). Above capacity
// there is no static answer: the run is bounded by -max_steps and the check is friction_force_mean
// = m L (the whole sheet slides at full friction), with end_clearance_cells (the pulled end's
// distance from the right face, in cells) to show the sheet stayed clear of the roller's nodes.
// pullout_history.csv has the friction force and the pulled end's u_x after every step.
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <cmath>
#include <cstdio>

namespace pmpm {

class PulloutScene final : public Scene {
  double L_ = 1.0, P_ = 5e3, p_ = 2e4, H_ = 0.05, margin_ = 0.1, off_ = 0, t_ = 0.001;
  double xend0_ = 0; // the pulled end's initial x
  PetscInt ramp_ = 0;
  // after each step: time, friction on the sheet (against the pull), pulled end's u_x, and
  // whether the whole sheet slid that step (both faces, every point a cell or more from its ends)
  std::vector<double> time_, fric_, uend_;
  std::vector<char> sliding_;
  std::vector<double> slip_prev_; // last step's slips, top then bottom

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "pullout_", "Pull-out of a sheet between two stiff blocks",
                      nullptr);
    PetscCall(PmpmOptionsReal("-length", "Anchored length L of the sheet (m), whole cells", nullptr,
                              L_, &L_, nullptr));
    PetscCall(PmpmOptionsReal("-force", "Pull-out force P on the sheet's right end (N/m), >= 0",
                              nullptr, P_, &P_, nullptr));
    PetscCall(PmpmOptionsReal("-pressure",
                              "Normal stress p on the sheet (Pa), > 0: a traction on the upper "
                              "block's top face",
                              nullptr, p_, &p_, nullptr));
    PetscCall(PmpmOptionsReal("-block_height",
                              "Height H of each block (m); 2 H must be an odd number of cells "
                              "(the sheet at a cell centre)",
                              nullptr, H_, &H_, nullptr));
    PetscCall(PmpmOptionsReal("-margin",
                              "Block length beyond each end of the sheet (m), whole cells, >= 2 "
                              "cells",
                              nullptr, margin_, &margin_, nullptr));
    PetscCall(PmpmOptionsReal("-offset",
                              "Shift of the sheet along x against the grid (m, |dx| < h)", nullptr,
                              off_, &off_, nullptr));
    PetscOptionsEnd();
    PetscOptionsBegin(sim.comm, "membrane_", "The membrane", nullptr);
    PetscCall(
        PmpmOptionsReal("-thickness", "Membrane thickness t (m), > 0", nullptr, t_, &t_, nullptr));
    PetscOptionsEnd();
    const double h = sim.set.h;
    PmpmCheckInput(P_ >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-pullout_force must be >= 0 (got %g)", P_);
    PmpmCheckInput(p_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-pullout_pressure must be > 0 (got %g)", p_);
    PmpmCheckInput(std::fabs(off_) < h, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-pullout_offset must be within one cell (|dx| < %g m, got %g)", h, off_);
    PetscInt nl, nm, n2h;
    PetscCall(CheckCells(sim.comm, "-pullout_length", L_, h, &nl));
    PetscCall(CheckCells(sim.comm, "-pullout_margin", margin_, h, &nm));
    // the sheet's ends and their reach (one cell) stay clear of the roller nodes
    PmpmCheckInput(
        margin_ - std::fabs(off_) >= 2 * h * (1 - 1e-9), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-pullout_margin = %g m leaves the sheet's ends less than 2 cells (%g m) from the "
        "side faces, whose boundary condition holds every body's nodes",
        margin_, 2 * h);
    PetscCall(CheckCells(sim.comm, "-pullout_block_height (twice it)", 2 * H_, h, &n2h));
    PmpmCheckInput(
        n2h % 2 == 1 && n2h >= 3, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-pullout_block_height = %g m: twice it is %" PetscInt_FMT
        " cells of %g m; it must be an odd number >= 3 so the sheet lies at a cell centre "
        "(e.g. %g m)",
        H_, n2h, h, (2 * (n2h / 2) + 1) * 0.5 * h);
    // One particle per cell puts the blocks' particle centres on the two node rows the sheet
    // reaches: the normal force then passes through one row only, the other separates, and the
    // half of the sheet on it slides with no friction (measured: u0 several times the exact).
    PmpmCheckInput(
        sim.set.ppc >= 2, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-ppc must be >= 2 for the pullout scene (got %" PetscInt_FMT
        "): with one particle per cell the pressure passes through one of the sheet's two "
        "node rows only and the sheet slips freely on the other",
        sim.set.ppc);
    sim.model.ncell[0] = 2 * nm + nl;
    sim.model.ncell[1] = n2h;
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.face[YMAX] = FaceBC::Free;
    sim.model.face_traction[YMAX][0] = 0;
    sim.model.face_traction[YMAX][1] = -p_;
    ramp_ = sim.set.ramp_steps;
    sim.model.mats.resize(1);
    PetscCall(MaterialFromOptions(sim.comm, "block", sim.model.mats[0]));

    ChainSpec cs;
    cs.name = "membrane";
    cs.material = "membrane";
    cs.thickness = t_;
    xend0_ = margin_ + L_ + off_;
    cs.line = {margin_ + off_, H_, xend0_, H_};
    cs.end_force[0] = P_;
    cs.end_force[1] = 0;
    sim.model.chain_specs.push_back(cs);
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    // one material; the bodies (below / above the sheet) are assigned from the chain's line
    FillRegular(
        sim, [](const double *) { return 0; }, out);
    PetscFunctionReturn(0);
  }

  // checkpoint.hpp: the histories so far and the last step's slips
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointWriteArray(v, "history_t", time_));
    PetscCall(CheckpointWriteArray(v, "history_friction", fric_));
    PetscCall(CheckpointWriteArray(v, "history_u_end", uend_));
    PetscCall(CheckpointWriteArray(v, "history_sliding",
                                   std::vector<double>(sliding_.begin(), sliding_.end())));
    PetscCall(CheckpointWriteArray(v, "slip_previous", slip_prev_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &, PetscViewer v) override {
    std::vector<double> sl;
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "history_t", time_));
    PetscCall(CheckpointReadArray(v, "history_friction", fric_));
    PetscCall(CheckpointReadArray(v, "history_u_end", uend_));
    PetscCall(CheckpointReadArray(v, "history_sliding", sl));
    PetscCall(CheckpointReadArray(v, "slip_previous", slip_prev_));
    sliding_.assign(sl.size(), 0);
    for (size_t i = 0; i < sl.size(); ++i) sliding_[i] = sl[i] != 0;
    PetscFunctionReturn(0);
  }

  bool extrudes() const override { return true; }
  bool extrudes_chains() const override { return true; } // -dim 3: a strip across the depth

  // The sheet's state for the history and the answers, from the chain (2D) or from the strip of
  // 3D sheet (-dim 3; per unit width, over the depth): per point its initial x and its x slip on
  // each face; the friction on it against the pull; the pulled end's u_x (the mean of its
  // column); sum T l0 (the tension triangle's area); the last segment's tension; per point the
  // pressures and the length (area over the width) each stands for; the pulled end's x.
  struct SheetState {
    std::vector<double> X, slip_top, slip_bot, p_top, p_bot, length;
    double friction = 0, u_end = 0, area = 0, T_end = 0, x_end = 0, J = 0, mu_t = 0, mu_b = 0;
  };
  SheetState State(const Simulation &sim) const {
    SheetState q;
    if (!sim.chains.empty()) {
      const Chain &c = sim.chains[0];
      const int e = c.n - 1;
      for (int i = 0; i < c.n; ++i) q.X.push_back(c.x0[i * DIM]);
      q.slip_top = c.slip_top;
      q.slip_bot = c.slip_bot;
      q.p_top = c.p_top;
      q.p_bot = c.p_bot;
      q.length = c.length;
      q.friction = -c.friction_force;
      q.u_end = c.x[e * DIM] - c.x0[e * DIM];
      q.x_end = c.x[e * DIM];
      for (int k = 0; k + 1 < c.n; ++k) q.area += c.T[k] * c.l0[k];
      q.T_end = c.T[c.n - 2];
      q.J = c.law.J, q.mu_t = c.top.mu, q.mu_b = c.bottom.mu;
      return q;
    }
    const Sheet &s = sim.sheets[0];
    const double W = sim.set.depth, ex[3] = {1, 0, 0}, ez[3] = {0, 0, 1};
    for (int i = 0; i < s.n; ++i) {
      q.X.push_back(s.x0[3 * i]);
      q.slip_top.push_back(s.slip_top[3 * i]);
      q.slip_bot.push_back(s.slip_bot[3 * i]);
      q.p_top.push_back(s.p_top[i]);
      q.p_bot.push_back(s.p_bot[i]);
      q.length.push_back(s.area[i] / W);
    }
    if (!sim.contact_stats.friction3.empty()) q.friction = -sim.contact_stats.friction3[0] / W;
    const double xe0 = s.x0[3 * (s.n - 1)];
    double n_end = 0, a_end = 0;
    for (int i = 0; i < s.n; ++i)
      if (s.x0[3 * i] == xe0) {
        q.u_end += s.x[3 * i] - s.x0[3 * i];
        q.x_end += s.x[3 * i];
        n_end += 1;
      }
    q.u_end /= n_end;
    q.x_end /= n_end;
    for (int t = 0; t < s.nt; ++t) {
      const double Nx = s.J * (sheet_strain_along(s, t, ex) + s.nu * sheet_strain_along(s, t, ez));
      q.area += Nx * s.a0[t] / W;
      double cx = 0;
      for (int a = 0; a < 3; ++a) cx = std::fmax(cx, s.x0[3 * s.tri[3 * t + a]]);
      if (cx == xe0) q.T_end += Nx * s.a0[t], a_end += s.a0[t];
    }
    q.T_end /= a_end;
    q.J = s.J, q.mu_t = s.top.mu, q.mu_b = s.bottom.mu;
    return q;
  }

  PetscErrorCode monitor(Simulation &sim) override {
    if (sim.run.step == 0 || (sim.chains.empty() && sim.sheets.empty())) return 0;
    const SheetState q = State(sim);
    const size_t n = q.X.size();
    time_.push_back(sim.run.time);
    fric_.push_back(q.friction);
    uend_.push_back(q.u_end);
    bool all = !slip_prev_.empty();
    const double xs = q.X[0], h = sim.set.h;
    for (size_t i = 0; all && i < n; ++i) {
      if (q.X[i] < xs + h || q.X[i] > xend0_ - h) continue;
      all = q.slip_top[i] > slip_prev_[i] && q.slip_bot[i] > slip_prev_[n + i];
    }
    sliding_.push_back(all);
    slip_prev_.assign(q.slip_top.begin(), q.slip_top.end());
    slip_prev_.insert(slip_prev_.end(), q.slip_bot.begin(), q.slip_bot.end());
    return 0;
  }

  // pullout_history.csv: step, time, friction force on the sheet, pulled end's u_x
  PetscErrorCode write_files(Simulation &sim) override {
    PetscFunctionBeginUser;
    if (sim.rank == 0) {
      const std::string path = sim.set.output_dir + "/pullout_history.csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      std::fprintf(f, "step,time,friction_force,end_displacement,sliding\n");
      for (size_t k = 0; k < fric_.size(); ++k)
        std::fprintf(f, "%zu,%.9g,%.9g,%.9g,%d\n", k + 1, time_[k], fric_[k], uend_[k],
                     sliding_[k] ? 1 : 0);
      std::fclose(f);
      PetscCheck(std::rename((path + ".tmp").c_str(), path.c_str()) == 0, PETSC_COMM_SELF,
                 PETSC_ERR_FILE_WRITE, "cannot rename %s.tmp", path.c_str());
    }
    PetscCallMPI(MPI_Barrier(sim.comm));
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const SheetState q = State(sim);
    const double mu_t = q.mu_t, mu_b = q.mu_b, J = q.J;
    const double m = (mu_t + mu_b) * p_, capacity = m * L_;
    const bool out = P_ > capacity;
    const double xa_exact = m > 0 ? std::fmin(P_ / m, L_) : L_;
    const double u0_exact = out || m <= 0 ? NAN : P_ * P_ / (2 * m * J);
    // the tension triangle: its area sum T l0 = P x_a / 2
    const double xa = P_ > 0 ? 2 * q.area / P_ : 0.0;
    const double u_end = q.u_end;
    // contact pressure on each face, length-weighted over the points two cells or more from
    // the ends (at the ends a node's whole normal force is divided by a part of a sheet length)
    double pt = 0, pb = 0, len = 0;
    const double h = sim.set.h, xs = q.X[0];
    for (size_t i = 0; i < q.X.size(); ++i) {
      const double X = q.X[i];
      if (X < xs + 2 * h || X > xend0_ - 2 * h) continue;
      pt += q.p_top[i] * q.length[i], pb += q.p_bot[i] * q.length[i], len += q.length[i];
    }
    // friction: the last step; the mean over the last quarter of the steps after the ramp; the
    // mean over the steps after the ramp in which the whole sheet slid (after a kinetic-damping
    // reset the sheet is at rest and parts of it stick for a few steps: no measure of capacity)
    const size_t nf = fric_.size(), r0 = static_cast<size_t>(std::max<PetscInt>(ramp_, 0));
    double fmean = NAN, fslide = NAN, nslide = 0;
    if (nf > r0) {
      const size_t a = nf - std::max<size_t>(1, (nf - r0) / 4);
      double s = 0, ss = 0;
      for (size_t k = a; k < nf; ++k) s += fric_[k];
      fmean = s / double(nf - a);
      for (size_t k = r0; k < nf; ++k)
        if (sliding_[k]) ss += fric_[k], nslide += 1;
      if (nslide > 0) fslide = ss / nslide;
    }
    const double W = sim.model.ncell[0] * sim.set.h;
    const char *sep = ",\n    ";
    json = json_kv("force", P_) + sep + json_kv("pressure", p_) + sep + json_kv("mu_top", mu_t) +
           sep + json_kv("mu_bottom", mu_b) + sep + json_kv("axial_stiffness", J) + sep +
           json_kv("length", L_) + sep + json_kv("pulled_end_x0", xend0_) + sep +
           json_kv("shear_per_length", m) + sep + json_kv("capacity", capacity) + sep +
           "\"pulled_out\": " + (out ? "true" : "false") + sep +
           json_kv("end_displacement", u_end) + sep + json_kv("end_displacement_exact", u0_exact) +
           sep + json_kv("anchored_length", xa) + sep + json_kv("anchored_length_exact", xa_exact) +
           sep + json_kv("end_segment_tension", q.T_end) + sep +
           json_kv("friction_force", nf ? fric_.back() : 0.0) + sep +
           json_kv("friction_force_mean", fmean) + sep + json_kv("friction_force_sliding", fslide) +
           sep + json_kv("sliding_steps", nslide) + sep +
           json_kv("steps_after_ramp", nf > r0 ? double(nf - r0) : 0.0) + sep +
           json_kv("contact_pressure_top", len > 0 ? pt / len : NAN) + sep +
           json_kv("contact_pressure_bottom", len > 0 ? pb / len : NAN) + sep +
           json_kv("end_clearance_cells", (W - q.x_end) / h) + sep +
           json_kv("slip_nodes", sim.contact_stats.slip_nodes);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_pullout_scene() {
  return std::make_unique<PulloutScene>();
}

} // namespace pmpm
