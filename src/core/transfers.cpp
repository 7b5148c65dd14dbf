#include "pmpm/core/transfers.hpp"
#include "pmpm/core/affine.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/core/shape_cpgimp.hpp"
#include <algorithm>
#include <cmath>

// Every kernel here is written once for D = 2 and 3. The 2D instantiation must give the values of
// the 2D code written out, bit for bit (scripts/bitwise_compare.sh): every product and sum keeps
// its 2D order (x before y, the 1D factors multiplied left to right, the node loops y outer and x
// inner), and the loops over d and the directions' factors are unrolled by the compiler (D and NS
// are compile-time constants), so the 2D path compiles to the code it had (developer guide,
// "Dimensions").

namespace pmpm {

namespace {
// The 1D factors of one particle's tensor-product weights (w, physical gradients dw per metre, per
// direction), and a pointer to its first stencil node; node (a, b, c) is at
// node0 + c * plane + b * row + a * ND. With Affine (APIC, affine.hpp) also the node offsets
// x_i - x_p (r, m) and the affine weights (a, per m) per direction.
template <class Shape, int D> struct Stencil {
  static constexpr int NS = Shape::NS;
  double w[D][NS], dw[D][NS];
  double r[D][NS], a[D][NS]; // Affine only
  int n[D]; // nodes actually touched per direction (the rest have zero weight and gradient)
  double *node0;
};
// Always inlined: called out of line (as GCC chose) it took 17 % of a uGIMP step (BENCHMARKS.md,
// "A leaner explicit cycle").
template <class Shape, int D, bool Affine = false>
__attribute__((always_inline)) inline void stencil(const GridViewT<D> &G, const double *x,
                                                   const double *l, Stencil<Shape, D> &S) {
  constexpr int NS = Shape::NS;
  const double invh = 1.0 / G.h;
  int base[D];
  double xi[D];
  for (int d = 0; d < D; ++d) xi[d] = (x[d] - G.origin[d]) * invh;
  for (int d = 0; d < D; ++d) Shape::eval1d(xi[d], l[d] * invh, base[d], S.w[d], S.dw[d]);
  if (Affine)
    for (int d = 0; d < D; ++d)
      affine1d<Shape>(xi[d], base[d], S.w[d], S.dw[d], G.h, S.r[d], S.a[d]);
  // a block inside one cell touches two nodes only (uGIMP, cpGIMP); a small cpGIMP block three
  for (int d = 0; d < D; ++d) {
    S.n[d] = NS;
    while (S.n[d] > 2 && S.w[d][S.n[d] - 1] == 0.0 && S.dw[d][S.n[d] - 1] == 0.0) --S.n[d];
  }
  for (int a = 0; a < NS; ++a)
    for (int d = 0; d < D; ++d) S.dw[d][a] *= invh;
  PetscInt nb[D];
  for (int d = 0; d < D; ++d) nb[d] = base[d];
  S.node0 = G.node(nb);
}

// The factors of the stencil row (id[1], id[2]) (the nodes along x at those y and z): wo the
// product of the weights of directions 1..D-1, go[e] (e >= 1) the same product with direction e's
// derivative, ao[e] with its affine weight (Affine). Node a of the row then has the weight
// w[0][a] wo, gradient (dw[0][a] wo, w[0][a] go[1], ...) and affine weight (a[0][a] wo,
// w[0][a] ao[1], ...); in 2D wo = wy, go[1] = dwy, ao[1] = ay, the 2D kernels' factors.
template <class Shape, int D, bool Affine>
__attribute__((always_inline)) inline void row_factors(const Stencil<Shape, D> &S, const int *id,
                                                       double &wo, double *go, double *ao) {
  wo = S.w[1][id[1]];
  for (int d = 2; d < D; ++d) wo *= S.w[d][id[d]];
  for (int e = 1; e < D; ++e) {
    double g = e == 1 ? S.dw[1][id[1]] : S.w[1][id[1]];
    for (int d = 2; d < D; ++d) g *= d == e ? S.dw[d][id[d]] : S.w[d][id[d]];
    go[e] = g;
    if (Affine) {
      double q = e == 1 ? S.a[1][id[1]] : S.w[1][id[1]];
      for (int d = 2; d < D; ++d) q *= d == e ? S.a[d][id[d]] : S.w[d][id[d]];
      ao[e] = q;
    }
  }
}

// Multi: several bodies per node (each particle writes its own body's block, runtime stride);
// one body keeps the compile-time stride of before (measured: 5-11 % of a step otherwise).
// Affine: APIC momentum m (w v + B a) (affine.hpp).
// Axi (-geometry axisymmetric, geometry.hpp; 2D): the hoop stress's radial force
// -V sigma_thth N / r.
template <class Shape, int D, bool Multi, bool Affine, bool Axi = false>
void p2g_impl(const ParticleView &P, const LoadT<D> &load_, const GridViewT<D> &G_,
              const PetscInt *idx, PetscInt nidx, const double *pshift) {
  // Local copies: the stores into the nodes (double *) may alias the caller's doubles (the grid
  // spacing, the origin, the load factor), which were then reloaded, and 1 / h divided again,
  // for every particle; nothing aliases a local (BENCHMARKS.md, "A leaner explicit cycle").
  using Dof = GridDofT<D>;
  constexpr int NSt = NStress<D>;
  const GridViewT<D> G = G_;
  const LoadT<D> load = load_;
  const int ND = Multi ? G.nd : Dof::NDOF;
  const PetscInt row = G.row() * ND, plane = D == 3 ? G.rows() * row : 0;
  constexpr bool bodies = Multi;
  Stencil<Shape, D> S;
  const PetscInt n = idx ? nidx : P.n;
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt p = idx ? idx[k] : k;
    double lb[D];
    stencil<Shape, D, Affine>(G, P.x + p * D,
                              Shape::template half<D>(P.lp + p * D, P.F + p * D * D, lb), S);
    if (bodies) S.node0 += P.body[p] * Dof::NDOF;
    const double m = P.mass[p], V = P.vol[p];
    double mv[D];
    for (int d = 0; d < D; ++d) mv[d] = m * P.v[p * D + d];
    double mB[D * D] = {};
    if (Affine)
      for (int e = 0; e < D * D; ++e) mB[e] = m * P.B[p * D * D + e];
    const double *s = P.stress + p * NSt;
    // internal force -V sigma . grad S (eq. 9; with PMPM weights eq. 14)
    // (F-bar: the pressure is the group's, p_bar - p added to the normal stresses; antilock.hpp)
    const double ps = pshift ? pshift[p] : 0.0;
    double Vs[D][D];
    for (int d = 0; d < D; ++d)
      for (int e = 0; e < D; ++e) Vs[d][e] = d == e ? V * (s[d] + ps) : V * s[stress_slot(d, e)];
    const double shoop = Axi ? V * s[2] / P.x[p * D] : 0.0; // per unit N: V sigma_thth / r
    double fb[D];
    for (int d = 0; d < D; ++d) fb[d] = load.factor * P.weight[p] * load.gdir[d];
    const int nz = D == 3 ? S.n[D - 1] : 1;
    for (int c = 0; c < nz; ++c)
      for (int b = 0; b < S.n[1]; ++b) {
        const int id[3] = {0, b, c};
        double wo, go[D], ao[D];
        row_factors<Shape, D, Affine>(S, id, wo, go, ao);
        double *r = S.node0 + b * row + c * plane;
        for (int a = 0; a < S.n[0]; ++a) {
          double *node = r + a * ND;
          const double wa = S.w[0][a], w = wa * wo;
          double g[D];
          g[0] = S.dw[0][a] * wo;
          for (int e = 1; e < D; ++e) g[e] = wa * go[e];
          node[Dof::M] += w * m;
          for (int d = 0; d < D; ++d) node[Dof::P + d] += w * mv[d];
          if (Affine) { // m B a_ip, a_ip = (ax wy, wx ay) = w D^-1 (x_i - x_p)
            double af[D];
            af[0] = S.a[0][a] * wo;
            for (int e = 1; e < D; ++e) af[e] = wa * ao[e];
            for (int d = 0; d < D; ++d) {
              double t = mB[d * D] * af[0];
              for (int e = 1; e < D; ++e) t += mB[d * D + e] * af[e];
              node[Dof::P + d] += t;
            }
          }
          for (int d = 0; d < D; ++d) {
            double t = Vs[d][0] * g[0];
            for (int e = 1; e < D; ++e) t += Vs[d][e] * g[e];
            if (Axi && d == 0)
              node[Dof::F + 0] += w * fb[0] - t - w * shoop;
            else
              node[Dof::F + d] += w * fb[d] - t;
          }
          for (int d = 0; d < D; ++d) node[Dof::FEXT + d] += w * fb[d];
        }
      }
  }
}

} // namespace

