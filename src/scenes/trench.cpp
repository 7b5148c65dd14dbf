// A geomembrane over an open trench under a cohesionless cover: Giroud's regime (FIELD.md 3.2,
// 3.4, 3.5; REFERENCE.md 1.3).
//
// Geometry (x to the right, y up, origin at the bottom-left corner):
//   base   0 <= y < Hb, full width W, elastic ("base": waste or stiff soil), base fixed, sides on
//          rollers; an open trench (no particles) of width B and depth D centred at x = W / 2
//   sheet  a membrane chain ("membrane") laid flat on the base surface y = Hb from x = margin to
//          W - margin: it spans the trench and lies on the base over an anchorage of length La on
//          each side; its ends are free (held by friction only)
//   cover  Hb <= y < Hb + H, full width ("cover": Drucker-Prager, c = 0, or elastic)
// Every length is a whole number of cells. Gravity on every body; the cover over the trench is
// carried by the sheet and by arching onto the trench's sides.
//
// Results beside the closed forms:
//   - the sheet's sag at mid-trench (absolute, and relative to the chord between the current
//     sheet points at the trench edges), its strain (peak in the span and where, mean over the
//     material now over the void, at the edges), the pressure the cover puts on it over the
//     trench (p_top of the chain averaged over the span; and from the sheet's equilibrium: the
//     vertical components of the tension where the sheet crosses the edges, over B);
//   - the anchorage on each side: the edge tension T_e, the pull-in u (horizontal displacement of
//     the sheet material toward the trench at the edge, and the material length drawn over the
//     void), the stretched length (T falls to 5 % of T_e; and the length of the triangle with
//     the same area, 2 int T+ dx / T_e), the mobilised shear m = T_e / that length, beside
//     FIELD.md 3.2: x_a = T_e / m, m = (mu_t + mu_b) gamma H, u0 = T_e^2 / (2 m J);
//   - Terzaghi arching (FIELD.md 3.4) with K = 1, K = Ka and K tan phi = 0.25 (Giroud's);
//   - Giroud's self-consistent sag and strain (giroud.hpp, J the chain's axial stiffness) with
//     (a) the full overburden gamma H, (b) the simulated pressure, (c) Giroud's arching pressure;
//     and Giroud's circular arc with the anchorage added: the material over the void is B plus
//     the pull-in on both sides, arc length = (B + u_L + u_R)(1 + T / J), T = p B Omega(y):
//     (d) with the simulated pull-in and pressure, (e) with the closed-form pull-in
//     u = T^2 / (2 m J) on each side (rigid soil, full friction; FIELD.md 3.2).
#include "pmpm/giroud.hpp"
#include "pmpm/output.hpp"
#include "pmpm/scene_util.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace pmpm {

namespace {
enum Mat { BASE = 0, COVER = 1 };

// Root of f on (lo, hi) by bisection, f(lo) < 0 < f(hi).
double Bisect(const std::function<double(double)> &f, double lo, double hi) {
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double m = 0.5 * (lo + hi);
    (f(m) < 0 ? lo : hi) = m;
  }
  return 0.5 * (lo + hi);
}

// Giroud's circular arc over a void of width b under pressure p with the anchorage added: the
// material over the void is b + pull(T) long before it stretches by T / J, so
//   arc(y) / b = (1 + pull(T) / b) (1 + T / J),  T = p b Omega(y).
// theta = 2 atan(2 y / b) in (0, pi) parametrises y monotonically; the residual
// arc/b - (1 + pull/b)(1 + T/J) runs from -inf (theta -> 0: Omega -> inf) to > 0 at the
// semicircle for the loads of interest. Returns y (and T, eps = T / J) or y = -1 if no root.
struct ArcAnchored {
  double sag = -1, tension = 0, strain = 0, pull = 0;
};
ArcAnchored GiroudAnchored(double p, double b, double J, const std::function<double(double)> &pull) {
  auto res = [&](double th) {
    const double y = 0.5 * b * std::tan(0.5 * th);
    const double T = p * b * giroud::omega(y, b);
    return (1.0 + giroud::strain(y, b)) - (1.0 + pull(T) / b) * (1.0 + T / J);
  };
  ArcAnchored a;
  const double lo = 1e-6, hi = giroud::pi * (1 - 1e-9);
  if (!(res(lo) < 0 && res(hi) > 0)) return a;
  const double th = Bisect(res, lo, hi);
  a.sag = 0.5 * b * std::tan(0.5 * th);
  a.tension = p * b * giroud::omega(a.sag, b);
  a.strain = a.tension / J;
  a.pull = pull(a.tension);
  return a;
}

