// The transfer kernels of one explicit MPM step, as plain functions over plain views:
//   p2g          mass, momentum, internal and external force to the nodes   (eq. 7, 8, 9 / 14)
//   grid_update  nodal momentum balance with damping and boundary conditions (eq. 1, 2)
//   g2p          particle velocity, position and velocity gradient          (eq. 4, 5, 20)
// They touch no PETSc object; cycle.cpp calls them between the ghost exchanges. Each is a
// template on the dimension D (2 or 3, deduced from the grid view); the step runs D = 2, or D = 3
// under -dim 3, and the 2D results are those of the 2D kernels written out, bit for bit (developer
// guide, "Dimensions"). The particle arrays of ParticleView hold D (x, v, lp), D*D (F, B) and
// NStress<D> (stress) values per particle.
#pragma once
#include "pmpm/core/grid.hpp"
#include "pmpm/core/particles.hpp"
#include "pmpm/core/shape.hpp"
#include <vector>

namespace pmpm {

enum class FaceBC { Free = 0, Roller = 1, Fixed = 2 };
inline constexpr const char *FaceBCNames[] = {"free", "roller", "fixed", "FaceBC", "BC_", nullptr};
enum Face { XMIN = 0, XMAX = 1, YMIN = 2, YMAX = 3, ZMIN = 4, ZMAX = 5 };

// Loads at the current step: the ramp factor multiplies gravity and tractions alike.
// det F of a row-major D x D F (2D: the in-plane block's): a particle's volume ratio J.
template <int D> inline double det_of(const double *F) {
  if constexpr (D == 2)
    return F[0] * F[3] - F[1] * F[2];
  else
    return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
           F[2] * (F[3] * F[7] - F[4] * F[6]);
}

template <int D> struct LoadT {
  double factor = 1.0;
  double gdir[D] = {0.0, -1.0}; // unit direction of gravity (3D: set it; z is up there)
  double shrink = 0; // waste degradation: volumetric shrinkage this step (degradation.hpp)
};
using Load = LoadT<DIM>;

// The cells a rank owns, [lo, hi) per direction: a particle centred in another has left it.
template <int D> struct CellRangeT {
  PetscInt lo[D] = {}, hi[D] = {};
  bool owns(const PetscInt c[D]) const {
    for (int d = 0; d < D; ++d)
      if (c[d] < lo[d] || c[d] >= hi[d]) return false;
    return true;
  }
};
template <int D> inline CellRangeT<D> owned_cells(const GridT<D> &g) {
  CellRangeT<D> r;
  for (int d = 0; d < D; ++d) {
    r.lo[d] = g.cell_lo[d];
    r.hi[d] = g.cell_hi[d];
  }
  return r;
}

// idx (nidx entries) restricts the sum to some particles (an interface body); null: all.
// A view with an affine field (P.B, -transfer apic) adds APIC's affine momentum (affine.hpp).
// pshift (per particle, or null) is added to the in-plane normal stresses of the internal force:
// F-bar's group pressure (antilock.hpp).
template <class Shape, int D>
void p2g(const ParticleView &P, const LoadT<D> &load, const GridViewT<D> &G,
         const PetscInt *idx = nullptr, PetscInt nidx = 0, const double *pshift = nullptr);

// Interface normals (-interface_normals particles): sum_p V_p c_p grad S_ip / h over body 1, which
// points out of it (S_i falls away from node i), written over the FEXT slots of the whole view.
// In full cells it equals h times minus the central difference of the cell-average colour at
// the node; it differs in part-filled cells and reaches every node body 1's blocks touch.
// (D = 2, 3: the same in 3D, the gradient per h^2 of a volume.)
template <class Shape, int D>
void p2g_colour_gradient(const ParticleView &P, const PetscInt *idx, PetscInt nidx,
                         const GridViewT<D> &G);

// The paper's normals (section 3.2), first half: per cell, the volume of colour and the volume of
// all particles whose centres lie in it, summed over every particle (both bodies), into the FEXT
// slots of the cell's lower-left node. interface.hpp's cell_colour_normals finishes them.
template <int D> void p2g_cell_colour(const ParticleView &P, const GridViewT<D> &G);

// Surface tractions act at the particle's face point x + tface (tface scaled with the Shape's
// block when it deforms); linear hats there give the consistent nodal load of a traction on the
// body's face. idx lists the loaded particles; a load record (ParticleLoad in 2D) has D-vectors
// traction and tface.
template <class Shape, int D, class PLoad>
void p2g_traction(const ParticleView &P, const std::vector<PLoad> &loads,
                  const std::vector<PetscInt> &idx, double factor, const GridViewT<D> &G) {
  Weights<LinearShape, D> W;
  const double zero[D] = {};
  for (const PetscInt p : idx) {
    // The face sits where the shape's block ends: at the undeformed offset for PMPM, whose
    // blocks keep their initial size (consistent with eq. 14), scaled with the block for cpGIMP
    // (l / lp is exactly 1 for a block of fixed size).
    const PLoad &L = loads[P.load[p]];
    double lb[D], xf[D], t[D];
    const double *lp = P.lp + p * D, *l = Shape::template half<D>(lp, P.F + p * D * D, lb);
    for (int d = 0; d < D; ++d) {
      xf[d] = P.x[p * D + d] + L.tface[d] * (l[d] / lp[d]);
      t[d] = factor * L.traction[d];
    }
    weights<LinearShape, D>(xf, zero, G.origin, G.h, W);
    const int off = G.nbody > 1 ? P.body[p] * GridDofT<D>::NDOF : 0;
    for (int k = 0; k < W.NN; ++k) {
      PetscInt n[D];
      for (int d = 0, r = k; d < D; ++d, r /= 2) n[d] = W.base[d] + r % 2;
      double *node = G.node(n) + off;
      const double w = W.w[k];
      for (int d = 0; d < D; ++d) {
        node[GridDofT<D>::F + d] += w * t[d];
        node[GridDofT<D>::FEXT + d] += w * t[d];
      }
    }
  }
}

// Nodal dofs whose velocity is imposed (a moving or fixed support inside the box, such as a
// lowering trapdoor): entry k holds dof key[k] = (j * (ncell[0] + 1) + i) * DIM + d of node
// (i, j) at velocity v[k] (3D: ((k (ncell[1] + 1) + j) (ncell[0] + 1) + i) DIM + d, node
// (i, j, k), the same rule with x fastest). The grid update reports sum_k weight[k] f_k, with f the
// node's total force (internal + external) before the update: the force the body puts on the
// support, weighted (a weight v[k] / V for a support moving at V gives the force conjugate to V).
// Keys sorted ascending and unique (PrescribedVelocitySort).
struct PrescribedVelocity {
  std::vector<PetscInt> key;
  std::vector<double> v, weight;
  bool empty() const { return key.empty(); }
};
template <int D> inline PetscInt PrescribedKey(const PetscInt *n, int d, const PetscInt *ncell) {
  PetscInt key = n[D - 1];
  for (int e = D - 2; e >= 0; --e) key = key * (ncell[e] + 1) + n[e];
  return key * D + d;
}
inline PetscInt PrescribedKey(PetscInt i, PetscInt j, int d, const PetscInt ncell[DIM]) {
  const PetscInt n[2] = {i, j};
  return PrescribedKey<2>(n, d, ncell);
}
void PrescribedVelocitySort(PrescribedVelocity &pv);

template <int D> struct GridUpdateParamsT {
  double dt = 0;
  double damping_alpha = 0; // Cundall local non-viscous damping coefficient (0 = none)
  // FIRE (Bitzek et al. 2006, Phys. Rev. Lett. 97, 170201), the velocity mixing on the free dofs:
  //   v <- (1 - fire_mix) v + fire_mix s f / m,   s = |v|_M / |M^-1 f|_M (the last step's, global)
  // so that v turns toward the force; 0: none. The restart lives in the relaxation loop.
  double fire_mix = 0, fire_scale = 0;
  bool fire = false;       // sum GridStats::power, mv2, f2m (FIRE's restart test and norms)
  FaceBC face[2 * D] = {}; // FaceBC::Free
  const PrescribedVelocity *prescribed = nullptr; // may be null (none)
};
using GridUpdateParams = GridUpdateParamsT<DIM>;

// The grid update's report: its scalars (GridSums, the same in any dimension: the 3D step hands
// them on to the 2D report whole, cycle.cpp) and its D-vectors.
struct GridSums {
  double max_unbalanced = 0; // max over nodes with mass of |f_int + f_ext| (free dofs only)
  double sum_ext = 0;        // sum of |f_ext| over nodes with a load
  double n_ext = 0;          // number of those nodes
  double kinetic = 0;        // nodal kinetic energy 1/2 m v^2 after the update
  double support_power = 0;  // power of the supports on the body, -sum f v_prescribed (this rank)
  // over the free dofs of every body (this rank): the power of the nodal forces over the step,
  // sum f . (v_old + v_new) / 2 (not counting local damping, contact, friction or PIC), and
  // sum m v_new^2 and sum f^2 / m (FIRE's norms)
  double power = 0, mv2 = 0, f2m = 0;
};
template <int D> struct GridStatsT : GridSums {
  double max_at[D] = {};        // the node of max_unbalanced (this rank's)
  double support_force[D] = {}; // sum of weight f over the prescribed dofs (this rank)
};
using GridStats = GridStatsT<DIM>;

// On the owned nodes of the global vector: v = p/m, a = (f - alpha |f| sign(v)) / m, v += dt a,
// boundary conditions on both. Nodes without mass are skipped. A prescribed dof takes its
// velocity, a = (v_prescribed - p/m) / dt (0 when dt = 0), and counts as held in the unbalanced
// force.
template <int D>
void grid_update(const GridViewT<D> &G, const GridUpdateParamsT<D> &prm, GridStatsT<D> &stats);

template <int D> struct G2PParamsT {
  double dt = 0;
  double pic = 0;      // PIC fraction of the velocity update (0 = pure FLIP)
  double gdir[D] = {}; // gravity direction, for the power of the body forces
  // Fused stress update (null: none; dudx is written for the materials' batch update instead):
  // per material index, lambda and 2G of a linear elastic rate law, which g2p and
  // g2p_kinematics then apply to each particle's stress (elastic_rate_update) in place of
  // writing dudx. Only when every material is LinearElastic and nothing else reads dudx (no
  // F-bar, no eigenstrain): cycle.cpp decides. 2D only (elastic_rate_update is plane strain).
  const double *elastic = nullptr;
  // With elastic: per material E and nu, and G2P also sums the particles' elastic energy
  // (elastic_energy, material.hpp) of the stresses it updated into G2PStats::elastic: the pass
  // over the particles that relaxation's energy check made every few steps, fused (null: none).
  const double *energy = nullptr;
  // -geometry axisymmetric without the fused update: per particle the hoop strain increment
  // dt v_r / r and the hoop stretch r / r0, for the materials (StressBatch::hoop; null: none)
  double *hoop = nullptr;
};
using G2PParams = G2PParamsT<DIM>;

// G2P's report: its scalars (G2PSums, as GridSums) and the position of the first bad particle.
struct G2PSums {
  double max_c = 0, max_v = 0; // max_p c_p and max_p |v_p|
  double max_speed = 0;        // max_c + max_v (bounds c_p + |v_p|; the next stable step)
  double kinetic = 0;          // particle kinetic energy (APIC: with the affine part)
  double weight_power = 0;     // sum_p weight_p (gdir . v_p): body-force power per load factor
  PetscInt left_rank = 0;      // particles now centred outside this rank's cells
  PetscInt bad = 0;            // particles with J <= 0, a non-finite value, or off the grid
  PetscInt bad_pid = -1;       // the first such particle
  const char *bad_what = "";
  bool has_elastic = false; // G2PParams::energy given: elastic holds this rank's sum
  double elastic = 0;
};
template <int D> struct G2PStatsT : G2PSums {
  double bad_x[D] = {}; // where bad_pid is
};
using G2PStats = G2PStatsT<DIM>;

// USL in one pass: g2p_velocity and g2p_kinematics on the same nodal field. With P.B (APIC) the
// particle velocity is the nodal one interpolated (prm.pic unused), B_p is gathered, and the
// kinetic energy in stats includes the affine part; the velocity gradient for the stress update
// stays the weights' gradient form L = sum_i v_i grad w_ip^T (for linear hats it equals APIC's
// C_p, for uGIMP it does not: C_p is the L2-best affine fit over the block's weights).
// owned: the rank's cells (G2PStats::left_rank); the 2D overload takes them from the Grid.
template <class Shape, int D>
void g2p(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
         const CellRangeT<D> &owned, const G2PParamsT<D> &prm, const double *wave_modulus,
         double *dudx, G2PStatsT<D> &stats);
template <class Shape>
void g2p(const ParticleView &P, const GridView &G, const GridView *G1, const Grid &grid,
         const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats &stats) {
  g2p<Shape, DIM>(P, G, G1, owned_cells(grid), prm, wave_modulus, dudx, stats);
}

// Which nodal dofs a box face holds: a roller holds the normal one, fixed holds all. Node n (D
// indices) on the faces (XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX).
template <int D>
inline void held_dofs(const PetscInt *n, const PetscInt *ncell, const FaceBC *face, bool *held) {
  for (int d = 0; d < D; ++d) held[d] = false;
  for (int f = 0; f < 2 * D; ++f) {
    const bool on = f % 2 ? n[f / 2] == ncell[f / 2] : n[f / 2] == 0;
    if (!on || face[f] == FaceBC::Free) continue;
    if (face[f] == FaceBC::Fixed)
      for (int d = 0; d < D; ++d) held[d] = true;
    else
      held[f / 2] = true;
  }
}
inline void held_dofs(PetscInt i, PetscInt j, const PetscInt ncell[DIM], const FaceBC face[2 * DIM],
                      bool held[DIM]) {
  const PetscInt n[2] = {i, j};
  held_dofs<2>(n, ncell, face, held);
}

// Particle velocity from the nodal acceleration (FLIP, eq. 4) blended with the nodal velocity.
// G1 (may be null): the interface body's nodal field, read by particles with colour 1; it must
// share G's geometry (origin, h, ghost layout), as the interface grid does by construction.
template <class Shape, int D>
void g2p_velocity(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
                  const G2PParamsT<D> &prm);

// MUSL: mass and momentum of the updated particle velocities back to the grid, and the nodal
// velocity p/m with the boundary conditions (bounded even at nodes with tiny mass).
template <class Shape, int D> void p2g_momentum(const ParticleView &P, const GridViewT<D> &G);
template <int D>
void grid_velocity(const GridViewT<D> &G, const FaceBC *face,
                   const PrescribedVelocity *prescribed = nullptr);

// Particle kinematics from the nodal velocity: position (eq. 5), L dt into dudx (eq. 20),
// F <- (I + L dt) F, volume J V0; wave speeds and escape/instability checks into stats.
template <class Shape, int D>
void g2p_kinematics(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
                    const CellRangeT<D> &owned, const G2PParamsT<D> &prm,
                    const double *wave_modulus, double *dudx, G2PStatsT<D> &stats);
template <class Shape>
void g2p_kinematics(const ParticleView &P, const GridView &G, const GridView *G1, const Grid &grid,
                    const G2PParams &prm, const double *wave_modulus, double *dudx,
                    G2PStats &stats) {
  g2p_kinematics<Shape, DIM>(P, G, G1, owned_cells(grid), prm, wave_modulus, dudx, stats);
}

} // namespace pmpm
