// A landfill cover at field scale (docs/method.md, section 7), described in an options file:
// waste below a surface
// profile (a top deck at a grade, or a side slope with its toe and crest, or any polyline), cover
// layers over it from the top down, each a thickness (varying linearly across the width if asked)
// and a material, geomembranes as chains (chain.hpp) at the base of named layers, and stages
// that make the waste subside (stages.cpp):
//   stage 0        the geostatic state: gravity on, equilibrium; then the membranes are laid
//                  unstrained where they are and displacements are measured from here
//                  (-cover_geostatic 0: not laid, displacements from the start)
//   shrink stages  an imposed volumetric shrinkage of a zone of waste (degradation.hpp), the
//                  total split into equal stages
//   void stages    a void opening in the waste under the cover: the waste particles in a
//                  rectangle of growing width are removed (the material is lost), so the cover
//                  arches over it or falls into it
// Each stage is recorded in stages.csv and as a ParaView frame; the final state gives the design
// answers (peak membrane strain and tension against an allowable strain, slack, slip, plastic
// and tensile strain in the cover) beside the closed forms for the same geometry (Giroud with
// Terzaghi's arching for a void, infinite-slope and Koerner-Soong factors of safety for a slope).
//
// Geometry need not fit the grid: particles fill each band (waste, then each layer) column by
// column, with the band's thickness at the column split into whole rows, so a 0.3 m layer is
// 0.3 m thick at any cell size (blocks are at most h / ppc tall and at most h / 2, as PMPM needs).
#include "pmpm/util/options.hpp"
#include "pmpm/io/checkpoint.hpp"
#include "pmpm/scenes/giroud.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/registry.hpp"
#include "pmpm/io/output.hpp"
#include "pmpm/scenes/scene_util.hpp"
#include "pmpm/scenes/veneer.hpp"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace pmpm {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr int kMaxList = 16;
constexpr int kMaxPlan = 64; // nodes along x and along z of the plan grid (-cover_plan_*)

struct Layer { // bottom-up in Layer order inside the scene
  std::string name;
  int mat = 0;
  double t_start = 0, t_end = 0; // vertical thickness at x = 0 and x = W (m)
  double thickness(double x, double W) const { return t_start + (t_end - t_start) * x / W; }
};

struct Membrane {
  std::string name, material, under; // the chain lies at the base of layer `under`
  int layer = 0;                     // index of `under` in the bottom-up list
  double thickness = 0;
};

// A zone of the waste with its own material (a soft pocket, a stiff inclusion): a rectangle in
// x (the radius under -geometry axisymmetric, so a zone from 0 is a disc) and in depth below the
// waste surface, the depth measured at each particle's column, so a zone follows the surface.
// Under -dim 3 a zone is also bounded in z (-cover_zone_<name>_z; default the whole depth), or
// round in plan (-cover_zone_<name>_centre X,Z and _radius R, in place of _x and _z): pmpm's
// vertical is y, so the plan is (x, z).
struct Zone {
  std::string name, material;
  double x_lo = 0, x_hi = 0;          // (m)
  double d_top = 0, d_bottom = 0;     // depth below the waste surface (m), top < bottom
  double z_lo = -1e300, z_hi = 1e300; // -dim 3 (m)
  double cx = 0, cz = 0, radius = 0;  // -dim 3: a round zone when radius > 0 (m)
  int mat = 0;
  bool contains(double x, double depth) const {
    return x >= x_lo && x <= x_hi && depth >= d_top && depth <= d_bottom;
  }
  bool contains3(const double X[3], double depth) const {
    if (depth < d_top || depth > d_bottom) return false;
    if (radius > 0) return std::hypot(X[0] - cx, X[2] - cz) <= radius;
    return X[0] >= x_lo && X[0] <= x_hi && X[2] >= z_lo && X[2] <= z_hi;
  }
};

struct StageRow {
  int stage = 0;
  std::string kind;
  double shrink = 0, void_width = 0;
  double surface_settlement = 0, membrane_settlement = 0, differential = 0;
  double peak_strain = 0, peak_strain_x = 0, peak_tension = 0, slip = 0, cover_eps_p = 0;
  double void_pressure = 0, void_sag = 0; // on the sheet's top over the void; its sag there
  double peak_strain_minor = 0, peak_strain_z = 0; // -dim 3: the biaxial state there, its z
  double ratio = 0, wall = 0;
  PetscInt steps = 0;
  bool converged = false;
};

// Largest principal stretch minus one of a 2x2 F (the largest tensile strain).
double max_principal_strain(const double *F) {
  const double c11 = F[0] * F[0] + F[2] * F[2], c22 = F[1] * F[1] + F[3] * F[3],
               c12 = F[0] * F[1] + F[2] * F[3];
  const double m = 0.5 * (c11 + c22), d = std::sqrt(0.25 * (c11 - c22) * (c11 - c22) + c12 * c12);
  return std::sqrt(m + d) - 1.0;
}

// Largest principal stretch minus one of a 3x3 F (row-major).
double max_principal_strain3(const double *F) {
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> f(F);
  const Eigen::Matrix3d C = f.transpose() * f;
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues().maxCoeff()) -
         1.0;
}

// Names from a comma-separated string option (PetscOptionsStringArray's strings, freed).
// The sheet's peak strain and tension over a gauge length: each segment's strain read as the
// stretch of the sheet within +-gauge/2 of its centre (in laid length), its tension the mean over
// the same window. Point-to-point strains along a chain oscillate with the period of a cell (the
// nodal contact forces come in cell-sized lumps; 0.3-1.0 % segment to segment over a void where
// the one-cell mean is 0.9 %): a gauge of at least one cell reads the strain the grid resolves.
struct SheetPeak {
  double strain = 0, strain_x = 0, tension = 0, tension_x = 0; // gauge means
  double strain_segment = 0;                                   // the largest single segment's
};
SheetPeak sheet_peak(const Chain &c, double gauge) {
  SheetPeak pk;
  const int ns = c.n - 1;
  std::vector<double> s0(c.n, 0.0), s(c.n, 0.0), tl(c.n, 0.0); // cumulative laid, current, T l0
  for (int j = 0; j < ns; ++j) {
    // under -chain_strain_projection the sheet's strain is the projected one (its tension comes
    // from it), not the chord's stretch: the window's mean of it, as for the tension
    const double l = c.strain_projection ? c.l0[j] * (1.0 + c.eps[j])
                                         : std::hypot(c.x[(j + 1) * DIM] - c.x[j * DIM],
                                                      c.x[(j + 1) * DIM + 1] - c.x[j * DIM + 1]);
    s0[j + 1] = s0[j] + c.l0[j];
    s[j + 1] = s[j] + l;
    tl[j + 1] = tl[j] + c.T[j] * c.l0[j];
    // the largest principal strain: under -geometry axisymmetric the hoop strain too
    pk.strain_segment = std::fmax(pk.strain_segment, c.eps[j]);
    if (c.axisymmetric) pk.strain_segment = std::fmax(pk.strain_segment, c.eps_hoop[j]);
  }
  pk.strain = pk.tension = -1e300;
  int a = 0, b = 0;
  for (int j = 0; j < ns; ++j) {
    const double mid = 0.5 * (s0[j] + s0[j + 1]);
    while (a < j && s0[a + 1] <= mid - 0.5 * gauge) ++a; // window [a, b] of points
    while (b < ns && s0[b] < mid + 0.5 * gauge) ++b;
    const int lo = std::min(a, j), hi = std::max(b, j + 1);
    const double eps = (s[hi] - s[lo]) / (s0[hi] - s0[lo]) - 1.0;
    const double T = (tl[hi] - tl[lo]) / (s0[hi] - s0[lo]);
    const double x = 0.5 * (c.x0[j * DIM] + c.x0[(j + 1) * DIM]);
    if (eps > pk.strain) pk.strain = eps, pk.strain_x = x;
    if (T > pk.tension) pk.tension = T, pk.tension_x = x;
  }
  return pk;
}

void TakeNames(char **names, PetscInt n, std::vector<std::string> &out) {
  out.clear();
  for (PetscInt k = 0; k < n; ++k) {
    out.emplace_back(names[k]);
    PetscFree(names[k]);
  }
}
} // namespace

class CoverScene final : public Scene {
  // geometry (m)
  double W_ = 40, Hw_ = 10, grade_ = 0; // width, waste height, deck grade (%)
  double grade_z_ = 0; // -dim 3: the waste surface's grade along z (per cent, rising with z)
  // -dim 3: the waste surface as heights on a plan grid (bilinear between its nodes), the plane's
  // profile then the highest height at each x; empty: the profile, risen along z at grade_z_
  std::vector<double> plan_x_, plan_z_, plan_h_;     // plan_h_[j * nx + i] at (x_i, z_j)
  double slope_deg_ = 0, slope_len_ = 0, toe_x_ = 0; // side slope
  std::vector<double> surf_;                         // waste surface polyline x,y,...
  std::vector<Layer> layers_;                        // bottom-up
  std::vector<Membrane> mem_;                        // bottom-up
  std::string waste_mat_ = "waste";
  std::vector<Zone> zones_; // waste zones with their own materials
  // stages
  double shrink_total_ = 0;
  PetscInt shrink_stages_ = 0, shrink_steps_ = 0;
  double void_x_ = 0, void_h_ = 0, void_depth_ = 0;
  double void_z_ = 0; // -dim 3: the round void's centre z
  std::vector<double> void_w_;
  double allowable_ = 0.03;
  double gauge_ = 0; // strain gauge length (m); 0: one cell
  PetscBool geostatic_paper_ = PETSC_TRUE;
  PetscBool geostatic_ = PETSC_TRUE; // stage 0 a separate geostatic stage (sheets laid after it)
  std::vector<FaceType> face_types_; // the chains' own face types (top, bottom per chain)
  // derived
  double dxp_ = 0;                    // particle column spacing h / ppc
  double h_ = 0;                      // the cell size
  PetscInt ncol_ = 0, R_ = 0;         // columns; pid stride per column
  std::vector<PetscInt> surface_pid_; // the top particle of each column (sorted)
  std::vector<char> cover_mat_;       // per material: a cover layer's
  std::vector<char> waste_mat_of_;    // per material: the waste's or a waste zone's
  double cum_shrink_ = 0, void_now_ = 0, void_eff_ = 0;
  bool dim3_ = false;  // -dim 3: the cover extruded along z, its membranes 3D sheets
  PetscInt nzp_ = 0;   // -dim 3: particles along z (the extruded ids' stride)
  bool round_ = false; // -geometry axisymmetric with -cover_void_x 0, or -dim 3: a round void
                       // (widths are diameters)
  // references at the end of stage 0 (rank 0 for the surface; chains on every rank)
  std::map<PetscInt, double> surf_ref_;
  std::vector<double> sheet_ref_; // the reported (top-most) sheet's points at stage 0's end
  std::vector<StageRow> rows_;

