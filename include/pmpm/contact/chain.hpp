// A membrane (geomembrane, geotextile) as a chain of material points: the seed paper's "single
// layer of material points" (section 3.2) at any cell size. Its thickness t is a property, not a
// resolved dimension (docs/method.md, section 7.1).
//
// A chain is an ordered line of points from left to right (x increasing). Segment k joins points
// k and k + 1; its engineering strain eps_k = l_k / l0_k - 1 gives the axial force per unit width
// T_k (N/m) from the membrane law (membrane_law.hpp), with axial stiffness J = E t / (1 - nu^2)
// (plane strain, the default: the sheet cannot strain out of plane) or E t (uniaxial). Point i
// carries the mass and weight of half of each adjacent segment and the internal force
//   f_i = T_i tau_i - T_{i-1} tau_{i-1}      (tau_k the unit vector along segment k).
//
// On the grid a chain is a body of its own (bodies: the material below a chain is body b - 1,
// the chain b, the material above b + 1). Its points reach the nodes through uGIMP blocks one
// cell long along the sheet and thin across it (chain.cpp, point_halfsize), so the sheet touches
// the nodes of the cells it crosses: exactly the nodes both its neighbours share. The chain's
// geometry sums (ChainDof) give the contact normal at a node as the weighted mean of its points'
// normals (the paper's single-layer rule: the normal of point i is perpendicular to
// x_{i+1} - x_{i-1}). contact_stack.hpp resolves the stacked bodies at each node: no
// interpenetration, separation where the faces pull apart (contact) or not (paper, bonded),
// Coulomb friction per face.
//
// Under -geometry axisymmetric (x the radius r) a chain is a membrane of revolution, every
// quantity per radian as the grid's: point i carries its mass, weight and end load times its
// initial radius, and segment k, besides its meridional strain eps_k, a hoop strain
// th_k = r_k / R_k - 1 (r_k its midpoint's radius, R_k the same when laid). From the energy per
// radian sum_k l0_k R_k W(eps_k, th_k) of a plane-stress sheet, W = J/2 (eps^2 + 2 nu eps th +
// th^2), J = E t / (1 - nu^2): meridional and hoop tensions N = J (eps + nu th), N_th = J (th +
// nu eps) per unit length, and the forces
//   f_i = R_i N_i tau_i - R_{i-1} N_{i-1} tau_{i-1} - (l0_{i-1} N_th,i-1 + l0_i N_th,i) / 2 e_r.
// The tension_only law is a tension-field (wrinkling) model there: a compressive principal
// tension is zero and the other direction carries the uniaxial E t strain. A point on the axis
// keeps r = 0.
//
// Distribution: a chain has O(width / h) points against O(area / h^2) particles, so every rank
// holds all its points. The rank owning a point's cell (DMSwarm's rule, Grid::owns_cell) maps it
// to the grid and updates it; one allreduce per step (sum, other ranks contribute zeros) makes
// the points identical everywhere, so neighbours across rank boundaries need no search and the
// answer does not depend on the rank count.
#pragma once
#include "pmpm/contact/contact_stack.hpp"
#include "pmpm/core/grid.hpp"
#include "pmpm/materials/membrane_law.hpp"
#include "pmpm/core/shape.hpp"
#include "pmpm/core/transfers.hpp"
#include <string>
#include <vector>

