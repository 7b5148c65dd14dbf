#include "pmpm/util/options.hpp"
#include "pmpm/contact/chain.hpp"
#include "pmpm/core/shape.hpp"
#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace pmpm {

namespace {
// Below this the chains' normal sum at a node is round-off: no normal, the bodies move as one.
constexpr double kNoNormal = 1e-300;

// Unit tangent at point i from its neighbours (one-sided at the ends); the normal is its left
// perpendicular, which points to the body above for a chain running in +x.
void point_frame(const Chain &c, int i, double tau[DIM], double nrm[DIM]) {
  const int a = std::max(i - 1, 0), b = std::min(i + 1, c.n - 1);
  double d[DIM] = {c.x[b * DIM] - c.x[a * DIM], c.x[b * DIM + 1] - c.x[a * DIM + 1]};
  const double l = std::hypot(d[0], d[1]);
  tau[0] = d[0] / l;
  tau[1] = d[1] / l;
  nrm[0] = -tau[1];
  nrm[1] = tau[0];
}

// A point's block: one cell along the sheet and thin across it (the axis-aligned box of a
// segment of length h along the tangent tau, at least 1e-3 h per axis), clipped at the box faces
// (nodes outside the box carry nothing). Thin across: the sheet then reaches the nodes of the
// cells it crosses, which are exactly the nodes its neighbours above and below share (a
// particle's block ends at the sheet, so it reaches no node row a cell beyond it); a footprint a
// cell deep reached rows where only one neighbour was, where the contact let the sheet go and the
// friction landfill never converged (ratio 7e-3 after 20,000 steps; 2,408 steps to 1e-5 now).
// One cell along: with blocks as short as the point spacing the catenary stalled at ratio 3e-3.
void point_halfsize(const GridView &G, const double *x, const double tau[DIM], double lp[DIM]) {
  for (int d = 0; d < DIM; ++d) {
    const double lo = x[d] - G.origin[d], hi = G.origin[d] + G.ncell[d] * G.h - x[d];
    const double l = std::fmax(1e-3 * G.h, 0.5 * G.h * std::fabs(tau[d]));
    lp[d] = std::fmax(1e-6 * G.h, std::fmin(l, std::fmin(lo, hi)));
  }
}

// Point i's frame (point_frame) and its uGIMP weights over its block (point_halfsize) on G.
void point_stencil(const Chain &c, int i, const GridView &G, double tau[DIM], double nrm[DIM],
                   Weights<UGIMPShape> &W) {
  const double *x = &c.x[i * DIM];
  double lp[DIM];
  point_frame(c, i, tau, nrm);
  point_halfsize(G, x, tau, lp);
  weights<UGIMPShape>(x, lp, G.origin, G.h, W);
}

// Segment k's weight in the strain projection: its rest length (times its rest radius under
// -geometry axisymmetric, so that the projection stays symmetric in the energy's weights).
double seg_weight(const Chain &c, int k) {
  return c.axisymmetric ? c.l0[k] * c.r0[k] : c.l0[k];
}

bool pinned(const Chain &c, int i) {
  return (i == 0 && c.pin[0]) || (i == c.n - 1 && c.pin[1]);
}

bool owned_by(const Grid &grid, const GridView &G, const double *x) {
  PetscInt cell[DIM];
  for (int d = 0; d < DIM; ++d) {
    const double xi = (x[d] - G.origin[d]) / G.h;
    if (!(xi >= 0 && xi <= G.ncell[d])) return false; // off the grid: nobody (reported)
    cell[d] = std::min(static_cast<PetscInt>(xi), G.ncell[d] - 1); // a point on the far face
  }
  return grid.owns_cell(cell);
}

// The spec's own checks: a positive thickness and a line of at least two points running left to
// right.
PetscErrorCode CheckChainSpec(MPI_Comm comm, const ChainSpec &spec) {
  PetscFunctionBeginUser;
  PetscCheck(spec.thickness > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "chain %s: the thickness must be > 0 (got %g)", spec.name.c_str(), spec.thickness);
  const size_t nv = spec.line.size() / DIM;
  PetscCheck(nv >= 2 && spec.line.size() % DIM == 0, comm, PETSC_ERR_ARG_WRONG,
             "chain %s: its line needs at least two points x0,y0,x1,y1", spec.name.c_str());
  for (size_t k = 1; k < nv; ++k)
    PetscCheck(spec.line[k * DIM] > spec.line[(k - 1) * DIM], comm, PETSC_ERR_ARG_WRONG,
               "chain %s: its points must run left to right (x increasing; vertex %zu at x = %g "
               "follows x = %g)",
               spec.name.c_str(), k, spec.line[k * DIM], spec.line[(k - 1) * DIM]);
  PetscFunctionReturn(0);
}

// The membrane's material, -mat_<material>_*: its law, stiffness J, weight and mass per length.
PetscErrorCode ReadMembraneMaterial(MPI_Comm comm, const ChainSpec &spec, Chain &c) {
  PetscFunctionBeginUser;
  const std::string prefix = "mat_" + spec.material + "_";
  PetscBool hasE = PETSC_FALSE;
  double sigma_y = 0, H = 0;
  c.nu = 0.0;
  PetscOptionsBegin(comm, prefix.c_str(), ("Membrane material " + spec.material).c_str(), nullptr);
  PetscCall(PmpmOptionsEnum("-law", MembraneLaws::help().c_str(), nullptr, MembraneLawNames,
                            (PetscEnum)c.law.kind, (PetscEnum *)&c.law.kind, nullptr));
  PetscCall(PmpmOptionsReal("-E", "Young's modulus (Pa), > 0", nullptr, c.E, &c.E, &hasE));
  PetscCall(PmpmOptionsReal("-nu", "Poisson's ratio, 0 <= nu < 0.5 (plane-strain stiffness)",
                            nullptr, c.nu, &c.nu, nullptr));
  PetscCall(PmpmOptionsReal("-gamma", "Unit weight (N/m^3), >= 0; the sheet weighs gamma t",
                            nullptr, c.gamma, &c.gamma, nullptr));
  PetscCall(PmpmOptionsReal("-density", "Inertial density (kg/m^3), > 0 (default gamma / 9.81)",
                            nullptr, c.density, &c.density, nullptr));
  PetscCall(PmpmOptionsEnum(
      "-axial_stiffness", "J = E t / (1 - nu^2) (plane_strain) or E t (uniaxial)", nullptr,
      StiffnessKindNames, (PetscEnum)c.stiffness, (PetscEnum *)&c.stiffness, nullptr));
  PetscCall(PmpmOptionsReal("-yield_stress", "Uniaxial yield stress (Pa), > 0 (elastoplastic)",
                            nullptr, sigma_y, &sigma_y, nullptr));
  PetscCall(PmpmOptionsReal("-hardening", "Linear hardening modulus (Pa), >= 0 (elastoplastic)",
                            nullptr, H, &H, nullptr));
  PetscOptionsEnd();
  PmpmCheckInput(hasE, comm, PETSC_ERR_USER_INPUT, "-%sE is required (Young's modulus in Pa)",
                 prefix.c_str());
  PmpmCheckInput(c.E > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sE must be > 0 (got %g)",
                 prefix.c_str(), c.E);
  PmpmCheckInput(c.nu >= 0 && c.nu < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%snu must be in [0, 0.5) (got %g)", prefix.c_str(), c.nu);
  PmpmCheckInput(c.gamma >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sgamma must be >= 0 (got %g)",
                 prefix.c_str(), c.gamma);
  PmpmCheckInput(c.density >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sdensity must be > 0 (got %g)",
                 prefix.c_str(), c.density);
  if (c.density <= 0) c.density = c.gamma > 0 ? c.gamma / 9.81 : 1000.0;
  const double Eeff = c.stiffness == StiffnessKind::PlaneStrain ? c.E / (1 - c.nu * c.nu) : c.E;
  c.law.J = Eeff * c.thickness;
  if (c.law.plastic()) {
    PmpmCheckInput(sigma_y > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-%syield_stress must be > 0 with -%slaw %s (got %g)", prefix.c_str(),
                   prefix.c_str(), MembraneLawNames[c.law.kind], sigma_y);
    PmpmCheckInput(H >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%shardening must be >= 0",
                   prefix.c_str());
    c.law.yield_T = sigma_y * c.thickness;
    c.law.hardening = H * c.thickness;
  }
  c.line_weight = c.gamma * c.thickness;
  c.line_mass = c.density * c.thickness; // SimulationSetup may scale it
  PetscFunctionReturn(0);
}

// The interfaces on its faces, -chain_<name>_*: type, friction and adhesion of each face.
PetscErrorCode ReadChainFaces(MPI_Comm comm, const ChainSpec &spec, Chain &c) {
  PetscFunctionBeginUser;
  const std::string cp = "chain_" + spec.name + "_";
  double delta[2] = {-1, -1};
  PetscOptionsBegin(comm, cp.c_str(), ("Chain " + spec.name + ": interfaces").c_str(), nullptr);
  FaceType ft = c.top.type;
  PetscCall(PmpmOptionsEnum("-interface",
                            "Both faces: contact (Bardenhagen, separates), paper (one normal "
                            "velocity), bonded",
                            nullptr, FaceTypeNames, (PetscEnum)ft, (PetscEnum *)&ft, nullptr));
  c.top.type = c.bottom.type = ft;
  PetscCall(PmpmOptionsReal("-mu_top", "Friction coefficient on the upper face, >= 0", nullptr,
                            c.top.mu, &c.top.mu, nullptr));
  PetscCall(PmpmOptionsReal("-mu_bottom", "Friction coefficient on the lower face, >= 0", nullptr,
                            c.bottom.mu, &c.bottom.mu, nullptr));
  PetscCall(PmpmOptionsReal("-delta_top",
                            "Interface friction angle of the upper face (degrees, 0..60; "
                            "replaces mu_top by tan delta)",
                            nullptr, delta[0], &delta[0], nullptr));
  PetscCall(PmpmOptionsReal("-delta_bottom", "Interface friction angle of the lower face (degrees)",
                            nullptr, delta[1], &delta[1], nullptr));
  PetscCall(PmpmOptionsReal("-adhesion_top", "Adhesion of the upper face (Pa), >= 0", nullptr,
                            c.top.adhesion, &c.top.adhesion, nullptr));
  PetscCall(PmpmOptionsReal("-adhesion_bottom", "Adhesion of the lower face (Pa), >= 0", nullptr,
                            c.bottom.adhesion, &c.bottom.adhesion, nullptr));
  PetscOptionsEnd();
  ChainFace *faces[2] = {&c.top, &c.bottom};
  const char *fname[2] = {"top", "bottom"};
  for (int k = 0; k < 2; ++k) {
    if (delta[k] >= 0) {
      PmpmCheckInput(delta[k] <= 60, comm, PETSC_ERR_ARG_OUTOFRANGE,
                     "-%sdelta_%s must be in [0, 60] degrees (got %g)", cp.c_str(), fname[k],
                     delta[k]);
      faces[k]->mu = std::tan(delta[k] * M_PI / 180);
    }
    PmpmCheckInput(faces[k]->mu >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-%smu_%s must be >= 0 (got %g)", cp.c_str(), fname[k], faces[k]->mu);
    PmpmCheckInput(faces[k]->adhesion >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "-%sadhesion_%s must be >= 0 (got %g)", cp.c_str(), fname[k],
                   faces[k]->adhesion);
  }
  PetscFunctionReturn(0);
}

// The points: each polyline piece divided evenly with spacing at most ds; the segments' rest
// lengths, the points' lengths of sheet, and every per-point and per-segment array at rest.
PetscErrorCode PlaceChainPoints(MPI_Comm comm, const ChainSpec &spec, double ds, Chain &c) {
  PetscFunctionBeginUser;
  const size_t nv = spec.line.size() / DIM;
  PetscCheck(ds > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "chain point spacing must be > 0");
  c.x.clear();
  for (size_t k = 0; k + 1 < nv; ++k) {
    const double *a = &spec.line[k * DIM], *b = &spec.line[(k + 1) * DIM];
    const double L = std::hypot(b[0] - a[0], b[1] - a[1]);
    const int ns = std::max(1, static_cast<int>(std::ceil(L / ds - 1e-9)));
    for (int s = (k == 0 ? 0 : 1); s <= ns; ++s)
      for (int d = 0; d < DIM; ++d) c.x.push_back(a[d] + (b[d] - a[d]) * double(s) / ns);
  }
  c.n = static_cast<int>(c.x.size() / DIM);
  c.x0 = c.x;
  c.v.assign(c.x.size(), 0.0);
  c.f.assign(c.x.size(), 0.0);
  c.l0.assign(c.n - 1, 0.0);
  c.length.assign(c.n, 0.0);
  for (int k = 0; k + 1 < c.n; ++k) {
    c.l0[k] =
        std::hypot(c.x[(k + 1) * DIM] - c.x[k * DIM], c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1]);
    c.length[k] += 0.5 * c.l0[k];
    c.length[k + 1] += 0.5 * c.l0[k];
  }
  c.r0.assign(c.n - 1, 0.0);
  for (int k = 0; k + 1 < c.n; ++k) c.r0[k] = 0.5 * (c.x[k * DIM] + c.x[(k + 1) * DIM]);
  c.eps_hoop.assign(c.n - 1, 0.0);
  c.T_hoop.assign(c.n - 1, 0.0);
  c.eps.assign(c.n - 1, 0.0);
  c.eps_p.assign(c.n - 1, 0.0);
  c.alpha.assign(c.n - 1, 0.0);
  c.T.assign(c.n - 1, 0.0);
  c.slack.assign(c.n - 1, 0);
  c.slip_top.assign(c.n, 0.0);
  c.slip_bot.assign(c.n, 0.0);
  c.p_top.assign(c.n, 0.0);
  c.p_bot.assign(c.n, 0.0);
  c.owned.assign(c.n, 0);
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ChainCreate(MPI_Comm comm, const ChainSpec &spec, double ds, Chain &c) {
  PetscFunctionBeginUser;
  c.name = spec.name;
  c.material = spec.material;
  c.thickness = spec.thickness;
  c.pin[0] = spec.pin_start;
  c.pin[1] = spec.pin_end;
  for (int d = 0; d < DIM; ++d) c.end_force[d] = spec.end_force[d];
  PetscCall(CheckChainSpec(comm, spec));
  PetscCall(ReadMembraneMaterial(comm, spec, c));
  PetscCall(ReadChainFaces(comm, spec, c));
  PetscCall(PlaceChainPoints(comm, spec, ds, c));
  PetscFunctionReturn(0);
}

// The segments' chord strains projected on the grid's nodes and back (-chain_strain_projection):
// node I gets e_I = sum_k w_Ik l0_k e_k / sum_k w_Ik l0_k, segment k then sum_I w_Ik e_I, with
// w_Ik the uGIMP weights of a block at the segment's midpoint along its chord (the points'
// blocks, point_halfsize). The sheet's points move with the grid's velocity interpolated over
// one-cell blocks, so their displacement is a quadratic spline of the nodes': its slope w' is
// linear within a cell and w'^2 / 2 quadratic, which the axial part u' (linear) cannot cancel,
// and a sheet that bends while hardly stretching (strain << w'^2 / 2) carries a chord strain
// that swings within each cell by about (w'' h)^2 / 8 (membrane locking; Stolarski and
// Belytschko 1982). The projection keeps what the grid resolves, as F-bar keeps a cell's
// volume change: with T_k = J e_k the internal force sum_k T_k tau_k de_k/dx is the gradient of
// the energy J/2 sum_k l0_k e_k (P e)_k, P the projection (symmetric in the l0-weighted sum).
// (P is taken at given positions: relaxation's at the current ones; Newton's frozen at the load
// step's start, with its stencils, so that its tangent is exact.)
void chain_projection(const Chain &c, const double *x, ChainProjection &P) {
  GridView G;
  G.h = c.grid_h;
  for (int d = 0; d < DIM; ++d) {
    G.origin[d] = c.grid_origin[d];
    G.ncell[d] = c.grid_ncell[d];
  }
  constexpr int NS = UGIMPShape::NS;
  const int ns = c.n - 1;
  const long long row = c.grid_ncell[0] + 1;
  std::unordered_map<long long, int> id;
  id.reserve(static_cast<size_t>(4 * ns));
  P.start.assign(1, 0);
  P.node.clear();
  P.w.clear();
  P.mass.clear();
  Weights<UGIMPShape> W;
  for (int k = 0; k < ns; ++k) {
    const double *a = &x[k * DIM], *b = &x[(k + 1) * DIM];
    const double xm[DIM] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
    const double l = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double tau[DIM] = {(b[0] - a[0]) / l, (b[1] - a[1]) / l};
    double lp[DIM];
    point_halfsize(G, xm, tau, lp);
    weights<UGIMPShape>(xm, lp, G.origin, G.h, W);
    for (int q = 0; q < NS * NS; ++q) {
      const double w = W.w[q];
      if (w == 0.0) continue;
      const long long key = (W.base[1] + q / NS) * row + W.base[0] + q % NS;
      const auto it = id.emplace(key, static_cast<int>(P.mass.size())).first;
      if (it->second == static_cast<int>(P.mass.size())) P.mass.push_back(0.0);
      P.node.push_back(it->second);
      P.w.push_back(w);
      P.mass[it->second] += w * seg_weight(c, k);
    }
    P.start.push_back(static_cast<int>(P.w.size()));
  }
}

void chain_project(const Chain &c, const ChainProjection &P, const double *e, double *out) {
  const int ns = c.n - 1;
  std::vector<double> eI(P.mass.size(), 0.0);
  for (int k = 0; k < ns; ++k)
    for (int q = P.start[k]; q < P.start[k + 1]; ++q)
      eI[P.node[q]] += P.w[q] * seg_weight(c, k) * e[k];
  for (size_t I = 0; I < eI.size(); ++I) eI[I] /= P.mass[I];
  for (int k = 0; k < ns; ++k) {
    double ek = 0;
    for (int q = P.start[k]; q < P.start[k + 1]; ++q) ek += P.w[q] * eI[P.node[q]];
    out[k] = ek;
  }
}

namespace {
// -geometry axisymmetric: meridional and hoop tensions from the (projected) meridional strains,
// the hoop strains th and their projection thp (the energy's nu coupling, chain.hpp), and the
// forces per radian. tension_only: the tension field of a wrinkled sheet (a compressive principal
// tension is zero, the other carries E t times its strain), slack when both are.
void chain_update_tension_axi(Chain &c) {
  const int ns = c.n - 1;
  std::vector<double> th(ns), thp(ns);
  for (int k = 0; k < ns; ++k) {
    th[k] = 0.5 * (c.x[k * DIM] + c.x[(k + 1) * DIM]) / c.r0[k] - 1.0;
    thp[k] = th[k];
  }
  if (c.strain_projection) {
    ChainProjection P;
    chain_projection(c, c.x.data(), P);
    chain_project(c, P, c.eps.data(), c.eps.data());
    chain_project(c, P, th.data(), thp.data());
  }
  const double J = c.law.J, nu = c.nu, Et = J * (1 - nu * nu);
  const bool field = c.law.kind == MembraneLawId<TensionOnlyMembrane>;
  for (int k = 0; k < ns; ++k) {
    double N = J * (c.eps[k] + nu * thp[k]), Nh = J * (th[k] + nu * c.eps[k]);
    bool slack = false;
    if (field && (N < 0 || Nh < 0)) {
      // not taut: slack if neither principal strain stretches, else wrinkled, the more stretched
      // direction carrying E t times its strain
      const double e = c.eps[k], t = th[k];
      N = Nh = 0;
      slack = e <= 0 && t <= 0;
      if (!slack && e >= t) N = Et * e;
      if (!slack && e < t) Nh = Et * t;
    }
    c.T[k] = N;
    c.T_hoop[k] = Nh;
    c.eps_hoop[k] = th[k];
    c.slack[k] = slack;
  }
  std::fill(c.f.begin(), c.f.end(), 0.0);
  for (int k = 0; k < ns; ++k) {
    const double dx = c.x[(k + 1) * DIM] - c.x[k * DIM],
                 dy = c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1];
    const double l = std::hypot(dx, dy), RN = c.r0[k] * c.T[k];
    const double fh = 0.5 * c.l0[k] * c.T_hoop[k]; // the hoop tension pulls toward the axis
    c.f[k * DIM] += RN * dx / l - fh;
    c.f[k * DIM + 1] += RN * dy / l;
    c.f[(k + 1) * DIM] -= RN * dx / l + fh;
    c.f[(k + 1) * DIM + 1] -= RN * dy / l;
  }
}
} // namespace

void chain_update_tension(Chain &c) {
  c.eps_chord.resize(c.n - 1);
  for (int k = 0; k + 1 < c.n; ++k) {
    const double dx = c.x[(k + 1) * DIM] - c.x[k * DIM],
                 dy = c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1];
    c.eps_chord[k] = std::hypot(dx, dy) / c.l0[k] - 1.0;
  }
  c.eps = c.eps_chord;
  if (c.axisymmetric) {
    chain_update_tension_axi(c);
  } else {
    if (c.strain_projection) {
      ChainProjection P;
      chain_projection(c, c.x.data(), P);
      chain_project(c, P, c.eps.data(), c.eps.data());
    }
    for (int k = 0; k + 1 < c.n; ++k) {
      bool slack = false;
      c.T[k] = c.law.tension(c.eps[k], c.eps_p[k], c.alpha[k], slack);
      c.slack[k] = slack;
    }
    std::fill(c.f.begin(), c.f.end(), 0.0);
    for (int k = 0; k + 1 < c.n; ++k) {
      const double dx = c.x[(k + 1) * DIM] - c.x[k * DIM],
                   dy = c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1];
      const double l = std::hypot(dx, dy), fx = c.T[k] * dx / l, fy = c.T[k] * dy / l;
      c.f[k * DIM] += fx; // the segment pulls its ends toward each other under tension
      c.f[k * DIM + 1] += fy;
      c.f[(k + 1) * DIM] -= fx;
      c.f[(k + 1) * DIM + 1] -= fy;
    }
  }
  // what the supports hold: minus the sheet's pull on the pinned points
  for (int e = 0; e < 2; ++e) {
    const int i = e == 0 ? 0 : c.n - 1;
    for (int d = 0; d < DIM; ++d) c.reaction[e][d] = c.pin[e] ? -c.f[i * DIM + d] : 0.0;
  }
}