template <class Shape, int D>
void p2g(const ParticleView &P, const LoadT<D> &load, const GridViewT<D> &G, const PetscInt *idx,
         PetscInt nidx, const double *pshift) {
  const bool multi = G.nbody > 1, affine = P.B != nullptr;
  // axisymmetric: 2D only; several bodies with membrane chains
  if constexpr (D == 2) {
    if (G.axisymmetric && multi && affine)
      return p2g_impl<Shape, D, true, true, true>(P, load, G, idx, nidx, pshift);
    else if (G.axisymmetric && multi)
      return p2g_impl<Shape, D, true, false, true>(P, load, G, idx, nidx, pshift);
    else if (G.axisymmetric && affine)
      return p2g_impl<Shape, D, false, true, true>(P, load, G, idx, nidx, pshift);
    else if (G.axisymmetric)
      return p2g_impl<Shape, D, false, false, true>(P, load, G, idx, nidx, pshift);
  }
  if (multi && affine)
    p2g_impl<Shape, D, true, true>(P, load, G, idx, nidx, pshift);
  else if (multi)
    p2g_impl<Shape, D, true, false>(P, load, G, idx, nidx, pshift);
  else if (affine)
    p2g_impl<Shape, D, false, true>(P, load, G, idx, nidx, pshift);
  else
    p2g_impl<Shape, D, false, false>(P, load, G, idx, nidx, pshift);
}

