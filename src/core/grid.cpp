#include "pmpm/core/grid.hpp"
#include <algorithm>

namespace pmpm {

template <int D>
PetscErrorCode GridCreate(MPI_Comm comm, double h, const double origin[D], const PetscInt ncell[D],
                          int nbody, int extra, GridT<D> &g, PetscInt px, PetscInt py,
                          const PetscInt *lx, const PetscInt *ly, PetscInt pz, const PetscInt *lz) {
  PetscFunctionBeginUser;
  g.h = h;
  g.nbody = nbody;
  g.nd = nbody * GridDofT<D>::NDOF + extra;
  for (int d = 0; d < D; ++d) {
    g.origin[d] = origin[d];
    g.ncell[d] = ncell[d];
  }
  // GHOSTED boundaries give every rank two ghost layers outside the box too, so a particle at the
  // box face can write its (zero-weight) outer stencil nodes without a bounds test.
  if constexpr (D == 2) {
    PetscCall(DMDACreate2d(comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX,
                           ncell[0] + 1, ncell[1] + 1, px, py, g.nd, 2, lx, ly, &g.da));
  } else {
    PetscCall(DMDACreate3d(comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED,
                           DMDA_STENCIL_BOX, ncell[0] + 1, ncell[1] + 1, ncell[2] + 1, px, py, pz,
                           g.nd, 2, lx, ly, lz, &g.da));
  }
  PetscCall(DMSetFromOptions(g.da));
  PetscCall(DMSetUp(g.da));
  PetscCall(DMDASetUniformCoordinates(g.da, origin[0], origin[0] + ncell[0] * h, origin[1],
                                      origin[1] + ncell[1] * h, D == 3 ? origin[D - 1] : 0.0,
                                      D == 3 ? origin[D - 1] + ncell[D - 1] * h : 0.0));
  PetscCall(DMDASetFieldName(g.da, GridDofT<D>::M, "mass"));
  PetscInt s[3] = {0, 0, 0}, m[3] = {1, 1, 1}, gs[3] = {0, 0, 0}, gm[3] = {1, 1, 1};
  PetscCall(DMDAGetCorners(g.da, &s[0], &s[1], &s[2], &m[0], &m[1], &m[2]));
  PetscCall(DMDAGetGhostCorners(g.da, &gs[0], &gs[1], &gs[2], &gm[0], &gm[1], &gm[2]));
  for (int d = 0; d < D; ++d) {
    g.s[d] = s[d];
    g.m[d] = m[d];
    g.gs[d] = gs[d];
    g.gm[d] = gm[d];
    g.cell_lo[d] = g.s[d] == 0 ? 0 : g.s[d] - 1;
    g.cell_hi[d] = g.s[d] + g.m[d] == ncell[d] + 1 ? ncell[d] : g.s[d] + g.m[d] - 1;
  }
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  g.shared = size == 1;
  PetscCall(DMCreateLocalVector(g.da, &g.local));
  if (!g.shared) PetscCall(DMCreateGlobalVector(g.da, &g.global));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridDestroy(GridT<D> &g) {
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&g.local));
  PetscCall(VecDestroy(&g.global));
  PetscCall(DMDestroy(&g.da));
  PetscFunctionReturn(0);
}

namespace {
// The geometry of a view: the ghosted node range for the local vector, the owned one for the
// global vector.
template <int D> void SetView(const GridT<D> &g, bool ghosted, GridViewT<D> &v) {
  v.h = g.h;
  v.axisymmetric = g.axisymmetric;
  for (int d = 0; d < D; ++d) {
    v.origin[d] = g.origin[d];
    v.ncell[d] = g.ncell[d];
    v.gs[d] = ghosted ? g.gs[d] : g.s[d];
    v.gm[d] = ghosted ? g.gm[d] : g.m[d];
  }
  v.ld = 0;
  v.ldr = 0;
  v.nbody = g.nbody;
  v.nd = g.nd;
}

// Offset (in doubles) of the first owned node inside the ghosted local array.
template <int D> PetscInt OwnedOffset(const GridT<D> &g) {
  PetscInt off = g.s[D - 1] - g.gs[D - 1];
  if constexpr (D == 3) off = off * g.gm[1] + (g.s[1] - g.gs[1]);
  return (off * g.gm[0] + (g.s[0] - g.gs[0])) * g.nd;
}
} // namespace