void chain_lay(Chain &c) {
  for (int k = 0; k + 1 < c.n; ++k)
    c.l0[k] =
        std::hypot(c.x[(k + 1) * DIM] - c.x[k * DIM], c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1]);
  for (int k = 0; k + 1 < c.n; ++k) c.r0[k] = 0.5 * (c.x[k * DIM] + c.x[(k + 1) * DIM]);
  std::fill(c.eps_p.begin(), c.eps_p.end(), 0.0);
  std::fill(c.alpha.begin(), c.alpha.end(), 0.0);
  std::fill(c.slip_top.begin(), c.slip_top.end(), 0.0);
  std::fill(c.slip_bot.begin(), c.slip_bot.end(), 0.0);
  chain_update_tension(c);
}

// The length of face each node stands for if the sheet ran on unbroken (ChainDof::AREA): its
// points' w l (LEN), plus what a pinned end point and the sheet's continuation beyond each end
// (straight on along the end segment, at the points' spacing, as far as a point's weights reach)
// would have added. A node at a sheet's end carries the normal impulse of its whole face, part of
// it beyond the sheet (blocks bonded past a pulled-out sheet's end, the gap between a cover's
// sheet and its wall); the sheet's share of that impulse is LEN / AREA, not all of it.
static void chain_face_area_ends(const Chain &c, const GridView &G, const Grid &grid) {
  if (c.n < 3) return;
  Weights<UGIMPShape> W;
  constexpr int NS = UGIMPShape::NS;
  const double s = c.length[c.n / 2]; // an interior point's length: the spacing
  const int nk = static_cast<int>(std::ceil(2.0 * G.h / s));
  for (int e = 0; e < 2; ++e) {
    const int i = e == 0 ? 0 : c.n - 1, j = e == 0 ? 1 : c.n - 2;
    const double *xe = &c.x[i * DIM], *xj = &c.x[j * DIM];
    const double d[DIM] = {xe[0] - xj[0], xe[1] - xj[1]}, ld = std::hypot(d[0], d[1]);
    const double tau[DIM] = {std::fabs(d[0]) / ld, std::fabs(d[1]) / ld};
    // the end point's missing share of a full spacing (all of it if pinned: p2g skips it),
    // then whole spacings beyond the end
    for (int k = 0; k <= nk; ++k) {
      const double len = k == 0 ? (pinned(c, i) ? s : s - c.length[i]) : s;
      if (len <= 0) continue;
      const double xv[DIM] = {xe[0] + k * s * d[0] / ld, xe[1] + k * s * d[1] / ld};
      if (!owned_by(grid, G, xv)) continue; // off the grid (past a wall) or another rank's
      double lp[DIM];
      point_halfsize(G, xv, tau, lp);
      weights<UGIMPShape>(xv, lp, G.origin, G.h, W);
      const double area = c.axisymmetric ? len * xv[0] : len; // per radian: times the radius
      for (int q = 0; q < NS * NS; ++q)
        if (W.w[q] != 0.0)
          G.node(W.base[0] + q % NS, W.base[1] + q / NS)[c.slot + ChainDof::AREA] += W.w[q] * area;
    }
  }
}