namespace {
// Zero the FEXT slots of every node of a whole-array view (the body grid's local array).
template <int D> void zero_fext(const GridViewT<D> &G) {
  PetscInt nodes = G.gm[0];
  for (int d = 1; d < D; ++d) nodes *= G.gm[d];
  for (PetscInt q = 0; q < nodes; ++q)
    for (int d = 0; d < D; ++d) G.data[q * G.nd + GridDofT<D>::FEXT + d] = 0.0;
}
} // namespace

template <class Shape, int D>
void p2g_colour_gradient(const ParticleView &P, const PetscInt *idx, PetscInt nidx,
                         const GridViewT<D> &G) {
  // the body grid has no use for its external force: its FEXT slots carry the gradient
  zero_fext<D>(G);
  constexpr int NS = Shape::NS, NN = Weights<Shape, D>::NN;
  // per h^(D-1): a jump of 1 in colour gives O(1) (V is an area in 2D, a volume in 3D)
  const double scale = D == 2 ? G.h : G.h * G.h;
  Weights<Shape, D> W;
  for (PetscInt k = 0; k < nidx; ++k) {
    const PetscInt p = idx[k];
    double lb[D];
    weights<Shape, D>(P.x + p * D, Shape::template half<D>(P.lp + p * D, P.F + p * D * D, lb),
                      G.origin, G.h, W);
    const double vc = P.vol[p] * P.colour[p] / scale;
    for (int a = 0; a < NN; ++a) { // node a: base + (a % NS, a / NS % NS, a / NS^2)
      PetscInt n[D];
      for (int d = 0, r = a; d < D; ++d, r /= NS) n[d] = W.base[d] + r % NS;
      double *node = G.node(n);
      for (int d = 0; d < D; ++d) node[GridDofT<D>::FEXT + d] += vc * W.grad[a][d];
    }
  }
}

template <int D> void p2g_cell_colour(const ParticleView &P, const GridViewT<D> &G) {
  zero_fext<D>(G);
  const double invh = 1.0 / G.h;
  for (PetscInt p = 0; p < P.n; ++p) {
    // particles lie inside the grid (checked every step), so the truncation is a floor
    PetscInt c[D];
    for (int d = 0; d < D; ++d) {
      c[d] = static_cast<PetscInt>((P.x[p * D + d] - G.origin[d]) * invh);
      c[d] = std::min(std::max(c[d], PetscInt(0)), G.ncell[d] - 1);
    }
    double *node = G.node(c);
    node[GridDofT<D>::FEXT + 0] += P.vol[p] * P.colour[p];
    node[GridDofT<D>::FEXT + 1] += P.vol[p];
  }
}
template void p2g_cell_colour<2>(const ParticleView &, const GridViewT<2> &);
template void p2g_cell_colour<3>(const ParticleView &, const GridViewT<3> &);

void PrescribedVelocitySort(PrescribedVelocity &pv) {
  std::vector<size_t> o(pv.key.size());
  for (size_t k = 0; k < o.size(); ++k) o[k] = k;
  std::sort(o.begin(), o.end(), [&pv](size_t a, size_t b) { return pv.key[a] < pv.key[b]; });
  PrescribedVelocity s;
  for (const size_t k : o) {
    if (!s.key.empty() && s.key.back() == pv.key[k]) continue; // the first entry of a dof wins
    s.key.push_back(pv.key[k]);
    s.v.push_back(pv.v[k]);
    s.weight.push_back(pv.weight[k]);
  }
  pv = std::move(s);
}