template <int D> PetscErrorCode GridGetLocal(GridT<D> &g, bool zero, GridViewT<D> &v) {
  PetscFunctionBeginUser;
  if (zero) PetscCall(VecZeroEntries(g.local));
  SetView(g, true, v);
  PetscCall(VecGetArray(g.local, &v.data));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridRestoreLocal(GridT<D> &g, GridViewT<D> &v) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(g.local, &v.data));
  v.data = nullptr;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridGetGlobal(GridT<D> &g, GridViewT<D> &v) {
  PetscFunctionBeginUser;
  SetView(g, false, v);
  if (!g.shared) {
    PetscCall(VecGetArray(g.global, &v.data));
    PetscFunctionReturn(0);
  }
  // the owned nodes inside the ghosted array: node s onwards, rows of gm[0] nodes, planes of
  // gm[1] rows
  double *a;
  PetscCall(VecGetArray(g.local, &a));
  v.ld = g.gm[0];
  if constexpr (D == 3) v.ldr = g.gm[1];
  v.data = a + OwnedOffset(g);
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridRestoreGlobal(GridT<D> &g, GridViewT<D> &v) {
  PetscFunctionBeginUser;
  if (!g.shared) {
    PetscCall(VecRestoreArray(g.global, &v.data));
  } else {
    double *a = v.data - OwnedOffset(g);
    PetscCall(VecRestoreArray(g.local, &a));
  }
  v.data = nullptr;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridLocalToGlobalAdd(GridT<D> &g) {
  PetscFunctionBeginUser;
  if (g.shared) PetscFunctionReturn(0); // the local array holds the sums already
  PetscCall(VecZeroEntries(g.global));
  PetscCall(DMLocalToGlobalBegin(g.da, g.local, ADD_VALUES, g.global));
  PetscCall(DMLocalToGlobalEnd(g.da, g.local, ADD_VALUES, g.global));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode GridGlobalToLocal(GridT<D> &g) {
  PetscFunctionBeginUser;
  if (!g.shared) {
    PetscCall(DMGlobalToLocalBegin(g.da, g.global, INSERT_VALUES, g.local));
    PetscCall(DMGlobalToLocalEnd(g.da, g.global, INSERT_VALUES, g.local));
  }
  // Ghost nodes outside the box are not part of the solve: the scatter leaves them holding this
  // rank's P2G sums, so zero them (a support reaching past the box sees v = a = 0 there).
  // Row by row (a row along x, one per (y, z)): a row outside the box whole, a row inside it its
  // runs left and right of the box.
  double *a;
  PetscCall(VecGetArray(g.local, &a));
  const PetscInt i0 = g.gs[0], i1 = g.gs[0] + g.gm[0];
  auto zero = [&](double *row, PetscInt lo, PetscInt hi) { // nodes [lo, hi) of a row
    if (lo >= hi) return;
    std::fill(row + (lo - i0) * g.nd, row + (hi - i0) * g.nd, 0.0);
  };
  const PetscInt k0 = D == 3 ? g.gs[D - 1] : 0, k1 = D == 3 ? k0 + g.gm[D - 1] : 1;
  for (PetscInt k = k0; k < k1; ++k) {
    const bool plane_out = D == 3 && (k < 0 || k > g.ncell[D - 1]);
    for (PetscInt j = g.gs[1]; j < g.gs[1] + g.gm[1]; ++j) {
      double *row = a + ((k - k0) * g.gm[1] + (j - g.gs[1])) * g.gm[0] * g.nd;
      if (plane_out || j < 0 || j > g.ncell[1]) {
        zero(row, i0, i1);
      } else {
        zero(row, i0, std::min(i1, PetscInt(0)));
        zero(row, std::max(i0, g.ncell[0] + 1), i1);
      }
    }
  }
  PetscCall(VecRestoreArray(g.local, &a));
  PetscFunctionReturn(0);
}

#define PMPM_GRID_INSTANTIATE(D)                                                                   \
  template PetscErrorCode GridCreate<D>(MPI_Comm, double, const double *, const PetscInt *, int,   \
                                        int, GridT<D> &, PetscInt, PetscInt, const PetscInt *,     \
                                        const PetscInt *, PetscInt, const PetscInt *);             \
  template PetscErrorCode GridDestroy<D>(GridT<D> &);                                              \
  template PetscErrorCode GridGetLocal<D>(GridT<D> &, bool, GridViewT<D> &);                       \
  template PetscErrorCode GridRestoreLocal<D>(GridT<D> &, GridViewT<D> &);                         \
  template PetscErrorCode GridGetGlobal<D>(GridT<D> &, GridViewT<D> &);                            \
  template PetscErrorCode GridRestoreGlobal<D>(GridT<D> &, GridViewT<D> &);                        \
  template PetscErrorCode GridLocalToGlobalAdd<D>(GridT<D> &);                                     \
  template PetscErrorCode GridGlobalToLocal<D>(GridT<D> &);
PMPM_GRID_INSTANTIATE(2)
PMPM_GRID_INSTANTIATE(3)
#undef PMPM_GRID_INSTANTIATE

} // namespace pmpm