void p2g_chain(const Chain &c, const Load &load, const GridView &G, const Grid &grid) {
  Weights<UGIMPShape> W;
  constexpr int NS = UGIMPShape::NS;
  const int body = c.body * GridDof::NDOF, slot = c.slot;
  for (int i = 0; i < c.n; ++i) {
    const double *x = &c.x[i * DIM];
    if (pinned(c, i) || !owned_by(grid, G, x)) continue;
    double tau[DIM], nrm[DIM];
    point_stencil(c, i, G, tau, nrm, W);
    // per radian under -geometry axisymmetric: mass and loads times the initial radius, the face
    // times the current one (chain.hpp)
    const double ring = c.ring(i), area = c.axisymmetric ? c.length[i] * x[0] : c.length[i];
    const double m = c.line_mass * c.length[i] * ring,
                 wt = load.factor * c.line_weight * c.length[i] * ring;
    double fext[DIM] = {wt * load.gdir[0], wt * load.gdir[1]};
    if (i == c.n - 1)
      for (int d = 0; d < DIM; ++d) fext[d] += load.factor * ring * c.end_force[d];
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        const double w = W.w[b * NS + a];
        if (w == 0.0) continue;
        double *node = G.node(W.base[0] + a, W.base[1] + b);
        double *nb = node + body, *ns = node + slot;
        nb[GridDof::M] += w * m;
        for (int d = 0; d < DIM; ++d) {
          nb[GridDof::P + d] += w * m * c.v[i * DIM + d];
          nb[GridDof::F + d] += w * (c.f[i * DIM + d] + fext[d]);
          nb[GridDof::FEXT + d] += w * fext[d];
        }
        ns[ChainDof::NX] += w * m * nrm[0];
        ns[ChainDof::NY] += w * m * nrm[1];
        ns[ChainDof::LEN] += w * area;
        ns[ChainDof::AREA] += w * area;
      }
  }
  chain_face_area_ends(c, G, grid);
}