namespace {
// Which of node n's dofs are prescribed (entry index, or -1). The nodes of the box are visited in
// key order (x fastest), so one cursor walks the sorted keys once per sweep.
template <int D> struct PrescribedCursor {
  const PrescribedVelocity *pv;
  size_t c = 0;
  void at(const PetscInt *n, const PetscInt *ncell, long idx[D]) {
    for (int d = 0; d < D; ++d) idx[d] = -1;
    // nodes outside the box (a view's ghost layers) have no keys, and would break the order
    if (!pv) return;
    for (int d = 0; d < D; ++d)
      if (n[d] < 0 || n[d] > ncell[d]) return;
    const PetscInt k0 = PrescribedKey<D>(n, 0, ncell);
    while (c < pv->key.size() && pv->key[c] < k0) ++c;
    for (int d = 0; d < D; ++d)
      if (c < pv->key.size() && pv->key[c] == k0 + d) idx[d] = static_cast<long>(c++);
  }
};

// Call f(n) for every node n of the view's box, x fastest (2D: rows j, then columns i).
template <int D, class Fn>
__attribute__((always_inline)) inline void for_each_node(const GridViewT<D> &G, Fn &&f) {
  PetscInt n[D];
  const PetscInt k0 = D == 3 ? G.gs[D - 1] : 0, k1 = D == 3 ? G.gs[D - 1] + G.gm[D - 1] : 1;
  for (PetscInt k = k0; k < k1; ++k) {
    if (D == 3) n[D - 1] = k;
    for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j) {
      n[1] = j;
      for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
        n[0] = i;
        f(n);
      }
    }
  }
}
} // namespace

template <int D>
void grid_update(const GridViewT<D> &G, const GridUpdateParamsT<D> &prm, GridStatsT<D> &st) {
  using Dof = GridDofT<D>;
  const double dt = prm.dt, alpha = prm.damping_alpha, mix = prm.fire_mix;
  constexpr int ND = Dof::NDOF;
  const PrescribedVelocity *pv =
      prm.prescribed && !prm.prescribed->empty() ? prm.prescribed : nullptr;
  PrescribedCursor<D> cur{pv};
  for_each_node<D>(
      G, [&](const PetscInt *n) __attribute__((always_inline)) {
        double *node0 = G.node(n);
        // the node's totals over its bodies: the unbalanced force and the load are the sums (the
        // forces between bodies at a node cancel)
        double msum = 0.0, ftot[D] = {}, fext[D] = {};
        for (int b = 0; b < G.nbody; ++b) {
          const double *node = node0 + b * ND;
          if (node[Dof::M] <= 0.0) continue;
          msum += node[Dof::M];
          for (int d = 0; d < D; ++d) {
            ftot[d] += node[Dof::F + d];
            fext[d] += node[Dof::FEXT + d];
          }
        }
        if (msum <= 0.0) return; // empty node: nothing to update (its slots stay zero)
        bool held[D];
        held_dofs<D>(n, G.ncell, prm.face, held);
        long pi[D];
        cur.at(n, G.ncell, pi);
        for (int d = 0; d < D; ++d)
          if (pi[d] >= 0) {
            held[d] = true; // a support: out of the unbalanced force
            st.support_force[d] += pv->weight[pi[d]] * ftot[d];
            st.support_power -= ftot[d] * pv->v[pi[d]];
          }
        double fext2 = 0.0;
        for (int d = 0; d < D; ++d) fext2 += fext[d] * fext[d];
        if (fext2 > 0.0) {
          st.sum_ext += std::sqrt(fext2);
          st.n_ext += 1.0;
        }
        double f2 = 0.0; // |f_int + f_ext|^2 over the free dofs
        for (int d = 0; d < D; ++d)
          if (!held[d]) f2 += ftot[d] * ftot[d];
        if (std::sqrt(f2) > st.max_unbalanced) {
          st.max_unbalanced = std::sqrt(f2);
          for (int d = 0; d < D; ++d) st.max_at[d] = G.origin[d] + n[d] * G.h;
        }
        // each body's own momentum balance
        for (int b = 0; b < G.nbody; ++b) {
          double *node = node0 + b * ND;
          const double m = node[Dof::M];
          if (m <= 0.0) continue;
          for (int d = 0; d < D; ++d) {
            double v = node[Dof::P + d] / m;
            double f = node[Dof::F + d];
            if (pi[d] >= 0) {
              const double vp = pv->v[pi[d]];
              node[Dof::P + d] = vp;
              node[Dof::F + d] = dt > 0.0 ? (vp - v) / dt : 0.0;
              st.kinetic += 0.5 * m * vp * vp;
              continue;
            }
            if (held[d]) {
              node[Dof::P + d] = 0.0;
              node[Dof::F + d] = 0.0;
              continue;
            }
            const double v0 = v, f0 = f;
            if (alpha > 0.0 && v != 0.0) f -= alpha * std::fabs(f) * (v > 0.0 ? 1.0 : -1.0);
            double a = f / m;
            v += dt * a;
            if (prm.fire) {
              st.power += 0.5 * f0 * (v0 + v);
              st.mv2 += m * v * v;
              st.f2m += f0 * f0 / m;
            }
            if (mix > 0.0 && dt > 0.0) {
              const double vm = (1.0 - mix) * v + mix * prm.fire_scale * f0 / m;
              a += (vm - v) / dt;
              v = vm;
            }
            node[Dof::P + d] = v;
            node[Dof::F + d] = a;
            st.kinetic += 0.5 * m * v * v;
          }
        }
      });
}