namespace pmpm {

// Per-node slots of one chain's geometry, after the bodies' blocks (Grid::nd).
struct ChainDof {
  static constexpr int NX = 0, NY = 1; // sum_i w m_i n_i (the normal, pointing to the body above)
  static constexpr int LEN = 2;        // sum_i w l_i (the sheet's length the node carries)
  static constexpr int NTOP = 3, NBOT = 4; // normal impulse on the upper / lower face (N s/m)
  static constexpr int STOP = 5, SBOT = 6; // friction impulse on the chain along tau, per face
  static constexpr int PTOP = 7, PBOT = 8; // normal impulse pooled over the sheet (N s/m)
  static constexpr int AREA = 9; // LEN had the sheet run on past its ends (chain_face_area_ends)
  static constexpr int NDOF = 10;
};

enum class StiffnessKind { PlaneStrain = 0, Uniaxial = 1 };
inline constexpr const char *StiffnessKindNames[] = {"plane_strain", "uniaxial", "StiffnessKind",
                                                     "STIFFNESS_", nullptr};

// -chain_<name>_interface: contact_stack's FaceType, in its order.
inline constexpr const char *FaceTypeNames[] = {"bonded",   "paper", "contact",
                                                "FaceType", "FACE_", nullptr};

// Friction on one face of a chain: Coulomb mu (or tan delta) plus an adhesion (Pa).
using ChainFace = MembraneFace;

// What a scene gives to make a chain.
struct ChainSpec {
  std::string name;         // options prefix -chain_<name>_ and output chain_<name>.csv
  std::string material;     // options prefix -mat_<material>_
  std::vector<double> line; // polyline x0, y0, x1, y1, ... (x increasing)
  double thickness = 0;     // t (m)
  bool pin_start = false, pin_end = false; // end points held fixed (supports)
  double end_force[DIM] = {0, 0};          // dead load on the last point (N/m), ramped
};

struct Chain {
  std::string name, material;
  int body = 1; // its body index on the grid
  int slot = 0; // offset of its ChainDof block in a node
  double thickness = 0, E = 0, nu = 0, gamma = 0, density = 0;
  StiffnessKind stiffness = StiffnessKind::PlaneStrain;
  MembraneLaw law;
  double line_mass = 0;   // inertial mass per unit initial length (kg/m), possibly scaled
  double line_weight = 0; // gamma t (N/m per m): the load, never scaled
  ChainFace top, bottom;
  bool pin[2] = {false, false};
  double end_force[DIM] = {0, 0};
  // points (every rank holds all of them)
  int n = 0;
  std::vector<double> x, x0, v, mass, weight, length; // length: l0 share of each point
  std::vector<double> f;                              // internal force (DIM per point)
  // segments
  std::vector<double> l0, eps, eps_p, alpha, T;
  // -chain_strain_projection: each segment's strain is the grid's projection of the chord
  // strains (chain.cpp, chain_update_tension); eps_chord keeps the chord strains. The grid's
  // geometry is kept for it (every rank projects all segments, as it holds all points).
  bool strain_projection = false; // set from -chain_strain_projection (on by default)
  double grid_h = 0, grid_origin[DIM] = {0, 0};
  PetscInt grid_ncell[DIM] = {0, 0};
  std::vector<double> eps_chord;
  std::vector<char> slack;
  // -geometry axisymmetric (above): per segment the rest radius R_k of its midpoint, its hoop
  // strain and hoop tension (N/m)
  bool axisymmetric = false;
  std::vector<double> r0, eps_hoop, T_hoop;
  // point i's weight per radian: its initial radius (axisymmetric), else 1
  double ring(int i) const { return axisymmetric ? x0[i * DIM] : 1.0; }
  // per point, accumulated from the grid: slip on each face (m), contact pressure (Pa)
  std::vector<double> slip_top, slip_bot, p_top, p_bot;
  std::vector<char> owned;   // this rank updates the point (scratch of g2p_chain)
  std::vector<double> x_new; // the points' new positions (scratch of g2p_chain)
  // last step's totals: friction force on the chain along its tangent (N/m) and the reaction at
  // pinned ends (N/m)
  double friction_force = 0;
  double reaction[2][DIM] = {{0, 0}, {0, 0}};

  double wave_speed() const { return std::sqrt(law.J / line_mass); }