bool chain_point_weights(const Chain &c, int i, const GridView &G, const Grid &grid,
                         Weights<UGIMPShape> &W) {
  double tau[DIM], nrm[DIM];
  point_stencil(c, i, G, tau, nrm, W);
  return !pinned(c, i) && owned_by(grid, G, &c.x[i * DIM]);
}

void g2p_chain(Chain &c, const GridView &G, const Grid &grid, const G2PParams &prm,
               double tail_share) {
  Weights<UGIMPShape> W;
  constexpr int NS = UGIMPShape::NS, ND = GridDof::NDOF;
  const double dt = prm.dt, pic = prm.pic;
  const int body = c.body * ND, above = (c.body + 1) * ND, below = (c.body - 1) * ND;
  const int slot = c.slot;
  // Every point's frame, block and owner come from the step-start positions: moving a point in
  // place turned its next neighbour's frame into a mix of old and new positions that depended on
  // which neighbours this rank had moved, i.e. on the rank count (catenary, 3-4 against 1 rank:
  // 2e-8 to 7e-8 of the span). The new positions are written after the loop.
  std::vector<double> &xn = c.x_new;
  xn = c.x;
  for (int i = 0; i < c.n; ++i) {
    const double *x = &c.x[i * DIM];
    double *v = &c.v[i * DIM];
    c.owned[i] = owned_by(grid, G, x);
    if (!c.owned[i]) {
      // off the grid: nobody owns it; the caller counts the owners
      continue;
    }
    if (pinned(c, i)) {
      v[0] = v[1] = 0.0;
      continue;
    }
    double tau[DIM], nrm[DIM];
    point_stencil(c, i, G, tau, nrm, W);
    double vg[DIM] = {0, 0}, ag[DIM] = {0, 0}, va[DIM] = {0, 0}, vb[DIM] = {0, 0};
    double ma = 0, mb = 0, nt = 0, nbt = 0;
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        const double w = W.w[b * NS + a];
        if (w == 0.0) continue;
        const double *node = G.node(W.base[0] + a, W.base[1] + b);
        const double *nc = node + body, *na = node + above, *nb = node + below, *ns = node + slot;
        for (int d = 0; d < DIM; ++d) {
          vg[d] += w * nc[GridDof::P + d];
          ag[d] += w * nc[GridDof::F + d];
        }
        // slip: the sheet's velocity relative to each neighbouring body at the same nodes, the
        // nodes of the point's stencil where that body holds more than a tail share (a
        // mass-weighted mean of the body's velocity against the sheet's own mean compared node
        // rows a cell apart: a sheet bonded on both faces slipped 5.7, 3.0, 1.4 mm at h = 0.5,
        // 0.25, 0.125 m, the shear over half a cell, on an elastic degrading cover; a tail's
        // velocity is the node's common one, or a round-off mass's meaningless one: FaceSlips-
        // AndPressures, step/sheets.cpp)
        const double tail = tail_share * G.body_mass_sum(node);
        if (na[GridDof::M] > tail) {
          for (int d = 0; d < DIM; ++d) va[d] += w * (nc[GridDof::P + d] - na[GridDof::P + d]);
          ma += w;
        }
        if (nb[GridDof::M] > tail) {
          for (int d = 0; d < DIM; ++d) vb[d] += w * (nc[GridDof::P + d] - nb[GridDof::P + d]);
          mb += w;
        }
        // the point's share of the node's normal impulse: w l_i / AREA of it (AREA >= w l_i > 0),
        // tension included (a bonded face's rows of nodes carry impulses of both signs that add
        // up to its load: keeping only the compressive ones tripled a bonded sheet's pressure)
        const double share = ns[ChainDof::AREA] > 0 ? w / ns[ChainDof::AREA] : 0.0;
        nt += share * ns[ChainDof::NTOP];
        nbt += share * ns[ChainDof::NBOT];
      }

    for (int d = 0; d < DIM; ++d) v[d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
    if (c.axisymmetric && x[0] == 0.0) v[0] = vg[0] = 0.0; // a point on the axis stays there
    if (ma > 0) c.slip_top[i] += dt * (va[0] * tau[0] + va[1] * tau[1]) / ma;
    if (mb > 0) c.slip_bot[i] += dt * (vb[0] * tau[0] + vb[1] * tau[1]) / mb;
    // contact pressure (negative: tension): the point's shares of its nodes' normal impulses over
    // its length (sum_q w_q N_q / AREA_q, so the pressures times the lengths add up to the
    // sheet's share of the impulses)
    c.p_top[i] = nt / dt;
    c.p_bot[i] = nbt / dt;
    xn[i * DIM] = x[0] + dt * vg[0];
    xn[i * DIM + 1] = x[1] + dt * vg[1];
  }
  c.x.swap(xn);
}

