// A geomembrane as a sheet in 3D (issue 23): the chain's ideas (chain.hpp) lifted one dimension.
// The sheet is a lattice of points joined by triangles (a structured mesh of the sheet); its
// thickness t is a property, not a resolved dimension. This file holds the sheet's own mechanics,
// plain functions over its arrays: the lattice, the membrane law and the internal point forces.
// Coupling to the 3D grid: src/step/sheets.cpp (mass, momentum and forces to the nodes, the
// points moved by the grid's velocity), and for a sheet between bodies the contact on both faces,
// sheet_contact.hpp.
//
// Kinematics: each triangle maps its reference (laid) position to the current one with a constant
// deformation gradient F (3 x 2, over the triangle's own orthonormal in-plane reference basis
// e1, e2). C = F^T F = U^2 gives the principal stretches l1 >= l2 and their reference directions
// n1, n2; the Biot strains b_i = l_i - 1 are the chain's engineering strain l / l0 - 1 in each
// principal direction.
//
// Law (per unit reference area): the plane-stress sheet of the chain of revolution,
//   W = J/2 (b1^2 + 2 nu b1 b2 + b2^2),   J = E t / (1 - nu^2),
// with principal tensions (N/m) N1 = J (b1 + nu b2), N2 = J (b2 + nu b1). A strip stretched
// along one direction with the other held (b2 = 0) carries N1 = J b1: the plane-strain chain's
// T = J eps, so an extruded chain and its sheet share one law. The tension-field law
// (-mat_<name>_law tension_only, as for chains) is the mixed criterion of tension-field theory
// (Stein and Hedgepeth 1961; Roddeman et al. 1987): taut when N2 >= 0 (the law above); wrinkled
// when N2 < 0 < b1 (the wrinkles carry nothing across: N2 = 0, N1 = E t b1, W = E t b1^2 / 2);
// slack when b1 <= 0 (nothing). W is continuous across the three states.
// The elastoplastic law (-mat_<name>_law elastoplastic): sheet_plastic_forces below.
//
// Forces: the first Piola-Kirchhoff tension P = F sum_i (N_i / l_i) n_i n_i^T (3 x 2; the
// rotation of the Biot tension, which is coaxial with U) and, for each corner a of a triangle of
// reference area A0 with linear shape gradient g_a (in e1, e2),
//   f_a -= A0 P g_a,
// the gradient of -sum A0 W over the points (tests/unit/test_sheet.cpp checks it by differences).
// Each point carries a third of the mass and weight of every triangle it belongs to.
#pragma once
#include "pmpm/contact/contact_stack.hpp"
#include <cmath>
#include <string>
#include <vector>