  // The checkpointed scalars (checkpoint.cpp, /chains/<k> attributes): f(name, field) for each;
  // the evolving arrays are checkpoint_arrays'.
  template <class F> PetscErrorCode checkpoint_fields(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("top_type", top.type));
    PetscCall(f("bottom_type", bottom.type));
    PetscCall(f("top_mu", top.mu));
    PetscCall(f("bottom_mu", bottom.mu));
    PetscCall(f("line_mass", line_mass));
    PetscCall(f("friction_force", friction_force));
    PetscFunctionReturn(0);
  }
  // The checkpointed arrays (checkpoint.cpp, /chains/<k> datasets): f(name, array) for each of
  // the evolving per-point and per-segment arrays, the segments' slack flags and the pinned ends'
  // reactions.
  template <class F> PetscErrorCode checkpoint_arrays(F &&f) {
    PetscFunctionBeginUser;
    PetscCall(f("x", x));
    PetscCall(f("x0", x0));
    PetscCall(f("v", v));
    PetscCall(f("f", this->f));
    PetscCall(f("length", length));
    PetscCall(f("l0", l0));
    PetscCall(f("eps", eps));
    PetscCall(f("eps_p", eps_p));
    PetscCall(f("alpha", alpha));
    PetscCall(f("T", T));
    PetscCall(f("slip_top", slip_top));
    PetscCall(f("slip_bot", slip_bot));
    PetscCall(f("p_top", p_top));
    PetscCall(f("p_bot", p_bot));
    PetscCall(f("slack", slack));
    PetscCall(f("reaction", reaction));
    if (axisymmetric) PetscCall(f("r0", r0));
    PetscFunctionReturn(0);
  }
};

// The strain projection (-chain_strain_projection) at given positions x (DIM per point): segment
// k's chord strain goes to node I with w_Ik, the uGIMP weight there of a block at the segment's
// midpoint along its chord (the points' blocks), node I's strain is e_I = sum_k w_Ik l0_k e_k /
// M_I with M_I = sum_k w_Ik l0_k, and segment k's projected strain sum_I w_Ik e_I. The operator
// is linear in e: (P e)_k = sum_j P_kj e_j with P_kj = sum_I w_Ik w_Ij l0_j / M_I, and l0_k P_kj
// is symmetric. Nodes are numbered compactly in the order segments first reach them.
struct ChainProjection {
  std::vector<int> start;   // segment k's entries are [start[k], start[k + 1])
  std::vector<int> node;    // an entry's node (compact number)
  std::vector<double> w;    // an entry's weight w_Ik
  std::vector<double> mass; // per node: M_I
};
void chain_projection(const Chain &c, const double *x, ChainProjection &P);
// out = P e (out may be e).
void chain_project(const Chain &c, const ChainProjection &P, const double *e, double *out);

// Build the points from a spec: spacing at most `ds` along the polyline; material constants and
// law from -mat_<material>_*; friction per face from -chain_<name>_* (defaults: the
// -interface_* options). Collective (options).
PetscErrorCode ChainCreate(MPI_Comm comm, const ChainSpec &spec, double ds, Chain &c);

// Kernels (plain functions; cycle.cpp calls them between the PETSc exchanges).
// Segment strains and tensions from the current positions (law, plastic state), then the
// internal point forces.
void chain_update_tension(Chain &c);
// Mass, momentum, force (internal, weight, end load) and geometry of the points this rank owns
// into body c.body's block and the chain's slots.
void p2g_chain(const Chain &c, const Load &load, const GridView &G, const Grid &grid);
// Point i's uGIMP weights on the grid (its thin block, as p2g_chain maps it) from the current
// positions, and whether this rank maps it: it owns the point's cell and the point is not pinned
// (Grid::owns_cell; a point off the grid is nobody's). Only origin, ncell and h of G are read.
bool chain_point_weights(const Chain &c, int i, const GridView &G, const Grid &grid,
                         Weights<UGIMPShape> &W);
// Points this rank owns (Chain::owned): FLIP/PIC velocity, position; slip and pressure on each
// face from the neighbouring bodies (a body counts at a node above tail_share of the node's
// mass: -interface_tail_share, as the 3D sheet's, step/sheets.cpp). The caller shares them
// (chain_pack, allreduce, unpack).
void g2p_chain(Chain &c, const GridView &G, const Grid &grid, const G2PParams &prm,
               double tail_share);