  // waste surface height at x
  double ys(double x) const {
    const size_t n = surf_.size() / 2;
    if (x <= surf_[0]) return surf_[1];
    for (size_t k = 0; k + 1 < n; ++k)
      if (x <= surf_[2 * k + 2]) {
        const double r = (x - surf_[2 * k]) / (surf_[2 * k + 2] - surf_[2 * k]);
        return surf_[2 * k + 1] + r * (surf_[2 * k + 3] - surf_[2 * k + 1]);
      }
    return surf_[2 * n - 1];
  }
  // band boundaries at x, bottom-up: 0, waste top, top of each layer
  void bands(double x, std::vector<double> &b) const {
    b.assign(1, 0.0);
    b.push_back(ys(x));
    for (const Layer &l : layers_) b.push_back(b.back() + l.thickness(x, W_));
  }
  // height of the base of layer k at x
  double layer_base(int k, double x) const {
    double y = ys(x);
    for (int j = 0; j < k; ++j) y += layers_[j].thickness(x, W_);
    return y;
  }
  // -dim 3: the waste surface's height on the plan grid at (x, z), bilinear in its cell
  double plan_height(double x, double z) const {
    const size_t nx = plan_x_.size();
    const auto cell = [](const std::vector<double> &g, double v, size_t *k) {
      *k = 0;
      while (*k + 2 < g.size() && v > g[*k + 1]) ++*k;
      return std::fmin(1.0, std::fmax(0.0, (v - g[*k]) / (g[*k + 1] - g[*k])));
    };
    size_t i, j;
    const double r = cell(plan_x_, x, &i), t = cell(plan_z_, z, &j);
    const double *h0 = &plan_h_[j * nx], *h1 = &plan_h_[(j + 1) * nx];
    return (1 - t) * ((1 - r) * h0[i] + r * h0[i + 1]) + t * ((1 - r) * h1[i] + r * h1[i + 1]);
  }
  // -dim 3: the waste surface's height at (x, z): the plan grid's, or the plane's ys(x) risen at
  // -cover_deck_grade_z
  double ys3(const double X[3]) const {
    if (!plan_h_.empty()) return plan_height(X[0], X[2]);
    return ys(X[0]) + grade_z_ / 100.0 * X[2];
  }
  // -dim 3 (Scene::extruded_height): the plane's waste stretched to the surface at this z
  // (dy'/dy = ys3 / ys), what lies on it lifted with it
  double extruded_height(double x, double y, double z, double *stretch) const override {
    *stretch = 1;
    if (grade_z_ == 0 && plan_h_.empty()) return y;
    const double s = ys(x);
    const double lift = plan_h_.empty() ? grade_z_ / 100.0 * z : plan_height(x, z) - s;
    if (y > s) return y + lift;
    *stretch = 1 + lift / s;
    return y + lift * (y / s); // y = s: the same height as the layers' (y + lift)
  }
  // -dim 3: a round void of diameter `width` about (void_x_, void_z_) in plan
  bool in_void3(const double X[3], double width) const {
    if (width <= 0) return false;
    const double top = ys3(X) - void_depth_;
    return std::hypot(X[0] - void_x_, X[2] - void_z_) <= 0.5 * width && X[1] <= top &&
           X[1] >= top - void_h_;
  }
  bool in_void(const double X[DIM], double width) const {
    if (width <= 0) return false;
    const double top = ys(X[0]) - void_depth_;
    return std::fabs(X[0] - void_x_) <= 0.5 * width && X[1] <= top && X[1] >= top - void_h_;
  }
  // the waste's material at x, depth below the waste surface: a zone's, or the waste's
  int waste_material_at(double x, double depth) const {
    for (const Zone &z : zones_)
      if (z.contains(x, depth)) return z.mat;
    return 0;
  }
  // rows of a band of thickness d: whole rows no taller than the particle spacing
  PetscInt rows_in(double d) const {
    return d > 0 ? static_cast<PetscInt>(std::ceil(d / dxp_ - 1e-9)) : 0;
  }

  // The cover's own options block, read into raw lists (checked by ReadOptions).
  struct RawCoverOptions {
    PetscInt nsurf = 2 * kMaxList, nvoid = kMaxList, nz = 2, ng = 2, nl = kMaxList, nm = kMaxList,
             nzones = kMaxList;
    PetscBool surf_set = PETSC_FALSE, vw_set = PETSC_FALSE, zx_set = PETSC_FALSE,
              gr_set = PETSC_FALSE, l_set = PETSC_FALSE, m_set = PETSC_FALSE,
              zones_set = PETSC_FALSE;
    std::vector<double> surf = std::vector<double>(2 * kMaxList),
                        vw = std::vector<double>(kMaxList);
    double zx[2] = {0, 0}, gr[2] = {1, 1}, sc[2] = {0, 0};
    PetscInt nsc = 2;
    PetscBool sc_set = PETSC_FALSE;
    // -dim 3: the plan grid of waste surface heights
    PetscInt npx = kMaxPlan, npz = kMaxPlan, nph = kMaxPlan * kMaxPlan;
    PetscBool px_set = PETSC_FALSE, pz_set = PETSC_FALSE, ph_set = PETSC_FALSE;
    std::vector<double> px = std::vector<double>(kMaxPlan), pz = std::vector<double>(kMaxPlan),
                        ph = std::vector<double>(kMaxPlan * kMaxPlan);
    char *lnames[kMaxList], *mnames[kMaxList], *znames[kMaxList], wbuf[64];
  };
  PetscErrorCode ReadCoverBlock(Simulation &sim, RawCoverOptions &raw) {
    PetscFunctionBeginUser;
    PetscCall(PetscStrncpy(raw.wbuf, waste_mat_.c_str(), sizeof(raw.wbuf)));
    PetscOptionsBegin(sim.comm, "cover_", "Field-scale landfill cover (docs/cover.md)", nullptr);
    PetscCall(PmpmOptionsReal("-width", "Width of the model W (m)", nullptr, W_, &W_, nullptr));
    PetscCall(PmpmOptionsReal("-waste_height",
                              "Waste thickness at x = 0 (m; the deck, without a side slope)",
                              nullptr, Hw_, &Hw_, nullptr));
    PetscCall(PmpmOptionsReal("-deck_grade", "Top deck grade (per cent, rising to the right)",
                              nullptr, grade_, &grade_, nullptr));
    PetscCall(PmpmOptionsReal("-deck_grade_z",
                              "-dim 3: the waste surface's grade along z (per cent, rising with "
                              "z; its layers and membranes follow it)",
                              nullptr, grade_z_, &grade_z_, nullptr));
    PetscCall(PmpmOptionsReal("-slope_angle", "Side slope angle beta (degrees; 0: no side slope)",
                              nullptr, slope_deg_, &slope_deg_, nullptr));
    PetscCall(PmpmOptionsReal("-slope_length",
                              "Side slope length along the slope from toe to crest (m)", nullptr,
                              slope_len_, &slope_len_, nullptr));
    PetscCall(PmpmOptionsReal("-toe_x",
                              "x of the slope's toe (m); the ground left of it is level at "
                              "-cover_waste_height",
                              nullptr, toe_x_, &toe_x_, nullptr));
    PetscCall(PmpmOptionsRealArray("-surface",
                                   "Waste surface as a polyline x0,y0,x1,y1,... (m, x "
                                   "increasing from 0 to W; overrides the deck and slope)",
                                   nullptr, raw.surf.data(), &raw.nsurf, &raw.surf_set));
    PetscCall(PmpmOptionsRealArray(
        "-plan_x",
        "-dim 3: the plan grid's x nodes for -cover_plan_heights (m, increasing from 0 to W)",
        nullptr, raw.px.data(), &raw.npx, &raw.px_set));
    PetscCall(PmpmOptionsRealArray(
        "-plan_z",
        "-dim 3: the plan grid's z nodes for -cover_plan_heights (m, increasing from 0 to -depth)",
        nullptr, raw.pz.data(), &raw.npz, &raw.pz_set));
    PetscCall(PmpmOptionsRealArray(
        "-plan_heights",
        "-dim 3: the waste surface's height (m) at each plan node, row by row in z, x fastest "
        "(bilinear between nodes; a surface of any shape in plan, in place of -cover_surface, "
        "the deck and slope and -cover_deck_grade_z)",
        nullptr, raw.ph.data(), &raw.nph, &raw.ph_set));
    PetscCall(PetscOptionsStringArray("-layers", "Cover layers from the top down (names)", nullptr,
                                      raw.lnames, &raw.nl, &raw.l_set));
    PetscCall(PetscOptionsString("-waste_material", "Material of the waste (-mat_<name>_*)",
                                 nullptr, raw.wbuf, raw.wbuf, sizeof(raw.wbuf), nullptr));
    PetscCall(PetscOptionsStringArray("-zones",
                                      "Waste zones with their own material (names; each "
                                      "-cover_zone_<name>_material, _x, _depth)",
                                      nullptr, raw.znames, &raw.nzones, &raw.zones_set));
    PetscCall(PetscOptionsStringArray(
        "-membranes", "Geomembranes as chains (names; each -cover_membrane_<name>_under)", nullptr,
        raw.mnames, &raw.nm, &raw.m_set));
    PetscCall(PmpmOptionsReal("-shrink_total",
                              "Waste degradation: total volumetric shrinkage e_v of the zone "
                              "(log strain, 0..0.6; 0: none)",
                              nullptr, shrink_total_, &shrink_total_, nullptr));
    PetscCall(PmpmOptionsInt("-shrink_stages", "Stages the shrinkage is applied in (equal parts)",
                             nullptr, shrink_stages_, &shrink_stages_, nullptr));
    PetscCall(PmpmOptionsInt("-shrink_steps",
                             "Steps over which each stage's shrinkage is applied (0: auto, "
                             "25 wave transits of the model's height)",
                             nullptr, shrink_steps_, &shrink_steps_, nullptr));
    PetscCall(PmpmOptionsEnum("-shrink_mode",
                              "Shrinkage eigenstrain: vertical (e*_yy = -e_v) or isotropic "
                              "(-e_v/3 on xx, yy, zz)",
                              nullptr, ShrinkModeNames, (PetscEnum)sim.model.shrink.mode,
                              (PetscEnum *)&sim.model.shrink.mode, nullptr));
    PetscCall(PmpmOptionsRealArray("-shrink_x", "Degrading zone x_lo,x_hi (m; default all)",
                                   nullptr, raw.zx, &raw.nz, &raw.zx_set));
    PetscCall(PmpmOptionsRealArray("-shrink_centre",
                                   "-dim 3: X,Z of a degrading zone round in plan (m; with "
                                   "-cover_shrink_radius, in place of -cover_shrink_x)",
                                   nullptr, raw.sc, &raw.nsc, &raw.sc_set));
    PetscCall(PmpmOptionsReal("-shrink_radius",
                              "-dim 3: the round degrading zone's radius (m), > 0; the "
                              "shrinkage tapers over -cover_shrink_taper beyond it",
                              nullptr, sim.model.shrink.radius, &sim.model.shrink.radius, nullptr));
    PetscCall(PmpmOptionsReal("-shrink_taper",
                              "Shrinkage falls linearly to 0 over this distance outside the "
                              "zone (m)",
                              nullptr, sim.model.shrink.taper, &sim.model.shrink.taper, nullptr));
    PetscCall(PmpmOptionsRealArray("-shrink_grade",
                                   "Shrinkage factors at the waste base and top, bottom,top "
                                   "(linear with height; 1,1: uniform)",
                                   nullptr, raw.gr, &raw.ng, &raw.gr_set));
    PetscCall(PmpmOptionsReal("-void_x", "Void centre x (m)", nullptr, void_x_, &void_x_, nullptr));
    PetscCall(PmpmOptionsReal("-void_z",
                              "-dim 3: the round void's centre z (m; its widths are diameters)",
                              nullptr, void_z_, &void_z_, nullptr));
    PetscCall(PmpmOptionsRealArray("-void_widths",
                                   "Void width at each void stage (m, non-decreasing; none: no "
                                   "void)",
                                   nullptr, raw.vw.data(), &raw.nvoid, &raw.vw_set));
    PetscCall(
        PmpmOptionsReal("-void_height", "Void height (m)", nullptr, void_h_, &void_h_, nullptr));
    PetscCall(PmpmOptionsReal("-void_depth",
                              "Depth of the void's top below the waste surface (m; 0: it "
                              "touches the cover)",
                              nullptr, void_depth_, &void_depth_, nullptr));
    PetscCall(PmpmOptionsReal("-allowable_strain",
                              "Allowable membrane strain for the PASS / EXCEEDED verdict "
                              "(local design limits: a few per cent, docs/method.md section 7.2)",
                              nullptr, allowable_, &allowable_, nullptr));
    PetscCall(PmpmOptionsReal("-strain_gauge",
                              "Gauge length (m) over which the membrane's peak strain and tension "
                              "are read, >= one cell (0: one cell)",
                              nullptr, gauge_, &gauge_, nullptr));
    PetscCall(PetscOptionsBool(
        "-geostatic_paper",
        "Stage 0 with the membranes' faces bilateral (paper: friction, no separation); their own "
        "types from stage 1. Under gravity alone nothing separates, and velocity-based contact "
        "let the soft waste run ahead of the cover by 12 % of a cell",
        nullptr, geostatic_paper_, &geostatic_paper_, nullptr));
    PetscCall(PetscOptionsBool(
        "-geostatic",
        "Stage 0 is a separate geostatic stage: the membranes are laid unstrained after it and "
        "displacements are measured from it. 0: the sheets carry the strain of the first load "
        "and displacements are measured from the start (the seed paper's model)",
        nullptr, geostatic_, &geostatic_, nullptr));
    PetscOptionsEnd();
    PetscFunctionReturn(0);
  }