// Owner's values, zeros elsewhere: x, v, slips, pressures, contact stencil per point (+ 1
// ownership count).
constexpr int kPack = 2 * DIM + 5;
void chain_pack(const Chain &c, std::vector<double> &buf) {
  constexpr int W = kPack;
  buf.assign(static_cast<size_t>(c.n) * W, 0.0);
  for (int i = 0; i < c.n; ++i) {
    if (!c.owned[i]) continue;
    double *b = &buf[static_cast<size_t>(i) * W];
    for (int d = 0; d < DIM; ++d) {
      b[d] = c.x[i * DIM + d];
      b[DIM + d] = c.v[i * DIM + d];
    }
    b[2 * DIM + 0] = c.slip_top[i];
    b[2 * DIM + 1] = c.slip_bot[i];
    b[2 * DIM + 2] = c.p_top[i];
    b[2 * DIM + 3] = c.p_bot[i];
    b[2 * DIM + 4] = 1.0;
  }
}

void chain_unpack(Chain &c, const std::vector<double> &buf) {
  constexpr int W = kPack;
  for (int i = 0; i < c.n; ++i) {
    const double *b = &buf[static_cast<size_t>(i) * W];
    for (int d = 0; d < DIM; ++d) {
      c.x[i * DIM + d] = b[d];
      c.v[i * DIM + d] = b[DIM + d];
    }
    c.slip_top[i] = b[2 * DIM + 0];
    c.slip_bot[i] = b[2 * DIM + 1];
    c.p_top[i] = b[2 * DIM + 2];
    c.p_bot[i] = b[2 * DIM + 3];
  }
}