// Pack / unpack the fields the owner updates, for the allreduce.
void chain_pack(const Chain &c, std::vector<double> &buf);
void chain_unpack(Chain &c, const std::vector<double> &buf);
// How many points a summed buffer says were owned (each must be, exactly once).
int chain_owner_count(const std::vector<double> &buf, int n);

// The contact between stacked bodies at every owned node where two or more bodies meet, after
// grid_update: per-body velocities and accelerations replaced by contact_stack's answer.
struct ContactParams {
  double dt = 0;
  double tail_share = 1e-3; // continuum body below this share of the node: common acceleration
  // A sheet below this share of the node with no body on one side of it there (the lowest or
  // highest body at the node, bodies below tail_share not counted) moves with the bodies at the
  // node (chain.cpp, contact_bodies).
  double chain_tail_share = 0.05;
  FaceBC face[2 * DIM] = {FaceBC::Free, FaceBC::Free, FaceBC::Free, FaceBC::Free};
};
struct ContactStats {
  double contact_nodes = 0, slip_nodes = 0, separated_nodes = 0;
  double compression = 0, tension = 0; // normal impulse this step (N s/m)
  std::vector<double> friction;        // per chain: friction force on it along its tangent (N/m)
  std::vector<double>
      friction3; // per 3D sheet (sheet_contact.hpp): the friction force on it (N, 3)
};
// One resolved node's counts: a contact node, and a slip / separated node when any of its k - 1
// faces slipped / let go; each face's normal impulse into compression or tension. Result is
// contact_stack's (2D) or contact_stack3's (3D) face result.
template <class Result> void count_stack_faces(int k, const Result *res, ContactStats &st) {
  st.contact_nodes += 1;
  bool slipped = false, separated = false;
  for (int q = 0; q + 1 < k; ++q) {
    slipped = slipped || res[q].slip;
    separated = separated || !res[q].contact;
    if (res[q].normal > 0)
      st.compression += res[q].normal;
    else
      st.tension -= res[q].normal;
  }
  if (slipped) st.slip_nodes += 1;
  if (separated) st.separated_nodes += 1;
}
// normal_pass: only the normal impulses (into the chains' NTOP / NBOT slots; velocities
// untouched); then chain_friction_capacity; then the full pass with that friction capacity.
void contact_bodies(const GridView &G, const std::vector<Chain> &chains, const ContactParams &prm,
                    bool normal_pass, ContactStats &st);
// The friction capacity of each chain face at the owned nodes of G (PTOP / PBOT: sheet length
// times contact pressure, N s/m per dt), from the normal impulses of the normal pass read from
// the ghosted view L. Each point's pressure is its stencil's normal impulse over its sheet length,
// over the nodes where that face is in contact, and goes back to those nodes only. The sheet
// straddles two node rows and its force reaches them with its own weights, whereas the bodies
// beside it press the rows unevenly: with each node's own impulse as the capacity the
// less-pressed row slipped first and the sheet crept, holding 2 mu min(N_j, N_j+1) per column
// instead of mu (N_j + N_j+1) (pull-out: anchored length 14 % long at h = 0.02 m, 51 % at 0.01 m).
// Returning the pressure to the contact nodes only keeps it under the bodies' footprint (spread
// over all of a point's stencil, a block's ends lost 10 % of the incline's friction).
void chain_friction_capacity(const GridView &L, const GridView &G,
                             const std::vector<Chain> &chains);

// Lay the sheet where it is, unstrained: each segment's rest length becomes its current length,
// plastic state, slip and tension start from zero (a membrane placed on settled ground; x0 keeps
// the initial positions, so totals stay available).
void chain_lay(Chain &c);

// Elastic energy of a chain (J/m): sum_k T_k^2 l0_k / (2 J).
double chain_elastic_energy(const Chain &c);

} // namespace pmpm