namespace {
enum class G2PMode { Fused, Velocity, Kinematics };

// What a particle gathers from its nodes, as sums into the caller's locals (fixed-size arrays,
// kept in registers once inlined): velocity vg, acceleration ag (FLIP), velocity gradient L
// (row-major; eq. 20 with PMPM weights) and APIC's B = sum_i w v_i (x_i - x_p)^T. row, plane: a
// grid row's and plane's doubles, ND: a node's.
template <class Shape, int D, bool vel, bool kin, bool Affine>
__attribute__((always_inline)) inline void g2p_gather(const Stencil<Shape, D> &S, PetscInt row,
                                                      PetscInt plane, int ND, double *vg,
                                                      double *ag, double *L, double *Bn) {
  using Dof = GridDofT<D>;
  const int nz = D == 3 ? S.n[D - 1] : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < S.n[1]; ++b) {
      const int id[3] = {0, b, c};
      double wo, go[D], ao[D];
      row_factors<Shape, D, false>(S, id, wo, go, ao);
      const double *r = S.node0 + b * row + c * plane;
      for (int a = 0; a < S.n[0]; ++a) {
        const double *node = r + a * ND;
        const double wa = S.w[0][a], w = wa * wo;
        double nv[D];
        for (int d = 0; d < D; ++d) nv[d] = node[Dof::P + d];
        for (int d = 0; d < D; ++d) vg[d] += w * nv[d];
        if (vel && !Affine)
          for (int d = 0; d < D; ++d) ag[d] += w * node[Dof::F + d];
        if (vel && Affine) {
          double rr[D];
          rr[0] = S.r[0][a];
          for (int e = 1; e < D; ++e) rr[e] = S.r[e][id[e]];
          for (int d = 0; d < D; ++d) {
            const double wv = w * nv[d];
            for (int e = 0; e < D; ++e) Bn[d * D + e] += wv * rr[e];
          }
        }
        if (kin) {
          double g[D];
          g[0] = S.dw[0][a] * wo;
          for (int e = 1; e < D; ++e) g[e] = wa * go[e];
          for (int d = 0; d < D; ++d)
            for (int e = 0; e < D; ++e) L[d * D + e] += nv[d] * g[e];
        }
      }
    }
}

// Particle p's kinematics from the gathered sums: its position (eq. 5), L dt (into the fused
// stress update when el, 2D; else into dudx), the hoop increment and stretch (Axi, 2D),
// F <- (I + L dt) F and the volume; returns the volume ratio J.
template <int D, bool Axi>
__attribute__((always_inline)) inline double
g2p_deform(const ParticleView &P, PetscInt p, double *x, const double *vg, const double *L,
           double dt, const double *el, double *hoop, double *dudx) {
  const double dhoop = Axi ? dt * vg[0] / x[0] : 0.0; // at the step's start, where L is taken
  for (int d = 0; d < D; ++d) x[d] += dt * vg[d];     // eq. 5
  double du[D * D], *F = P.F + p * D * D;
  for (int k = 0; k < D * D; ++k) du[k] = L[k] * dt;
  if (D == 2 && el) { // the stress update fused (one pass over the particles, no dudx round trip)
    const double *e = el + 2 * P.mat[p];
    elastic_rate_update(e[0], e[1], du, du[0], du[D * D - 1], dhoop, P.stress + p * NSTRESS);
  } else
    for (int k = 0; k < D * D; ++k) dudx[p * D * D + k] = du[k];
  const double Fhoop = Axi ? x[0] / P.x0[p * D] : 1.0;
  if (Axi && hoop) {
    hoop[2 * p] = dhoop;
    hoop[2 * p + 1] = Fhoop;
  }
  // F <- (I + L dt) F, each entry summed over k in order
  double F0[D * D];
  for (int k = 0; k < D * D; ++k) F0[k] = F[k];
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      double t = (i == 0 ? 1.0 + du[i * D] : du[i * D]) * F0[j];
      for (int k = 1; k < D; ++k)
        t += (i == k ? 1.0 + du[i * D + k] : du[i * D + k]) * F0[k * D + j];
      F[i * D + j] = t;
    }
  const double J = Axi ? det_of<D>(F) * Fhoop : det_of<D>(F);
  P.vol[p] = J * P.vol0[p];
  return J;
}