int chain_owner_count(const std::vector<double> &buf, int n) {
  constexpr int W = kPack;
  int k = 0;
  for (int i = 0; i < n; ++i) k += buf[static_cast<size_t>(i) * W + 2 * DIM + 4] == 1.0;
  return k;
}

void chain_friction_capacity(const GridView &L, const GridView &G,
                             const std::vector<Chain> &chains) {
  Weights<UGIMPShape> W;
  constexpr int NS = UGIMPShape::NS;
  double tau[DIM], nrm[DIM];
  for (const Chain &c : chains)
    for (int i = 0; i < c.n; ++i) {
      if (pinned(c, i)) continue;
      point_stencil(c, i, L, tau, nrm, W);
      // only points whose stencil lies in this rank's ghosted range can reach its nodes
      if (W.base[0] < L.gs[0] || W.base[1] < L.gs[1] || W.base[0] + NS > L.gs[0] + L.gm[0] ||
          W.base[1] + NS > L.gs[1] + L.gm[1])
        continue;
      // the point's pressure on each face: its stencil's normal impulse over its sheet length
      // (every node: a node where the sheet is thin carries little of the point's length), and
      // the weight of the nodes where that face is in contact. (Not the point's shares of its
      // nodes' impulses, w l / AREA, as its reported pressure is: that is right where the ratio
      // of sums overstates a sheet between two rows of nodes by 13-17 %, but with the projected
      // strain it let the pulled-out sheet go unstable at -cfl 0.5; docs/limitations.md.)
      double n[2] = {0, 0}, len = 0, wc[2] = {0, 0};
      const double area = c.axisymmetric ? c.length[i] * c.x[i * DIM] : c.length[i];
      for (int q = 0; q < NS * NS; ++q) {
        if (W.w[q] == 0.0) continue;
        const double *ns = L.node(W.base[0] + q % NS, W.base[1] + q / NS) + c.slot;
        len += W.w[q] * ns[ChainDof::LEN];
        for (int f = 0; f < 2; ++f) {
          const double N = ns[f == 0 ? ChainDof::NTOP : ChainDof::NBOT];
          if (N <= 0) continue;
          n[f] += W.w[q] * N;
          wc[f] += W.w[q];
        }
      }
      // its pressure times its length, back to those nodes (the ones this rank owns)
      for (int q = 0; q < NS * NS; ++q) {
        if (W.w[q] == 0.0) continue;
        const PetscInt a = W.base[0] + q % NS, b = W.base[1] + q / NS;
        if (a < G.gs[0] || a >= G.gs[0] + G.gm[0] || b < G.gs[1] || b >= G.gs[1] + G.gm[1])
          continue;
        const double *ns = L.node(a, b) + c.slot;
        double *out = G.node(a, b) + c.slot;
        for (int f = 0; f < 2; ++f)
          if (len > 0 && ns[f == 0 ? ChainDof::NTOP : ChainDof::NBOT] > 0)
            out[f == 0 ? ChainDof::PTOP : ChainDof::PBOT] += W.w[q] / wc[f] * area * n[f] / len;
      }
    }
}

