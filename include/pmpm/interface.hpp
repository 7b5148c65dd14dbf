// Frictional interfaces at the geomembrane (seed paper section 3.2; REFERENCE.md 5).
//
// Particles with colour 1 form body 1 (the geomembrane); all others body 2. Where a scene has an
// interface, body 1's mass, momentum, force and colour gradient are summed on a second DMDA with
// the grid's layout and partition. After the grid update, at nodes where both bodies have mass:
//   n = g / |g|, g = sum_p V_p c_p grad S_ip   outward normal of body 1 (colour-gradient normals;
//                                              g is minus the nodal gradient of the colour)
//   d = v1 - v_cm,  d_n = d . n,  d_t = d - d_n n
//   paper:   the normal velocity is common (no interpenetration, no separation);
//   contact: Bardenhagen et al. (2001): only where the bodies approach (d_n > 0); else free;
//   Coulomb in velocity form: stick (v1 = v_cm) if |d_t| <= mu |d_n|, else slip with the
//   tangential difference reduced by mu |d_n| (F dt = m dv applied to the force form);
//   v2 follows from momentum conservation, m1 v1 + m2 v2 = m v_cm.
// mu is chosen per face of body 1: mu_top where n points against gravity, mu_bottom elsewhere.
// Bonded (no interface) is the single velocity field of plain MPM: the cycle skips all of this.
#pragma once
#include "pmpm/grid.hpp"
#include "pmpm/transfers.hpp"

namespace pmpm {

enum class InterfaceType { Bonded = 0, Paper = 1, Contact = 2 };
inline constexpr const char *InterfaceTypeNames[] = {"bonded",        "paper",      "contact",
                                                     "InterfaceType", "INTERFACE_", nullptr};

struct InterfaceParams {
  InterfaceType type = InterfaceType::Bonded;
  double mu_top = 0.5, mu_bottom = 0.5;
  double min_share = 1e-3;     // smallest mass fraction of either body at a contact node
  double up[DIM] = {0.0, 1.0}; // against gravity
  double dt = 0, damping_alpha = 0;
  FaceBC face[2 * DIM] = {FaceBC::Free, FaceBC::Free, FaceBC::Free, FaceBC::Free};
};

struct InterfaceStats {
  double contact_nodes = 0; // nodes where both bodies meet
  double slip_nodes = 0;    // of those, nodes that slipped this step
};

// On owned nodes: T is the total field after grid_update (v_cm, a_cm); B holds body 1's sums
// (mass, momentum, force, colour gradient). On return B holds body 1's velocity and acceleration
// and T body 2's, wherever both bodies meet (elsewhere B = T).
void interface_update(const GridView &T, const GridView &B, const InterfaceParams &prm,
                      InterfaceStats &stats);

// The second DMDA (same partition as the grid) that carries body 1.
struct InterfaceGrid {
  Grid body;
  bool active = false;
};
PetscErrorCode InterfaceGridCreate(Grid &g, InterfaceGrid &ig);
PetscErrorCode InterfaceGridDestroy(InterfaceGrid &ig);

} // namespace pmpm
