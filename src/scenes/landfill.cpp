// The landfill cover of the seed paper, Section 4 (Figure 6, Table I; docs/method.md,
// sections 1.1-1.4): waste 30 mm, geomembrane 1 mm, cover soil 8 mm, 30 mm wide, a soft 6
// mm-diameter zone just below the membrane at X = 15 mm; base fixed, sides on rollers, plane
// strain; unit weights of Table I applied as body forces. The membrane can be the regular particle
// fill, N layers of particles across its thickness (N = 1 is the paper's single layer), or a
// membrane chain
// (-landfill_membrane_chain, chain.hpp): a line of points at the top of the membrane layer
// (y = 31 mm) whose 1 mm of thickness is a property. The layer it leaves is given to the waste
// (the closest material: E 131.7 against 207 MPa, a weight of 2e3 against 9.6e3 N/m^2 under
// 1.2e7 N/m^2 of cover soil), so the soft zone lies 1 mm below the sheet and the heights and
// loads are the paper's; its ends lie next to the roller walls, which hold them horizontally as
// they hold the resolved membrane's ends.
//
// Results: the membrane's mid-surface profile (per column of membrane particles: position,
// displacement, chain strain = current/initial length of the mid-surface chain, the particles'
// own axial strain from F, axial stress), settlements, and Giroud's analytical solution in the
// paper's form (simulated sag plugged in) and in the self-consistent form (J = E t).
#include "pmpm/util/options.hpp"
#include "pmpm/scenes/giroud.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace pmpm {

namespace {
enum Mat { SOIL = 0, MEMBRANE = 1, WASTE = 2, SOFT = 3 };
const char *const kMatNames[] = {"soil", "membrane", "waste", "soft"};

struct ProfilePoint {
  double x0, y0, x, y, strain_particle, stress_axial, s0 = 0, strain_chain = 0;
};
} // namespace

class LandfillScene final : public Scene {
  // geometry (m)
  double W_ = 0.030, Hw_ = 0.030, t_ = 0.001, Hs_ = 0.008, D_ = 0.006, Xc_ = 0.015;
  PetscInt layers_ = 0;
  PetscBool chain_ = PETSC_FALSE;
  std::vector<ProfilePoint> prof_;        // rank 0: membrane mid-surface profile
  double slip_top_ = 0, slip_bottom_ = 0; // rank 0: max relative x displacement at the faces

  // The chain is the profile (every rank holds it).
  void ChainProfile(const Simulation &sim) {
    const Chain &c = sim.chains[0];
    prof_.clear();
    double s0 = 0;
    for (int i = 0; i < c.n; ++i) {
      ProfilePoint q{};
      q.x0 = c.x0[i * DIM];
      q.y0 = c.x0[i * DIM + 1];
      q.x = c.x[i * DIM];
      q.y = c.x[i * DIM + 1];
      const int a = std::max(i - 1, 0), b = std::min(i, c.n - 2);
      q.strain_chain = q.strain_particle = 0.5 * (c.eps[a] + c.eps[b]);
      q.stress_axial = 0.5 * (c.T[a] + c.T[b]) / c.thickness;
      if (i > 0) s0 += c.l0[i - 1];
      q.s0 = s0;
      prof_.push_back(q);
      slip_top_ = std::fmax(slip_top_, std::fabs(c.slip_top[i]));
      slip_bottom_ = std::fmax(slip_bottom_, std::fabs(c.slip_bot[i]));
    }
  }