double chain_elastic_energy(const Chain &c) {
  double u = 0;
  if (c.axisymmetric) { // per radian: l0 R (N eps + N_th th) / 2
    for (int k = 0; k + 1 < c.n; ++k)
      u += 0.5 * c.l0[k] * c.r0[k] * (c.T[k] * c.eps[k] + c.T_hoop[k] * c.eps_hoop[k]);
    return u;
  }
  for (int k = 0; k + 1 < c.n; ++k) u += 0.5 * c.T[k] * c.T[k] * c.l0[k] / c.law.J;
  return u;
}

namespace {
// The face between two present bodies lo < hi at a node (face_between_membranes, every chain).
StackFace face_between(const std::vector<Chain> &chains, int lo, int hi) {
  return face_between_membranes(chains, lo, hi, [](const Chain &) { return true; });
}
} // namespace

namespace {
constexpr int kMaxBodies = 8; // bodies per node contact_bodies handles (guarded at setup)

// The k bodies with mass at one node (ids, in body order, msum their total mass): their masses
// m, velocities after the step v and before it vold, and the node's common acceleration
// acm = sum f / sum m (added to).
void gather_bodies(const double *node, int k, const int *ids, double msum, double dt, double *m,
                   double *v, double *vold, double *acm) {
  constexpr int ND = GridDof::NDOF;
  for (int q = 0; q < k; ++q) {
    const double *nbk = node + ids[q] * ND;
    m[q] = nbk[GridDof::M];
    for (int d = 0; d < DIM; ++d) {
      v[q * DIM + d] = nbk[GridDof::P + d];
      vold[q * DIM + d] = nbk[GridDof::P + d] - dt * nbk[GridDof::F + d];
      acm[d] += m[q] * nbk[GridDof::F + d] / msum;
    }
  }
}

// The faces between neighbouring bodies at the node (face_between): bonded where the chains give
// no normal (nn <= kNoNormal); adhesion as an impulse capacity, adhesion times the sheet length at
// the node times dt. A chain face's friction capacity: mu times the sheet's contact pressure
// times its length at this node (chain_friction_capacity, from this step's normal pass), not mu
// times this node's own normal impulse; passed as an impulse capacity (the adhesion slot,
// counted only in contact). See chain_friction_capacity for why. The normal pass has neither.
void node_faces(const double *node, const std::vector<Chain> &chains, int k, const int *ids,
                double nn, double dt, bool normal_pass, StackFace *faces) {
  for (int q = 0; q + 1 < k; ++q) {
    faces[q] = face_between(chains, ids[q], ids[q + 1]);
    if (nn <= kNoNormal) faces[q].type = FaceType::Bonded;
    if (faces[q].adhesion > 0) {
      double len = 0;
      for (const Chain &c : chains)
        if (c.body >= ids[q] && c.body <= ids[q + 1]) len += node[c.slot + ChainDof::LEN];
      faces[q].adhesion *= len * dt;
    }
    if (normal_pass) {
      faces[q].mu = faces[q].adhesion = 0;
    } else if (faces[q].type != FaceType::Bonded) {
      for (const Chain &c : chains) {
        const double pl = c.body == ids[q]       ? node[c.slot + ChainDof::PTOP]
                          : c.body == ids[q + 1] ? node[c.slot + ChainDof::PBOT]
                                                 : -1.0;
        if (pl < 0) continue;
        faces[q].adhesion += faces[q].mu * pl; // pl is an impulse (N s/m)
        faces[q].mu = 0;
        break;
      }
    }
  }
}

// The normal pass's result: each face's normal impulse on the chains' NTOP / NBOT slots.
void store_normal_impulses(double *node, const std::vector<Chain> &chains, int k, const int *ids,
                           const StackFaceResult *res) {
  for (int q = 0; q + 1 < k; ++q)
    for (const Chain &c : chains) {
      if (c.body == ids[q]) node[c.slot + ChainDof::NTOP] = res[q].normal;
      if (c.body == ids[q + 1]) node[c.slot + ChainDof::NBOT] = res[q].normal;
    }
}

// The full pass's counts and impulses: the node's statistics, and on the chain's slots its
// faces' friction impulses (along tau = -t, t = (-n_y, n_x) being contact_stack's tangent).
void record_contact(double *node, const std::vector<Chain> &chains, int k, const int *ids,
                    const StackFaceResult *res, double dt, ContactStats &st) {
  count_stack_faces(k, res, st);
  for (int q = 0; q + 1 < k; ++q)
    for (size_t ci = 0; ci < chains.size(); ++ci) {
      const Chain &c = chains[ci];
      if (c.body == ids[q]) { // the chain is the lower body: its top face
        node[c.slot + ChainDof::STOP] -= res[q].tangential;
        st.friction[ci] -= res[q].tangential / dt;
      } else if (c.body == ids[q + 1]) { // the upper body: its bottom face
        node[c.slot + ChainDof::SBOT] += res[q].tangential;
        st.friction[ci] += res[q].tangential / dt;
      }
    }
}

// The bodies' new velocities and forces back on the node (held dofs zero).
void scatter_bodies(double *node, int k, const int *ids, const double *v, const double *vold,
                    const bool held[DIM], double dt) {
  constexpr int ND = GridDof::NDOF;
  for (int q = 0; q < k; ++q) {
    double *nbk = node + ids[q] * ND;
    for (int d = 0; d < DIM; ++d) {
      const double vn = held[d] ? 0.0 : v[q * DIM + d];
      nbk[GridDof::P + d] = vn;
      nbk[GridDof::F + d] = held[d] ? 0.0 : (vn - vold[q * DIM + d]) / dt;
    }
  }
}
} // namespace

