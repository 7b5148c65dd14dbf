// A 3D sheet between bodies on the 3D grid (sheet_contact.hpp): the stacked bodies at each node,
// resolved by contact_stack3, and each face's friction capacity pooled over the sheet.
#include "pmpm/contact/sheet_contact.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

namespace {
using G3 = GridDofT<3>;
constexpr int kMaxBodies = 8;
constexpr double kNoNormal = 1e-300; // as chain.cpp's: no sheet point reaches the node

// The face between two present bodies lo < hi at a node (face_between_membranes, the sheets
// between bodies).
StackFace face_between(const std::vector<Sheet> &sheets, int lo, int hi) {
  return face_between_membranes(sheets, lo, hi, [](const Sheet &s) { return s.in_contact(); });
}

// The faces between neighbouring bodies at the node: bonded where no sheet gives a normal;
// adhesion times the sheet's area at the node times dt; in the full pass a sheet face's friction
// capacity is its pooled impulse (PTOP / PBOT) times mu, passed in the adhesion slot.
void node_faces(const double *node, const std::vector<Sheet> &sheets, int k, const int *ids,
                double nn, double dt, bool normal_pass, StackFace *faces) {
  for (int q = 0; q + 1 < k; ++q) {
    faces[q] = face_between(sheets, ids[q], ids[q + 1]);
    if (nn <= kNoNormal) faces[q].type = FaceType::Bonded;
    if (faces[q].adhesion > 0) {
      double area = 0;
      for (const Sheet &s : sheets)
        if (s.in_contact() && s.body >= ids[q] && s.body <= ids[q + 1])
          area += node[s.slot + SheetDof::AREA];
      faces[q].adhesion *= area * dt;
    }
    if (normal_pass) {
      faces[q].mu = faces[q].adhesion = 0;
    } else if (faces[q].type != FaceType::Bonded) {
      for (const Sheet &s : sheets) {
        if (!s.in_contact()) continue;
        const double pa = s.body == ids[q]       ? node[s.slot + SheetDof::PTOP]
                          : s.body == ids[q + 1] ? node[s.slot + SheetDof::PBOT]
                                                 : -1.0;
        if (pa < 0) continue;
        faces[q].adhesion += faces[q].mu * pa;
        faces[q].mu = 0;
        break;
      }
    }
  }
}

// The tail rule of chain.cpp (contact_bodies' comment): a continuum sliver of the node, or a
// sheet sliver with nothing but continuum slivers on one side, takes the node's common
// acceleration; the others share the momentum that changes.
void tail_rule(int k, const int *ids, const double *m, double msum, const double *vold,
               const double *acm, double dt, const SheetContactParams &prm, double *v) {
  auto continuum_tail = [&](int q) { return ids[q] % 2 == 0 && m[q] < prm.tail_share * msum; };
  auto is_tail = [&](int q) {
    if (ids[q] % 2 == 0) return continuum_tail(q);
    if (!(m[q] < prm.chain_tail_share * msum)) return false;
    bool none_below = true, none_above = true;
    for (int r = 0; r < q; ++r) none_below = none_below && continuum_tail(r);
    for (int r = q + 1; r < k; ++r) none_above = none_above && continuum_tail(r);
    return none_below || none_above;
  };
  double ptot[3] = {0, 0, 0}, pnew[3] = {0, 0, 0}, mfull = 0;
  bool tail[kMaxBodies];
  for (int q = 0; q < k; ++q) {
    tail[q] = is_tail(q);
    for (int d = 0; d < 3; ++d) {
      ptot[d] += m[q] * v[3 * q + d];
      if (tail[q]) v[3 * q + d] = vold[3 * q + d] + dt * acm[d];
      pnew[d] += m[q] * v[3 * q + d];
    }
    if (!tail[q]) mfull += m[q];
  }
  if (mfull <= 0) return;
  for (int q = 0; q < k; ++q)
    if (!tail[q])
      for (int d = 0; d < 3; ++d) v[3 * q + d] += (ptot[d] - pnew[d]) / mfull;
}
} // namespace