  // One row per membrane particle (x0 y0 x y strain_particle stress_axial volume0 kind=0) and
  // per particle of the rows just above (kind 1) and below (kind 2) it, for the interface slip.
  static constexpr int NF = 8;
  PetscErrorCode MembraneRows(Simulation &sim, std::vector<double> &mine) const {
    ParticleView P;
    PetscFunctionBeginUser;
    const double dx = sim.set.h / sim.set.ppc, ytop = Hw_ + t_, ybot = Hw_;
    const int D = sim.parts.dim, NS = D == 3 ? NStress<3> : NSTRESS; // -dim 3: extruded
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p) {
      const double y0 = P.x0[p * D + 1];
      if (P.mat[p] != MEMBRANE) {
        const double kind = (y0 > ytop && y0 < ytop + dx)   ? 1
                            : (y0 < ybot && y0 > ybot - dx) ? 2
                                                            : 0;
        if (kind > 0) {
          const double row[NF] = {P.x0[p * D], y0, P.x[p * D], P.x[p * D + 1],
                                  0,           0,  P.vol0[p],  kind};
          mine.insert(mine.end(), row, row + NF);
        }
        continue;
      }
      const double *F = P.F + p * D * D, *s = P.stress + p * NS;
      // axial direction: the initial x axis, carried by F
      const double ax = F[0], ay = F[D], lam = std::hypot(ax, ay);
      const double tx = ax / lam, ty = ay / lam;
      const double sig = tx * tx * s[0] + ty * ty * s[1] + 2 * tx * ty * s[3];
      const double row[NF] = {P.x0[p * D], P.x0[p * D + 1], P.x[p * D], P.x[p * D + 1], lam - 1.0,
                              sig,         P.vol0[p],       0.0};
      mine.insert(mine.end(), row, row + NF);
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscFunctionReturn(0);
  }

  using Columns = std::map<long, std::vector<const double *>>; // rows by column (x0)

  // Slip: tangential (x) displacement of the membrane's outer particle rows relative to the
  // neighbouring rows of soil (top) and waste (bottom), per column; the largest of each.
  void ProfileSlip(const Columns &cols, Columns &above, Columns &below) {
    auto ux_mean = [](const std::vector<const double *> &v) {
      double s = 0;
      for (const double *r : v) s += r[2] - r[0];
      return v.empty() ? 0.0 : s / v.size();
    };
    slip_top_ = slip_bottom_ = 0;
    for (auto &c : cols) {
      double ymin = 1e300, ymax = -1e300;
      for (const double *r : c.second) ymin = std::fmin(ymin, r[1]), ymax = std::fmax(ymax, r[1]);
      std::vector<const double *> top, bot;
      for (const double *r : c.second) {
        if (r[1] > ymax - 1e-9) top.push_back(r);
        if (r[1] < ymin + 1e-9) bot.push_back(r);
      }
      if (above.count(c.first))
        slip_top_ = std::fmax(slip_top_, std::fabs(ux_mean(top) - ux_mean(above[c.first])));
      if (below.count(c.first))
        slip_bottom_ = std::fmax(slip_bottom_, std::fabs(ux_mean(bot) - ux_mean(below[c.first])));
    }
  }

  // The mid-surface points: each column's volume-weighted average (the layers are symmetric about
  // the mid-plane), then the chain strain, each segment's current over initial length averaged
  // onto its two ends.
  void ProfileColumns(const Columns &cols) {
    for (auto &c : cols) {
      ProfilePoint q{};
      double wsum = 0;
      for (const double *r : c.second) {
        const double w = r[6];
        q.x0 += w * r[0];
        q.y0 += w * r[1];
        q.x += w * r[2];
        q.y += w * r[3];
        q.strain_particle += w * r[4];
        q.stress_axial += w * r[5];
        wsum += w;
      }
      q.x0 /= wsum, q.y0 /= wsum, q.x /= wsum, q.y /= wsum;
      q.strain_particle /= wsum, q.stress_axial /= wsum;
      prof_.push_back(q);
    }
    const size_t m = prof_.size();
    std::vector<double> seg(m > 0 ? m - 1 : 0);
    for (size_t k = 0; k + 1 < m; ++k) {
      const double L0 = std::hypot(prof_[k + 1].x0 - prof_[k].x0, prof_[k + 1].y0 - prof_[k].y0);
      const double L = std::hypot(prof_[k + 1].x - prof_[k].x, prof_[k + 1].y - prof_[k].y);
      seg[k] = L / L0 - 1.0;
      prof_[k + 1].s0 = prof_[k].s0 + L0;
    }
    for (size_t k = 0; k < m; ++k) {
      if (k == 0)
        prof_[k].strain_chain = seg.empty() ? 0 : seg[0];
      else if (k + 1 == m)
        prof_[k].strain_chain = seg[k - 1];
      else
        prof_[k].strain_chain = 0.5 * (seg[k - 1] + seg[k]);
    }
  }

