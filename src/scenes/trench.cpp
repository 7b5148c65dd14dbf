// A geomembrane over an open trench under a cohesionless cover: Giroud's regime (docs/method.md,
// sections 6.2, 6.4, 6.5 and 1.3).
//
// Geometry (x to the right, y up; the grid starts -trench_surface_offset cells below y = 0):
//   base   y < Hb, full width W, elastic ("base": stiff soil), base fixed, sides on rollers; an
//          open trench (no particles) of width B and depth D centred at x = W / 2
//   sheet  a membrane chain ("membrane") laid flat on the base surface y = Hb from x = margin to
//          W - margin: it spans the trench and lies on the base over an anchorage of length La on
//          each side; its ends are free (friction holds them) or pinned (-trench_pin_ends)
//   cover  Hb <= y < Hb + H, full width ("cover": Drucker-Prager with c = 0, or elastic)
// Lengths are whole numbers of cells. With -trench_surface_offset 0.5 (default) the base surface
// and the sheet lie at mid-cell: the sheet's two node rows both carry base, sheet and cover. On a
// grid line (offset 0) the span agrees within 2 % at h = 0.0625 m (mid-span strain 4.53 %
// against 4.52 %, chord sag 0.284 against 0.289 m) and the relaxation reaches a lower ratio
// (0.03 against 0.14 at 16,000 steps), but the strain peak where the sheet bends over the edge is
// 7.6 % against 5.5 %, and it grows with refinement (6.1, 7.3, 7.6 % at h = 0.25, 0.125, 0.0625)
// where at mid-cell it falls (6.5, 5.7, 5.5, 4.8 % down to h = 0.03125): the peak at the corner
// depends on where the sheet sits in its cells; the span does not.
//
// Results beside the closed forms (summary.json "results"; trench_history.csv every
// -trench_history_every steps):
//   - the sheet's sag at mid-trench (absolute, and relative to the chord between the current
//     sheet points above the trench edges), its strain (at mid-span; the mean of the material
//     now over the void; the peak over the span and where; at the edge points), its tension at
//     mid-span and at the edges;
//   - the pressure of the cover on the sheet over the trench: p = T_mid / R, the pressure that
//     holds a circular sheet of the simulated chord sag under the simulated mid-span tension
//     (Giroud's own T = p R); the chain's p_top over the span and over its central 80 %; and the
//     sheet's vertical equilibrium (the tension's vertical components where it crosses the edges,
//     or x = xc -+ 0.4 B, over that width). The pressure is not uniform (lower at mid-span), and
//     p_top counts only nodes in contact, so the arc pressure is the one compared;
//   - the anchorage on each side: the edge tension T_e, the pull-in (the material length drawn
//     over the void, and the horizontal displacement of the edge's material point), the
//     stretched length (T falls to 5 % of T_e; and the triangle of the same area,
//     2 int T+ dx / T_e), the mobilised shear T_e / that length, beside docs/method.md,
//     section 6.2: x_a = T_e / m, m = (mu_t + mu_b) gamma H, u0 = T_e^2 / (2 m J);
//   - Terzaghi arching (docs/method.md, section 6.4, c = 0) with K = 1, K = Ka of the cover's phi,
//   and
//     K tan phi = 0.25 (Giroud's choice);
//   - Giroud's self-consistent sag and strain (giroud.hpp, with E t = J, the chain's axial
//     stiffness) for (a) the full overburden gamma H, (b) the arc pressure, the chain's p_top
//     over the central span, (c) Giroud's arching pressure; and Giroud's arc with the anchorage:
//     the material over the void is B plus the pull-in of both sides before it stretches, so
//     arc(y) = (B + u_L + u_R)(1 + T / J), T = p B Omega(y), with (d) the simulated pull-in,
//     (e) the closed-form pull-in u = T^2 / (2 m J) per side (rigid soil, full friction on both
//     faces), (f) the same with the simulated mobilised shear, (g) (e) under the overburden.
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/scenes/giroud.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
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
// theta = 2 atan(2 y / b) parametrises y monotonically (theta = pi / 2 is the semicircle); the
// residual arc/b - (1 + pull/b)(1 + T/J) runs from -inf (theta -> 0: Omega -> inf) to > 0 at the
// semicircle for the loads of interest (arc/b = pi/2 there, T = p b / 2). Returns y (and T,
// eps = T / J) or y = -1 if there is no root up to the semicircle.
struct ArcAnchored {
  double sag = -1, tension = 0, strain = 0, pull = 0;
};
ArcAnchored GiroudAnchored(double p, double b, double J,
                           const std::function<double(double)> &pull) {
  auto res = [&](double th) {
    const double y = 0.5 * b * std::tan(0.5 * th);
    const double T = p * b * giroud::omega(y, b);
    return (1.0 + giroud::strain(y, b)) - (1.0 + pull(T) / b) * (1.0 + T / J);
  };
  ArcAnchored a;
  const double lo = 1e-6, hi = 0.5 * giroud::pi;
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

// The sheet's points and segments as plain arrays (chain.hpp: every rank holds them all).
struct TrenchSheet {
  int n = 0;
  std::vector<double> x0, x, y, length, p_top, p_bot, slip_top, slip_bot; // points
  std::vector<double> eps, T, l0;                                         // segments
};

TrenchSheet FullSheet(const Chain &c) {
  TrenchSheet s;
  s.n = c.n;
  for (int i = 0; i < c.n; ++i) {
    s.x0.push_back(c.x0[i * DIM]);
    s.x.push_back(c.x[i * DIM]);
    s.y.push_back(c.x[i * DIM + 1]);
  }
  s.length = c.length;
  s.p_top = c.p_top;
  s.p_bot = c.p_bot;
  s.slip_top = c.slip_top;
  s.slip_bot = c.slip_bot;
  s.eps = c.eps;
  s.T = c.T;
  s.l0 = c.l0;
  return s;
}
} // namespace