namespace pmpm {

enum class SheetLaw { Linear = 0, TensionField = 1, Elastoplastic = 2 };

// The elastoplastic sheet (-mat_<name>_law elastoplastic): plane-stress von Mises on the membrane
// forces with linear isotropic hardening, the chain's 1D law lifted (its yield force
// N_y = sigma_y t and hardening H t per width). Over a triangle's laid basis, with the Biot strain
// B (e11, e22, e12: tensor components), the plastic strain Bp and the accumulated plastic strain
// alpha, the forces are N = C (B - Bp) with C the plane-stress elasticity (J = E t / (1 - nu^2):
// N11 = J (e11 + nu e22), N22 = J (e22 + nu e11), N12 = J (1 - nu) e12), and
//   q(N) = sqrt(N11^2 - N11 N22 + N22^2 + 3 N12^2) <= N_y + H alpha.
// Past it the return is closest-point (associative): in the coordinates a = (N11 + N22) / sqrt 2,
// b = (N22 - N11) / sqrt 2, c = N12, where C and q are both diagonal, a = a_tr / (1 + J (1 + nu)
// l / 2), b = b_tr / (1 + 3 J (1 - nu) l / 2), c likewise, with the one scalar l >= 0 from
// q(l) (1 - H l) = N_y + H alpha_n (bisection: q falls monotonically in l); then
// d alpha = l q and dBp = l (a / 2, 3 b / 2, 3 c / 2) in those coordinates (Simo and Hughes 1998,
// section 3.4, the plane-stress return in forces). A state on the yield surface (within 1e-12 of
// its radius) is left as it is, so a restart that recomputes the forces at the checkpoint's
// positions changes nothing. N: out (N11, N22, N12); Bp (3) and alpha updated in place.
void sheet_plastic_forces(double J, double nu, double yield_N, double hardening, const double B[3],
                          double Bp[3], double &alpha, double N[3]);

// Principal tensions (N/m) for principal Biot strains b1 >= b2 and the sheet's state there.
enum class SheetState { Taut = 0, Wrinkled = 1, Slack = 2 };
struct SheetTensions {
  double N1 = 0, N2 = 0;
  SheetState state = SheetState::Taut;
};
SheetTensions sheet_tensions(SheetLaw law, double J, double nu, double b1, double b2);
// The law's energy per unit reference area (J/m^2), W above.
double sheet_energy_density(SheetLaw law, double J, double nu, double b1, double b2);

struct Sheet {
  std::string name = "membrane"; // its files' and its material's name
  SheetLaw law = SheetLaw::Linear;
  double J = 0, nu = 0;                  // J = E t / (1 - nu^2) (N/m), Poisson's ratio
  double yield_N = 0, hardening = 0;     // Elastoplastic: sigma_y t, H t (N/m)
  double area_mass = 0, area_weight = 0; // rho t (kg/m^2), gamma t (N/m^2)
  // points (3 per point in x, x0, v, f)
  int n = 0;
  std::vector<double> x, x0, v, f;
  std::vector<double> nrm; // unit normal per point (the mean of its triangles'), sheet_normals
  std::vector<double> area, mass, weight; // a third of each adjacent triangle's reference area
  std::vector<char> pinned;               // held fixed (a clamped rim)
  std::vector<char> held; // per point, bit d: component d held (a roller; empty: none)
  // triangles: corners (3 per triangle), reference area, the inverse of the reference edge
  // matrix D = [X1 - X0, X2 - X0] in e1, e2 (row-major 2 x 2), the basis e1, e2 (6 per triangle)
  int nt = 0;
  std::vector<int> tri;
  std::vector<double> a0, dinv, basis;
  // per triangle after sheet_update_forces: the Biot strain U - I in e1, e2 (B11, B22, B12), the
  // principal strains b1 >= b2 and tensions N1, N2, the state
  std::vector<double> biot, b, N;
  std::vector<SheetState> state;
  // per triangle: the forces' tensor (N11, N22, N12 in e1, e2; its principal values are N), and
  // under the elastoplastic law the plastic strain (3) and the accumulated plastic strain
  std::vector<double> tens, bp, alpha;
  // per triangle: its first Piola-Kirchhoff tension P (3 x 2, row-major; its corners' forces are
  // -A0 P g_a), and whether this rank's values of the triangle's arrays are those of the current
  // positions (under MPI a rank computes only the triangles near its cells,
  // src/step/sheets.cpp)
  std::vector<double> P;
  std::vector<char> fresh;
  // Under MPI (src/step/sheets.cpp): the points whose blocks can reach this rank's nodes,
  // increasing (empty: every point, as on one rank); the points this rank moves (the owner of
  // their cell; valid when mine_valid); per point, whether this rank's position and velocity are
  // the current ones (the points of its own and its neighbours' cells; empty: every point).
  std::vector<int> reach, mine;
  bool mine_valid = false;
  std::vector<char> here;

  // On the grid (sheet_contact.hpp): a sheet alone is the grid's only body (body 0, no slots);
  // a sheet between bodies is a body of its own, body - 1 below it and body + 1 above, with its
  // SheetDof slots at `slot` of each node, `up` (+1 or -1) turning its points' normals to point
  // from the body below to the body above, and friction on each face.
  int body = 0, slot = -1;
  double thickness = 0; // t (m), for the answers beside closed forms (the law holds J)
  double up = 1;
  MembraneFace top, bottom;
  // per point: a dead load (N, 3 per point; ramped with the load factor; empty: none), and from
  // the grid when between bodies: the slip on each face (a vector in the sheet's plane, m, 3 per
  // point) and the contact pressure on each face (Pa, negative: tension)
  std::vector<double> fend, slip_top, slip_bot, p_top, p_bot;
  bool in_contact() const { return slot >= 0; }

  // the in-plane wave speed sqrt(J / rho t) (the stable step's)
  double wave_speed() const { return std::sqrt(J / area_mass); }