  // -dim 3: the plan grid of waste surface heights (the grid's extent is checked in Validate)
  PetscErrorCode ReadPlan(Simulation &sim, const RawCoverOptions &raw) {
    PetscFunctionBeginUser;
    if (!raw.px_set && !raw.pz_set && !raw.ph_set) PetscFunctionReturn(0);
    PmpmCheckInput(sim.set.dim == 3, sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_plan_x, -cover_plan_z and -cover_plan_heights are for -dim 3 (in 2D "
                   "the waste surface is -cover_surface)");
    PmpmCheckInput(raw.px_set && raw.pz_set && raw.ph_set, sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_plan_x, -cover_plan_z and -cover_plan_heights go together (the grid's "
                   "nodes and a height at each)");
    PmpmCheckInput(raw.npx >= 2 && raw.npz >= 2 && raw.nph == raw.npx * raw.npz, sim.comm,
                   PETSC_ERR_USER_INPUT,
                   "-cover_plan_heights needs a height at every plan node: %d x nodes "
                   "(-cover_plan_x) times %d z nodes (-cover_plan_z) = %d values, at least 2 of "
                   "each, got %d",
                   (int)raw.npx, (int)raw.npz, (int)(raw.npx * raw.npz), (int)raw.nph);
    // the plan grid is the whole surface: the plane's own surface options would be ignored
    const char *plane[] = {"-cover_surface",      "-cover_waste_height", "-cover_deck_grade",
                           "-cover_deck_grade_z", "-cover_slope_angle",  "-cover_slope_length",
                           "-cover_toe_x"};
    for (const char *o : plane) {
      PetscBool given = PETSC_FALSE;
      PetscCall(PetscOptionsHasName(nullptr, nullptr, o, &given));
      PmpmCheckInput(!given, sim.comm, PETSC_ERR_USER_INPUT,
                     "%s and -cover_plan_heights both give the waste surface: the plan grid is "
                     "the whole surface, drop %s",
                     o, o);
    }
    if (raw.npx < 2 || raw.npz < 2 || raw.nph != raw.npx * raw.npz)
      PetscFunctionReturn(0); // under -help the checks above let it through: no grid
    plan_x_.assign(raw.px.begin(), raw.px.begin() + raw.npx);
    plan_z_.assign(raw.pz.begin(), raw.pz.begin() + raw.npz);
    plan_h_.assign(raw.ph.begin(), raw.ph.begin() + raw.nph);
    PetscFunctionReturn(0);
  }

  PetscErrorCode ReadOptions(Simulation &sim) {
    std::vector<std::string> layer_names, mem_names, zone_names;
    RawCoverOptions raw;
    PetscFunctionBeginUser;
    PetscCall(ReadCoverBlock(sim, raw));
    waste_mat_ = raw.wbuf;
    if (raw.l_set) TakeNames(raw.lnames, raw.nl, layer_names);
    if (raw.m_set) TakeNames(raw.mnames, raw.nm, mem_names);
    if (raw.zones_set) TakeNames(raw.znames, raw.nzones, zone_names);
    void_w_.assign(raw.vw.begin(), raw.vw.begin() + (raw.vw_set ? raw.nvoid : 0));
    if (raw.surf_set) {
      PmpmCheckInput(raw.nsurf >= 4 && raw.nsurf % 2 == 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-cover_surface needs pairs x,y (at least 2 points), got %d numbers",
                     (int)raw.nsurf);
      surf_.assign(raw.surf.begin(), raw.surf.begin() + raw.nsurf);
    }
    PetscCall(ReadPlan(sim, raw));
    if (raw.zx_set) {
      PmpmCheckInput(raw.nz == 2 && raw.zx[1] > raw.zx[0], sim.comm, PETSC_ERR_USER_INPUT,
                     "-cover_shrink_x needs x_lo,x_hi with x_lo < x_hi");
      sim.model.shrink.x_lo = raw.zx[0];
      sim.model.shrink.x_hi = raw.zx[1];
    }
    const bool round_zone = raw.sc_set || sim.model.shrink.radius != 0;
    PmpmCheckInput(!round_zone || sim.set.dim == 3, sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_shrink_centre and -cover_shrink_radius are for -dim 3 (the run is 2D; "
                   "-cover_shrink_x bounds the zone in x)");
    PmpmCheckInput(!round_zone ||
                       (raw.sc_set && raw.nsc == 2 && sim.model.shrink.radius > 0 && !raw.zx_set),
                   sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_shrink_centre X,Z and -cover_shrink_radius R > 0 go together, in place "
                   "of -cover_shrink_x");
    if (round_zone) sim.model.shrink.cx = raw.sc[0], sim.model.shrink.cz = raw.sc[1];
    PmpmCheckInput(!raw.gr_set || raw.ng == 2, sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_shrink_grade needs bottom,top");
    sim.model.shrink.grade_bottom = raw.gr[0];
    sim.model.shrink.grade_top = raw.gr[1];
    PetscCall(ReadLayers(sim, layer_names));
    PetscCall(ReadMembranes(sim, mem_names));
    PetscCall(ReadZones(sim, zone_names));
    PetscFunctionReturn(0);
  }

  // Each waste zone's own prefixed options (-cover_zone_<name>_*).
  PetscErrorCode ReadZones(Simulation &sim, const std::vector<std::string> &zone_names) {
    PetscFunctionBeginUser;
    zones_.clear();
    for (const std::string &nm : zone_names) {
      Zone Z;
      Z.name = nm;
      char mat[64];
      PetscCall(PetscStrncpy(mat, nm.c_str(), sizeof(mat)));
      double x[2] = {0, 0}, d[2] = {0, 0}, z[2] = {0, 0}, c[2] = {0, 0}, R = 0;
      PetscInt nx = 2, nd = 2, nzr = 2, nc = 2;
      PetscBool xset = PETSC_FALSE, dset = PETSC_FALSE, zset = PETSC_FALSE, cset = PETSC_FALSE,
                rset = PETSC_FALSE;
      const std::string pre = "cover_zone_" + nm + "_";
      PetscOptionsBegin(sim.comm, pre.c_str(), ("Waste zone " + nm).c_str(), nullptr);
      PetscCall(PetscOptionsString("-material", "Material (-mat_<name>_*; default: the zone's)",
                                   nullptr, mat, mat, sizeof(mat), nullptr));
      PetscCall(PmpmOptionsRealArray("-x",
                                     "x_lo,x_hi (m; under -geometry axisymmetric the radii, so "
                                     "0,R is a disc)",
                                     nullptr, x, &nx, &xset));
      PetscCall(PmpmOptionsRealArray("-depth",
                                     "top,bottom: depths below the waste surface (m), 0 <= top "
                                     "< bottom",
                                     nullptr, d, &nd, &dset));
      PetscCall(PmpmOptionsRealArray("-z", "-dim 3: z_lo,z_hi (m; default the whole depth)",
                                     nullptr, z, &nzr, &zset));
      PetscCall(PmpmOptionsRealArray("-centre",
                                     "-dim 3: X,Z of a round zone's centre in plan (m; with "
                                     "_radius, in place of _x and _z)",
                                     nullptr, c, &nc, &cset));
      PetscCall(PmpmOptionsReal("-radius", "-dim 3: a round zone's radius in plan (m), > 0",
                                nullptr, R, &R, &rset));
      PetscOptionsEnd();
      const bool round = cset || rset;
      PmpmCheckInput(sim.set.dim == 3 || !(zset || round), sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sz, -%scentre and -%sradius are for -dim 3 (the run is 2D)", pre.c_str(),
                     pre.c_str(), pre.c_str());
      PmpmCheckInput(!round || (cset && nc == 2 && rset && R > 0 && !xset && !zset), sim.comm,
                     PETSC_ERR_USER_INPUT,
                     "-%scentre X,Z and -%sradius R > 0 go together, in place of -%sx and -%sz",
                     pre.c_str(), pre.c_str(), pre.c_str(), pre.c_str());
      PmpmCheckInput(round || (xset && nx == 2 && x[0] < x[1]), sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sx is required: x_lo,x_hi with x_lo < x_hi%s", pre.c_str(),
                     sim.set.dim == 3 ? " (or a round zone: _centre X,Z and _radius R)" : "");
      PmpmCheckInput(!zset || (nzr == 2 && z[0] < z[1]), sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sz needs z_lo,z_hi with z_lo < z_hi", pre.c_str());
      PmpmCheckInput(dset && nd == 2 && d[0] >= 0 && d[0] < d[1], sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sdepth is required: top,bottom below the waste surface with 0 <= top < "
                     "bottom",
                     pre.c_str());
      Z.material = mat;
      Z.x_lo = round ? c[0] - R : x[0];
      Z.x_hi = round ? c[0] + R : x[1];
      Z.d_top = d[0];
      Z.d_bottom = d[1];
      if (zset) Z.z_lo = z[0], Z.z_hi = z[1];
      if (round) Z.cx = c[0], Z.cz = c[1], Z.radius = R, Z.z_lo = c[1] - R, Z.z_hi = c[1] + R;
      // (their bounding boxes: two round zones may not touch even where the boxes do)
      for (const Zone &o : zones_)
        PmpmCheckInput(
            Z.x_hi <= o.x_lo || Z.x_lo >= o.x_hi || Z.d_bottom <= o.d_top ||
                Z.d_top >= o.d_bottom || Z.z_hi <= o.z_lo || Z.z_lo >= o.z_hi,
            sim.comm, PETSC_ERR_USER_INPUT,
            "-cover_zones: zones %s and %s overlap (give them disjoint -%sx, -%sdepth or "
            "(-dim 3) -%sz ranges)",
            o.name.c_str(), nm.c_str(), pre.c_str(), pre.c_str(), pre.c_str());
      zones_.push_back(Z);
    }
    PetscFunctionReturn(0);
  }

  // Each layer's own prefixed options (-cover_layer_<name>_*), bottom-up into layers_.
  PetscErrorCode ReadLayers(Simulation &sim, const std::vector<std::string> &layer_names) {
    PetscFunctionBeginUser;
    PmpmCheckInput(!layer_names.empty(), sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_layers needs at least one layer");
    layers_.clear();
    for (auto it = layer_names.rbegin(); it != layer_names.rend(); ++it) {
      Layer L;
      L.name = *it;
      char mat[64];
      PetscCall(PetscStrncpy(mat, L.name.c_str(), sizeof(mat)));
      double t = 0, te = -1;
      const std::string pre = "cover_layer_" + L.name + "_";
      PetscOptionsBegin(sim.comm, pre.c_str(), ("Cover layer " + L.name).c_str(), nullptr);
      PetscCall(
          PmpmOptionsReal("-thickness", "Vertical thickness (m), > 0", nullptr, t, &t, nullptr));
      PetscCall(PmpmOptionsReal("-thickness_end",
                                "Thickness at x = W (m; default: -thickness, uniform)", nullptr, te,
                                &te, nullptr));
      PetscCall(PetscOptionsString("-material", "Material (-mat_<name>_*; default: the layer's)",
                                   nullptr, mat, mat, sizeof(mat), nullptr));
      PetscOptionsEnd();
      PmpmCheckInput(t > 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sthickness is required and must be > 0 (got %g)", pre.c_str(), t);
      PmpmCheckInput(te < 0 || te > 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sthickness_end must be > 0 (got %g)", pre.c_str(), te);
      L.t_start = t;
      L.t_end = te > 0 ? te : t;
      L.mat = -1;
      layers_.push_back(L);
      layer_mats_.push_back(mat);
    }
    PetscFunctionReturn(0);
  }

  // Each membrane's own prefixed options (-cover_membrane_<name>_*), sorted by layer.
  PetscErrorCode ReadMembranes(Simulation &sim, const std::vector<std::string> &mem_names) {
    PetscFunctionBeginUser;
    mem_.clear();
    for (const std::string &nm : mem_names) {
      Membrane M;
      M.name = nm;
      M.material = nm;
      char under[64] = "", mat[64];
      PetscCall(PetscStrncpy(mat, nm.c_str(), sizeof(mat)));
      const std::string pre = "cover_membrane_" + nm + "_";
      PetscOptionsBegin(sim.comm, pre.c_str(), ("Cover membrane " + nm).c_str(), nullptr);
      PetscCall(PetscOptionsString("-under", "The layer the membrane lies under (its base)",
                                   nullptr, under, under, sizeof(under), nullptr));
      PetscCall(PmpmOptionsReal("-thickness", "Sheet thickness t (m), > 0", nullptr, M.thickness,
                                &M.thickness, nullptr));
      PetscCall(PetscOptionsString("-material", "Material (-mat_<name>_*; default: the membrane's)",
                                   nullptr, mat, mat, sizeof(mat), nullptr));
      PetscOptionsEnd();
      M.material = mat;
      M.under = under;
      M.layer = -1;
      for (size_t k = 0; k < layers_.size(); ++k)
        if (layers_[k].name == M.under) M.layer = static_cast<int>(k);
      PmpmCheckInput(M.layer >= 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sunder must name one of -cover_layers (got \"%s\")", pre.c_str(), under);
      PmpmCheckInput(M.thickness > 0, sim.comm, PETSC_ERR_USER_INPUT,
                     "-%sthickness is required and must be > 0 (got %g)", pre.c_str(), M.thickness);
      // two sheets at the base of one layer would lie on top of each other
      for (const Membrane &o : mem_)
        PmpmCheckInput(o.layer != M.layer, sim.comm, PETSC_ERR_USER_INPUT,
                       "-%sunder %s: membrane %s already lies under layer %s (one membrane per "
                       "layer; put it under another of -cover_layers)",
                       pre.c_str(), under, o.name.c_str(), under);
      mem_.push_back(M);
    }
    std::sort(mem_.begin(), mem_.end(),
              [](const Membrane &a, const Membrane &b) { return a.layer < b.layer; });
    PetscFunctionReturn(0);
  }
  std::vector<std::string> layer_mats_; // bottom-up, parallel to layers_

  // -dim 3: the plan grid spans the box, its heights leave at least half of the waste at every
  // node; the plane's profile (what is extruded) is then the highest height at each x node, so the
  // waste is only ever compressed along y (extruded_height) and the box is the plane's
  PetscErrorCode ValidatePlan(Simulation &sim) {
    const size_t nx = plan_x_.size(), nz = plan_z_.size();
    const double D = sim.set.depth;
    PetscFunctionBeginUser;
    const auto spans = [](const std::vector<double> &g, double L) {
      bool ok = std::fabs(g.front()) < 1e-12 && std::fabs(g.back() - L) <= 1e-9 * L;
      for (size_t k = 0; k + 1 < g.size(); ++k) ok = ok && g[k + 1] > g[k];
      return ok;
    };
    PmpmCheckInput(spans(plan_x_, W_), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_plan_x must increase from 0 to -cover_width %g (got %g .. %g)", W_,
                   plan_x_.front(), plan_x_.back());
    PmpmCheckInput(spans(plan_z_, D), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_plan_z must increase from 0 to -depth %g (got %g .. %g)", D,
                   plan_z_.front(), plan_z_.back());
    surf_.clear();
    for (size_t i = 0; i < nx; ++i) {
      double lo = 1e300, hi = 0;
      for (size_t j = 0; j < nz; ++j) {
        const double y = plan_h_[j * nx + i];
        PmpmCheckInput(y > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                       "-cover_plan_heights must be > 0 (node x = %g, z = %g: %g)", plan_x_[i],
                       plan_z_[j], y);
        lo = std::fmin(lo, y);
        hi = std::fmax(hi, y);
      }
      PmpmCheckInput(lo >= 0.5 * hi, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_plan_heights at x = %g range from %g to %g m along z: the lowest "
                     "must be at least half the highest (the waste is generated at the highest "
                     "and compressed along y to the surface)",
                     plan_x_[i], lo, hi);
      surf_.push_back(plan_x_[i]);
      surf_.push_back(hi);
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode Validate(Simulation &sim) {
    PetscFunctionBeginUser;
    PmpmCheckInput(W_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE, "-cover_width must be > 0 (got %g)",
                   W_);
    PmpmCheckInput(Hw_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_waste_height must be > 0 (got %g)", Hw_);
    if (!plan_h_.empty()) PetscCall(ValidatePlan(sim));
    if (surf_.empty()) {
      const double g = grade_ / 100.0;
      if (slope_len_ > 0) {
        PmpmCheckInput(slope_deg_ > 0 && slope_deg_ < 60, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                       "-cover_slope_angle must be in (0, 60) degrees with -cover_slope_length "
                       "(got %g)",
                       slope_deg_);
        const double xc = toe_x_ + slope_len_ * std::cos(slope_deg_ * kDeg);
        const double yc = Hw_ + slope_len_ * std::sin(slope_deg_ * kDeg);
        PmpmCheckInput(
            toe_x_ >= 0 && xc < W_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
            "-cover_toe_x %g and -cover_slope_length %g put the crest at x = %g m, beyond "
            "-cover_width %g",
            toe_x_, slope_len_, xc, W_);
        surf_ = {0, Hw_, toe_x_, Hw_, xc, yc, W_, yc + g * (W_ - xc)};
      } else {
        surf_ = {0, Hw_, W_, Hw_ + g * W_};
      }
    }
    const size_t n = surf_.size() / 2;
    PmpmCheckInput(std::fabs(surf_[0]) < 1e-12 && std::fabs(surf_[2 * n - 2] - W_) < 1e-9 * W_,
                   sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_surface must run from x = 0 to x = -cover_width %g", W_);
    for (size_t k = 0; k < n; ++k) {
      PmpmCheckInput(surf_[2 * k + 1] > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_surface: the waste surface must lie above y = 0 (point %d)", (int)k);
      if (k + 1 < n)
        PmpmCheckInput(surf_[2 * k + 2] > surf_[2 * k], sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                       "-cover_surface: x must increase (point %d)", (int)k + 1);
    }
    PmpmCheckInput(shrink_total_ >= 0 && shrink_total_ <= 0.6, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_shrink_total must be in [0, 0.6] (got %g)", shrink_total_);
    PmpmCheckInput(shrink_stages_ >= 0 && shrink_stages_ <= 100, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_shrink_stages must be in 0..100 (got %d)", (int)shrink_stages_);
    PmpmCheckInput(!(shrink_total_ > 0 && shrink_stages_ == 0), sim.comm, PETSC_ERR_USER_INPUT,
                   "-cover_shrink_total %g needs -cover_shrink_stages >= 1", shrink_total_);
    PmpmCheckInput(shrink_steps_ >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_shrink_steps must be >= 0");
    // -solver newton solves bonded chains only (newton.cpp checks their own faces): the
    // geostatic stage's paper faces would be a frictional interface in stage 0 (-help only lists)
    PetscBool help = PETSC_FALSE;
    PetscCall(PetscOptionsHasHelp(nullptr, &help));
    const bool friction = sim.solver->supports(SolverFeature::FrictionalFaces);
    PmpmCheckInput(help || friction || !(geostatic_paper_ && !mem_.empty()), sim.comm,
                   PETSC_ERR_SUP,
                   "-solver %s needs the membranes bonded in every stage, and "
                   "-cover_geostatic_paper (on by default) runs stage 0 with paper faces: add "
                   "-cover_geostatic_paper false (with -chain_<name>_interface bonded), or use "
                   "-solver relaxation",
                   sim.set.solver.c_str());
    PmpmCheckInput(sim.model.shrink.taper >= 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_shrink_taper must be >= 0");
    PmpmCheckInput(sim.model.shrink.grade_bottom >= 0 && sim.model.shrink.grade_top >= 0, sim.comm,
                   PETSC_ERR_ARG_OUTOFRANGE, "-cover_shrink_grade factors must be >= 0");
    for (size_t k = 0; k < void_w_.size(); ++k)
      PmpmCheckInput(void_w_[k] > 0 && (k == 0 || void_w_[k] >= void_w_[k - 1]), sim.comm,
                     PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_void_widths must be positive and non-decreasing (entry %d: %g)",
                     (int)k, void_w_[k]);
    dim3_ = sim.set.dim == 3; // its membranes strips of 3D sheet along z (extrude.cpp)
    if (grade_z_ != 0) {      // the waste stretched along y by ys3 / ys: at least half of it left
      PmpmCheckInput(dim3_, sim.comm, PETSC_ERR_ARG_INCOMP,
                     "-cover_deck_grade_z %g is for -dim 3 (a grade across the plane)", grade_z_);
      double lowest = 1e300;
      for (size_t k = 0; k < surf_.size() / 2; ++k) lowest = std::fmin(lowest, surf_[2 * k + 1]);
      PmpmCheckInput(std::fabs(grade_z_) <= 50 && grade_z_ / 100.0 * sim.set.depth > -0.5 * lowest,
                     sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_deck_grade_z must be in [-50, 50] per cent and leave at least half "
                     "of the waste at z = %g (-depth; the lowest waste surface is %g m; got %g)",
                     sim.set.depth, lowest, grade_z_);
    }
    if (!void_w_.empty() && dim3_) { // a round void about (x, z), widths its diameters
      const double w = void_w_.back(), D = sim.set.depth;
      round_ = true;
      PmpmCheckInput((void_x_ == 0 || void_x_ - w / 2 > 0) && void_x_ + w / 2 < W_ &&
                         (void_z_ == 0 || void_z_ - w / 2 > 0) && void_z_ + w / 2 < D,
                     sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-dim 3: -cover_void_x %g, -cover_void_z %g with diameter %g put the round "
                     "void outside the box (0, %g) x (0, %g) (a centre at 0 is on a symmetry "
                     "plane)",
                     void_x_, void_z_, w, W_, D);
    }
    if (!void_w_.empty() && !dim3_) {
      const double w = void_w_.back();
      // under -geometry axisymmetric a void at x = 0 is round: its width is the diameter
      round_ = sim.set.geometry == Geometry::Axisymmetric && void_x_ == 0;
      PmpmCheckInput(
          (round_ || void_x_ - w / 2 > 0) && void_x_ + w / 2 < W_, sim.comm,
          PETSC_ERR_ARG_OUTOFRANGE,
          "-cover_void_x %g with width %g puts the void outside (0, %g) (under -geometry "
          "axisymmetric, -cover_void_x 0 is a round void of that diameter)",
          void_x_, w, W_);
    }
    if (!void_w_.empty()) {
      const double at[3] = {void_x_, 0, void_z_}, thick = dim3_ ? ys3(at) : ys(void_x_);
      PmpmCheckInput(void_h_ > 0 && void_depth_ >= 0 && void_depth_ + void_h_ < thick, sim.comm,
                     PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_void_height %g (> 0) and -cover_void_depth %g (>= 0) must fit in the "
                     "waste (%g m thick at the void)",
                     void_h_, void_depth_, thick);
      PmpmCheckInput(void_w_.front() >= 2 * dxp_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_void_widths %g is less than two particle columns (%g m): refine "
                     "-cell_size",
                     void_w_.front(), 2 * dxp_);
    }
    for (const Zone &z : zones_) {
      if (z.radius > 0) {
        PmpmCheckInput(z.cx >= 0 && z.cx <= W_ && z.cz >= 0 && z.cz <= sim.set.depth, sim.comm,
                       PETSC_ERR_ARG_OUTOFRANGE,
                       "-cover_zone_%s_centre %g,%g must lie in the box [0, %g] x [0, %g]",
                       z.name.c_str(), z.cx, z.cz, W_, sim.set.depth);
        continue;
      }
      PmpmCheckInput(z.x_lo >= 0 && z.x_hi <= W_, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-cover_zone_%s_x %g,%g must lie in [0, -cover_width %g]", z.name.c_str(),
                     z.x_lo, z.x_hi, W_);
    }
    PmpmCheckInput(allowable_ > 0, sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-cover_allowable_strain must be > 0");
    PmpmCheckInput(
        gauge_ == 0 || gauge_ >= sim.set.h * (1 - 1e-9), sim.comm, PETSC_ERR_ARG_OUTOFRANGE,
        "-cover_strain_gauge %g m is shorter than a cell (%g m): the grid does not resolve "
        "strain over less (0 picks one cell)",
        gauge_, sim.set.h);
    if (gauge_ == 0) gauge_ = sim.set.h;
    PetscFunctionReturn(0);
  }

public:
  PetscErrorCode setup(Simulation &sim) override {
    PetscFunctionBeginUser;
    dxp_ = sim.set.h / sim.set.ppc;
    h_ = sim.set.h;
    PetscCall(ReadOptions(sim));
    PetscCall(Validate(sim));
    // the box: the width (a whole number of cells) and the highest cover top plus headroom
    PetscInt nW;
    PetscCall(CheckCells(sim.comm, "-cover_width", W_, sim.set.h, &nW));
    double top = 0;
    std::vector<double> b;
    for (size_t k = 0; k < surf_.size() / 2; ++k) {
      bands(surf_[2 * k], b);
      top = std::fmax(top, b.back());
    }
    if (grade_z_ > 0) top += grade_z_ / 100.0 * sim.set.depth; // -dim 3: risen along z
    sim.model.origin[0] = sim.model.origin[1] = 0;
    sim.model.ncell[0] = nW;
    sim.model.ncell[1] = static_cast<PetscInt>(std::ceil(top / sim.set.h - 1e-9)) + 2;
    sim.model.face[XMIN] = sim.model.face[XMAX] = FaceBC::Roller;
    sim.model.face[YMIN] = FaceBC::Fixed;
    // materials: the waste first, then each distinct layer material
    std::vector<std::string> names = {waste_mat_};
    for (size_t k = 0; k < layers_.size(); ++k) {
      auto it = std::find(names.begin(), names.end(), layer_mats_[k]);
      layers_[k].mat = static_cast<int>(it - names.begin());
      if (it == names.end()) names.push_back(layer_mats_[k]);
    }
    const size_t nlayer_mats = names.size();
    for (Zone &z : zones_) { // zones after the layers: a layer's material is not the waste's
      auto it = std::find(names.begin(), names.end(), z.material);
      PmpmCheckInput(it == names.begin() || it - names.begin() >= (long)nlayer_mats, sim.comm,
                     PETSC_ERR_USER_INPUT,
                     "-cover_zone_%s_material %s is a cover layer's material: give the zone its "
                     "own",
                     z.name.c_str(), z.material.c_str());
      z.mat = static_cast<int>(it - names.begin());
      if (it == names.end()) names.push_back(z.material);
    }
    sim.model.mats.resize(names.size());
    cover_mat_.assign(names.size(), 0);
    waste_mat_of_.assign(names.size(), 0);
    for (size_t m = 0; m < names.size(); ++m)
      PetscCall(MaterialFromOptions(sim.comm, names[m], sim.model.mats[m]));
    for (const Layer &l : layers_) cover_mat_[l.mat] = 1;
    waste_mat_of_[0] = 1;
    for (const Zone &z : zones_) waste_mat_of_[z.mat] = 1;
    PmpmCheckInput(
        !cover_mat_[0], sim.comm, PETSC_ERR_USER_INPUT,
        "-cover_waste_material %s is also a cover layer's material: give the waste its own",
        waste_mat_.c_str());
    // degradation: the waste and its zones shrink (rate-form materials only)
    sim.model.shrink.degrades.assign(waste_mat_of_.begin(), waste_mat_of_.end());
    sim.model.shrink.y_lo = 0;
    sim.model.shrink.y_hi = 1e300;
    if (shrink_total_ > 0) {
      double ytop = 0;
      for (size_t k = 0; k < surf_.size() / 2; ++k) ytop = std::fmax(ytop, surf_[2 * k + 1]);
      if (grade_z_ > 0) ytop += grade_z_ / 100.0 * sim.set.depth; // -dim 3: risen along z
      sim.model.shrink.y_hi = ytop; // grading is linear from the base to the highest waste surface
      for (size_t m = 0; m < names.size(); ++m)
        PmpmCheckInput(!waste_mat_of_[m] || sim.model.mats[m].model->rate_form(), sim.comm,
                       PETSC_ERR_SUP,
                       "-cover_shrink_total needs rate-form waste materials (%s), not "
                       "-mat_%s_model %s",
                       MaterialLawList(&MaterialLaw::rate_form).c_str(), names[m].c_str(),
                       sim.model.mats[m].model->model());
    }
    // membranes: chains at the base of their layers, ends half a point spacing inside the walls
    // (under -geometry axisymmetric the first point on the axis: a sheet without a hole)
    for (const Membrane &M : mem_) {
      ChainSpec cs;
      cs.name = M.name;
      cs.material = M.material;
      cs.thickness = M.thickness;
      const double e = 0.5 * sim.model.chain_spacing * sim.set.h;
      // -dim 3: from wall to wall, its edges on the faces' rollers (extrude.cpp)
      const double e0 = sim.set.geometry == Geometry::Axisymmetric || dim3_ ? 0.0 : e;
      const double e1 = dim3_ ? 0.0 : e;
      cs.line = {e0, layer_base(M.layer, e0)};
      for (size_t k = 1; k + 1 < surf_.size() / 2; ++k)
        if (surf_[2 * k] > e && surf_[2 * k] < W_ - e) {
          cs.line.push_back(surf_[2 * k]);
          cs.line.push_back(layer_base(M.layer, surf_[2 * k]));
        }
      cs.line.push_back(W_ - e1);
      cs.line.push_back(layer_base(M.layer, W_ - e1));
      sim.model.chain_specs.push_back(cs);
    }
    // particle columns and their ids: column i holds at most R_ rows
    ncol_ = static_cast<PetscInt>(std::llround(W_ / dxp_));
    R_ = sim.model.ncell[1] * sim.set.ppc + static_cast<PetscInt>(layers_.size()) + 2;
    surface_pid_.clear();
    for (PetscInt i = 0; i < ncol_; ++i) {
      bands((i + 0.5) * dxp_, b);
      PetscInt rows = 0;
      for (size_t k = 0; k + 1 < b.size(); ++k) rows += rows_in(b[k + 1] - b[k]);
      surface_pid_.push_back(i * R_ + rows - 1);
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode generate(Simulation &sim, ParticleList &out) override {
    PetscFunctionBeginUser;
    std::vector<double> b;
    for (PetscInt i = 0; i < ncol_; ++i) {
      const double x = (i + 0.5) * dxp_;
      bands(x, b);
      PetscInt row = 0;
      for (size_t k = 0; k + 1 < b.size(); ++k) {
        const double d = b[k + 1] - b[k];
        const PetscInt n = rows_in(d);
        for (PetscInt r = 0; r < n; ++r, ++row) {
          ParticleInit q{};
          const double dy = d / n;
          q.x[0] = x;
          q.x[1] = b[k] + (r + 0.5) * dy;
          // (-dim 3: the zones are decided per extruded particle, extruded_material)
          const int mat =
              k == 0 ? (dim3_ ? 0 : waste_material_at(x, b[1] - q.x[1])) : layers_[k - 1].mat;
          const PetscInt c[DIM] = {static_cast<PetscInt>(std::floor(q.x[0] / sim.set.h)),
                                   static_cast<PetscInt>(std::floor(q.x[1] / sim.set.h))};
          if (!sim.grid.owns_cell(c)) continue;
          q.lp[0] = 0.5 * dxp_;
          q.lp[1] = 0.5 * dy;
          q.vol = dxp_ * dy;
          q.mat = mat;
          q.density = sim.model.mats[mat].density;
          q.gamma = sim.model.mats[mat].gamma;
          q.pid = i * R_ + row;
          out.push_back(q);
        }
      }
    }
    PetscFunctionReturn(0);
  }

  bool extrudes() const override { return true; }
  bool extrudes_chains() const override { return true; } // -dim 3: strips of 3D sheet
  // -dim 3: a waste particle in a zone (bounded in z, or round in plan) takes its material
  int extruded_material(const double X[3], int mat) const override {
    if (mat != 0) return mat; // the waste's particles only
    for (const Zone &z : zones_)
      if (z.contains3(X, ys3(X) - X[1])) return z.mat;
    return mat;
  }

  PetscInt stages() const override {
    return (shrink_total_ > 0 ? shrink_stages_ : 0) + static_cast<PetscInt>(void_w_.size());
  }

  StageChange stage_change(PetscInt k) const override {
    const PetscInt ns = shrink_total_ > 0 ? shrink_stages_ : 0;
    return k == 0 ? StageChange::Loads : k <= ns ? StageChange::Shrink : StageChange::Void;
  }

  PetscErrorCode begin_stage(Simulation &sim, PetscInt k) override {
    PetscFunctionBeginUser;
    if (k == 0) {
      if (!geostatic_) { // displacements from the start: the sheets carry the first load too
        double none;
        PetscCall(SurfaceSettlement(sim, true, &none));
        if (!sim.chains.empty()) sheet_ref_ = sim.chains.back().x;
        if (!sim.sheets.empty()) sheet_ref_ = sim.sheets.back().x;
      }
      face_types_.clear();
      for (Chain &c : sim.chains) {
        face_types_.push_back(c.top.type);
        face_types_.push_back(c.bottom.type);
        if (geostatic_paper_) c.top.type = c.bottom.type = FaceType::Paper;
      }
      for (Sheet &c : sim.sheets) { // -dim 3: the same for the sheets
        face_types_.push_back(c.top.type);
        face_types_.push_back(c.bottom.type);
        if (geostatic_paper_) c.top.type = c.bottom.type = FaceType::Paper;
      }
      PetscFunctionReturn(0);
    }
    if (k == 1) {
      for (size_t i = 0; i < sim.chains.size(); ++i) {
        sim.chains[i].top.type = face_types_[2 * i];
        sim.chains[i].bottom.type = face_types_[2 * i + 1];
      }
      for (size_t i = 0; i < sim.sheets.size(); ++i) {
        sim.sheets[i].top.type = face_types_[2 * i];
        sim.sheets[i].bottom.type = face_types_[2 * i + 1];
      }
    }
    const PetscInt ns = shrink_total_ > 0 ? shrink_stages_ : 0;
    if (k <= ns) {
      sim.stage_shrink = shrink_total_ / double(ns);
      // apply it over many wave transits of the model's height (a transit is about
      // ncell / cfl steps): applied in 4 transits the waste ran ahead of the cover, which
      // velocity-based contact then held a gap above (4 m column, e_v = 0.03: settlement 28 %
      // short); in 25 transits the cover follows within 0.2 %
      PetscInt steps = shrink_steps_;
      if (steps == 0) steps = static_cast<PetscInt>(25 * sim.model.ncell[1] / sim.set.cfl);
      sim.stage_ramp = steps;
      cum_shrink_ += sim.stage_shrink;
      PetscFunctionReturn(0);
    }
    // a void stage: remove the waste particles inside the void's current width
    void_now_ = void_w_[k - ns - 1];
    ParticleView P;
    std::vector<PetscInt> gone;
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p)
      if (waste_mat_of_[P.mat[p]] &&
          (dim3_ ? in_void3(P.x0 + 3 * p, void_now_) : in_void(P.x0 + p * DIM, void_now_)))
        gone.push_back(p);
    PetscCall(ParticlesRestoreView(sim.parts, P));
    for (auto it = gone.rbegin(); it != gone.rend(); ++it)
      PetscCall(DMSwarmRemovePointAtIndex(sim.parts.sw, *it));
    PetscCall(SimulationIndexParticles(sim));
    if (dim3_) {
      void_eff_ = RoundVoidDiameter(sim);
      PetscFunctionReturn(0);
    }
    // the void's width as the particles see it: whole columns
    PetscInt ncols = 0;
    for (PetscInt i = 0; i < ncol_; ++i)
      ncols += std::fabs((i + 0.5) * dxp_ - void_x_) <= 0.5 * void_now_;
    void_eff_ = (round_ ? 2.0 : 1.0) * ncols * dxp_; // round: the columns are the radius
    PetscFunctionReturn(0);
  }

  // -dim 3: the round void's diameter as the particles see it: the plan area of the particle
  // columns whose centres lie inside it, over the share of its circle that lies in the box (a
  // quarter for a void centred on two symmetry planes), read as a circle's.
  double RoundVoidDiameter(const Simulation &sim) const {
    const double dzp = sim.set.h / sim.set.ppc, D = void_now_;
    double cols = 0, inside = 0;
    const PetscInt nx = ncol_, nz = static_cast<PetscInt>(std::llround(sim.set.depth / dzp));
    for (PetscInt i = 0; i < nx; ++i)
      for (PetscInt k = 0; k < nz; ++k)
        cols += std::hypot((i + 0.5) * dxp_ - void_x_, (k + 0.5) * dzp - void_z_) <= 0.5 * D;
    const int n = 400; // the circle's share in the box, by a fine sampling of its square
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double u = ((a + 0.5) / n - 0.5) * D, v = ((b + 0.5) / n - 0.5) * D;
        const double x = void_x_ + u, z = void_z_ + v;
        inside += std::hypot(u, v) <= 0.5 * D && x >= 0 && x <= W_ && z >= 0 && z <= sim.set.depth;
      }
    const double share = inside / (kPi / 4 * n * n);
    return 2 * std::sqrt(cols * dxp_ * dzp / share / kPi);
  }

  // Surface settlement per column relative to stage 0 (rank 0): gather the top particles.
  // With reference, the current heights become the reference instead (smax = 0).
  PetscErrorCode SurfaceSettlement(Simulation &sim, bool reference, double *smax) {
    ParticleView P;
    std::vector<double> mine;
    PetscFunctionBeginUser;
    PetscCall(ParticlesGetView(sim.parts, P));
    if (dim3_) { // the extruded ids: the plane's id x particles along z + the z index
      const PetscInt nz = sim.grid3.ncell[2] * sim.set.ppc;
      for (PetscInt p = 0; p < P.n; ++p)
        if (std::binary_search(surface_pid_.begin(), surface_pid_.end(), P.pid[p] / nz)) {
          mine.push_back(static_cast<double>(P.pid[p]));
          mine.push_back(P.x[3 * p + 1]);
        }
    }
    for (PetscInt p = 0; p < P.n && !dim3_; ++p)
      if (std::binary_search(surface_pid_.begin(), surface_pid_.end(), P.pid[p])) {
        mine.push_back(static_cast<double>(P.pid[p]));
        mine.push_back(P.x[p * DIM + 1]);
      }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    std::vector<double> all;
    PetscCall(GatherToRoot(sim.comm, mine, all));
    *smax = 0;
    for (size_t j = 0; j + 1 < all.size(); j += 2) {
      const PetscInt id = static_cast<PetscInt>(all[j]);
      if (reference)
        surf_ref_[id] = all[j + 1];
      else if (surf_ref_.count(id))
        *smax = std::fmax(*smax, surf_ref_[id] - all[j + 1]);
    }
    PetscFunctionReturn(0);
  }

  // Largest plastic strain and tensile strain in the cover layers (global).
  PetscErrorCode CoverStrains(Simulation &sim, std::vector<double> &layer_tension, double *epmax) {
    ParticleView P;
    PetscFunctionBeginUser;
    std::vector<double> mx(sim.model.mats.size() + 1, 0.0);
    PetscCall(ParticlesGetView(sim.parts, P));
    for (PetscInt p = 0; p < P.n; ++p) {
      const int m = static_cast<int>(P.mat[p]);
      if (!cover_mat_[m]) continue;
      mx[m] = std::fmax(mx[m], dim3_ ? max_principal_strain3(P.F + 9 * p)
                                     : max_principal_strain(P.F + p * DIM * DIM));
      mx.back() = std::fmax(mx.back(), P.eps_p[p]);
    }
    PetscCall(ParticlesRestoreView(sim.parts, P));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mx.data(), static_cast<int>(mx.size()), MPI_DOUBLE,
                               MPI_MAX, sim.comm));
    layer_tension.assign(mx.begin(), mx.end() - 1);
    *epmax = mx.back();
    PetscFunctionReturn(0);
  }

  // stages.csv: the record of every stage so far
  PetscErrorCode WriteStages(Simulation &sim) {
    PetscFunctionBeginUser;
    PetscCall(OutputPrepareDirectory(sim));
    if (sim.rank == 0) {
      const std::string path = sim.set.output_dir + "/stages.csv";
      FILE *f = std::fopen((path + ".tmp").c_str(), "w");
      PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path.c_str());
      std::fprintf(
          f,
          "stage,kind,shrinkage,void_width,surface_settlement,membrane_settlement,"
          "differential_settlement,peak_strain,peak_strain_x,peak_tension,max_slip,"
          "cover_max_eps_p,void_pressure,void_sag,steps,ratio,converged,verdict,wall_seconds%s\n",
          dim3_ ? ",peak_strain_minor,peak_strain_z" : "");
      // each stage's own verdict on its peak strain (no error estimate per stage): from the
      // first stage that stopped at its cap on, NOT CONVERGED
      bool capped = false;
      for (const StageRow &q : rows_) {
        capped = capped || !q.converged;
        const Verdict v = capped         ? Verdict::NotConverged
                          : mem_.empty() ? Verdict::None
                                         : judge(q.peak_strain, 0.0, allowable_);
        std::fprintf(f,
                     "%d,%s,%.6g,%.6g,%.8e,%.8e,%.8e,%.8e,%.6g,%.8e,%.8e,%.8e,%.8e,%.8e,%d,%.3e,%d,"
                     "%s,%.3f",
                     q.stage, q.kind.c_str(), q.shrink, q.void_width, q.surface_settlement,
                     q.membrane_settlement, q.differential, q.peak_strain, q.peak_strain_x,
                     q.peak_tension, q.slip, q.cover_eps_p, q.void_pressure, q.void_sag,
                     (int)q.steps, q.ratio, q.converged ? 1 : 0, verdict_name(v), q.wall);
        if (dim3_) // the biaxial state at the peak and its z
          std::fprintf(f, ",%.8e,%.6g", q.peak_strain_minor, q.peak_strain_z);
        std::fprintf(f, "\n");
      }
      std::fclose(f);
    }
    PetscCall(OutputCommit(sim, "stages.csv"));
    PetscFunctionReturn(0);
  }

  // -dim 3: a stage's membrane answers from the top-most sheet: settlement since the reference,
  // the largest slip on either face, the peak principal strain of a point (sheet.hpp,
  // sheet_peak_principal) with the minor strain there, and over the void its pressure and sag.
  void SheetStage(const Sheet &s, StageRow &r) const {
    double smax = -1e300, smin = 1e300;
    for (int i = 0; i < s.n; ++i) {
      const double d = sheet_ref_[3 * i + 1] - s.x[3 * i + 1];
      smax = std::fmax(smax, d);
      smin = std::fmin(smin, d);
      r.slip = std::fmax(r.slip, std::fmax(SlipOf(s.slip_top, i), SlipOf(s.slip_bot, i)));
    }
    r.membrane_settlement = smax;
    r.differential = smax - smin;
    const PeakPrincipal pk = sheet_peak_principal(s);
    r.peak_strain = pk.strain1;
    r.peak_strain_minor = pk.strain2;
    r.peak_strain_x = s.x0[3 * pk.point];
    r.peak_strain_z = s.x0[3 * pk.point + 2];
    r.peak_tension = pk.tension1;
    if (r.void_width > 0) VoidPressureSag3(s, r.void_width, &r.void_pressure, &r.void_sag);
  }
  static double SlipOf(const std::vector<double> &sl, int i) {
    return std::sqrt(sl[3 * i] * sl[3 * i] + sl[3 * i + 1] * sl[3 * i + 1] +
                     sl[3 * i + 2] * sl[3 * i + 2]);
  }
  // -dim 3: the mean contact pressure on the sheet's top over the round void (area-weighted over
  // its points inside it), and its sag: the settlement at the point nearest the void's centre less
  // the mean at the points within a cell of its rim.
  void VoidPressureSag3(const Sheet &s, double B, double *p, double *sag) const {
    double a = 0, sr = 0, nr = 0, dc = 1e300, sc = 0;
    const double h = h_;
    *p = 0;
    for (int i = 0; i < s.n; ++i) {
      const double r = std::hypot(s.x0[3 * i] - void_x_, s.x0[3 * i + 2] - void_z_);
      const double d = sheet_ref_[3 * i + 1] - s.x[3 * i + 1];
      if (r < 0.5 * B) *p += s.p_top[i] * s.area[i], a += s.area[i];
      if (r < dc) dc = r, sc = d;
      if (std::fabs(r - 0.5 * B) < 0.5 * h) sr += d, nr += 1;
    }
    *p = a > 0 ? *p / a : 0;
    *sag = nr > 0 ? sc - sr / nr : 0;
  }

  PetscErrorCode end_stage(Simulation &sim, PetscInt k) override {
    PetscFunctionBeginUser;
    if (k == 0 && geostatic_) { // displacements from here on
      if (!sim.chains.empty()) sheet_ref_ = sim.chains.back().x;
      if (!sim.sheets.empty()) sheet_ref_ = sim.sheets.back().x;
    }
    StageRow r;
    r.stage = static_cast<int>(k);
    const PetscInt ns = shrink_total_ > 0 ? shrink_stages_ : 0;
    r.kind = k == 0 ? (geostatic_ ? "geostatic" : "load") : k <= ns ? "shrink" : "void";
    r.shrink = cum_shrink_;
    r.void_width = void_now_ > 0 ? void_eff_ : 0;
    PetscCall(SurfaceSettlement(sim, k == 0 && geostatic_, &r.surface_settlement));
    std::vector<double> lt;
    PetscCall(CoverStrains(sim, lt, &r.cover_eps_p));
    if (!sim.chains.empty()) { // the top-most membrane is the one reported per stage
      const Chain &c = sim.chains.back();
      const std::vector<double> &ref = sheet_ref_;
      double smax = -1e300, smin = 1e300;
      for (int i = 0; i < c.n; ++i) {
        const double s = ref[i * DIM + 1] - c.x[i * DIM + 1];
        smax = std::fmax(smax, s);
        smin = std::fmin(smin, s);
        r.slip = std::fmax(r.slip, std::fmax(std::fabs(c.slip_top[i]), std::fabs(c.slip_bot[i])));
      }
      r.membrane_settlement = smax;
      r.differential = smax - smin;
      const SheetPeak pk = sheet_peak(c, gauge_);
      r.peak_strain = pk.strain;
      r.peak_strain_x = pk.strain_x;
      r.peak_tension = pk.tension;
      if (r.void_width > 0) VoidPressureSag(c, r.void_width, &r.void_pressure, &r.void_sag);
    }
    if (!sim.sheets.empty()) SheetStage(sim.sheets.back(), r); // -dim 3
    r.steps = sim.run.stage_step;
    r.ratio = sim.run.ratio;
    r.wall = sim.run.stage_seconds;
    r.converged = sim.run.converged;
    rows_.push_back(r);
    // stage 0 is recorded as it is (a veneer's slip under its own weight, the strain the cover's
    // weight gave); then the membranes are laid unstrained on the settled ground
    if (k == 0 && geostatic_) {
      for (Chain &c : sim.chains) chain_lay(c);
      for (Sheet &c : sim.sheets) sheet_lay(c);
    }
    // the record so far, complete after every stage; a frame for ParaView
    PetscCall(WriteStages(sim));
    if (sim.nstages > 0) { // one frame per stage (stage 0 alone is particles.h5)
      char name[64];
      snprintf(name, sizeof(name), "series/stage_%03d.h5", (int)k);
      PetscCall(OutputParticles(sim, name));
    }
    if (!sim.set.quiet)
      PetscCall(PetscPrintf(sim.comm,
                            "stage %d (%s): surface settlement %.4g m, membrane settlement %.4g m "
                            "(differential %.4g m), peak membrane strain %.3f %%, tension %.4g "
                            "N/m, %d steps\n",
                            r.stage, r.kind.c_str(), r.surface_settlement, r.membrane_settlement,
                            r.differential, 100 * r.peak_strain, r.peak_tension, (int)r.steps));
    PetscFunctionReturn(0);
  }

  // What changes during a run: the chains' own face types (stage 0 may run them as paper), the
  // shrinkage and void applied so far, the stage-0 references and the stage record.
  static constexpr int kRow = 18;
  // a stage row's kind, checkpointed as its index here (the order is the file format)
  static constexpr const char *kStageKinds[4] = {"geostatic", "shrink", "void", "load"};
  PetscErrorCode checkpoint_write(Simulation &, PetscViewer v) override {
    PetscFunctionBeginUser;
    std::vector<double> ft, ref, rows;
    for (FaceType t : face_types_) ft.push_back(static_cast<double>(t));
    for (const auto &q : surf_ref_) {
      ref.push_back(static_cast<double>(q.first));
      ref.push_back(q.second);
    }
    for (const StageRow &q : rows_) {
      const double kind =
          static_cast<double>(std::find(std::begin(kStageKinds), std::end(kStageKinds), q.kind) -
                              std::begin(kStageKinds));
      const double row[kRow] = {double(q.stage),
                                kind,
                                q.shrink,
                                q.void_width,
                                q.surface_settlement,
                                q.membrane_settlement,
                                q.differential,
                                q.peak_strain,
                                q.peak_strain_x,
                                q.peak_tension,
                                q.slip,
                                q.cover_eps_p,
                                q.void_pressure,
                                q.void_sag,
                                q.ratio,
                                q.wall,
                                double(q.steps),
                                q.converged ? 1.0 : 0.0};
      rows.insert(rows.end(), row, row + kRow);
    }
    PetscCall(CheckpointWriteArray(v, "face_types", ft));
    PetscCall(CheckpointWriteArray(v, "surface_reference", ref)); // rank 0's
    PetscCall(CheckpointWriteArray(v, "sheet_reference", sheet_ref_));
    PetscCall(CheckpointWriteArray(v, "stage_rows", rows));
    if (dim3_) { // -dim 3: each row's minor strain and z at the peak
      std::vector<double> r3;
      for (const StageRow &q : rows_) r3.insert(r3.end(), {q.peak_strain_minor, q.peak_strain_z});
      PetscCall(CheckpointWriteArray(v, "stage_rows_3d", r3));
    }
    PetscCall(CheckpointWriteReal(v, "shrinkage", cum_shrink_));
    PetscCall(CheckpointWriteReal(v, "void_width", void_now_));
    PetscCall(CheckpointWriteReal(v, "void_width_effective", void_eff_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode checkpoint_read(Simulation &sim, PetscViewer v) override {
    std::vector<double> ft, ref, rows;
    PetscFunctionBeginUser;
    PetscCall(CheckpointReadArray(v, "face_types", ft));
    PetscCall(CheckpointReadArray(v, "surface_reference", ref));
    PetscCall(CheckpointReadArray(v, "sheet_reference", sheet_ref_));
    PetscCall(CheckpointReadArray(v, "stage_rows", rows));
    PetscCall(CheckpointReadReal(v, "shrinkage", &cum_shrink_));
    PetscCall(CheckpointReadReal(v, "void_width", &void_now_));
    PetscCall(CheckpointReadReal(v, "void_width_effective", &void_eff_));
    PetscCheck(rows.size() % kRow == 0 && ref.size() % 2 == 0, sim.comm, PETSC_ERR_FILE_UNEXPECTED,
               "-restart %s: damaged checkpoint (the cover's state)", sim.set.restart.c_str());
    face_types_.clear();
    for (double t : ft) face_types_.push_back(static_cast<FaceType>(static_cast<int>(t)));
    surf_ref_.clear();
    if (sim.rank == 0) // the surface is gathered on rank 0
      for (size_t j = 0; j < ref.size(); j += 2)
        surf_ref_[static_cast<PetscInt>(ref[j])] = ref[j + 1];
    rows_.clear();
    for (size_t j = 0; j < rows.size(); j += kRow) {
      const double *q = &rows[j];
      StageRow r;
      r.stage = static_cast<int>(q[0]);
      r.kind = kStageKinds[static_cast<int>(q[1])];
      r.shrink = q[2];
      r.void_width = q[3];
      r.surface_settlement = q[4];
      r.membrane_settlement = q[5];
      r.differential = q[6];
      r.peak_strain = q[7];
      r.peak_strain_x = q[8];
      r.peak_tension = q[9];
      r.slip = q[10];
      r.cover_eps_p = q[11];
      r.void_pressure = q[12];
      r.void_sag = q[13];
      r.ratio = q[14];
      r.wall = q[15];
      r.steps = static_cast<PetscInt>(q[16]);
      r.converged = q[17] != 0;
      rows_.push_back(r);
    }
    if (dim3_) {
      std::vector<double> r3;
      PetscCall(CheckpointReadArray(v, "stage_rows_3d", r3));
      PetscCheck(r3.size() == 2 * rows_.size(), sim.comm, PETSC_ERR_FILE_UNEXPECTED,
                 "-restart %s: damaged checkpoint (the cover's 3D stage rows)",
                 sim.set.restart.c_str());
      for (size_t j = 0; j < rows_.size(); ++j) {
        rows_[j].peak_strain_minor = r3[2 * j];
        rows_[j].peak_strain_z = r3[2 * j + 1];
      }
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode results(Simulation &sim, std::string &json) override {
    PetscFunctionBeginUser;
    std::vector<double> lt;
    double ep = 0;
    PetscCall(CoverStrains(sim, lt, &ep));
    const char *sep = ",\n    ";
    std::string layers = "{";
    for (size_t k = layers_.size(); k-- > 0;) {
      layers += "\"" + layers_[k].name + "\": {" +
                json_kv("max_tensile_strain", lt[layers_[k].mat]) + "}";
      if (k > 0) layers += ", ";
    }
    layers += "}";
    json = json_kv("stages", double(rows_.size() - 1)) + sep + json_kv("cover_max_eps_p", ep) +
           sep + "\"layers\": " + layers;
    json += sep + json_kv("surface_settlement", rows_.back().surface_settlement);
    if (!sim.chains.empty()) {
      const Chain &c = sim.chains.back();
      const SheetPeak pk = sheet_peak(c, gauge_);
      // the design answer is the largest peak over the stages (OverStages)
      double peak_hist = pk.strain, tension_hist = pk.tension;
      int peak_stage = rows_.back().stage;
      OverStages(peak_hist, tension_hist, peak_stage);
      int it = 0, ib = 0;
      double slack_len = 0, slack_lo = 1e300, slack_hi = -1e300;
      for (int j = 0; j + 1 < c.n; ++j)
        if (c.slack[j]) {
          slack_len += c.l0[j];
          slack_lo = std::fmin(slack_lo, c.x0[j * DIM]);
          slack_hi = std::fmax(slack_hi, c.x0[(j + 1) * DIM]);
        }
      for (int i = 0; i < c.n; ++i) {
        if (std::fabs(c.slip_top[i]) > std::fabs(c.slip_top[it])) it = i;
        if (std::fabs(c.slip_bot[i]) > std::fabs(c.slip_bot[ib])) ib = i;
      }
      json += sep + std::string("\"membrane\": {") + "\"name\": \"" + c.name + "\", " +
              json_kv("peak_strain", pk.strain) + ", " + json_kv("peak_strain_x", pk.strain_x) +
              ", " + json_kv("strain_gauge", gauge_) + ", " +
              json_kv("peak_strain_segment", pk.strain_segment) + ", " +
              json_kv("peak_strain_over_stages", peak_hist) + ", " +
              json_kv("peak_strain_stage", double(peak_stage)) + ", " +
              json_kv("peak_tension", pk.tension) + ", " + json_kv("peak_tension_x", pk.tension_x) +
              ", " + json_kv("allowable_strain", allowable_) + ", " +
              json_kv("slack_length", slack_len) + ", " +
              json_kv("slack_x_min", slack_len > 0 ? slack_lo : 0.0) + ", " +
              json_kv("slack_x_max", slack_len > 0 ? slack_hi : 0.0) + ", " +
              json_kv("max_slip_top", std::fabs(c.slip_top[it])) + ", " +
              json_kv("max_slip_top_x", c.x0[it * DIM]) + ", " +
              json_kv("max_slip_bottom", std::fabs(c.slip_bot[ib])) + ", " +
              json_kv("max_slip_bottom_x", c.x0[ib * DIM]) + ", " +
              json_kv("membrane_settlement", rows_.back().membrane_settlement) + ", " +
              json_kv("differential_settlement", rows_.back().differential) + "}";
      char line[384];
      snprintf(line, sizeof(line),
               "membrane %s: peak strain %.3f %% at x = %.2f m (over a %.3g m gauge), tension "
               "%.4g kN/m at x = %.2f m",
               c.name.c_str(), 100 * pk.strain, pk.strain_x, gauge_, pk.tension / 1e3,
               pk.tension_x);
      where_ = line;
      SetDesign(peak_hist, tension_hist, peak_stage, "");
      double p = 0, sag = 0;
      if (!void_w_.empty() && void_eff_ > 0) VoidPressureSag(c, void_eff_, &p, &sag);
      PetscCall(ComparisonJson(sim, c.law.J, c.thickness, c.top.mu, p, sag, json));
    }
    if (!sim.sheets.empty()) PetscCall(SheetResults(sim, json)); // -dim 3
    PetscFunctionReturn(0);
  }

  // The design answer is the largest peak over the stages: a sheet strained past its allowable at
  // one stage has failed there, even if a later stage unloads it (a round void widening under a
  // plug of cover does: docs/cover.md, "A round void"). peak, tension: the last stage's, raised
  // to the stages' largest; stage: where the peak strain is.
  void OverStages(double &peak, double &tension, int &stage) const {
    for (const StageRow &q : rows_) {
      if (q.peak_strain > peak) peak = q.peak_strain, stage = q.stage;
      tension = std::fmax(tension, q.peak_tension);
    }
  }
  // The design record (checked: the peak strain) and, after where_, the stage of the largest
  // peak when it is not the last; `kind` qualifies the strain and tension (3D: major principal).
  void SetDesign(double peak, double tension, int stage, const std::string &kind) {
    if (stage != rows_.back().stage) {
      char line[128];
      snprintf(line, sizeof(line), "; its largest over the stages %.3f %% at stage %d", 100 * peak,
               stage);
      where_ += line;
    }
    design_ = DesignRecord{};
    design_.has_check = true;
    design_.allowable = allowable_;
    design_.answers = {
        {"peak_strain", "peak membrane strain" + kind, peak, 100, "%", true},
        {"peak_tension", "peak membrane tension" + kind, tension, 1e-3, "kN/m", false},
        {"surface_settlement", "surface settlement", rows_.back().surface_settlement, 1, "m",
         false},
        {"membrane_settlement", "membrane settlement", rows_.back().membrane_settlement, 1, "m",
         false},
        {"differential_settlement", "differential settlement of the membrane",
         rows_.back().differential, 1, "m", false}};
  }

  // -dim 3: the top-most sheet's answers (results() above gives a chain's): the peak principal
  // strain of a point with the minor strain there (the biaxial state) and where, its largest
  // over the stages, the tensions, the largest slip on each face and where, the settlements;
  // the design record; the closed forms beside them.
  PetscErrorCode SheetResults(Simulation &sim, std::string &json) {
    PetscFunctionBeginUser;
    const char *sep = ",\n    ";
    const Sheet &s = sim.sheets.back();
    const PeakPrincipal pk = sheet_peak_principal(s);
    double peak_hist = pk.strain1, tension_hist = pk.tension1;
    int peak_stage = rows_.back().stage;
    OverStages(peak_hist, tension_hist, peak_stage);
    int it = 0, ib = 0;
    for (int i = 0; i < s.n; ++i) {
      if (SlipOf(s.slip_top, i) > SlipOf(s.slip_top, it)) it = i;
      if (SlipOf(s.slip_bot, i) > SlipOf(s.slip_bot, ib)) ib = i;
    }
    auto at = [&](const double *x) {
      return "[" + json_num(x[0]) + ", " + json_num(x[1]) + ", " + json_num(x[2]) + "]";
    };
    json += sep + std::string("\"membrane\": {") + "\"name\": \"" + s.name + "\", " +
            json_kv("peak_strain", pk.strain1) + ", " + json_kv("peak_strain_minor", pk.strain2) +
            ", \"peak_at\": " + at(&s.x0[3 * pk.point]) + ", " +
            json_kv("peak_strain_triangle", pk.triangle_strain1) + ", " +
            json_kv("peak_strain_over_stages", peak_hist) + ", " +
            json_kv("peak_strain_stage", double(peak_stage)) + ", " +
            json_kv("peak_tension", pk.tension1) + ", " +
            json_kv("peak_tension_minor", pk.tension2) + ", " +
            json_kv("allowable_strain", allowable_) + ", " +
            json_kv("max_slip_top", SlipOf(s.slip_top, it)) +
            ", \"max_slip_top_at\": " + at(&s.x0[3 * it]) + ", " +
            json_kv("max_slip_bottom", SlipOf(s.slip_bot, ib)) +
            ", \"max_slip_bottom_at\": " + at(&s.x0[3 * ib]) + ", " +
            json_kv("membrane_settlement", rows_.back().membrane_settlement) + ", " +
            json_kv("differential_settlement", rows_.back().differential) + "}";
    char line[384];
    snprintf(line, sizeof(line),
             "membrane %s: peak principal strain %.3f %% (minor %.3f %%) at (x, z) = (%.2f, "
             "%.2f) m, tension %.4g kN/m",
             s.name.c_str(), 100 * pk.strain1, 100 * pk.strain2, s.x0[3 * pk.point],
             s.x0[3 * pk.point + 2], pk.tension1 / 1e3);
    where_ = line;
    SetDesign(peak_hist, tension_hist, peak_stage, " (major principal)");
    double p = 0, sag = 0;
    if (!void_w_.empty() && void_eff_ > 0) VoidPressureSag3(s, void_eff_, &p, &sag);
    PetscCall(ComparisonJson(sim, s.J, s.thickness, s.top.mu, p, sag, json));
    PetscFunctionReturn(0);
  }

  // Mean contact pressure on the top membrane's upper face over the void's width, and its sag
  // there (settlement since stage 0 at the void's centre less the mean at its edges).
  void VoidPressureSag(const Chain &c, double B, double *p, double *sag) const {
    double n = 0;
    *p = 0;
    for (int i = 0; i < c.n; ++i) // over a round void, the mean over its area
      if (std::fabs(c.x0[i * DIM] - void_x_) < 0.5 * B)
        *p += c.p_top[i] * c.ring(i), n += c.ring(i);
    *p = n > 0 ? *p / n : 0;
    auto settle = [&](double X) {
      int i = 0;
      while (i + 1 < c.n && c.x0[(i + 1) * DIM] < X) ++i;
      return sheet_ref_[i * DIM + 1] - c.x[i * DIM + 1];
    };
    if (round_)
      *sag = settle(0.0) - settle(B / 2);
    else
      *sag = settle(void_x_) - 0.5 * (settle(void_x_ - B / 2) + settle(void_x_ + B / 2));
  }

  // Closed forms for the same geometry: the void (Giroud with Terzaghi's arching) and the slope
  // (infinite slope, Koerner-Soong), with the simulated counterparts.
  // J, t: the membrane's stiffness and thickness; mu_top its upper face's friction; p, sag: its
  // pressure and sag over the void (VoidPressureSag, VoidPressureSag3).
  PetscErrorCode ComparisonJson(Simulation &sim, double J, double thickness, double mu_top,
                                double p, double sag, std::string &json) {
    PetscFunctionBeginUser;
    const char *sep = ",\n    ";
    const Membrane &M = mem_.back();
    // the soil above the membrane: thickness, mean unit weight, friction of the layer on it
    auto above = [&](double x, double &H, double &gamma) {
      H = 0;
      double w = 0;
      for (size_t k = M.layer; k < layers_.size(); ++k) {
        const double t = layers_[k].thickness(x, W_);
        H += t;
        w += t * sim.model.mats[layers_[k].mat].gamma;
      }
      gamma = w / H;
    };
    const MaterialEntry &soil = sim.model.mats[layers_[M.layer].mat];
    double phi = 0, coh = 0;
    if (auto *dp = dynamic_cast<const DruckerPrager *>(soil.model.get())) {
      phi = dp->params().phi_deg;
      coh = dp->params().cohesion;
    }
    if (!void_w_.empty() && void_eff_ > 0) {
      double H, gamma;
      above(void_x_, H, gamma);
      const double B = void_eff_;
      std::string g = "{" + json_kv("B", B) + ", " + json_kv("H", H) + ", " +
                      json_kv("gamma", gamma) + ", " + json_kv("J", J) + ", " +
                      json_kv("pmpm_pressure", p) + ", " + json_kv("pmpm_sag", sag) + ", " +
                      json_kv("overburden", gamma * H);
      // a round void of diameter B arches as a long one of width B / 2 (the same area over
      // perimeter, B / 4); Giroud's sheet over it is a spherical cap (giroud.hpp)
      const double Bt = round_ ? 0.5 * B : B;
      if (round_) g += ", \"round\": true";
      if (dim3_) // the round void's centre in plan (x, z)
        g += ", \"centre\": [" + json_num(void_x_) + ", " + json_num(void_z_) + "]";
      if (phi > 0) {
        const double tp = std::tan(phi * kDeg), sp = std::sin(phi * kDeg);
        const double Ka = (1 - sp) / (1 + sp);
        // the bracket with the cohesion of the layer on the sheet (Terzaghi's c term)
        g += ", " + json_kv("terzaghi_K1", giroud::terzaghi_pressure(gamma, Bt, H, tp, coh)) +
             ", " + json_kv("terzaghi_Ka", giroud::terzaghi_pressure(gamma, Bt, H, Ka * tp, coh)) +
             ", " + json_kv("phi", phi) + ", " + json_kv("cohesion", coh);
      }
      try {
        const auto gs =
            round_ ? giroud::self_consistent_round(gamma, B, H, 0.0, thickness, J / thickness)
                   : giroud::self_consistent(gamma, B, H, 0.0, thickness, J / thickness);
        g += ", " + json_kv("giroud_pressure", gs.pressure) + ", " +
             json_kv("giroud_strain", gs.strain) + ", " + json_kv("giroud_sag", gs.sag) + ", " +
             json_kv("giroud_tension", gs.tension);
      } catch (const std::exception &) {
      }
      json += sep + std::string("\"void\": ") + g + "}";
    }
    if (slope_len_ > 0) {
      double H, gamma;
      const double beta = slope_deg_ * kDeg;
      const double xm = toe_x_ + 0.5 * slope_len_ * std::cos(beta);
      above(xm, H, gamma);
      const double delta = std::atan(mu_top), h = H * std::cos(beta); // normal thickness
      json +=
          sep + std::string("\"slope\": {") + json_kv("beta", slope_deg_) + ", " +
          json_kv("delta", delta / kDeg) + ", " + json_kv("phi", phi) + ", " +
          json_kv("h_normal", h) + ", " + json_kv("L", slope_len_) + ", " +
          json_kv("fs_infinite", veneer::fs_infinite(beta, delta)) + ", " +
          json_kv("fs_koerner_soong",
                  phi > 0 ? veneer::fs_koerner_soong(gamma, h, slope_len_, beta, phi * kDeg, delta)
                          : std::nan("")) +
          "}";
    }
    PetscFunctionReturn(0);
  }

  PetscErrorCode write_files(Simulation &sim) override {
    PetscFunctionBeginUser;
    // again at the end: a run restarted from the last stage's checkpoint ran no stage
    PetscCall(WriteStages(sim));
    if (!where_.empty() && !sim.set.quiet) PetscCall(PetscPrintf(sim.comm, "%s\n", where_.c_str()));
    PetscFunctionReturn(0);
  }

  // The top membrane's answers (results() computed them); the peak strain is checked against
  // -cover_allowable_strain. A cover without a membrane has none.
  bool has_design() const override { return !mem_.empty(); }
  PetscErrorCode design(Simulation &, DesignRecord &d) override {
    d = design_;
    return 0;
  }

private:
  std::string where_; // the top membrane's peak strain and tension, where they are
  DesignRecord design_;
};

std::unique_ptr<Scene> make_cover_scene() {
  return std::make_unique<CoverScene>();
}

} // namespace pmpm