class TrenchScene final : public Scene {
  // geometry (m): trench width and depth, cover thickness, base height, anchorage, margin
  double B_ = 2.0, D_ = 0.8, H_ = 1.0, Hb_ = 1.0, La_ = 2.0, margin_ = 0.5, t_ = 0.0015;
  double W_ = 0, xe_[2] = {0, 0}, xc_ = 0;
  double offset_ = 0.5;         // -trench_surface_offset (cells)
  PetscBool pin_ = PETSC_FALSE; // -trench_pin_ends: the sheet's far ends held
  double phi_ = 30;             // the cover's friction angle (deg) for Terzaghi's bracket
  PetscInt every_ = 100;        // -trench_history_every (0: none)
  // history rows: step, time, ratio, sag, edge tension, pull-in of the ends, pressure on the
  // span, pressure on the metre of anchorage beside the edges (top face), pull-in at the edges,
  // strain at mid-span, peak strain over the span
  std::vector<double> hist_;
  static constexpr int kHist = 11;

  // where the current sheet crosses x = s: segment k and fraction r
  static void Cross(const TrenchSheet &q, double s, int &k, double &r) {
    k = 0;
    while (k + 2 < q.n && q.x[k + 1] < s) ++k;
    r = (s - q.x[k]) / (q.x[k + 1] - q.x[k]);
  }
  static int Index0(const TrenchSheet &q, double s) {
    int best = 0;
    for (int i = 0; i < q.n; ++i)
      if (std::fabs(q.x0[i] - s) < std::fabs(q.x0[best] - s)) best = i;
    return best;
  }

  // What the sheet does over the trench: sag, the edges' crossings, pull-in, strains.
  struct Span {
    double sag_abs = 0, sag_chord = 0, pull[2] = {0, 0}, u_edge[2] = {0, 0};
    int kx[3] = {0, 0, 0}, ie[2] = {0, 0}, kpk = -1, kall = 0;
    double rx[3] = {0, 0, 0};
    double mat0 = 0, eps_mean_span = 0, eps_geom = 0, xpk = 0;
  };
  // The pressure on the sheet over the trench, from p_top / p_bot and from its equilibrium.
  struct SpanPressure {
    double all = 0, bottom = 0, top_inner = 0, eq_inner = 0, eq_edges = 0;
  };
  // The anchorage on one side, from the edge outward.
  struct Anchorage {
    double T_edge = 0, eps_edge = 0, len5 = 0, len_eq = 0, m = 0, p_top = 0, slip_bot = 0,
           slip_top = 0, u_end = 0;
  };