// APIC's kinetic energy of particle p beyond the grid velocity's: its affine part, with the D_p
// that B_p was just taken at (affine.hpp).
template <class Shape, int D>
__attribute__((always_inline)) inline double g2p_affine_kinetic(const ParticleView &P, PetscInt p,
                                                                const Stencil<Shape, D> &S) {
  double Dp[D] = {};
  for (int d = 0; d < D; ++d)
    for (int a = 0; a < S.n[d]; ++a) Dp[d] += S.w[d][a] * S.r[d][a] * S.r[d][a];
  return affine_kinetic<D>(P.mass[p], P.B + p * D * D, Dp);
}

template <class Shape, int D, G2PMode mode, bool Multi, bool Affine, bool Axi = false>
void g2p_one(const ParticleView &P, const GridViewT<D> &G0_, const GridViewT<D> *G1_,
             const CellRangeT<D> *owned, const G2PParamsT<D> &prm, const double *wave_modulus,
             double *dudx, G2PStatsT<D> *st) {
  using Dof = GridDofT<D>;
  // local copies of the views, as in p2g_impl (the particle stores may alias the caller's)
  const GridViewT<D> G0 = G0_;
  GridViewT<D> G1v;
  if (G1_) G1v = *G1_;
  const GridViewT<D> *G1 = G1_ ? &G1v : nullptr;
  const int ND = Multi ? G0.nd : Dof::NDOF;
  constexpr bool vel = mode != G2PMode::Kinematics, kin = mode != G2PMode::Velocity;
  const double dt = prm.dt, pic = prm.pic;
  const PetscInt row = G0.row() * ND, plane = D == 3 ? G0.rows() * row : 0; // G1: G0's layout
  constexpr bool bodies = Multi; // each particle reads its own body's block
  double lo[D], hi[D], gd[D];
  for (int d = 0; d < D; ++d) {
    hi[d] = G0.origin[d] + G0.ncell[d] * G0.h;
    lo[d] = G0.origin[d];
    gd[d] = prm.gdir[d];
  }
  const double invh = 1.0 / G0.h;
  const double *el = D == 2 ? prm.elastic : nullptr;
  const double *en = D == 2 && prm.elastic ? prm.energy : nullptr;
  double *const hoop = prm.hoop;
  // the sums in registers (through st they were stored and reloaded every particle: the stores
  // into the particle arrays may alias them); the same order, the same sums
  double c2max = 0, v2max = 0, kinetic = 0, weight_power = 0, elastic = 0;
  PetscInt left = 0;
  Stencil<Shape, D> S;
  for (PetscInt p = 0; p < P.n; ++p) {
    double *x = P.x + p * D, *v = P.v + p * D;
    const GridViewT<D> &G = (G1 && P.colour[p] > 0.5) ? *G1 : G0; // interface body field
    double lb[D];
    stencil<Shape, D, Affine && vel>(G, x,
                                     Shape::template half<D>(P.lp + p * D, P.F + p * D * D, lb), S);
    if (bodies) S.node0 += P.body[p] * Dof::NDOF;
    double vg[D] = {}, ag[D] = {}, L[D * D] = {}, Bn[D * D] = {};
    g2p_gather<Shape, D, vel, kin, Affine>(S, row, plane, ND, vg, ag, L, Bn);
    if (vel && Affine) { // APIC
      for (int d = 0; d < D; ++d) v[d] = vg[d];
      for (int k = 0; k < D * D; ++k) P.B[p * D * D + k] = Bn[k];
    } else if (vel) { // FLIP (eq. 4) with an optional PIC blend
      for (int d = 0; d < D; ++d) v[d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
    }
    if (!kin) continue;
    const double J = g2p_deform<D, Axi>(P, p, x, vg, L, dt, el, hoop, dudx);
    if constexpr (D == 2)
      if (en) { // every particle, in order, as ElasticEnergy (relaxation.cpp)
        const double *c = en + 2 * P.mat[p];
        elastic += elastic_energy(c[0], c[1], P.vol[p], P.stress + p * NSTRESS);
      }
    double speed2 = v[0] * v[0];
    for (int d = 1; d < D; ++d) speed2 += v[d] * v[d];
    kinetic += 0.5 * P.mass[p] * speed2;
    if (Affine && vel) kinetic += g2p_affine_kinetic<Shape, D>(P, p, S);
    double gv = gd[0] * v[0];
    for (int d = 1; d < D; ++d) gv += gd[d] * v[d];
    weight_power += P.weight[p] * gv;
    // Instability and escape checks, reported by the caller with the particle's id. The centre
    // must stay on the grid (the ghosted DMDA has room for the support beyond it). (Written out:
    // as a helper, another branch layout cost 0.3 % of a run's instructions.)
    double xv = x[0];
    for (int d = 1; d < D; ++d) xv += x[d];
    for (int d = 0; d < D; ++d) xv += v[d];
    bool on = true;
    for (int d = 0; d < D; ++d) on = on && x[d] >= lo[d] && x[d] < hi[d];
    const char *what = nullptr;
    if (!(J > 0.0) || !std::isfinite(J))
      what = "non-positive or non-finite volume ratio J";
    else if (!std::isfinite(xv))
      what = "non-finite position or velocity";
    else if (!on)
      what = "particle left the grid";
    else if (Axi && !(x[0] > 0.0))
      what = "particle reached the axis r = 0";
    if (what) {
      if (st->bad++ == 0) {
        st->bad_pid = P.pid[p];
        for (int d = 0; d < D; ++d) st->bad_x[d] = x[d];
        st->bad_what = what;
      }
      continue;
    }
    // squared wave speed and particle speed; their roots are taken once, after the loop (no
    // std::fmax: GCC calls libm's through the PLT; both are finite here, so a compare is exact)
    const double c2 = wave_modulus[P.mat[p]] * P.vol[p] / P.mass[p];
    c2max = c2 > c2max ? c2 : c2max;
    v2max = speed2 > v2max ? speed2 : v2max;
    // on the grid, so the truncation is a floor
    PetscInt cell[D];
    for (int d = 0; d < D; ++d) cell[d] = static_cast<PetscInt>((x[d] - lo[d]) * invh);
    if (!owned->owns(cell)) ++left;
  }
  if (kin && en) {
    st->has_elastic = true;
    st->elastic += elastic;
  }
  if (kin) {
    st->kinetic += kinetic;
    st->weight_power += weight_power;
    st->left_rank += left;
  }
  // max_p (c_p + |v_p|) <= max c + max |v|: slightly conservative, two roots per step; the
  // caller reduces both maxima across ranks before adding them
  if (kin) {
    st->max_c = std::fmax(st->max_c, std::sqrt(c2max));
    st->max_v = std::fmax(st->max_v, std::sqrt(v2max));
    st->max_speed = st->max_c + st->max_v;
  }
}
template <class Shape, int D, G2PMode mode>
void g2p_impl(const ParticleView &P, const GridViewT<D> &G0, const GridViewT<D> *G1,
              const CellRangeT<D> *owned, const G2PParamsT<D> &prm, const double *wave_modulus,
              double *dudx, G2PStatsT<D> *st) {
  const bool multi = G0.nbody > 1, affine = P.B != nullptr;
  // axisymmetric: 2D only; several bodies with membrane chains
  if constexpr (D == 2) {
    if (G0.axisymmetric && multi && affine)
      return g2p_one<Shape, D, mode, true, true, true>(P, G0, G1, owned, prm, wave_modulus, dudx,
                                                       st);
    else if (G0.axisymmetric && multi)
      return g2p_one<Shape, D, mode, true, false, true>(P, G0, G1, owned, prm, wave_modulus, dudx,
                                                        st);
    else if (G0.axisymmetric && affine)
      return g2p_one<Shape, D, mode, false, true, true>(P, G0, G1, owned, prm, wave_modulus, dudx,
                                                        st);
    else if (G0.axisymmetric)
      return g2p_one<Shape, D, mode, false, false, true>(P, G0, G1, owned, prm, wave_modulus, dudx,
                                                         st);
  }
  if (multi && affine)
    g2p_one<Shape, D, mode, true, true>(P, G0, G1, owned, prm, wave_modulus, dudx, st);
  else if (multi)
    g2p_one<Shape, D, mode, true, false>(P, G0, G1, owned, prm, wave_modulus, dudx, st);
  else if (affine)
    g2p_one<Shape, D, mode, false, true>(P, G0, G1, owned, prm, wave_modulus, dudx, st);
  else
    g2p_one<Shape, D, mode, false, false>(P, G0, G1, owned, prm, wave_modulus, dudx, st);
}
} // namespace

