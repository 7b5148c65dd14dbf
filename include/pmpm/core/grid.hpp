// The background grid: a DMDA of (n+1)^D nodes over the scene's box (D = 2, 3; the driver's is
// DIM = 2 today), uniform cell size h. Nodal fields live in one vector. Every body on the grid (a
// continuum region with its own velocity field, or a membrane chain, chain.hpp) has a block of
// GridDof::NDOF values per node; a scene without chains has one body, and the blocks are followed
// by `extra` values per node (a chain's geometry sums, ChainDof). Particle-to-grid sums go into the
// local (ghosted) vector and are added across ranks; grid-to-particle reads ghosted values.
#pragma once
#include "pmpm/util/config.hpp"
#include <petscdmda.h>
#include <type_traits>

namespace pmpm {

// Nodal layout. During P2G a node holds mass, momentum, total force and external force; after the
// grid update the same slots hold mass, new velocity and acceleration (what G2P reads).
template <int D> struct GridDofT {
  static constexpr int M = 0;            // mass
  static constexpr int P = 1;            // momentum -> velocity after the update
  static constexpr int F = 1 + D;        // total force -> acceleration after the update
  static constexpr int FEXT = 1 + 2 * D; // external force (for the unbalanced-force ratio)
  static constexpr int NDOF = 1 + 3 * D;
};
using GridDof = GridDofT<DIM>;

// A plain view of the ghosted local nodal array of a D-dimensional grid (D = 2, 3), for kernels:
// node idx (global indices, x fastest) is at data[off * nd], off = (i - gs[0]) + row() ((j - gs[1])
// + rows() (k - gs[2])); body b's block starts b * NDOF further. A view of a part of an array
// (the owned nodes inside the ghosted array, Grid::shared) has rows of ld nodes and (3D) planes
// of ldr rows; a view of a whole array leaves ld = ldr = 0 (rows of gm[0] nodes, planes of gm[1]
// rows).
template <int D> struct GridViewT {
  static_assert(D == 2 || D == 3, "2D or 3D");
  double h = 0;
  double origin[D] = {};
  PetscInt ncell[D] = {};
  PetscInt gs[D] = {}, gm[D] = {}; // ghosted start and size, node indices
  PetscInt ld = 0;                 // nodes per row of data (0: gm[0])
  PetscInt ldr = 0;                // 3D: rows per plane of data (0: gm[1])
  int nbody = 1;                   // bodies (blocks of NDOF) per node
  int nd = GridDofT<D>::NDOF;      // values per node: nbody * NDOF + extra
  bool axisymmetric = false;       // x is the radius (geometry.hpp; 2D only)
  double *data = nullptr;
  PetscInt row() const { return ld ? ld : gm[0]; }
  PetscInt rows() const { return ldr ? ldr : gm[1]; }
  // node idx (D global indices)
  double *node(const PetscInt *idx) const {
    PetscInt off = idx[D - 1] - gs[D - 1];
    if constexpr (D == 3) off = off * rows() + (idx[1] - gs[1]);
    return data + (off * row() + (idx[0] - gs[0])) * nd;
  }
  double *node(PetscInt i, PetscInt j) const {
    static_assert(D == 2, "node(i, j): 2D");
    return data + ((j - gs[1]) * row() + (i - gs[0])) * nd;
  }
  double *node(PetscInt i, PetscInt j, PetscInt k) const {
    static_assert(D == 3, "node(i, j, k): 3D");
    return data + (((k - gs[2]) * rows() + (j - gs[1])) * row() + (i - gs[0])) * nd;
  }
  // the mass of all bodies at a node (node: its first block), summed body by body
  double body_mass_sum(const double *node) const {
    double m = 0;
    for (int b = 0; b < nbody; ++b) m += node[b * GridDofT<D>::NDOF + GridDofT<D>::M];
    return m;
  }
  // doubles between neighbouring nodes along y (a row) and z (a plane)
  PetscInt row_stride() const { return row() * nd; }
  PetscInt plane_stride() const { return D == 3 ? rows() * row() * nd : 0; }
};
using GridView = GridViewT<DIM>;

// The grid of dimension D (2, 3): Grid (= GridT<DIM>) is the driver's, GridT<3> the 3D one.
template <int D> struct GridT {
  static_assert(D == 2 || D == 3, "2D or 3D");
  DM da = nullptr;
  double h = 0;
  double origin[D] = {};
  PetscInt ncell[D] = {};
  int nbody = 1, nd = GridDofT<D>::NDOF;     // see GridViewT
  bool axisymmetric = false;                 // see GridViewT
  PetscInt s[D] = {}, m[D] = {};             // owned nodes
  PetscInt gs[D] = {}, gm[D] = {};           // ghosted nodes
  PetscInt cell_lo[D] = {}, cell_hi[D] = {}; // owned cells [lo, hi)
  Vec local = nullptr, global = nullptr;
  // One rank: the owned nodes are the ghosted array's interior (the ghosts are the two layers
  // outside the box), so the global vector is not used: the ghost add and the scatter have
  // nothing to move, and the grid update works in the local array (GridGetGlobal's view).
  bool shared = false;

  // A particle centred in cell c is owned by the rank that owns node c + 1 (DMSwarm's rule).
  bool owns_cell(const PetscInt c[D]) const {
    for (int d = 0; d < D; ++d)
      if (c[d] < cell_lo[d] || c[d] >= cell_hi[d]) return false;
    return true;
  }
};
using Grid = GridT<DIM>;

// Create the DMDA (2D or 3D, box stencil): ncell cells of size h from origin; stencil width 2
// (uGIMP support); nbody blocks of NDOF values per node followed by extra values. The partition
// is PETSc's (or -da_processors_x/y/z) unless px x py (x pz) ranks with lx, ly (, lz) nodes per
// rank slab along x, y (, z) are given (balance.hpp); pz and lz are for D = 3 only.
template <int D>
PetscErrorCode GridCreate(MPI_Comm comm, double h, const double origin[D], const PetscInt ncell[D],
                          int nbody, int extra, GridT<D> &g, PetscInt px = PETSC_DECIDE,
                          PetscInt py = PETSC_DECIDE, const PetscInt *lx = nullptr,
                          const PetscInt *ly = nullptr, PetscInt pz = PETSC_DECIDE,
                          const PetscInt *lz = nullptr);
template <int D> PetscErrorCode GridDestroy(GridT<D> &g);
// Zero the local vector and hand out a writable view of it (restore with GridRestoreLocal).
template <int D> PetscErrorCode GridGetLocal(GridT<D> &g, bool zero, GridViewT<D> &v);
template <int D> PetscErrorCode GridRestoreLocal(GridT<D> &g, GridViewT<D> &v);
// A view of the owned nodes of the global vector (for the grid update); with shared, of the owned
// nodes of the local vector (a view that aliases GridGetLocal's: read and write different slots).
template <int D> PetscErrorCode GridGetGlobal(GridT<D> &g, GridViewT<D> &v);
template <int D> PetscErrorCode GridRestoreGlobal(GridT<D> &g, GridViewT<D> &v);
// f(view) between GridGetLocal (zero as there) and GridRestoreLocal, or between GridGetGlobal and
// GridRestoreGlobal: a view that lives for one piece of work. f returns nothing or an error code.
template <int D, class F> PetscErrorCode GridWithLocal(GridT<D> &g, bool zero, F &&f);
template <int D, class F> PetscErrorCode GridWithGlobal(GridT<D> &g, F &&f);
// Sum the ghosted local contributions into the global vector (ADD_VALUES); with shared, nothing.
template <int D> PetscErrorCode GridLocalToGlobalAdd(GridT<D> &g);
// Scatter owned values (and ghosts) back into the local vector, and zero the ghost nodes outside
// the box; with shared, only the latter.
template <int D> PetscErrorCode GridGlobalToLocal(GridT<D> &g);

namespace detail {
template <class F, class View> PetscErrorCode CallOnView(F &f, View &v) {
  if constexpr (std::is_void_v<decltype(f(v))>) {
    f(v);
    return 0;
  } else {
    return f(v);
  }
}
} // namespace detail

template <int D, class F> PetscErrorCode GridWithLocal(GridT<D> &g, bool zero, F &&f) {
  GridViewT<D> v;
  PetscFunctionBeginUser;
  PetscCall(GridGetLocal(g, zero, v));
  PetscCall(detail::CallOnView(f, v));
  PetscCall(GridRestoreLocal(g, v));
  PetscFunctionReturn(0);
}
template <int D, class F> PetscErrorCode GridWithGlobal(GridT<D> &g, F &&f) {
  GridViewT<D> v;
  PetscFunctionBeginUser;
  PetscCall(GridGetGlobal(g, v));
  PetscCall(detail::CallOnView(f, v));
  PetscCall(GridRestoreGlobal(g, v));
  PetscFunctionReturn(0);
}

} // namespace pmpm