  // point values from the adjacent segments
  static double PointValue(const TrenchSheet &q, const std::vector<double> &seg, int i) {
    const int a = std::max(i - 1, 0), b = std::min(i, q.n - 2);
    return 0.5 * (seg[a] + seg[b]);
  }
  // a point field at initial abscissa s (linear interpolation between points)
  static double At0(const TrenchSheet &q, double s, const std::function<double(int)> &f) {
    int k = 0;
    while (k + 2 < q.n && q.x0[k + 1] < s) ++k;
    const double r = (s - q.x0[k]) / (q.x0[k + 1] - q.x0[k]);
    return (1 - r) * f(k) + r * f(k + 1);
  }

  Span MeasureSpan(const TrenchSheet &q) const {
    Span sp;
    const int n = q.n;
    // sag: absolute at mid-trench, and relative to the chord between the current sheet points
    // above the trench edges
    sp.sag_abs = -At0(q, xc_, [&](int i) { return q.y[i] - Hb_; });
    const double xs[3] = {xe_[0], xc_, xe_[1]};
    double ycross[3], X0x[3];
    for (int e = 0; e < 3; ++e) {
      Cross(q, xs[e], sp.kx[e], sp.rx[e]);
      ycross[e] = (1 - sp.rx[e]) * q.y[sp.kx[e]] + sp.rx[e] * q.y[sp.kx[e] + 1];
      X0x[e] = (1 - sp.rx[e]) * q.x0[sp.kx[e]] + sp.rx[e] * q.x0[sp.kx[e] + 1];
    }
    sp.sag_chord = 0.5 * (ycross[0] + ycross[2]) - ycross[1];
    // pull-in: the material now above each edge came from X0x; drawn-in length per side
    sp.pull[0] = xe_[0] - X0x[0];
    sp.pull[1] = X0x[2] - xe_[1];
    // the material points at the edges: their horizontal displacement toward the trench
    sp.ie[0] = Index0(q, xe_[0]);
    sp.ie[1] = Index0(q, xe_[1]);
    sp.u_edge[0] = q.x[sp.ie[0]] - q.x0[sp.ie[0]];
    sp.u_edge[1] = -(q.x[sp.ie[1]] - q.x0[sp.ie[1]]);
    // arc length over the void and the material's mean strain there
    double arc = 0;
    for (int k = sp.kx[0]; k <= sp.kx[2]; ++k) {
      const double a = k == sp.kx[0] ? sp.rx[0] : 0.0, b = k == sp.kx[2] ? sp.rx[2] : 1.0;
      if (b <= a) continue;
      arc += (b - a) * std::hypot(q.x[k + 1] - q.x[k], q.y[k + 1] - q.y[k]);
      sp.mat0 += (b - a) * q.l0[k];
    }
    sp.eps_mean_span = arc / sp.mat0 - 1;
    sp.eps_geom = arc / B_ - 1;
    // peak strain over the span (segments whose initial midpoint is over the trench) and over
    // the whole sheet
    for (int k = 0; k + 1 < n; ++k) {
      const double xm = 0.5 * (q.x0[k] + q.x0[k + 1]);
      if (xm > xe_[0] && xm < xe_[1] && (sp.kpk < 0 || q.eps[k] > q.eps[sp.kpk])) sp.kpk = k;
      if (q.eps[k] > q.eps[sp.kall]) sp.kall = k;
    }
    sp.xpk = sp.kpk >= 0 ? 0.5 * (q.x0[sp.kpk] + q.x0[sp.kpk + 1]) : 0.0;
    return sp;
  }