template <class Shape, int D>
void g2p_velocity(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
                  const G2PParamsT<D> &prm) {
  g2p_impl<Shape, D, G2PMode::Velocity>(P, G, G1, nullptr, prm, nullptr, nullptr, nullptr);
}

template <class Shape, int D>
void g2p_kinematics(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
                    const CellRangeT<D> &owned, const G2PParamsT<D> &prm,
                    const double *wave_modulus, double *dudx, G2PStatsT<D> &st) {
  g2p_impl<Shape, D, G2PMode::Kinematics>(P, G, G1, &owned, prm, wave_modulus, dudx, &st);
}

template <class Shape, int D>
void g2p(const ParticleView &P, const GridViewT<D> &G, const GridViewT<D> *G1,
         const CellRangeT<D> &owned, const G2PParamsT<D> &prm, const double *wave_modulus,
         double *dudx, G2PStatsT<D> &st) {
  g2p_impl<Shape, D, G2PMode::Fused>(P, G, G1, &owned, prm, wave_modulus, dudx, &st);
}

// (no affine term: SimulationSetup refuses -musl with -transfer apic)
template <class Shape, int D> void p2g_momentum(const ParticleView &P, const GridViewT<D> &G) {
  using Dof = GridDofT<D>;
  constexpr int NS = Shape::NS;
  Weights<Shape, D> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    double lb[D];
    weights<Shape, D>(P.x + p * D, Shape::template half<D>(P.lp + p * D, P.F + p * D * D, lb),
                      G.origin, G.h, W);
    const double m = P.mass[p], *v = P.v + p * D;
    for (int k = 0; k < W.NN; ++k) {
      PetscInt n[D];
      for (int d = 0, r = k; d < D; ++d, r /= NS) n[d] = W.base[d] + r % NS;
      double *node = G.node(n);
      const double wm = W.w[k] * m;
      node[Dof::M] += wm;
      for (int d = 0; d < D; ++d) node[Dof::P + d] += wm * v[d];
    }
  }
}

