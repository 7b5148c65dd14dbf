#include "pmpm/contact/interface.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

namespace {
// Both normal kernels give the colour gradient times h: O(1) where the colour jumps by O(1)
// across a cell, and round-off (1e-16) where it is uniform. Below this there is no normal: a
// direction drawn from round-off would depend on the summation order, that is on the ranks.
constexpr double kNoNormal = 1e-8;
// A share of a node's mass at or below this is round-off (the body does not reach the node).
constexpr double kRoundOff = 1e-12;
} // namespace

namespace {
// |v| of a D-vector: hypot in 2D, as it always was (the 2D outputs bit for bit)
template <int D> double norm(const double *v) {
  if constexpr (D == 2)
    return std::hypot(v[0], v[1]);
  else
    return std::hypot(v[0], v[1], v[2]);
}

// a . b of D-vectors, one expression (as the 2D code always had it: the compiler contracts it
// into the same fused multiply-adds, so the 2D outputs stay bit for bit)
template <int D> double dot(const double *a, const double *b) {
  if constexpr (D == 2)
    return a[0] * b[0] + a[1] * b[1];
  else
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// f(n) for every node n (D indices) of a view's box, z outermost, x innermost.
template <int D, class F> void for_nodes(const GridViewT<D> &V, F &&f) {
  const PetscInt k0 = D == 3 ? V.gs[D - 1] : 0, k1 = D == 3 ? V.gs[D - 1] + V.gm[D - 1] : 1;
  for (PetscInt k = k0; k < k1; ++k)
    for (PetscInt j = V.gs[1]; j < V.gs[1] + V.gm[1]; ++j)
      for (PetscInt i = V.gs[0]; i < V.gs[0] + V.gm[0]; ++i) {
        const PetscInt n[3] = {i, j, k};
        f(n);
      }
}
} // namespace

template <int D>
void interface_update(const GridViewT<D> &T, const GridViewT<D> &B, const InterfaceParams &prm,
                      InterfaceStats &st) {
  using Dof = GridDofT<D>;
  const double dt = prm.dt, alpha = prm.damping_alpha;
  // every owned node, z outermost (as for_nodes; plain loops: the body inlined, so the 2D
  // instantiation compiles to the fused multiply-adds it always had, bit for bit)
  const PetscInt k0 = D == 3 ? T.gs[D - 1] : 0, k1 = D == 3 ? T.gs[D - 1] + T.gm[D - 1] : 1;
  for (PetscInt k = k0; k < k1; ++k)
    for (PetscInt j = T.gs[1]; j < T.gs[1] + T.gm[1]; ++j)
      for (PetscInt i = T.gs[0]; i < T.gs[0] + T.gm[0]; ++i) {
        const PetscInt nid[3] = {i, j, k};
        double *t = T.node(nid), *b = B.node(nid);
        const double m = t[Dof::M], m1 = b[Dof::M];
        if (m1 <= 0.0) continue;
        bool held[D];
        held_dofs<D>(nid, T.ncell, prm.face, held);
        double vcm[D], acm[D], v1[D], v1old[D];
        for (int d = 0; d < D; ++d) {
          vcm[d] = t[Dof::P + d];
          acm[d] = t[Dof::F + d];
          // body 1 on its own: the same damped momentum balance as the total field
          v1old[d] = b[Dof::P + d] / m1;
          double f = b[Dof::F + d];
          if (alpha > 0.0 && v1old[d] != 0.0) f -= alpha * std::fabs(f) * (v1old[d] > 0 ? 1 : -1);
          v1[d] = held[d] ? 0.0 : v1old[d] + dt * f / m1;
        }
        const double m2 = m - m1;
        double g[D];
        for (int d = 0; d < D; ++d) g[d] = b[Dof::FEXT + d];
        // -dim 3: a z face on rollers is a symmetry plane (an extruded scene's plane-strain faces),
        // where the mirrored body cancels the colour gradient's z component; the particles'
        // gradient
        // (-interface_normals particles) sees only one side there and would tilt the normal out of
        // the plane. (The x and y faces keep their one-sided gradient, as in 2D.)
        if constexpr (D == 3)
          if ((nid[2] == 0 && prm.face[ZMIN] == FaceBC::Roller) ||
              (nid[2] == T.ncell[2] && prm.face[ZMAX] == FaceBC::Roller))
            g[2] = 0.0;
        const double gn = norm<D>(g);
        // A contact node needs a normal and both bodies' mass; every share above round-off counts.
        if (m1 <= kRoundOff * m || m2 <= kRoundOff * m || gn <= kNoNormal) {
          for (int d = 0; d < D; ++d) {
            b[Dof::P + d] = vcm[d];
            b[Dof::F + d] = acm[d];
          }
          continue;
        }
        double v2old[D]; // body 2's old velocity from the old total and body-1 momenta
        for (int d = 0; d < D; ++d) v2old[d] = (m * (vcm[d] - dt * acm[d]) - m1 * v1old[d]) / m2;
        // A body with a tail share (uGIMP's blocks reach the next row of nodes with shares down
        // to 1e-8) has an unreliable own acceleration f/m there: it takes the common acceleration
        // and keeps its velocity relative to the other body. Bonding such nodes instead glued the
        // sliding block on the incline (4.7 % slow at mu = 0 for shares below 1e-3, 1 % below
        // 1e-6); their own f/m made the friction landfill relax 3.9x slower (7142 steps, not 1823).
        if (m1 < prm.tail_share * m) {
          for (int d = 0; d < D; ++d) v1[d] = held[d] ? 0.0 : v1old[d] + dt * acm[d];
        } else if (m2 < prm.tail_share * m) { // v1 such that body 2 takes the common acceleration
          for (int d = 0; d < D; ++d)
            v1[d] = held[d] ? 0.0 : (m * vcm[d] - m2 * (v2old[d] + dt * acm[d])) / m1;
        }
        st.contact_nodes += 1;
        double n[D], dv[D];
        for (int d = 0; d < D; ++d) {
          n[d] = g[d] / gn;
          dv[d] = v1[d] - vcm[d];
        }
        const double dn = dot<D>(dv, n);
        if (prm.type == InterfaceType::Paper || dn > 0.0) {
          const double impulse = m1 * dn; // on body 1, along -n: what keeps the normals common
          if (impulse > 0.0)
            st.compression += impulse;
          else
            st.tension -= impulse;
          double tv[D];
          for (int d = 0; d < D; ++d) tv[d] = dv[d] - dn * n[d];
          const double tn = norm<D>(tv);
          const double mu = dot<D>(n, prm.up) > 0 ? prm.mu_top : prm.mu_bottom;
          // Coulomb needs compression: only an approaching normal velocity gives friction capacity
          const double cap = mu * std::fmax(dn, 0.0);
          const double keep = tn > cap ? 1.0 - cap / tn : 0.0;
          if (keep > 0.0) st.slip_nodes += 1;
          for (int d = 0; d < D; ++d) dv[d] = keep * tv[d];
        }
        for (int d = 0; d < D; ++d) {
          const double v1n = held[d] ? 0.0 : vcm[d] + dv[d];
          const double v2n = held[d] ? 0.0 : vcm[d] - m1 / m2 * dv[d];
          b[Dof::P + d] = v1n;
          b[Dof::F + d] = (v1n - v1old[d]) / dt;
          t[Dof::P + d] = v2n;
          t[Dof::F + d] = (v2n - v2old[d]) / dt;
        }
      }
}

template <int D> void cell_colour_normals(const GridViewT<D> &C, const GridViewT<D> &B) {
  using Dof = GridDofT<D>;
  // Average colour of cell c; a cell without particles has colour 0 (a free surface is an edge
  // of the body), a cell off the grid that of the nearest cell on it (a box face is not).
  auto avg = [&C](const PetscInt *c0) {
    PetscInt c[D];
    for (int d = 0; d < D; ++d) c[d] = std::min(std::max(c0[d], PetscInt(0)), C.ncell[d] - 1);
    const double *v = C.node(c);
    return v[Dof::FEXT + 1] > 0.0 ? v[Dof::FEXT] / v[Dof::FEXT + 1] : 0.0;
  };
  // The gradient at a cell centre is the central difference between its neighbours' centres;
  // a node takes the mean of its 2^D cells' gradients (it reaches cells i - 2 .. i + 1, within
  // the ghost width of 2). Minus the gradient points out of body 1.
  const double s = 0.5 / (1 << D); // 1/2^D of the cells times 1/2: the gradient times h, O(1)
  for_nodes<D>(B, [&](const PetscInt *nid) {
    double g[D] = {};
    const PetscInt k0 = D == 3 ? nid[2] - 1 : 0, k1 = D == 3 ? nid[2] : 0;
    for (PetscInt ck = k0; ck <= k1; ++ck)
      for (PetscInt cj = nid[1] - 1; cj <= nid[1]; ++cj)
        for (PetscInt ci = nid[0] - 1; ci <= nid[0]; ++ci)
          for (int d = 0; d < D; ++d) {
            PetscInt hi[3] = {ci, cj, ck}, lo[3] = {ci, cj, ck};
            ++hi[d];
            --lo[d];
            g[d] += avg(hi) - avg(lo);
          }
    double *b = B.node(nid);
    for (int d = 0; d < D; ++d) b[Dof::FEXT + d] = -s * g[d];
  });
}

template <int D> PetscErrorCode InterfaceGridCreate(GridT<D> &g, InterfaceGrid &ig) {
  const PetscInt *l[3] = {nullptr, nullptr, nullptr};
  PetscMPIInt p[3] = {1, 1, 1};
  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(g.da, nullptr, nullptr, nullptr, nullptr, &p[0], &p[1], &p[2], nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscCall(DMDAGetOwnershipRanges(g.da, &l[0], &l[1], &l[2]));
  GridT<D> &body = ig.body_of<D>();
  body = g;
  const MPI_Comm comm = PetscObjectComm((PetscObject)g.da);
  if constexpr (D == 2)
    PetscCall(DMDACreate2d(comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX,
                           g.ncell[0] + 1, g.ncell[1] + 1, p[0], p[1], GridDofT<D>::NDOF, 2, l[0],
                           l[1], &body.da));
  else
    PetscCall(DMDACreate3d(comm, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED,
                           DMDA_STENCIL_BOX, g.ncell[0] + 1, g.ncell[1] + 1, g.ncell[2] + 1, p[0],
                           p[1], p[2], GridDofT<D>::NDOF, 2, l[0], l[1], l[2], &body.da));
  PetscCall(DMSetUp(body.da));
  // one body's block per node
  body.nbody = 1;
  body.nd = GridDofT<D>::NDOF;
  // the body grid keeps its global vector on one rank too: cell_colour_normals writes the slots
  // it reads from the neighbouring nodes
  body.shared = false;
  PetscCall(DMCreateLocalVector(body.da, &body.local));
  PetscCall(DMCreateGlobalVector(body.da, &body.global));
  ig.active = true;
  PetscFunctionReturn(0);
}

PetscErrorCode InterfaceGridDestroy(InterfaceGrid &ig) {
  PetscFunctionBeginUser;
  if (ig.active && ig.body.da) PetscCall(GridDestroy(ig.body));
  if (ig.active && ig.body3.da) PetscCall(GridDestroy(ig.body3));
  ig.active = false;
  PetscFunctionReturn(0);
}

template void interface_update<2>(const GridViewT<2> &, const GridViewT<2> &,
                                  const InterfaceParams &, InterfaceStats &);
template void interface_update<3>(const GridViewT<3> &, const GridViewT<3> &,
                                  const InterfaceParams &, InterfaceStats &);
template void cell_colour_normals<2>(const GridViewT<2> &, const GridViewT<2> &);
template void cell_colour_normals<3>(const GridViewT<3> &, const GridViewT<3> &);
template PetscErrorCode InterfaceGridCreate<2>(GridT<2> &, InterfaceGrid &);
template PetscErrorCode InterfaceGridCreate<3>(GridT<3> &, InterfaceGrid &);

} // namespace pmpm