  // The pressure on the sheet over the void: the chain's p_top (length-weighted) over the points
  // now above the trench, and over its central 80 % (clear of the corners, where the sheet bends
  // over the edges and the cover presses it onto them); and from the sheet's equilibrium.
  SpanPressure MeasurePressure(const TrenchSheet &q, const Span &sp, double line_weight) const {
    SpanPressure sp_p;
    const double a_in = 0.4 * B_;
    double pw[2] = {0, 0}, pwi[2] = {0, 0}, pb[2] = {0, 0};
    for (int i = 0; i < q.n; ++i) {
      if (q.x[i] <= xe_[0] || q.x[i] >= xe_[1]) continue;
      pw[0] += q.p_top[i] * q.length[i];
      pw[1] += q.length[i];
      pb[0] += q.p_bot[i] * q.length[i];
      pb[1] += q.length[i];
      if (std::fabs(q.x[i] - xc_) < a_in) {
        pwi[0] += q.p_top[i] * q.length[i];
        pwi[1] += q.length[i];
      }
    }
    sp_p.all = pw[1] > 0 ? pw[0] / pw[1] : 0;
    sp_p.bottom = pb[1] > 0 ? pb[0] / pb[1] : 0;
    sp_p.top_inner = pwi[1] > 0 ? pwi[0] / pwi[1] : 0;
    // the sheet's equilibrium over the same central 80 %: the vertical components of the tension
    // where the sheet crosses x = xc -+ 0.4 B carry the pressure and the sheet's weight
    auto vertical = [&](int k) {
      const double dx = q.x[k + 1] - q.x[k], dy = q.y[k + 1] - q.y[k];
      return q.T[k] * std::fabs(dy) / std::hypot(dx, dy);
    };
    double V = 0, L0in = 0;
    int kin[2];
    double rin[2];
    for (int e = 0; e < 2; ++e) {
      Cross(q, xc_ + (e == 0 ? -a_in : a_in), kin[e], rin[e]);
      V += vertical(kin[e]);
    }
    for (int k = kin[0]; k <= kin[1]; ++k) {
      const double a = k == kin[0] ? rin[0] : 0.0, b = k == kin[1] ? rin[1] : 1.0;
      if (b > a) L0in += (b - a) * q.l0[k];
    }
    sp_p.eq_inner = (V - line_weight * L0in) / (2 * a_in);
    // ... and over the whole span (the crossings of the edges; includes what the sheet hands to
    // the corners where it bends over them)
    double Ve = 0;
    for (int e : {0, 2}) Ve += vertical(sp.kx[e]);
    sp_p.eq_edges = (Ve - line_weight * sp.mat0) / B_;
    return sp_p;
  }

  // The anchorage on side e (0 left, 1 right), from the edge's point i0 outward.
  static Anchorage MeasureAnchorage(const TrenchSheet &q, int e, int i0) {
    const int n = q.n, step = e == 0 ? -1 : 1;
    Anchorage a;
    a.T_edge = PointValue(q, q.T, i0);
    a.eps_edge = PointValue(q, q.eps, i0);
    double area = 0;
    bool found = false;
    for (int i = i0; i + step >= 0 && i + step < n; i += step) {
      const int k = e == 0 ? i - 1 : i; // the segment between i and i + step
      area += std::fmax(q.T[k], 0.0) * q.l0[k];
      if (!found && q.T[k] <= 0.05 * a.T_edge) {
        a.len5 = std::fabs(0.5 * (q.x0[i] + q.x0[i + step]) - q.x0[i0]);
        found = true;
      }
    }
    if (!found) a.len5 = std::fabs(q.x0[e == 0 ? 0 : n - 1] - q.x0[i0]);
    a.len_eq = a.T_edge > 0 ? 2 * area / a.T_edge : 0;
    a.m = a.len_eq > 0 ? a.T_edge / a.len_eq : 0;
    double ps = 0, ls = 0;
    for (int i = 0; i < n; ++i) {
      const double d = e == 0 ? q.x0[i0] - q.x0[i] : q.x0[i] - q.x0[i0];
      if (d > 0 && d <= a.len_eq) {
        ps += q.p_top[i] * q.length[i];
        ls += q.length[i];
      }
    }
    a.p_top = ls > 0 ? ps / ls : 0;
    a.slip_bot = std::fabs(q.slip_bot[i0]);
    a.slip_top = std::fabs(q.slip_top[i0]);
    a.u_end = e == 0 ? q.x[0] - q.x0[0] : -(q.x[n - 1] - q.x0[n - 1]); // toward the trench
    return a;
  }

