// A 3D sheet (sheet.hpp) between bodies on the 3D grid: the chain's stacked-bodies contact
// (chain.hpp, contact_bodies) lifted one dimension. The sheet is a body of its own on the grid
// (Sheet::body; the continuum below it is body - 1, above it body + 1); its points put their
// mass, momentum and forces into its block and their geometry into its SheetDof slots
// (src/step/sheets.cpp). After the momentum balance every node where two bodies or more have
// mass is resolved by contact_stack3 (contact_stack.hpp) along the normal the sheet's points give
// there: no interpenetration, separation where the faces pull apart, and Coulomb friction as a
// cone on each face, the impulse opposing the sliding in the sheet's plane. As for chains: a
// normal pass first, then each face's friction capacity from the pressure pooled over the sheet
// (sheet_friction_capacity), then the full pass; the tail rule for slivers of a body at a node
// (chain.cpp, contact_bodies). Plain kernels over a node view: no PETSc objects, no MPI.
#pragma once
#include "pmpm/contact/chain.hpp"
#include "pmpm/contact/sheet.hpp"

namespace pmpm {

// Per-node slots of one sheet's geometry, after the bodies' blocks (GridT<3>::nd).
struct SheetDof {
  static constexpr int NX = 0, NY = 1, NZ = 2; // sum_i w m_i up n_i (toward the body above)
  static constexpr int AREA = 3;               // sum_i w A_i (the sheet's area the node carries)
  static constexpr int NTOP = 4, NBOT = 5;     // normal impulse on the upper / lower face (N s)
  static constexpr int PTOP = 6, PBOT = 7;     // normal impulse pooled over the sheet (N s)
  static constexpr int NDOF = 8;
};

// The 3D form of ContactParams: the tail shares and the box's six faces.
struct SheetContactParams {
  double dt = 0;
  double tail_share = 1e-3, chain_tail_share = 0.05; // as ContactParams'
  FaceBC face[6] = {FaceBC::Free, FaceBC::Free, FaceBC::Free,
                    FaceBC::Free, FaceBC::Free, FaceBC::Free};
};
// normal_pass: only the normal impulses (into the sheets' NTOP / NBOT slots; velocities
// untouched); then sheet_friction_capacity; then the full pass, which adds its counts to st and
// sets st.friction3. Every node of G (a view of the owned nodes) where two bodies or more have
// mass.
void contact_sheets(const GridViewT<3> &G, const std::vector<Sheet> &sheets,
                    const SheetContactParams &prm, bool normal_pass, ContactStats &st);

// A 3D sheet made of the material a chain reads from the same -mat_<name>_* options (chain.hpp:
// ChainCreate): its law (linear, tension_only as the tension field, elastoplastic), J, nu, mass
// and weight per area, yield force and hardening. The caller lays its lattice.
Sheet SheetMaterialOf(const Chain &probe);

// Point i's uGIMP weights on the 3D grid: a square patch of the sheet one cell wide in its
// tangent plane, thin across it, kept inside the box (src/step/sheets.cpp).
void sheet_point_weights(const Sheet &s, int i, const GridViewT<3> &G, Weights<UGIMPShape, 3> &W);

// Each face's friction capacity at the owned nodes of G (PTOP / PBOT, an impulse: pressure times
// area times dt), from the normal pass's impulses read from the ghosted view L: each point's
// pressure on a face is its stencil's normal impulse over its stencil's sheet area, and goes back
// to the nodes of its stencil where that face is in contact, in proportion to their weights
// (chain_friction_capacity's rule and its reasons).
void sheet_friction_capacity(const GridViewT<3> &L, const GridViewT<3> &G,
                             const std::vector<Sheet> &sheets);

} // namespace pmpm