std::string Obj(const std::vector<std::pair<std::string, double>> &kv) {
  std::string s = "{";
  for (size_t k = 0; k < kv.size(); ++k) s += (k ? ", " : "") + json_kv(kv[k].first, kv[k].second);
  return s + "}";
}
} // namespace

class TrenchScene final : public Scene {
  // geometry (m): trench width and depth, cover thickness, base height, anchorage, margin
  double B_ = 2.0, D_ = 0.6, H_ = 1.0, Hb_ = 1.0, La_ = 2.0, margin_ = 0.5, t_ = 0.0015;
  double W_ = 0, xe_[2] = {0, 0}, xc_ = 0;
  double offset_ = 0.5; // -trench_surface_offset: the grid's bottom lies this many cells below y = 0
  double phi_ = 30; // the cover's friction angle (deg) for Terzaghi's bracket
  double pull_ = 0; // DEBUG -trench_debug_pull: no trench, end force on the right end
  PetscInt every_ = 100;     // -trench_history_every: steps between history rows (0: none)
  std::vector<double> hist_; // step, time, ratio, sag, edge tension, end pull-in, span pressure
  static constexpr int kHist = 7;

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "trench_", "Trench: a membrane over an open trench under a cover",
                      nullptr);
    PetscCall(PetscOptionsReal("-width", "Trench width B (m)", nullptr, B_, &B_, nullptr));
    PetscCall(PetscOptionsReal("-depth", "Trench depth D (m), < base height", nullptr, D_, &D_,
                               nullptr));
    PetscCall(PetscOptionsReal("-cover", "Cover thickness H (m)", nullptr, H_, &H_, nullptr));
    PetscCall(PetscOptionsReal("-base_height", "Base layer height Hb (m), > trench depth", nullptr,
                               Hb_, &Hb_, nullptr));
    PetscCall(PetscOptionsReal("-anchorage", "Sheet length on the base beyond each edge (m)",
                               nullptr, La_, &La_, nullptr));
    PetscCall(PetscOptionsReal("-margin", "Base and cover beyond each end of the sheet (m)",
                               nullptr, margin_, &margin_, nullptr));
    PetscCall(PetscOptionsReal("-surface_offset",
                               "Grid lines this fraction of a cell below the bodies' faces: 0.5 "
                               "(the base surface and the sheet at mid-cell) or 0 (on a grid line)",
                               nullptr, offset_, &offset_, nullptr));
    PetscCall(PetscOptionsReal("-debug_pull", "DEBUG", nullptr, pull_, &pull_, nullptr));
    PetscCall(PetscOptionsInt("-history_every",
                              "Steps between rows of trench_history.csv (sag, edge tension, "
                              "pull-in of the ends, span pressure); 0: none",
                              nullptr, every_, &every_, nullptr));
    PetscOptionsEnd();
    PetscOptionsBegin(sim.comm, "membrane_", "The membrane", nullptr);
    PetscCall(
        PetscOptionsReal("-thickness", "Membrane thickness t (m), > 0", nullptr, t_, &t_, nullptr));
    PetscOptionsEnd();
    const double h = sim.set.h;
    PetscInt nB, nD, nH, nHb, nLa, nM;
    PetscCall(CheckCells(sim.comm, "-trench_width", B_, h, &nB));
    PetscCall(CheckCells(sim.comm, "-trench_depth", D_, h, &nD));
    PetscCall(CheckCells(sim.comm, "-trench_cover", H_, h, &nH));
    PetscCall(CheckCells(sim.comm, "-trench_base_height", Hb_, h, &nHb));
    PetscCall(CheckCells(sim.comm, "-trench_anchorage", La_, h, &nLa));
    PetscCall(CheckCells(sim.comm, "-trench_margin", margin_, h, &nM));
    PetscCheck(nD < nHb, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-trench_depth %g must be less than -trench_base_height %g (the trench has a floor)",
               D_, Hb_);
    PetscCheck((offset_ == 0 || offset_ == 0.5) && std::fmod(offset_ * sim.set.ppc, 1.0) == 0,
               sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-trench_surface_offset must be 0 or 0.5, and 0.5 needs an even -ppc (no particle "
               "on a face; got %g with -ppc %" PetscInt_FMT ")",
               offset_, sim.set.ppc);
    PetscCheck(t_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-membrane_thickness must be > 0 (got %g)", t_);
    W_ = B_ + 2 * La_ + 2 * margin_;
    xc_ = 0.5 * W_;
    xe_[0] = margin_ + La_;
    xe_[1] = margin_ + La_ + B_;
    // the base fills the grid from its bottom face, y = -offset h (a half cell more base)
    sim.origin[0] = 0;
    sim.origin[1] = -offset_ * h;
    sim.ncell[0] = nB + 2 * nLa + 2 * nM;
    sim.ncell[1] = nHb + nH + 2 + (offset_ > 0 ? 1 : 0);
    sim.face[XMIN] = sim.face[XMAX] = FaceBC::Roller;
    sim.face[YMIN] = FaceBC::Fixed;
    sim.face[YMAX] = FaceBC::Free;
    sim.mats.resize(2);
    PetscCall(MaterialFromOptions(sim.comm, "base", sim.mats[BASE]));
    PetscCall(MaterialFromOptions(sim.comm, "cover", sim.mats[COVER]));
    PetscCheck(sim.mats[COVER].gamma > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-mat_cover_gamma must be > 0 (the cover's weight is the load)");
    // Terzaghi's phi: the cover's own friction angle when it has one
    PetscBool has = PETSC_FALSE;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-mat_cover_friction_angle", &phi_, &has));
    PetscOptionsBegin(sim.comm, "trench_", "Trench: closed forms", nullptr);
    PetscCall(PetscOptionsReal("-terzaghi_phi",
                               "Friction angle (deg) for Terzaghi's bracket (default: "
                               "-mat_cover_friction_angle, else 30)",
                               nullptr, phi_, &phi_, nullptr));
    PetscOptionsEnd();
    PetscCheck(phi_ > 0 && phi_ < 90, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
               "-trench_terzaghi_phi must be in (0, 90) degrees (got %g)", phi_);
    ChainSpec cs;
    cs.name = "membrane";
    cs.material = "membrane";
    cs.thickness = t_;
    // vertices at the edges, so chain points fall on them whatever the spacing
    cs.line = {margin_, Hb_, xe_[0], Hb_, xe_[1], Hb_, W_ - margin_, Hb_};
    cs.end_force[0] = pull_;
    sim.chain_specs.push_back(cs);
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, std::vector<ParticleInit> &out) override {
    PetscFunctionBeginUser;
    const double Hb = Hb_, top = Hb_ + H_, floor = Hb_ - D_, x0 = xe_[0], x1 = xe_[1];
    const bool debug = pull_ > 0;
    FillRegular(
        sim,
        [=](const double x[DIM]) {
          if (x[1] >= top) return -1;
          if (x[1] >= Hb) return int(COVER);
          if (x[0] > x0 && x[0] < x1 && x[1] > floor && !debug) return -1; // the trench
          return int(BASE);
        },
        out);
    PetscFunctionReturn(0);
  }

  // The relaxation's history (every rank holds the chain): how the sag and the anchorage settle.
  PetscErrorCode monitor(Simulation &sim) override {
    if (every_ <= 0 || sim.run.step % every_ != 0 || sim.chains.empty()) return 0;
    const Chain &c = sim.chains[0];
    const int n = c.n;
    int im = 0, ie0 = 0, ie1 = 0;
    for (int i = 0; i < n; ++i) {
      const double x0 = c.x0[i * DIM];
      if (std::fabs(x0 - xc_) < std::fabs(c.x0[im * DIM] - xc_)) im = i;
      if (std::fabs(x0 - xe_[0]) < std::fabs(c.x0[ie0 * DIM] - xe_[0])) ie0 = i;
      if (std::fabs(x0 - xe_[1]) < std::fabs(c.x0[ie1 * DIM] - xe_[1])) ie1 = i;
    }
    double pw = 0, lw = 0;
    for (int i = 0; i < n; ++i)
      if (c.x[i * DIM] > xe_[0] && c.x[i * DIM] < xe_[1]) {
        pw += c.p_top[i] * c.length[i];
        lw += c.length[i];
      }
    const double row[kHist] = {double(sim.run.step),
                               sim.run.time,
                               sim.run.ratio,
                               c.x0[im * DIM + 1] - c.x[im * DIM + 1],
                               0.25 * (c.T[ie0 - 1] + c.T[ie0] + c.T[ie1 - 1] + c.T[ie1]),
                               0.5 * ((c.x[0] - c.x0[0]) - (c.x[(n - 1) * DIM] - c.x0[(n - 1) * DIM])),
                               lw > 0 ? pw / lw : 0.0};
    hist_.insert(hist_.end(), row, row + kHist);
    return 0;
  }

  PetscErrorCode write_files(Simulation &sim) override {
    PetscFunctionBeginUser;
    if (every_ <= 0) PetscFunctionReturn(0);
    if (sim.rank == 0) {
      const std::string path = sim.set.output_dir + "/trench_history.csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      std::fprintf(f, "step,time,ratio,sag,tension_edge,pull_in_ends,pressure_span\n");
      for (size_t k = 0; k + kHist <= hist_.size(); k += kHist)
        std::fprintf(f, "%.0f,%.9g,%.6g,%.9g,%.9g,%.9g,%.9g\n", hist_[k], hist_[k + 1],
                     hist_[k + 2], hist_[k + 3], hist_[k + 4], hist_[k + 5], hist_[k + 6]);
      std::fclose(f);
    }
    PetscCall(OutputCommit(sim, "trench_history.csv"));
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const Chain &c = sim.chains[0];
    const int n = c.n;
    auto X0 = [&](int i) { return c.x0[i * DIM]; };
    auto X = [&](int i) { return c.x[i * DIM]; };
    auto Y = [&](int i) { return c.x[i * DIM + 1]; };
    // a point field at initial abscissa s (linear interpolation between points)
    auto at0 = [&](double s, const std::function<double(int)> &f) {
      int k = 0;
      while (k + 2 < n && X0(k + 1) < s) ++k;
      const double r = (s - X0(k)) / (X0(k + 1) - X0(k));
      return (1 - r) * f(k) + r * f(k + 1);
    };
    // the point index at initial abscissa s (the edges are points)
    auto index0 = [&](double s) {
      int best = 0;
      for (int i = 0; i < n; ++i)
        if (std::fabs(X0(i) - s) < std::fabs(X0(best) - s)) best = i;
      return best;
    };
    // where the current sheet crosses x = s: segment k and fraction r
    auto cross = [&](double s, int &k, double &r) {
      k = 0;
      while (k + 2 < n && X(k + 1) < s) ++k;
      r = (s - X(k)) / (X(k + 1) - X(k));
    };
    const double h = sim.set.h, B = B_, J = c.law.J;
    const double gamma = sim.mats[COVER].gamma, sigma_n = gamma * H_;
    const double mu_sum = c.top.mu + c.bottom.mu, m_cf = mu_sum * sigma_n;
    auto uy = [&](int i) { return c.x[i * DIM + 1] - c.x0[i * DIM + 1]; };
    auto ux = [&](int i) { return c.x[i * DIM] - c.x0[i * DIM]; };
    // point values from the adjacent segments
    auto eps_pt = [&](int i) {
      const int a = std::max(i - 1, 0), b = std::min(i, n - 2);
      return 0.5 * (c.eps[a] + c.eps[b]);
    };
    auto T_pt = [&](int i) {
      const int a = std::max(i - 1, 0), b = std::min(i, n - 2);
      return 0.5 * (c.T[a] + c.T[b]);
    };

    // sag: absolute at mid-trench, and relative to the chord between the current sheet points
    // above the trench edges
    const double sag_abs = -at0(xc_, uy);
    double ycross[3];
    const double xs[3] = {xe_[0], xc_, xe_[1]};
    int kx[3];
    double rx[3], X0x[3];
    for (int e = 0; e < 3; ++e) {
      cross(xs[e], kx[e], rx[e]);
      ycross[e] = (1 - rx[e]) * Y(kx[e]) + rx[e] * Y(kx[e] + 1);
      X0x[e] = (1 - rx[e]) * X0(kx[e]) + rx[e] * X0(kx[e] + 1);
    }
    const double sag_chord = 0.5 * (ycross[0] + ycross[2]) - ycross[1];
    // pull-in: the material now above each edge came from X0x; drawn-in length per side
    const double pull[2] = {xe_[0] - X0x[0], X0x[2] - xe_[1]};
    // the material points at the edges: their horizontal displacement toward the trench
    const int ie[2] = {index0(xe_[0]), index0(xe_[1])};
    const double u_edge[2] = {ux(ie[0]), -ux(ie[1])};
    // arc length over the void and the material's mean strain there
    double arc = 0, mat0 = 0;
    for (int k = kx[0]; k <= kx[2]; ++k) {
      const double a = k == kx[0] ? rx[0] : 0.0, b = k == kx[2] ? rx[2] : 1.0;
      if (b <= a) continue;
      const double l = std::hypot(X(k + 1) - X(k), Y(k + 1) - Y(k));
      arc += (b - a) * l;
      mat0 += (b - a) * c.l0[k];
    }
    const double eps_mean_span = arc / mat0 - 1, eps_geom = arc / B - 1;
    // peak strain over the span (segments whose initial midpoint is over the trench) and over
    // the whole sheet
    int kpk = -1, kall = 0;
    for (int k = 0; k + 1 < n; ++k) {
      const double xm = 0.5 * (X0(k) + X0(k + 1));
      if (xm > xe_[0] && xm < xe_[1] && (kpk < 0 || c.eps[k] > c.eps[kpk])) kpk = k;
      if (c.eps[k] > c.eps[kall]) kall = k;
    }
    const double eps_mid = at0(xc_, eps_pt);
    // pressure on the sheet over the void: the chain's p_top over the points now above the
    // trench (length-weighted), the whole span and its inner part (one cell clear of each edge)
    double pw[2] = {0, 0}, pwi[2] = {0, 0}, pb[2] = {0, 0};
    for (int i = 0; i < n; ++i) {
      if (X(i) <= xe_[0] || X(i) >= xe_[1]) continue;
      pw[0] += c.p_top[i] * c.length[i];
      pw[1] += c.length[i];
      pb[0] += c.p_bot[i] * c.length[i];
      pb[1] += c.length[i];
      if (X(i) > xe_[0] + h && X(i) < xe_[1] - h) {
        pwi[0] += c.p_top[i] * c.length[i];
        pwi[1] += c.length[i];
      }
    }
    const double p_top = pw[1] > 0 ? pw[0] / pw[1] : 0, p_bot = pb[1] > 0 ? pb[0] / pb[1] : 0;
    const double p_inner = pwi[1] > 0 ? pwi[0] / pwi[1] : 0;
    // from equilibrium: the tension's vertical components where the sheet crosses the edges
    // carry the pressure and the sheet's weight over the void
    double V = 0;
    for (int e : {0, 2}) {
      const int k = kx[e];
      const double dx = X(k + 1) - X(k), dy = Y(k + 1) - Y(k);
      V += c.T[k] * std::fabs(dy) / std::hypot(dx, dy);
    }
    const double p_eq = (V - c.line_weight * mat0) / B;
    // anchorage on each side: from the edge outward
    struct Anch {
      double T_edge = 0, eps_edge = 0, len5 = 0, len_eq = 0, m = 0, p_top = 0, slip_bot = 0,
             slip_top = 0, u_end = 0;
    } an[2];
    for (int e = 0; e < 2; ++e) {
      const int i0 = ie[e], step = e == 0 ? -1 : 1;
      Anch &a = an[e];
      a.T_edge = T_pt(i0);
      a.eps_edge = eps_pt(i0);
      double area = 0;
      bool found = false;
      for (int i = i0; i + step >= 0 && i + step < n; i += step) {
        const int k = e == 0 ? i - 1 : i; // the segment between i and i + step
        area += std::fmax(c.T[k], 0.0) * c.l0[k];
        if (!found && c.T[k] <= 0.05 * a.T_edge) {
          a.len5 = std::fabs(0.5 * (X0(i) + X0(i + step)) - X0(i0));
          found = true;
        }
      }
      if (!found) a.len5 = std::fabs(X0(e == 0 ? 0 : n - 1) - X0(i0));
      a.len_eq = a.T_edge > 0 ? 2 * area / a.T_edge : 0;
      a.m = a.len_eq > 0 ? a.T_edge / a.len_eq : 0;
      double ps = 0, ls = 0;
      for (int i = 0; i < n; ++i)
        if (std::fabs(X0(i) - X0(i0)) <= a.len_eq && (e == 0 ? X0(i) < X0(i0) : X0(i) > X0(i0))) {
          ps += c.p_top[i] * c.length[i];
          ls += c.length[i];
        }
      a.p_top = ls > 0 ? ps / ls : 0;
      a.slip_bot = std::fabs(c.slip_bot[i0]);
      a.slip_top = std::fabs(c.slip_top[i0]);
      a.u_end = e == 0 ? ux(0) : -ux(n - 1); // toward the trench
    }
    const double T_edge = 0.5 * (an[0].T_edge + an[1].T_edge);
    // the sheet's lowest point against the trench floor
    double ymin = 1e300;
    for (int i = 0; i < n; ++i) ymin = std::fmin(ymin, Y(i));
    const double gap_floor = ymin - (Hb_ - D_);

    // closed forms
    const double tphi = std::tan(phi_ * giroud::pi / 180), sphi = std::sin(phi_ * giroud::pi / 180);
    const double Ka = (1 - sphi) / (1 + sphi);
    auto terzaghi = [&](double ktan) {
      const double x = 2 * ktan * H_ / B;
      return 0.5 * gamma * B / ktan * (-std::expm1(-x));
    };
    const double p_K1 = terzaghi(tphi), p_Ka = terzaghi(Ka * tphi), p_025 = terzaghi(0.25);
    auto giroud_sc = [&](double p) -> std::string {
      try { // T = J eps: E t = J (q = p, no arching inside)
        const auto g = giroud::self_consistent(0.0, B, 0.0, p, t_, J / t_);
        return Obj({{"pressure", p}, {"sag", g.sag}, {"strain", g.strain}, {"tension", g.tension}});
      } catch (const std::exception &) {
        return "null";
      }
    };
    auto anchored = [&](double p, const std::function<double(double)> &pf) -> std::string {
      const ArcAnchored a = GiroudAnchored(p, B, J, pf);
      if (a.sag < 0) return "null";
      return Obj({{"pressure", p}, {"sag", a.sag}, {"strain", a.strain}, {"tension", a.tension},
                  {"pull_in_total", a.pull}});
    };
    const double pull_sim = pull[0] + pull[1];
    const std::string g_sim_pull = anchored(p_top, [&](double) { return pull_sim; });
    const std::string g_cf_pull =
        anchored(p_top, [&](double T) { return 2 * T * T / (2 * m_cf * J); });
    const std::string g_cf_pull_full =
        anchored(sigma_n, [&](double T) { return 2 * T * T / (2 * m_cf * J); });

    auto side = [&](int e) {
      const Anch &a = an[e];
      return Obj({{"tension_edge", a.T_edge},
                  {"strain_edge", a.eps_edge},
                  {"pull_in", pull[e]},
                  {"edge_displacement", u_edge[e]},
                  {"end_displacement", a.u_end},
                  {"length_5pct", a.len5},
                  {"length_equivalent", a.len_eq},
                  {"shear_mobilised", a.m},
                  {"pressure_top", a.p_top},
                  {"slip_top_edge", a.slip_top},
                  {"slip_bottom_edge", a.slip_bot},
                  {"x_a_closed_form", a.T_edge / m_cf},
                  {"u0_closed_form", a.T_edge * a.T_edge / (2 * m_cf * J)}});
    };
    const char *sep = ",\n    ";
    json = json_kv("trench_width", B) + sep + json_kv("trench_depth", D_) + sep +
           json_kv("cover", H_) + sep + json_kv("axial_stiffness", J) + sep +
           json_kv("overburden", sigma_n) + sep + json_kv("mu_sum", mu_sum) + sep +
           json_kv("terzaghi_phi", phi_) + sep + json_kv("sag", sag_abs) + sep +
           json_kv("sag_chord", sag_chord) + sep + json_kv("strain_mid", eps_mid) + sep +
           json_kv("strain_mean_span", eps_mean_span) + sep +
           json_kv("strain_geometric_span", eps_geom) + sep +
           json_kv("peak_strain_span", kpk >= 0 ? c.eps[kpk] : 0.0) + sep +
           json_kv("peak_strain_span_x0", kpk >= 0 ? 0.5 * (X0(kpk) + X0(kpk + 1)) : 0.0) + sep +
           json_kv("peak_strain_span_from_edge",
                   kpk >= 0 ? std::fmin(0.5 * (X0(kpk) + X0(kpk + 1)) - xe_[0],
                                        xe_[1] - 0.5 * (X0(kpk) + X0(kpk + 1)))
                            : 0.0) +
           sep + json_kv("peak_strain", c.eps[kall]) + sep +
           json_kv("peak_strain_x0", 0.5 * (X0(kall) + X0(kall + 1))) + sep +
           json_kv("strain_edge_left", an[0].eps_edge) + sep +
           json_kv("strain_edge_right", an[1].eps_edge) + sep + json_kv("tension_edge", T_edge) +
           sep + json_kv("pull_in_total", pull_sim) + sep +
           json_kv("pressure_span", p_top) + sep + json_kv("pressure_span_inner", p_inner) + sep +
           json_kv("pressure_equilibrium", p_eq) + sep + json_kv("pressure_bottom_span", p_bot) +
           sep + json_kv("gap_to_floor", gap_floor) + sep + "\"anchorage\": {\"left\": " +
           side(0) + ", \"right\": " + side(1) + "}" + sep + "\"terzaghi\": " +
           Obj({{"K1", p_K1}, {"Ka", p_Ka}, {"Ka_value", Ka}, {"ktan_025", p_025},
                {"overburden", sigma_n}}) +
           sep + "\"giroud\": {\"overburden\": " + giroud_sc(sigma_n) +
           ", \"simulated_pressure\": " + giroud_sc(p_top) +
           ", \"giroud_arching\": " + giroud_sc(p_025) +
           ", \"anchored_simulated_pull_in\": " + g_sim_pull +
           ", \"anchored_closed_form\": " + g_cf_pull +
           ", \"anchored_closed_form_overburden\": " + g_cf_pull_full + "}";
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_trench_scene() {
  return std::make_unique<TrenchScene>();
}

} // namespace pmpm