  // The closed forms beside the simulation: Terzaghi's bracket and Giroud's sheet, plain and
  // with the anchorage's pull-in (the header's list (a)-(g)).
  std::string ClosedForms(double gamma, double J, double m_cf, double m_sim, double p_arc,
                          double p_top, double pull_sim) const {
    const double B = B_, sigma_n = gamma * H_;
    const double rad = giroud::pi / 180, tphi = std::tan(phi_ * rad), sphi = std::sin(phi_ * rad);
    const double Ka = (1 - sphi) / (1 + sphi);
    auto terzaghi = [&](double ktan) { // docs/method.md, section 6.4, c = 0, q = 0
      return 0.5 * gamma * B / ktan * (-std::expm1(-2 * ktan * H_ / B));
    };
    const double p_K1 = terzaghi(tphi), p_Ka = terzaghi(Ka * tphi), p_025 = terzaghi(0.25);
    auto giroud_sc = [&](double p) -> std::string {
      try { // T = J eps with E t = J; the pressure enters as giroud's surcharge (no arching)
        const auto g = giroud::self_consistent(0.0, B, 0.0, p, t_, J / t_);
        return Obj({{"pressure", p}, {"sag", g.sag}, {"strain", g.strain}, {"tension", g.tension}});
      } catch (const std::exception &) {
        return "null";
      }
    };
    auto anchored = [&](double p, const std::function<double(double)> &pf) -> std::string {
      const ArcAnchored a = GiroudAnchored(p, B, J, pf);
      if (a.sag < 0) return "null";
      return Obj({{"pressure", p},
                  {"sag", a.sag},
                  {"strain", a.strain},
                  {"tension", a.tension},
                  {"pull_in_total", a.pull}});
    };
    auto pull_cf = [&](double m) { return [m, J](double T) { return 2 * T * T / (2 * m * J); }; };
    const char *sep = ",\n    ";
    return std::string("\"terzaghi\": ") +
           Obj({{"K1", p_K1},
                {"Ka", p_Ka},
                {"Ka_value", Ka},
                {"ktan_025", p_025},
                {"overburden", sigma_n}}) +
           sep + "\"giroud\": {\"overburden\": " + giroud_sc(sigma_n) +
           ",\n      \"simulated_pressure\": " + giroud_sc(p_arc) +
           ",\n      \"pressure_top_inner\": " + giroud_sc(p_top) +
           ",\n      \"giroud_arching\": " + giroud_sc(p_025) +
           ",\n      \"anchored_simulated_pull_in\": " +
           anchored(p_arc, [&](double) { return pull_sim; }) +
           ",\n      \"anchored_closed_form\": " + anchored(p_arc, pull_cf(m_cf)) +
           ",\n      \"anchored_mobilised_shear\": " + anchored(p_arc, pull_cf(m_sim)) +
           ",\n      \"anchored_closed_form_overburden\": " + anchored(sigma_n, pull_cf(m_cf)) +
           "}";
  }

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    PetscOptionsBegin(sim.comm, "trench_", "Trench: a membrane over an open trench under a cover",
                      nullptr);
    PetscCall(PmpmOptionsReal("-width", "Trench width B (m)", nullptr, B_, &B_, nullptr));
    PetscCall(
        PmpmOptionsReal("-depth", "Trench depth D (m), < base height", nullptr, D_, &D_, nullptr));
    PetscCall(PmpmOptionsReal("-cover", "Cover thickness H (m)", nullptr, H_, &H_, nullptr));
    PetscCall(PmpmOptionsReal("-base_height", "Base layer height Hb (m), > trench depth", nullptr,
                              Hb_, &Hb_, nullptr));
    PetscCall(PmpmOptionsReal("-anchorage", "Sheet length on the base beyond each edge (m)",
                              nullptr, La_, &La_, nullptr));
    PetscCall(PmpmOptionsReal("-margin", "Base and cover beyond each end of the sheet (m)", nullptr,
                              margin_, &margin_, nullptr));
    PetscCall(PmpmOptionsReal("-surface_offset",
                              "Grid lines this fraction of a cell below the bodies' faces: 0.5 "
                              "(the base surface and the sheet at mid-cell) or 0 (on a grid line)",
                              nullptr, offset_, &offset_, nullptr));
    PetscCall(PetscOptionsBool("-pin_ends",
                               "Hold the sheet's far ends fixed (an anchor trench) instead of "
                               "leaving them free on the base",
                               nullptr, pin_, &pin_, nullptr));
    PetscCall(PmpmOptionsInt("-history_every",
                             "Steps between rows of trench_history.csv (sag, edge tension, "
                             "pull-in, pressures); 0: none",
                             nullptr, every_, &every_, nullptr));
    PetscOptionsEnd();
    PetscCall(MembraneThicknessOption(sim.comm, "The membrane", &t_));
    const double h = sim.set.h;
    PetscInt nB, nD, nH, nHb, nLa, nM;
    PetscCall(CheckCells(sim.comm, "-trench_width", B_, h, &nB));
    PetscCall(CheckCells(sim.comm, "-trench_depth", D_, h, &nD));
    PetscCall(CheckCells(sim.comm, "-trench_cover", H_, h, &nH));
    PetscCall(CheckCells(sim.comm, "-trench_base_height", Hb_, h, &nHb));
    PetscCall(CheckCells(sim.comm, "-trench_anchorage", La_, h, &nLa));
    PetscCall(CheckCells(sim.comm, "-trench_margin", margin_, h, &nM));
    PmpmCheckInput(
        nD < nHb, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-trench_depth %g must be less than -trench_base_height %g (the trench has a floor)", D_,
        Hb_);
    PmpmCheckInput(
        (offset_ == 0 || offset_ == 0.5) && std::fmod(offset_ * sim.set.ppc, 1.0) == 0, sim.comm,
        PETSC_ERR_ARG_OUTOFRANGE,
        "-trench_surface_offset must be 0 or 0.5, and 0.5 needs an even -ppc (no particle "
        "centre on a face; got %g with -ppc %" PetscInt_FMT ")",
        offset_, sim.set.ppc);
    PetscCall(CheckMembraneThickness(sim.comm, t_));
    // x: the trench centred at W / 2
    W_ = B_ + 2 * La_ + 2 * margin_;
    xc_ = 0.5 * W_;
    xe_[0] = margin_ + La_;
    xe_[1] = margin_ + La_ + B_;
    // y: the base fills the grid from its bottom face, y = -offset h (half a cell more base)
    sim.model.origin[0] = 0;
    sim.model.origin[1] = -offset_ * h;
    sim.model.ncell[0] = nB + 2 * (nLa + nM);
    sim.model.ncell[1] = nHb + nH + 2 + (offset_ > 0 ? 1 : 0);
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    sim.model.face[YMAX] = FaceBC::Free;
    sim.model.mats.resize(2);
    PetscCall(MaterialFromOptions(sim.comm, "base", sim.model.mats[BASE]));
    PetscCall(MaterialFromOptions(sim.comm, "cover", sim.model.mats[COVER]));
    PmpmCheckInput(sim.model.mats[COVER].gamma > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-mat_cover_gamma must be > 0 (the cover's weight is the load)");
    // Terzaghi's phi: the cover's own friction angle when it has one
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-mat_cover_friction_angle", &phi_, nullptr));
    PetscOptionsBegin(sim.comm, "trench_", "Trench: closed forms", nullptr);
    PetscCall(PmpmOptionsReal("-terzaghi_phi",
                              "Friction angle (deg) for Terzaghi's bracket (default: "
                              "-mat_cover_friction_angle, else 30)",
                              nullptr, phi_, &phi_, nullptr));
    PetscOptionsEnd();
    PmpmCheckInput(phi_ > 0 && phi_ < 90, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-trench_terzaghi_phi must be in (0, 90) degrees (got %g)", phi_);
    ChainSpec cs;
    cs.name = "membrane";
    cs.material = "membrane";
    cs.thickness = t_;
    // vertices at the edges, so that chain points fall on them whatever the spacing
    cs.line = {margin_, Hb_, xe_[0], Hb_, xe_[1], Hb_, W_ - margin_, Hb_};
    cs.pin_start = cs.pin_end = pin_;
    sim.model.chain_specs.push_back(cs);
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    const double Hb = Hb_, top = Hb_ + H_, floor = Hb_ - D_, x0 = xe_[0], x1 = xe_[1];
    FillRegular(
        sim,
        [=](const double x[DIM]) {
          if (x[1] >= top) return -1;
          if (x[1] >= Hb) return int(COVER);
          if (x[0] > x0 && x[0] < x1 && x[1] > floor) return -1; // the trench
          return int(BASE);
        },
        out);
    PetscFunctionReturn(0);
  }

  // checkpoint.hpp: the history rows so far
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointWriteArray(v, "history", hist_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "history", hist_));
    PetscFunctionReturn(0);
  }