  // Gather the membrane particles to rank 0 and reduce them to a mid-surface profile.
  PetscErrorCode BuildProfile(Simulation &sim) {
    PetscFunctionBeginUser;
    if (chain_) {
      ChainProfile(sim);
      PetscFunctionReturn(0);
    }
    std::vector<double> mine, all;
    PetscCall(MembraneRows(sim, mine));
    PetscCall(GatherToRoot(sim.comm, mine, all));
    const int total = static_cast<int>(all.size());
    prof_.clear();
    if (sim.rank != 0) PetscFunctionReturn(0);
    // columns of membrane particles (and of the rows beside them) share x0
    const double dx = sim.set.h / sim.set.ppc;
    Columns cols, above, below;
    for (int k = 0; k < total; k += NF) {
      const long key = std::lround(all[k] / (0.5 * dx));
      (all[k + 7] == 0 ? cols : all[k + 7] == 1 ? above : below)[key].push_back(&all[k]);
    }
    ProfileSlip(cols, above, below);
    ProfileColumns(cols);
    PetscFunctionReturn(0);
  }

  // Vertical displacement of the mid-surface at initial X (linear interpolation), rank 0.
  double uy_at(double X) const {
    if (X <= prof_.front().x0) return prof_.front().y - prof_.front().y0;
    for (size_t k = 0; k + 1 < prof_.size(); ++k)
      if (X <= prof_[k + 1].x0) {
        const double a = (X - prof_[k].x0) / (prof_[k + 1].x0 - prof_[k].x0);
        return (1 - a) * (prof_[k].y - prof_[k].y0) + a * (prof_[k + 1].y - prof_[k + 1].y0);
      }
    return prof_.back().y - prof_.back().y0;
  }

public:
  // -dim 3: the cover extruded between rollers (plane strain; its interface in 3D), the membrane's
  // profile gathered over every z copy of a column
  bool extrudes() const override { return true; }

  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "landfill_", "Landfill cover (paper Section 4)", nullptr);
    PetscCall(PmpmOptionsReal("-width", "Domain width (m)", nullptr, W_, &W_, nullptr));
    PetscCall(PmpmOptionsReal("-waste_height", "Waste thickness (m)", nullptr, Hw_, &Hw_, nullptr));
    PetscCall(PmpmOptionsReal("-membrane_thickness", "Geomembrane thickness t (m)", nullptr, t_,
                              &t_, nullptr));
    PetscCall(
        PmpmOptionsReal("-soil_height", "Cover soil thickness H (m)", nullptr, Hs_, &Hs_, nullptr));
    PetscCall(PmpmOptionsReal("-soft_diameter",
                              "Soft zone diameter b (m), touching the "
                              "membrane's underside",
                              nullptr, D_, &D_, nullptr));
    PetscCall(PmpmOptionsReal("-soft_x", "Soft zone centre X (m)", nullptr, Xc_, &Xc_, nullptr));
    PetscCall(PmpmOptionsInt("-membrane_layers",
                             "Particle layers across the membrane: 0 = the "
                             "regular fill (ppc per cell), N >= 1 = N layers (1: the paper's)",
                             nullptr, layers_, &layers_, nullptr));
    PetscCall(PetscOptionsBool("-membrane_chain",
                               "The membrane as a chain of points on top of the membrane layer "
                               "(its thickness a property; -mat_membrane_law, -interface_type)",
                               nullptr, chain_, &chain_, nullptr));
    PetscOptionsEnd();
    PetscInt nW, nWaste, nT, nS;
    PetscCall(CheckCells(sim.comm, "-landfill_width", W_, sim.set.h, &nW));
    PetscCall(CheckCells(sim.comm, "-landfill_waste_height", Hw_, sim.set.h, &nWaste));
    PetscCall(CheckCells(sim.comm, "-landfill_soil_height", Hs_, sim.set.h, &nS));
    PmpmCheckInput(!(chain_ && layers_ > 0), sim.comm, PETSC_ERR_ARG_INCOMP,
                   "-landfill_membrane_chain and -landfill_membrane_layers %" PetscInt_FMT
                   " exclude each other",
                   layers_);
    if (layers_ == 0 && !chain_)
      PetscCall(CheckCells(sim.comm,
                           "-landfill_membrane_thickness (with -landfill_membrane_layers 0)", t_,
                           sim.set.h, &nT));
    PmpmCheckInput(layers_ >= 0 && layers_ <= 16, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-landfill_membrane_layers must be in 0..16 (got %" PetscInt_FMT ")", layers_);
    PmpmCheckInput(t_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-landfill_membrane_thickness must be > 0");
    // A layer's block is at most one cell thick (PMPM support): t / N > h would leave gaps.
    PmpmCheckInput(layers_ == 0 || t_ / layers_ <= sim.set.h * (1 + 1e-9), sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE,
                   "-landfill_membrane_layers %" PetscInt_FMT " gives layers %g m thick, more than "
                   "-cell_size %g m: their blocks would not cover the membrane; use at least %d "
                   "layers (or 0 for the regular fill)",
                   layers_, t_ / layers_, sim.set.h, (int)std::ceil(t_ / sim.set.h - 1e-9));
    PmpmCheckInput(
        D_ > 0 && D_ < Hw_ && Xc_ - D_ / 2 > 0 && Xc_ + D_ / 2 < W_, sim.comm,
        PETSC_ERR_ARG_OUTOFRANGE,
        "-landfill_soft_diameter %g / -landfill_soft_x %g: the soft zone must lie inside the "
        "waste",
        D_, Xc_);
    const double top = Hw_ + t_ + Hs_;
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nW;
    sim.model.ncell[1] = static_cast<PetscInt>(std::ceil(top / sim.set.h - 1e-9)) + 2;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.mats.resize(4);
    for (int m = 0; m < 4; ++m)
      PetscCall(MaterialFromOptions(sim.comm, kMatNames[m], sim.model.mats[m]));
    if (chain_) {
      ChainSpec cs;
      cs.name = "membrane";
      cs.material = "membrane";
      cs.thickness = t_;
      // ends half a point spacing inside the walls, as particle centres are (a point on the
      // wall itself would move with the interior node beside it, and could leave the box)
      const double e = 0.5 * sim.model.chain_spacing * sim.set.h;
      cs.line = {e, Hw_ + t_, W_ - e, Hw_ + t_};
      sim.model.chain_specs.push_back(cs);
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double Hw = Hw_, t = t_, top = Hw_ + t_ + Hs_, r = D_ / 2, xc = Xc_, yc = Hw_ - D_ / 2;
    const bool layered = layers_ > 0, chain = chain_;
    auto at = [=](const double x[DIM]) -> int {
      if (x[1] >= top) return -1;
      if (x[1] >= Hw + t) return SOIL;
      if (x[1] >= Hw) return chain ? WASTE : layered ? -1 : MEMBRANE;
      if ((x[0] - xc) * (x[0] - xc) + (x[1] - yc) * (x[1] - yc) < r * r) return SOFT;
      return WASTE;
    };
    FillRegular(sim, at, out);
    for (auto &q : out) q.colour = q.mat == MEMBRANE ? 1.0 : 0.0;
    if (layered) {
      // N rows across the thickness, h/ppc apart along it; a row's block half-height is capped
      // at h/2 (the PMPM support spans at most two cells per direction).
      const double dx = sim.set.h / sim.set.ppc, dy = t_ / layers_;
      const PetscInt ncol = static_cast<PetscInt>(std::llround(W_ / dx));
      const PetscInt base = sim.model.ncell[0] * sim.model.ncell[1] * sim.set.ppc * sim.set.ppc;
      for (PetscInt k = 0; k < layers_; ++k)
        for (PetscInt i = 0; i < ncol; ++i) {
          ParticleInit q{};
          q.x[0] = (i + 0.5) * dx;
          q.x[1] = Hw_ + (k + 0.5) * dy;
          const PetscInt c[DIM] = {static_cast<PetscInt>(std::floor(q.x[0] / sim.set.h)),
                                   static_cast<PetscInt>(std::floor(q.x[1] / sim.set.h))};
          if (!sim.grid.owns_cell(c)) continue;
          q.lp[0] = 0.5 * dx;
          q.lp[1] = std::fmin(0.5 * dy, 0.5 * sim.set.h);
          q.vol = dx * dy;
          q.mat = MEMBRANE;
          q.density = sim.model.mats[MEMBRANE].density;
          q.gamma = sim.model.mats[MEMBRANE].gamma;
          q.colour = 1.0;
          q.pid = base + k * ncol + i;
          out.push_back(q);
        }
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    PetscCall(BuildProfile(sim));
    if (sim.rank != 0) PetscFunctionReturn(0);
    PetscCheck(prof_.size() >= 3, PETSC_COMM_SELF, PETSC_ERR_PLIB, "membrane has < 3 columns");
    const double centre = -uy_at(Xc_);
    const double wall = -0.5 * (uy_at(prof_.front().x0) + uy_at(prof_.back().x0));
    const double sag = centre + 0.5 * (uy_at(Xc_ - D_ / 2) + uy_at(Xc_ + D_ / 2));
    size_t kmax = 0, kmin = 0, smax = 0, smin = 0;
    for (size_t k = 0; k < prof_.size(); ++k) {
      if (prof_[k].strain_chain > prof_[kmax].strain_chain) kmax = k;
      if (prof_[k].strain_chain < prof_[kmin].strain_chain) kmin = k;
      if (prof_[k].stress_axial > prof_[smax].stress_axial) smax = k;
      if (prof_[k].stress_axial < prof_[smin].stress_axial) smin = k;
    }
    double pk_particle = -1e300;
    for (const auto &q : prof_) pk_particle = std::fmax(pk_particle, q.strain_particle);
    const double gamma = sim.model.mats[SOIL].gamma;
    const double E = chain_ ? sim.chains[0].E : sim.model.mats[MEMBRANE].el.E;
    std::string paper = "null", selfc = "null";
    try {
      const auto gp = giroud::paper_form(gamma, D_, Hs_, 0.0, t_, sag);
      paper = "{" + json_kv("sag", gp.sag) + ", " + json_kv("strain", gp.strain) + ", " +
              json_kv("stress", gp.stress) + ", " + json_kv("pressure", gp.pressure) + "}";
    } catch (const std::exception &) { // a non-positive sag has no membrane solution
    }
    try {
      const auto gs = giroud::self_consistent(gamma, D_, Hs_, 0.0, t_, E);
      selfc = "{" + json_kv("sag", gs.sag) + ", " + json_kv("strain", gs.strain) + ", " +
              json_kv("stress", gs.stress) + ", " + json_kv("pressure", gs.pressure) + "}";
    } catch (const std::exception &) {
    }
    const char *sep = ",\n    ";
    json = json_kv("settlement_centre", centre) + sep + json_kv("settlement_wall", wall) + sep +
           json_kv("differential_settlement", centre - wall) + sep + json_kv("sag", sag) + sep +
           json_kv("peak_axial_strain", prof_[kmax].strain_chain) + sep +
           json_kv("peak_axial_strain_x", prof_[kmax].x0) + sep +
           json_kv("peak_axial_strain_particle", pk_particle) + sep +
           json_kv("min_axial_strain", prof_[kmin].strain_chain) + sep +
           json_kv("peak_axial_stress", prof_[smax].stress_axial) + sep +
           json_kv("peak_axial_stress_x", prof_[smax].x0) + sep +
           json_kv("min_axial_stress", prof_[smin].stress_axial) + sep +
           json_kv("membrane_layers", double(layers_)) + sep +
           "\"membrane_chain\": " + (chain_ ? "true" : "false") + sep +
           json_kv("max_slip_top", slip_top_) + sep + json_kv("max_slip_bottom", slip_bottom_) +
           sep + "\"interface\": \"" +
           (chain_ ? FaceTypeNames[(int)sim.chains[0].top.type]
                   : InterfaceTypeNames[(int)sim.model.iface.type]) +
           "\"" + sep + "\"giroud\": {\"paper\": " + paper + ", \"self_consistent\": " + selfc +
           "}";
    PetscFunctionReturn(0);
  }

  PetscErrorCode write_files(Simulation &sim) override {
    PetscFunctionBeginUser;
    if (sim.rank == 0) {
      const std::string path = sim.set.output_dir + "/membrane_profile.csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      std::fprintf(f, "s0,x0,y0,x,y,ux,uy,strain_chain,strain_particle,stress_axial\n");
      for (const auto &q : prof_)
        std::fprintf(f, "%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n", q.s0, q.x0,
                     q.y0, q.x, q.y, q.x - q.x0, q.y - q.y0, q.strain_chain, q.strain_particle,
                     q.stress_axial);
      std::fclose(f);
    }
    PetscCall(OutputCommit(sim, "membrane_profile.csv"));
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_landfill_scene() {
  return std::make_unique<LandfillScene>();
}

} // namespace pmpm