// The tail rule. A continuum body with a tail share of the node (uGIMP blocks reach the next row of
// nodes with weights down to 1e-8) has an unreliable own f/m there (interface.hpp): it takes the
// common acceleration, and its force goes to the other bodies at the node in proportion
// to their mass, so the node's momentum keeps every force (dropping the tail forces left
// an unbalanced force of 150x the mean nodal load in the landfill, which never converged).
// A sheet can be a tail too: with a small share of a node and no body on one side of it
// there, its share of the point's load has nothing to rest on at this node (the body beneath
// reaches the sheet's other row of nodes only: uGIMP blocks keep their size while the waste
// compresses), contact separates it from the body above, and the point crept down at a rate
// that falls with that share: the sinkhole's geostatic stage stalled at a ratio of 5e-4 for
// 20,000 steps. Moving with the bodies at the node, it converges in 1,084 steps to 1e-4.
// A body on that side with only a tail share counts as none: it takes the common
// acceleration, so it holds nothing up either. Where a sheet turns over a convex corner
// just under a node row (the slope's crest), the row above has the cover soil, a sliver of
// the sheet and a tail of the waste; the sheet and the waste's tail, one block under the
// normal projection, separated from the soil and ran at the sheet's own f / m (45 mm/s
// against the crest's 0.3 mm/s), and that sliver of velocity, carried into the points, kept
// the crest creeping: the slope's stage 2 at h = 0.25 m stopped at its 30,000-step cap
// (ratio 1.8e-2); with this rule it converges in 3,588 steps
// (docs/benchmarks/relaxation_steps.md).
//
// At every node with two bodies or more: the bodies with mass, the tail rule, the faces between
// them, the normal from the chains' weighted point normals, and contact_stack's exchange.
void contact_bodies(const GridView &G, const std::vector<Chain> &chains, const ContactParams &prm,
                    bool normal_pass, ContactStats &st) {
  constexpr int ND = GridDof::NDOF;
  const double dt = prm.dt;
  const int nb = G.nbody;
  if (nb > kMaxBodies) return; // guarded at setup
  if (!normal_pass) st.friction.assign(chains.size(), 0.0);
  for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j)
    for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
      double *node = G.node(i, j);
      const double msum = G.body_mass_sum(node);
      if (msum <= 0) continue;
      // every body with mass takes part (a share cut-off at round-off level decided differently
      // on different rank counts); tiny shares follow the tail rule (below)
      int ids[kMaxBodies], k = 0;
      for (int b = 0; b < nb; ++b)
        if (node[b * ND + GridDof::M] > 0) ids[k++] = b;
      if (k < 2) continue;
      bool held[DIM];
      held_dofs(i, j, G.ncell, prm.face, held);
      double n[DIM] = {0, 0}; // the chains' weighted point normals at this node
      for (const Chain &c : chains) {
        n[0] += node[c.slot + ChainDof::NX];
        n[1] += node[c.slot + ChainDof::NY];
      }
      const double nn = std::hypot(n[0], n[1]);
      double m[kMaxBodies], v[DIM * kMaxBodies], vold[DIM * kMaxBodies], acm[DIM] = {0, 0};
      gather_bodies(node, k, ids, msum, dt, m, v, vold, acm);
      // the tail rule (above): tails take the common acceleration, the others share their force
      double ptot[DIM] = {0, 0}, pnew[DIM] = {0, 0}, mfull = 0;
      auto continuum_tail = [&](int q) { return ids[q] % 2 == 0 && m[q] < prm.tail_share * msum; };
      auto is_tail = [&](int q) {
        if (ids[q] % 2 == 0) return continuum_tail(q);
        if (!(m[q] < prm.chain_tail_share * msum)) return false;
        bool none_below = true, none_above = true; // nothing but continuum tails on that side
        for (int r = 0; r < q; ++r) none_below = none_below && continuum_tail(r);
        for (int r = q + 1; r < k; ++r) none_above = none_above && continuum_tail(r);
        return none_below || none_above;
      };
      for (int q = 0; q < k; ++q) {
        const bool tail = is_tail(q);
        for (int d = 0; d < DIM; ++d) {
          ptot[d] += m[q] * v[q * DIM + d];
          if (tail) v[q * DIM + d] = vold[q * DIM + d] + dt * acm[d];
          pnew[d] += m[q] * v[q * DIM + d];
        }
        if (!tail) mfull += m[q];
      }
      for (int q = 0; q < k; ++q)
        if (!is_tail(q))
          for (int d = 0; d < DIM; ++d) v[q * DIM + d] += (ptot[d] - pnew[d]) / mfull;
      StackFace faces[kMaxBodies];
      StackFaceResult res[kMaxBodies];
      node_faces(node, chains, k, ids, nn, dt, normal_pass, faces);
      const double nu[DIM] = {nn > kNoNormal ? n[0] / nn : 0.0, nn > kNoNormal ? n[1] / nn : 1.0};
      contact_stack(k, m, v, faces, nu, res);
      if (normal_pass) { // the normal impulses only: they do not depend on the friction
        store_normal_impulses(node, chains, k, ids, res);
        continue;
      }
      record_contact(node, chains, k, ids, res, dt, st);
      scatter_bodies(node, k, ids, v, vold, held, dt);
    }
}

} // namespace pmpm