  // The relaxation's history (every rank holds the chain): how the sag and the anchorage settle.
  PetscErrorCode monitor(Simulation &sim) override {
    if (every_ <= 0 || sim.run.step % every_ != 0 || sim.chains.empty()) return 0;
    const TrenchSheet q = FullSheet(sim.chains[0]);
    const int n = q.n, im = Index0(q, xc_), ie0 = Index0(q, xe_[0]), ie1 = Index0(q, xe_[1]);
    double pw = 0, lw = 0, pa = 0, la = 0;
    for (int i = 0; i < n; ++i) {
      if (q.x[i] > xe_[0] && q.x[i] < xe_[1]) {
        pw += q.p_top[i] * q.length[i];
        lw += q.length[i];
      }
      const double d = std::fmin(std::fabs(q.x0[i] - xe_[0]), std::fabs(q.x0[i] - xe_[1]));
      if ((q.x0[i] < xe_[0] || q.x0[i] > xe_[1]) && d > sim.set.h && d < 1.0) {
        pa += q.p_top[i] * q.length[i];
        la += q.length[i];
      }
    }
    double peak = 0;
    for (int k = ie0; k < ie1; ++k) peak = std::fmax(peak, q.eps[k]);
    const double row[kHist] = {double(sim.run.step),
                               sim.run.time,
                               sim.run.ratio,
                               -(q.y[im] - Hb_),
                               0.25 * (q.T[ie0 - 1] + q.T[ie0] + q.T[ie1 - 1] + q.T[ie1]),
                               0.5 * ((q.x[0] - q.x0[0]) - (q.x[n - 1] - q.x0[n - 1])),
                               lw > 0 ? pw / lw : 0.0,
                               la > 0 ? pa / la : 0.0,
                               0.5 * ((q.x[ie0] - q.x0[ie0]) - (q.x[ie1] - q.x0[ie1])),
                               0.5 * (q.eps[im - 1] + q.eps[im]),
                               peak};
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
      std::fprintf(f, "step,time,ratio,sag,tension_edge,pull_in_ends,pressure_span,"
                      "pressure_anchorage,pull_in_edges,strain_mid,peak_strain_span\n");
      for (size_t k = 0; k + kHist <= hist_.size(); k += kHist) {
        std::fprintf(f, "%.0f", hist_[k]);
        for (int j = 1; j < kHist; ++j) std::fprintf(f, ",%.9g", hist_[k + j]);
        std::fprintf(f, "\n");
      }
      std::fclose(f);
    }
    PetscCall(OutputCommit(sim, "trench_history.csv"));
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    const Chain &c = sim.chains[0];
    const TrenchSheet q = FullSheet(c);
    const double J = c.law.J;
    const double gamma = sim.model.mats[COVER].gamma, sigma_n = gamma * H_;
    const double mu_sum = c.top.mu + c.bottom.mu, m_cf = mu_sum * sigma_n;
    const Span sp = MeasureSpan(q);
    const SpanPressure pr = MeasurePressure(q, sp, c.line_weight);
    const Anchorage an[2] = {MeasureAnchorage(q, 0, sp.ie[0]), MeasureAnchorage(q, 1, sp.ie[1])};
    const double eps_mid = At0(q, xc_, [&](int i) { return PointValue(q, q.eps, i); });
    const double T_mid = At0(q, xc_, [&](int i) { return PointValue(q, q.T, i); });
    // the pressure of Giroud's arc: a uniform normal pressure p holds a circular sheet of radius
    // R under the tension T = p R; R from the chord B and the simulated chord sag
    const double R_arc = (0.25 * B_ * B_ + sp.sag_chord * sp.sag_chord) / (2 * sp.sag_chord);
    const double p_arc = T_mid / R_arc;
    const double T_edge = 0.5 * (an[0].T_edge + an[1].T_edge);
    const double m_sim = 0.5 * (an[0].m + an[1].m);
    const double pull_sim = sp.pull[0] + sp.pull[1];
    // the sheet's lowest point against the trench floor
    double ymin = 1e300;
    for (int i = 0; i < q.n; ++i) ymin = std::fmin(ymin, q.y[i]);
    const double gap_floor = ymin - (Hb_ - D_);