void contact_sheets(const GridViewT<3> &G, const std::vector<Sheet> &sheets,
                    const SheetContactParams &prm, bool normal_pass, ContactStats &st) {
  constexpr int ND = G3::NDOF;
  const double dt = prm.dt;
  const int nb = G.nbody;
  if (nb > kMaxBodies || nb < 2) return; // guarded at setup
  if (!normal_pass) st.friction3.assign(3 * sheets.size(), 0.0);
  for (PetscInt kz = G.gs[2]; kz < G.gs[2] + G.gm[2]; ++kz)
    for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j)
      for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
        double *node = G.node(i, j, kz);
        double msum = 0;
        int ids[kMaxBodies], k = 0;
        for (int b = 0; b < nb; ++b)
          if (node[b * ND + G3::M] > 0) {
            msum += node[b * ND + G3::M];
            ids[k++] = b;
          }
        if (k < 2) continue;
        const PetscInt nid[3] = {i, j, kz};
        bool held[3];
        held_dofs<3>(nid, G.ncell, prm.face, held);
        double n[3] = {0, 0, 0}; // the sheets' weighted point normals, toward the body above
        for (const Sheet &s : sheets)
          if (s.in_contact())
            for (int d = 0; d < 3; ++d) n[d] += node[s.slot + SheetDof::NX + d];
        const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double m[kMaxBodies], v[3 * kMaxBodies], vold[3 * kMaxBodies], acm[3] = {0, 0, 0};
        for (int q = 0; q < k; ++q) {
          const double *nbk = node + ids[q] * ND;
          m[q] = nbk[G3::M];
          for (int d = 0; d < 3; ++d) {
            v[3 * q + d] = nbk[G3::P + d];
            vold[3 * q + d] = nbk[G3::P + d] - dt * nbk[G3::F + d];
            acm[d] += m[q] * nbk[G3::F + d] / msum;
          }
        }
        tail_rule(k, ids, m, msum, vold, acm, dt, prm, v);
        StackFace faces[kMaxBodies];
        StackFaceResult3 res[kMaxBodies];
        node_faces(node, sheets, k, ids, nn, dt, normal_pass, faces);
        const double nu[3] = {nn > kNoNormal ? n[0] / nn : 0.0, nn > kNoNormal ? n[1] / nn : 1.0,
                              nn > kNoNormal ? n[2] / nn : 0.0};
        contact_stack3(k, m, v, faces, nu, res);
        if (normal_pass) { // each face's normal impulse on its sheet's slots
          for (int q = 0; q + 1 < k; ++q)
            for (const Sheet &s : sheets) {
              if (!s.in_contact()) continue;
              if (s.body == ids[q]) node[s.slot + SheetDof::NTOP] = res[q].normal;
              if (s.body == ids[q + 1]) node[s.slot + SheetDof::NBOT] = res[q].normal;
            }
          continue;
        }
        count_stack_faces(k, res, st);
        for (int q = 0; q + 1 < k; ++q)
          for (size_t si = 0; si < sheets.size(); ++si) {
            const Sheet &s = sheets[si];
            // the impulse is on the lower body: the sheet's top face when it is the lower one
            const double sgn = s.body == ids[q] ? 1.0 : s.body == ids[q + 1] ? -1.0 : 0.0;
            for (int d = 0; d < 3 && sgn != 0.0; ++d)
              st.friction3[3 * si + d] += sgn * res[q].tangential[d] / dt;
          }
        for (int q = 0; q < k; ++q) { // the new velocities and forces (held dofs zero)
          double *nbk = node + ids[q] * ND;
          for (int d = 0; d < 3; ++d) {
            const double vn = held[d] ? 0.0 : v[3 * q + d];
            nbk[G3::P + d] = vn;
            nbk[G3::F + d] = held[d] ? 0.0 : (vn - vold[3 * q + d]) / dt;
          }
        }
      }
}

void sheet_friction_capacity(const GridViewT<3> &L, const GridViewT<3> &G,
                             const std::vector<Sheet> &sheets) {
  constexpr int NS = UGIMPShape::NS, NN = Weights<UGIMPShape, 3>::NN;
  Weights<UGIMPShape, 3> W;
  auto inside = [](const GridViewT<3> &V, PetscInt a, PetscInt b, PetscInt c) {
    return a >= V.gs[0] && a < V.gs[0] + V.gm[0] && b >= V.gs[1] && b < V.gs[1] + V.gm[1] &&
           c >= V.gs[2] && c < V.gs[2] + V.gm[2];
  };
  for (const Sheet &s : sheets) {
    if (!s.in_contact()) continue;
    const int m = s.reach.empty() ? s.n : static_cast<int>(s.reach.size());
    for (int k = 0; k < m; ++k) {
      const int i = s.reach.empty() ? k : s.reach[k];
      if (s.pinned[i]) continue;
      sheet_point_weights(s, i, L, W);
      // only points whose stencil lies in this rank's ghosted range reach its nodes
      if (!inside(L, W.base[0], W.base[1], W.base[2]) ||
          !inside(L, W.base[0] + NS - 1, W.base[1] + NS - 1, W.base[2] + NS - 1))
        continue;
      double n[2] = {0, 0}, area = 0, wc[2] = {0, 0};
      for (int q = 0; q < NN; ++q) {
        if (W.w[q] == 0.0) continue;
        const double *ns =
            L.node(W.base[0] + q % NS, W.base[1] + (q / NS) % NS, W.base[2] + q / (NS * NS)) +
            s.slot;
        area += W.w[q] * ns[SheetDof::AREA];
        for (int f = 0; f < 2; ++f) {
          const double N = ns[f == 0 ? SheetDof::NTOP : SheetDof::NBOT];
          if (N <= 0) continue;
          n[f] += W.w[q] * N;
          wc[f] += W.w[q];
        }
      }
      if (area <= 0) continue;
      for (int q = 0; q < NN; ++q) {
        if (W.w[q] == 0.0) continue;
        const PetscInt a = W.base[0] + q % NS, b = W.base[1] + (q / NS) % NS,
                       c = W.base[2] + q / (NS * NS);
        if (!inside(G, a, b, c)) continue;
        const double *ns = L.node(a, b, c) + s.slot;
        double *out = G.node(a, b, c) + s.slot;
        for (int f = 0; f < 2; ++f)
          if (ns[f == 0 ? SheetDof::NTOP : SheetDof::NBOT] > 0)
            out[f == 0 ? SheetDof::PTOP : SheetDof::PBOT] +=
                W.w[q] / wc[f] * s.area[i] * n[f] / area;
      }
    }
  }
}

Sheet SheetMaterialOf(const Chain &probe) {
  Sheet s;
  const int kind = probe.law.kind;
  s.law = kind == MembraneLawId<TensionOnlyMembrane>     ? SheetLaw::TensionField
          : kind == MembraneLawId<ElastoplasticMembrane> ? SheetLaw::Elastoplastic
                                                         : SheetLaw::Linear;
  s.J = probe.law.J;
  s.nu = probe.nu;
  s.area_mass = probe.line_mass;
  s.area_weight = probe.line_weight;
  s.yield_N = probe.law.yield_T; // sigma_y t
  s.hardening = probe.law.hardening;
  return s;
}

} // namespace pmpm