template <int D>
void grid_velocity(const GridViewT<D> &G, const FaceBC *face,
                   const PrescribedVelocity *prescribed) {
  using Dof = GridDofT<D>;
  PrescribedCursor<D> cur{prescribed && !prescribed->empty() ? prescribed : nullptr};
  for_each_node<D>(
      G, [&](const PetscInt *n) __attribute__((always_inline)) {
        double *node = G.node(n);
        const double m = node[Dof::M];
        if (m <= 0.0) return;
        bool held[D];
        held_dofs<D>(n, G.ncell, face, held);
        long pi[D];
        cur.at(n, G.ncell, pi);
        for (int d = 0; d < D; ++d)
          node[Dof::P + d] = pi[d] >= 0 ? cur.pv->v[pi[d]] : (held[d] ? 0.0 : node[Dof::P + d] / m);
      });
}

#define PMPM_INSTANTIATE_D(S, D)                                                                   \
  template void p2g<S, D>(const ParticleView &, const LoadT<D> &, const GridViewT<D> &,            \
                          const PetscInt *, PetscInt, const double *);                             \
  template void g2p_velocity<S, D>(const ParticleView &, const GridViewT<D> &,                     \
                                   const GridViewT<D> *, const G2PParamsT<D> &);                   \
  template void p2g_momentum<S, D>(const ParticleView &, const GridViewT<D> &);                    \
  template void g2p<S, D>(const ParticleView &, const GridViewT<D> &, const GridViewT<D> *,        \
                          const CellRangeT<D> &, const G2PParamsT<D> &, const double *, double *,  \
                          G2PStatsT<D> &);                                                         \
  template void g2p_kinematics<S, D>(                                                              \
      const ParticleView &, const GridViewT<D> &, const GridViewT<D> *, const CellRangeT<D> &,     \
      const G2PParamsT<D> &, const double *, double *, G2PStatsT<D> &);
#define PMPM_INSTANTIATE(S)                                                                        \
  PMPM_INSTANTIATE_D(S, 2)                                                                         \
  PMPM_INSTANTIATE_D(S, 3)                                                                         \
  template void p2g_colour_gradient<S, 2>(const ParticleView &, const PetscInt *, PetscInt,        \
                                          const GridViewT<2> &);                                   \
  template void p2g_colour_gradient<S, 3>(const ParticleView &, const PetscInt *, PetscInt,        \
                                          const GridViewT<3> &);
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
PMPM_INSTANTIATE(CPGIMPShape)
#undef PMPM_INSTANTIATE
#undef PMPM_INSTANTIATE_D
template void grid_update<2>(const GridViewT<2> &, const GridUpdateParamsT<2> &, GridStatsT<2> &);
template void grid_update<3>(const GridViewT<3> &, const GridUpdateParamsT<3> &, GridStatsT<3> &);
template void grid_velocity<2>(const GridViewT<2> &, const FaceBC *, const PrescribedVelocity *);
template void grid_velocity<3>(const GridViewT<3> &, const FaceBC *, const PrescribedVelocity *);

} // namespace pmpm