    auto side = [&](int e) {
      const Anchorage &a = an[e];
      return Obj({{"tension_edge", a.T_edge},
                  {"strain_edge", a.eps_edge},
                  {"pull_in", sp.pull[e]},
                  {"edge_displacement", sp.u_edge[e]},
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
    const double peak_span = sp.kpk >= 0 ? q.eps[sp.kpk] : 0.0;
    const std::vector<std::pair<std::string, double>> values = {
        {"trench_width", B_},
        {"trench_depth", D_},
        {"cover", H_},
        {"axial_stiffness", J},
        {"overburden", sigma_n},
        {"mu_sum", mu_sum},
        {"shear_closed_form", m_cf},
        {"terzaghi_phi", phi_},
        {"sag", sp.sag_abs},
        {"sag_chord", sp.sag_chord},
        {"strain_mid", eps_mid},
        {"strain_mean_span", sp.eps_mean_span},
        {"strain_geometric_span", sp.eps_geom},
        {"peak_strain_span", peak_span},
        {"peak_strain_span_x0", sp.xpk},
        {"peak_strain_span_from_edge", std::fmin(sp.xpk - xe_[0], xe_[1] - sp.xpk)},
        {"peak_strain", q.eps[sp.kall]},
        {"peak_strain_x0", 0.5 * (q.x0[sp.kall] + q.x0[sp.kall + 1])},
        {"strain_edge_left", an[0].eps_edge},
        {"strain_edge_right", an[1].eps_edge},
        {"tension_edge", T_edge},
        {"tension_mid", T_mid},
        {"pull_in_total", pull_sim},
        {"shear_mobilised", m_sim},
        {"pressure_arc", p_arc},
        {"arc_radius", R_arc},
        {"pressure_top_inner", pr.top_inner},
        {"pressure_top_span", pr.all},
        {"pressure_equilibrium_inner", pr.eq_inner},
        {"pressure_equilibrium_edges", pr.eq_edges},
        {"pressure_bottom_span", pr.bottom},
        {"gap_to_floor", gap_floor}};
    const char *sep = ",\n    ";
    json.clear();
    for (const auto &kv : values) json += json_kv(kv.first, kv.second) + sep;
    json += "\"anchorage\": {\"left\": " + side(0) + ", \"right\": " + side(1) + "}" + sep +
            ClosedForms(gamma, J, m_cf, m_sim, p_arc, pr.top_inner, pull_sim);
    PetscFunctionReturn(0);
  }
};

std::unique_ptr<Scene> make_trench_scene() {
  return std::make_unique<TrenchScene>();
}

} // namespace pmpm