  // The checkpointed state (checkpoint.cpp, /sheets/<k> datasets): f(name, array) for the
  // positions and velocities (and an elastoplastic sheet's plastic state); the lattice and its
  // reference come from the options, the forces, strains and normals from x (sheet_update_forces,
  // sheet_normals).
  template <class F> int checkpoint_arrays(F &&f) {
    int err = f("x", x);
    if (!err) err = f("v", v);
    if (!err && in_contact()) err = f("x0", x0); // a sheet between bodies may be laid (sheet_lay)
    if (!err && law == SheetLaw::Elastoplastic) err = f("plastic_strain", bp);
    if (!err && law == SheetLaw::Elastoplastic) err = f("alpha", alpha);
    if (!err && in_contact()) err = f("slip_top", slip_top);
    if (!err && in_contact()) err = f("slip_bottom", slip_bot);
    return err;
  }
};

// A flat disc of radius R centred at c, in the horizontal plane y = c[1] (pmpm's vertical is y;
// the sheet spans x and z): a centre point and rings at r_k = R k / K, K = ceil(R / ds), ring k
// holding 6k points (spacing pi/3 of the ring gap), joined ring to ring by triangles; the rim
// (ring K) is pinned. Points and triangles in a fixed order (rank-independent). Sets x = x0, v = 0
// and the reference (sheet_reference); the law and material constants are the caller's.
void sheet_disc(double R, double ds, const double c[3], Sheet &s);
// A flat rectangle in the horizontal plane y = y: points at x = x0 + i dx (i = 0 .. nx - 1) and
// z = z0 + j dz (j = 0 .. nz - 1), point (i, j) numbered i nz + j, each lattice square split into
// two triangles along its diagonal, the diagonals alternating square by square (no direction
// preferred). Nothing pinned. Sets x = x0, v = 0 and the reference (sheet_reference).
void sheet_rectangle(double x0, double dx, int nx, double z0, double dz, int nz, double y,
                     Sheet &s);
// A line (x_i, y_i), i = 0 .. nx - 1 (xy: 2 per point), swept along z: points at z = z0 + j dz
// (j = 0 .. nz - 1), numbered and triangulated as sheet_rectangle's (a level line with
// x_i = x0 + i dx is that rectangle). A sloped or bent line gives a ruled sheet: a cover's
// membrane over a side slope and its crest. Nothing pinned; x = x0, v = 0, the reference.
void sheet_strip(const double *xy, int nx, double z0, double dz, int nz, Sheet &s);
// The reference geometry from x0: areas, D^-1, bases; point areas, masses and weights.
void sheet_reference(Sheet &s);
// Strains, tensions and the internal point forces f from the current positions x.
void sheet_update_forces(Sheet &s);
// The same for the listed triangles only (increasing): f is complete at the points all of whose
// triangles are listed, and equal bit for bit to the whole sheet's there (the same sums in the
// same order). The other triangles' arrays keep older values (not fresh); an elastoplastic
// triangle's plastic state advances only where it is computed.
void sheet_update_forces(Sheet &s, const std::vector<int> &tris);
// f summed over every triangle from its stored P, once every triangle's arrays are those of the
// current positions (after a partial update, src/step/sheets.cpp's SheetsComplete takes the
// others' from the ranks that computed them); every triangle is then fresh.
void sheet_sum_forces(Sheet &s);
// Lay the sheet where it is, unstrained (chain_lay's 3D form): the current positions become the
// reference (sheet_reference), the plastic state and the slips start from zero, the forces are
// recomputed (zero).
void sheet_lay(Sheet &s);
// The stored energy sum_t A0 W (J).
double sheet_energy(const Sheet &s);
// The points' unit normals from the current positions: the area-weighted mean of the normals
// of the triangles around each point.
void sheet_normals(Sheet &s);
// The same from the listed triangles only: exact at the points all of whose triangles are listed.
void sheet_normals(Sheet &s, const std::vector<int> &tris);
// A disc's answers (sheet_disc's lattice of radius R and ring gap dr): the centre strain (the
// mean of (b1 + b2) / 2 over the triangles at the centre point) and the rim's radial strain (the
// area-weighted radial strain of the outer band of triangles, centroids within dr of the rim, and
// of the next band, extrapolated linearly to the rim, as a chain's two last segments are).
struct SheetDiscStrains {
  double centre = 0, rim = 0;
};
SheetDiscStrains sheet_disc_strains(const Sheet &s, const double c[3], double R, double dr);
// Principal values per point for reporting: the area-weighted mean over the point's triangles of
// the Biot strain tensor and of the tension tensor (each triangle's N1 n1 n1^T + N2 n2 n2^T), as
// 3D tensors over the reference configuration, projected on the plane normal to the triangles'
// mean reference normal; its two principal values, major first. strain and tension get 2 per
// point. A point's mean smooths a one-triangle peak: the peak itself is sheet_peak_principal's.
void sheet_point_principal(const Sheet &s, std::vector<double> &strain,
                           std::vector<double> &tension);
// Triangle t's major principal direction in 3D (the reference configuration's).
void sheet_major_direction(const Sheet &s, int t, double dir[3]);
// The design answer: the point with the largest major principal strain (sheet_point_principal's
// means: a triangle's own strain carries the lattice's triangle-to-triangle scatter, 1.36 to 1.52 %
// around a clamped disc's rim at h = 1 m), the minor strain there (the biaxial state), the
// tensions, the point's current position; and the largest strain of a single triangle.
struct PeakPrincipal {
  int point = -1;
  double strain1 = 0, strain2 = 0, tension1 = 0, tension2 = 0, x[3] = {0, 0, 0};
  double triangle_strain1 = 0;
};
PeakPrincipal sheet_peak_principal(const Sheet &s);
// Triangle t's Biot strain along a unit reference direction d (3 components, in the sheet's
// plane): d^T (U - I) d.
double sheet_strain_along(const Sheet &s, int t, const double d[3]);

} // namespace pmpm
