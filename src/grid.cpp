#include "pmpm/grid.hpp"
#include <algorithm>

namespace pmpm {

PetscErrorCode GridCreate(MPI_Comm comm, double h, const double origin[DIM],
                          const PetscInt ncell[DIM], int nbody, int extra, Grid &g, PetscInt px,
                          PetscInt py, const PetscInt *lx, const PetscInt *ly) {
  PetscFunctionBeginUser;
  g.h = h;
  g.nbody = nbody;
  g.nd = nbody * GridDof::NDOF + extra;
  for (int d = 0; d < DIM; ++d) {
    g.origin[d] = origin[d];
    g.ncell[d] = ncell[d];
  }
  // GHOSTED boundaries give every rank two ghost layers outside the box too, so a particle at the
  // box face can write its (zero-weight) outer stencil nodes without a bounds test.
  PetscCall(DMDACreate2d(comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX,
                         ncell[0] + 1, ncell[1] + 1, px, py, g.nd, 2, lx, ly, &g.da));
  PetscCall(DMSetFromOptions(g.da));
  PetscCall(DMSetUp(g.da));
  PetscCall(DMDASetUniformCoordinates(g.da, origin[0], origin[0] + ncell[0] * h, origin[1],
                                      origin[1] + ncell[1] * h, 0.0, 0.0));
  PetscCall(DMDASetFieldName(g.da, GridDof::M, "mass"));
  PetscCall(DMDAGetCorners(g.da, &g.s[0], &g.s[1], nullptr, &g.m[0], &g.m[1], nullptr));
  PetscCall(DMDAGetGhostCorners(g.da, &g.gs[0], &g.gs[1], nullptr, &g.gm[0], &g.gm[1], nullptr));
  for (int d = 0; d < DIM; ++d) {
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

PetscErrorCode GridDestroy(Grid &g) {
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&g.local));
  PetscCall(VecDestroy(&g.global));
  PetscCall(DMDestroy(&g.da));
  PetscFunctionReturn(0);
}

namespace {
// The geometry of a view: the ghosted node range for the local vector, the owned one for the
// global vector.
void SetView(const Grid &g, bool ghosted, GridView &v) {
  v.h = g.h;
  v.axisymmetric = g.axisymmetric;
  for (int d = 0; d < DIM; ++d) {
    v.origin[d] = g.origin[d];
    v.ncell[d] = g.ncell[d];
    v.gs[d] = ghosted ? g.gs[d] : g.s[d];
    v.gm[d] = ghosted ? g.gm[d] : g.m[d];
  }
  v.ld = 0;
  v.nbody = g.nbody;
  v.nd = g.nd;
}
} // namespace

PetscErrorCode GridGetLocal(Grid &g, bool zero, GridView &v) {
  PetscFunctionBeginUser;
  if (zero) PetscCall(VecZeroEntries(g.local));
  SetView(g, true, v);
  PetscCall(VecGetArray(g.local, &v.data));
  PetscFunctionReturn(0);
}

PetscErrorCode GridRestoreLocal(Grid &g, GridView &v) {
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArray(g.local, &v.data));
  v.data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode GridGetGlobal(Grid &g, GridView &v) {
  PetscFunctionBeginUser;
  SetView(g, false, v);
  if (!g.shared) {
    PetscCall(VecGetArray(g.global, &v.data));
    PetscFunctionReturn(0);
  }
  // the owned nodes inside the ghosted array: node (s[0], s[1]) onwards, rows of gm[0] nodes
  double *a;
  PetscCall(VecGetArray(g.local, &a));
  v.ld = g.gm[0];
  v.data = a + ((g.s[1] - g.gs[1]) * g.gm[0] + (g.s[0] - g.gs[0])) * g.nd;
  PetscFunctionReturn(0);
}

PetscErrorCode GridRestoreGlobal(Grid &g, GridView &v) {
  PetscFunctionBeginUser;
  if (!g.shared) {
    PetscCall(VecRestoreArray(g.global, &v.data));
  } else {
    double *a = v.data - ((g.s[1] - g.gs[1]) * g.gm[0] + (g.s[0] - g.gs[0])) * g.nd;
    PetscCall(VecRestoreArray(g.local, &a));
  }
  v.data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode GridLocalToGlobalAdd(Grid &g) {
  PetscFunctionBeginUser;
  if (g.shared) PetscFunctionReturn(0); // the local array holds the sums already
  PetscCall(VecZeroEntries(g.global));
  PetscCall(DMLocalToGlobalBegin(g.da, g.local, ADD_VALUES, g.global));
  PetscCall(DMLocalToGlobalEnd(g.da, g.local, ADD_VALUES, g.global));
  PetscFunctionReturn(0);
}

PetscErrorCode GridGlobalToLocal(Grid &g) {
  PetscFunctionBeginUser;
  if (!g.shared) {
    PetscCall(DMGlobalToLocalBegin(g.da, g.global, INSERT_VALUES, g.local));
    PetscCall(DMGlobalToLocalEnd(g.da, g.global, INSERT_VALUES, g.local));
  }
  // Ghost nodes outside the box are not part of the solve: the scatter leaves them holding this
  // rank's P2G sums, so zero them (a support reaching past the box sees v = a = 0 there).
  // Row by row: a row outside the box whole, a row inside it its runs left and right of the box.
  double *a;
  PetscCall(VecGetArray(g.local, &a));
  const PetscInt i0 = g.gs[0], i1 = g.gs[0] + g.gm[0];
  auto zero = [&](PetscInt j, PetscInt lo, PetscInt hi) { // nodes [lo, hi) of row j
    if (lo >= hi) return;
    double *row = a + (j - g.gs[1]) * g.gm[0] * g.nd;
    std::fill(row + (lo - i0) * g.nd, row + (hi - i0) * g.nd, 0.0);
  };
  for (PetscInt j = g.gs[1]; j < g.gs[1] + g.gm[1]; ++j) {
    if (j < 0 || j > g.ncell[1]) {
      zero(j, i0, i1);
    } else {
      zero(j, i0, std::min(i1, PetscInt(0)));
      zero(j, std::max(i0, g.ncell[0] + 1), i1);
    }
  }
  PetscCall(VecRestoreArray(g.local, &a));
  PetscFunctionReturn(0);
}

} // namespace pmpm
