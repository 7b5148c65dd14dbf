// Frictional interfaces at the geomembrane (seed paper section 3.2; docs/method.md, section 5).
//
// Particles with colour 1 form body 1 (the geomembrane); all others body 2. Where a scene has an
// interface, body 1's mass, momentum, force and the colour sums behind the normals are summed on a
// second DMDA with the grid's layout and partition. After the grid update, at every node where
// both bodies have mass and the normal is defined (a body with a tail share of the node's mass
// takes the common acceleration there, see tail_share):
//   n = g / |g|     outward normal of body 1: g is minus the colour gradient, by default the
//                   paper's central differences of cell-average colour (InterfaceNormals)
//   d = v1 - v_cm,  d_n = d . n,  d_t = d - d_n n      (d_n > 0: the bodies approach)
//   paper:   the normal velocity is common (no interpenetration, no separation);
//   contact: Bardenhagen et al. (2001): only where the bodies approach (d_n > 0); else free;
//   Coulomb in velocity form: stick (v1 = v_cm) if |d_t| <= mu max(d_n, 0), else slip with the
//   tangential difference reduced by mu max(d_n, 0) (F dt = m dv applied to the force form:
//   m1 d_n is the normal impulse, and only a pressing one gives friction);
//   v2 follows from momentum conservation, m1 v1 + m2 v2 = m v_cm.
// mu is chosen per face of body 1: mu_top where n points against gravity, mu_bottom elsewhere.
// The paper's common normal also holds the bodies together where they pull apart: right while the
// interface stays pressed (quasi-static loading), an over-grip when it rings in undamped dynamics;
// the tensile normal impulse is counted so that runs can say which case they were.
// Bonded (no interface) is the single velocity field of plain MPM: the cycle skips all of this.
#pragma once
#include "pmpm/core/grid.hpp"
#include "pmpm/core/transfers.hpp"

namespace pmpm {

enum class InterfaceType { Bonded = 0, Paper = 1, Contact = 2 };
inline constexpr const char *InterfaceTypeNames[] = {"bonded",        "paper",      "contact",
                                                     "InterfaceType", "INTERFACE_", nullptr};

// Where the normals come from. cells: the paper's scheme (section 3.2): the volume-weighted
// average colour of each cell, its gradient at the cell centres by central differences between
// neighbouring cells, mapped to a node as the mean over its four cells; a node is an interface
// node where that is non-zero. particles: sum_p V_p c_p grad S_ip / h, the colour field's
// gradient through the shape functions (Bardenhagen's mass-gradient form).
enum class InterfaceNormals { Cells = 0, Particles = 1 };
inline constexpr const char *InterfaceNormalsNames[] = {"cells", "particles", "InterfaceNormals",
                                                        "INTERFACE_NORMALS_", nullptr};

struct InterfaceParams {
  InterfaceType type = InterfaceType::Bonded;
  InterfaceNormals normals = InterfaceNormals::Cells;
  double mu_top = 0.5, mu_bottom = 0.5;
  double tail_share = 1e-3;       // below this share of a node's mass a body takes the common
                                  // acceleration there (its own f/m is unreliable)
  double up[3] = {0.0, 1.0, 0.0}; // against gravity (-dim 3: in the scene's plane)
  double dt = 0, damping_alpha = 0;
  FaceBC face[6] = {FaceBC::Free, FaceBC::Free, FaceBC::Free,
                    FaceBC::Free, FaceBC::Free, FaceBC::Free}; // the box's faces, as Model::face
};

struct InterfaceStats {
  double contact_nodes = 0; // nodes where both bodies meet
  double slip_nodes = 0;    // of those, nodes that slipped this step
  // Normal impulse exchanged this step (N s per unit thickness), summed over contact nodes where
  // it was applied: pressing the bodies together, and (paper type only) holding them together.
  double compression = 0, tension = 0;
};

// On owned nodes of a D-dimensional grid (D = 2, 3): T is the total field after grid_update
// (v_cm, a_cm); B holds body 1's sums (mass, momentum, force, colour gradient). On return B holds
// body 1's velocity and acceleration and T body 2's, wherever both bodies meet (elsewhere B = T).
// The normal, the tangential difference and the friction cone are vectors in D; the faces held
// are prm.face[0 .. 2D).
template <int D>
void interface_update(const GridViewT<D> &T, const GridViewT<D> &B, const InterfaceParams &prm,
                      InterfaceStats &stats);

// The paper's normals, second half: C is the ghosted view of the cell sums of p2g_cell_colour
// (cell c at node c), B the owned nodes of the body grid; B's FEXT slots receive minus the
// central difference of the cell-average colour times h (the mean over the node's 2^D cells),
// which points out of body 1.
template <int D> void cell_colour_normals(const GridViewT<D> &C, const GridViewT<D> &B);

// The second DMDA (same partition as the grid) that carries body 1: `body` beside the 2D grid,
// `body3` beside the 3D one (-dim 3).
struct InterfaceGrid {
  Grid body;
  GridT<3> body3;
  bool active = false;
  template <int D> GridT<D> &body_of() {
    if constexpr (D == 3)
      return body3;
    else
      return body;
  }
};
template <int D> PetscErrorCode InterfaceGridCreate(GridT<D> &g, InterfaceGrid &ig);
PetscErrorCode InterfaceGridDestroy(InterfaceGrid &ig);

} // namespace pmpm
