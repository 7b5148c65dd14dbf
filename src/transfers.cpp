#include "pmpm/transfers.hpp"
#include "pmpm/affine.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/shape_cpgimp.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

void held_dofs(PetscInt i, PetscInt j, const PetscInt ncell[DIM], const FaceBC face[2 * DIM],
               bool held[DIM]) {
  const bool on[2 * DIM] = {i == 0, i == ncell[0], j == 0, j == ncell[1]};
  held[0] = held[1] = false;
  for (int f = 0; f < 2 * DIM; ++f) {
    if (!on[f] || face[f] == FaceBC::Free) continue;
    if (face[f] == FaceBC::Fixed)
      held[0] = held[1] = true;
    else
      held[f / 2] = true;
  }
}

namespace {
// The 1D factors of one particle's tensor-product weights, physical gradients (per metre), and
// a pointer to its first stencil node; node (a, b) is at node0 + b * row + a * NDOF. With Affine
// (APIC, affine.hpp) also the node offsets x_i - x_p and the affine weights per direction.
template <class Shape> struct Stencil {
  static constexpr int NS = Shape::NS;
  double wx[NS], dwx[NS], wy[NS], dwy[NS];
  double rx[NS], ry[NS], ax[NS], ay[NS]; // Affine only: offsets (m), affine weights (per m)
  int nx, ny; // nodes actually touched per direction (the rest have zero weight and gradient)
  double *node0;
};
// Always inlined: called out of line (as GCC chose) it took 17 % of a uGIMP step (BENCHMARKS.md,
// "A leaner explicit cycle").
template <class Shape, bool Affine = false>
__attribute__((always_inline)) inline void stencil(const GridView &G, const double *x,
                                                   const double *l, Stencil<Shape> &S) {
  constexpr int NS = Shape::NS;
  const double invh = 1.0 / G.h;
  int base[DIM];
  const double xi[DIM] = {(x[0] - G.origin[0]) * invh, (x[1] - G.origin[1]) * invh};
  Shape::eval1d(xi[0], l[0] * invh, base[0], S.wx, S.dwx);
  Shape::eval1d(xi[1], l[1] * invh, base[1], S.wy, S.dwy);
  if (Affine) {
    affine1d<Shape>(xi[0], base[0], S.wx, S.dwx, G.h, S.rx, S.ax);
    affine1d<Shape>(xi[1], base[1], S.wy, S.dwy, G.h, S.ry, S.ay);
  }
  S.nx = S.ny = NS;
  // a block inside one cell touches two nodes only (uGIMP, cpGIMP); a small cpGIMP block three
  while (S.nx > 2 && S.wx[S.nx - 1] == 0.0 && S.dwx[S.nx - 1] == 0.0) --S.nx;
  while (S.ny > 2 && S.wy[S.ny - 1] == 0.0 && S.dwy[S.ny - 1] == 0.0) --S.ny;
  for (int a = 0; a < NS; ++a) {
    S.dwx[a] *= invh;
    S.dwy[a] *= invh;
  }
  S.node0 = G.node(base[0], base[1]);
}
} // namespace

namespace {
// Multi: several bodies per node (each particle writes its own body's block, runtime stride);
// one body keeps the compile-time stride of before (measured: 5-11 % of a step otherwise).
// Affine: APIC momentum m (w v + B a) (affine.hpp).
// Axi (-geometry axisymmetric, geometry.hpp): the hoop stress's radial force -V sigma_thth N / r.
template <class Shape, bool Multi, bool Affine, bool Axi = false>
void p2g_impl(const ParticleView &P, const Load &load_, const GridView &G_, const PetscInt *idx,
              PetscInt nidx, const double *pshift) {
  // Local copies: the stores into the nodes (double *) may alias the caller's doubles (the grid
  // spacing, the origin, the load factor), which were then reloaded, and 1 / h divided again,
  // for every particle; nothing aliases a local (BENCHMARKS.md, "A leaner explicit cycle").
  const GridView G = G_;
  const Load load = load_;
  const int ND = Multi ? G.nd : GridDof::NDOF;
  const PetscInt row = G.row() * ND;
  constexpr bool bodies = Multi;
  Stencil<Shape> S;
  const PetscInt n = idx ? nidx : P.n;
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt p = idx ? idx[k] : k;
    double lb[DIM];
    stencil<Shape, Affine>(G, P.x + p * DIM, Shape::half(P.lp + p * DIM, P.F + p * DIM * DIM, lb),
                           S);
    if (bodies) S.node0 += P.body[p] * GridDof::NDOF;
    const double m = P.mass[p], V = P.vol[p];
    const double mv0 = m * P.v[p * DIM], mv1 = m * P.v[p * DIM + 1];
    double mB[DIM * DIM] = {0, 0, 0, 0};
    if (Affine)
      for (int e = 0; e < DIM * DIM; ++e) mB[e] = m * P.B[p * DIM * DIM + e];
    const double *s = P.stress + p * NSTRESS;
    // internal force -V sigma . grad S (eq. 9; with PMPM weights eq. 14)
    // (F-bar: the pressure is the group's, p_bar - p added to the normal stresses; antilock.hpp)
    const double ps = pshift ? pshift[p] : 0.0;
    const double sxx = V * (s[0] + ps), syy = V * (s[1] + ps), sxy = V * s[3];
    const double shoop = Axi ? V * s[2] / P.x[p * DIM] : 0.0; // per unit N: V sigma_thth / r
    const double fb0 = load.factor * P.weight[p] * load.gdir[0];
    const double fb1 = load.factor * P.weight[p] * load.gdir[1];
    for (int b = 0; b < S.ny; ++b) {
      double *r = S.node0 + b * row;
      const double wy = S.wy[b], dwy = S.dwy[b];
      for (int a = 0; a < S.nx; ++a) {
        double *node = r + a * ND;
        const double w = S.wx[a] * wy, gx = S.dwx[a] * wy, gy = S.wx[a] * dwy;
        node[GridDof::M] += w * m;
        node[GridDof::P + 0] += w * mv0;
        node[GridDof::P + 1] += w * mv1;
        if (Affine) { // m B a_ip, a_ip = (ax wy, wx ay) = w D^-1 (x_i - x_p)
          const double a0 = S.ax[a] * wy, a1 = S.wx[a] * S.ay[b];
          node[GridDof::P + 0] += mB[0] * a0 + mB[1] * a1;
          node[GridDof::P + 1] += mB[2] * a0 + mB[3] * a1;
        }
        if (Axi)
          node[GridDof::F + 0] += w * fb0 - (sxx * gx + sxy * gy) - w * shoop;
        else
          node[GridDof::F + 0] += w * fb0 - (sxx * gx + sxy * gy);
        node[GridDof::F + 1] += w * fb1 - (sxy * gx + syy * gy);
        node[GridDof::FEXT + 0] += w * fb0;
        node[GridDof::FEXT + 1] += w * fb1;
      }
    }
  }
}

} // namespace

template <class Shape>
void p2g(const ParticleView &P, const Load &load, const GridView &G, const PetscInt *idx,
         PetscInt nidx, const double *pshift) {
  const bool multi = G.nbody > 1, affine = P.B != nullptr;
  // axisymmetric runs have one body (GeometryCheck refuses chains)
  if (G.axisymmetric && affine)
    p2g_impl<Shape, false, true, true>(P, load, G, idx, nidx, pshift);
  else if (G.axisymmetric)
    p2g_impl<Shape, false, false, true>(P, load, G, idx, nidx, pshift);
  else if (multi && affine)
    p2g_impl<Shape, true, true>(P, load, G, idx, nidx, pshift);
  else if (multi)
    p2g_impl<Shape, true, false>(P, load, G, idx, nidx, pshift);
  else if (affine)
    p2g_impl<Shape, false, true>(P, load, G, idx, nidx, pshift);
  else
    p2g_impl<Shape, false, false>(P, load, G, idx, nidx, pshift);
}

template <class Shape>
void p2g_traction(const ParticleView &P, const std::vector<ParticleLoad> &loads,
                  const std::vector<PetscInt> &idx, double factor, const GridView &G) {
  Weights<LinearShape> W;
  const double zero[DIM] = {0.0, 0.0};
  for (const PetscInt p : idx) {
    // The face sits where the shape's block ends: at the undeformed offset for PMPM, whose
    // blocks keep their initial size (consistent with eq. 14), scaled with the block for cpGIMP
    // (l / lp is exactly 1 for a block of fixed size).
    const ParticleLoad &L = loads[P.load[p]];
    double lb[DIM];
    const double *lp = P.lp + p * DIM, *l = Shape::half(lp, P.F + p * DIM * DIM, lb);
    const double *o = L.tface;
    const double xf[DIM] = {P.x[p * DIM] + o[0] * (l[0] / lp[0]),
                            P.x[p * DIM + 1] + o[1] * (l[1] / lp[1])};
    weights<LinearShape>(xf, zero, G.origin, G.h, W);
    const double t[DIM] = {factor * L.traction[0], factor * L.traction[1]};
    const int off = G.nbody > 1 ? P.body[p] * GridDof::NDOF : 0;
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        double *node = G.node(W.base[0] + a, W.base[1] + b) + off;
        const double w = W.w[b * 2 + a];
        for (int d = 0; d < DIM; ++d) {
          node[GridDof::F + d] += w * t[d];
          node[GridDof::FEXT + d] += w * t[d];
        }
      }
  }
}

template <class Shape>
void p2g_colour_gradient(const ParticleView &P, const PetscInt *idx, PetscInt nidx,
                         const GridView &G) {
  // the body grid has no use for its external force: its FEXT slots carry the gradient
  for (PetscInt q = 0; q < G.gm[0] * G.gm[1]; ++q)
    for (int d = 0; d < DIM; ++d) G.data[q * G.nd + GridDof::FEXT + d] = 0.0;
  constexpr int NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt k = 0; k < nidx; ++k) {
    const PetscInt p = idx[k];
    double lb[DIM];
    weights<Shape>(P.x + p * DIM, Shape::half(P.lp + p * DIM, P.F + p * DIM * DIM, lb), G.origin,
                   G.h, W);
    const double vc = P.vol[p] * P.colour[p] / G.h; // per h: a jump of 1 in colour gives O(1)
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        double *node = G.node(W.base[0] + a, W.base[1] + b);
        node[GridDof::FEXT + 0] += vc * W.grad[b * NS + a][0];
        node[GridDof::FEXT + 1] += vc * W.grad[b * NS + a][1];
      }
  }
}

void p2g_cell_colour(const ParticleView &P, const GridView &G) {
  for (PetscInt q = 0; q < G.gm[0] * G.gm[1]; ++q)
    for (int d = 0; d < DIM; ++d) G.data[q * G.nd + GridDof::FEXT + d] = 0.0;
  const double invh = 1.0 / G.h;
  for (PetscInt p = 0; p < P.n; ++p) {
    // particles lie inside the grid (checked every step), so the truncation is a floor
    PetscInt c[DIM];
    for (int d = 0; d < DIM; ++d) {
      c[d] = static_cast<PetscInt>((P.x[p * DIM + d] - G.origin[d]) * invh);
      c[d] = std::min(std::max(c[d], PetscInt(0)), G.ncell[d] - 1);
    }
    double *node = G.node(c[0], c[1]);
    node[GridDof::FEXT + 0] += P.vol[p] * P.colour[p];
    node[GridDof::FEXT + 1] += P.vol[p];
  }
}

PetscInt PrescribedKey(PetscInt i, PetscInt j, int d, const PetscInt ncell[DIM]) {
  return (j * (ncell[0] + 1) + i) * DIM + d;
}

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
// Which of node (i, j)'s dofs are prescribed (entry index, or -1). The nodes of the box are
// visited in key order (rows, then columns), so one cursor walks the sorted keys once per sweep.
struct PrescribedCursor {
  const PrescribedVelocity *pv;
  size_t c = 0;
  void at(PetscInt i, PetscInt j, const PetscInt ncell[DIM], long idx[DIM]) {
    idx[0] = idx[1] = -1;
    // nodes outside the box (a view's ghost layers) have no keys, and would break the order
    if (!pv || i < 0 || j < 0 || i > ncell[0] || j > ncell[1]) return;
    const PetscInt k0 = PrescribedKey(i, j, 0, ncell);
    while (c < pv->key.size() && pv->key[c] < k0) ++c;
    for (int d = 0; d < DIM; ++d)
      if (c < pv->key.size() && pv->key[c] == k0 + d) idx[d] = static_cast<long>(c++);
  }
};
} // namespace

void grid_update(const GridView &G, const GridUpdateParams &prm, GridStats &st) {
  const double dt = prm.dt, alpha = prm.damping_alpha, mix = prm.fire_mix;
  constexpr int ND = GridDof::NDOF;
  const PrescribedVelocity *pv =
      prm.prescribed && !prm.prescribed->empty() ? prm.prescribed : nullptr;
  PrescribedCursor cur{pv};
  for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j) {
    for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
      double *node0 = G.node(i, j);
      // the node's totals over its bodies: the unbalanced force and the load are the sums (the
      // forces between bodies at a node cancel)
      double msum = 0.0, ftot[DIM] = {0.0, 0.0}, fext[DIM] = {0.0, 0.0};
      for (int b = 0; b < G.nbody; ++b) {
        const double *node = node0 + b * ND;
        if (node[GridDof::M] <= 0.0) continue;
        msum += node[GridDof::M];
        for (int d = 0; d < DIM; ++d) {
          ftot[d] += node[GridDof::F + d];
          fext[d] += node[GridDof::FEXT + d];
        }
      }
      if (msum <= 0.0) continue; // empty node: nothing to update (its slots stay zero)
      bool held[DIM];
      held_dofs(i, j, G.ncell, prm.face, held);
      long pi[DIM];
      cur.at(i, j, G.ncell, pi);
      for (int d = 0; d < DIM; ++d)
        if (pi[d] >= 0) {
          held[d] = true; // a support: out of the unbalanced force
          st.support_force[d] += pv->weight[pi[d]] * ftot[d];
          st.support_power -= ftot[d] * pv->v[pi[d]];
        }
      double fext2 = 0.0;
      for (int d = 0; d < DIM; ++d) fext2 += fext[d] * fext[d];
      if (fext2 > 0.0) {
        st.sum_ext += std::sqrt(fext2);
        st.n_ext += 1.0;
      }
      double f2 = 0.0; // |f_int + f_ext|^2 over the free dofs
      for (int d = 0; d < DIM; ++d)
        if (!held[d]) f2 += ftot[d] * ftot[d];
      if (std::sqrt(f2) > st.max_unbalanced) {
        st.max_unbalanced = std::sqrt(f2);
        st.max_at[0] = G.origin[0] + i * G.h;
        st.max_at[1] = G.origin[1] + j * G.h;
      }
      // each body's own momentum balance
      for (int b = 0; b < G.nbody; ++b) {
        double *node = node0 + b * ND;
        const double m = node[GridDof::M];
        if (m <= 0.0) continue;
        for (int d = 0; d < DIM; ++d) {
          double v = node[GridDof::P + d] / m;
          double f = node[GridDof::F + d];
          if (pi[d] >= 0) {
            const double vp = pv->v[pi[d]];
            node[GridDof::P + d] = vp;
            node[GridDof::F + d] = dt > 0.0 ? (vp - v) / dt : 0.0;
            st.kinetic += 0.5 * m * vp * vp;
            continue;
          }
          if (held[d]) {
            node[GridDof::P + d] = 0.0;
            node[GridDof::F + d] = 0.0;
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
          node[GridDof::P + d] = v;
          node[GridDof::F + d] = a;
          st.kinetic += 0.5 * m * v * v;
        }
      }
    }
  }
}

namespace {
enum class G2PMode { Fused, Velocity, Kinematics };

// What a particle gathers from its nodes, as sums into the caller's locals (scalars, not a
// struct: the same registers and code as the loop written out): velocity vg, acceleration ag
// (FLIP), velocity gradient L (row-major; eq. 20 with PMPM weights) and APIC's
// B = sum_i w v_i (x_i - x_p)^T. row: a grid row's doubles, ND: a node's.
template <class Shape, bool vel, bool kin, bool Affine>
__attribute__((always_inline)) inline void
g2p_gather(const Stencil<Shape> &S, PetscInt row, int ND, double &vg0, double &vg1, double &ag0,
           double &ag1, double &L0, double &L1, double &L2, double &L3, double *Bn) {
  for (int b = 0; b < S.ny; ++b) {
    const double *r = S.node0 + b * row;
    const double wy = S.wy[b], dwy = S.dwy[b];
    for (int a = 0; a < S.nx; ++a) {
      const double *node = r + a * ND;
      const double w = S.wx[a] * wy;
      const double nv0 = node[GridDof::P], nv1 = node[GridDof::P + 1];
      vg0 += w * nv0;
      vg1 += w * nv1;
      if (vel && !Affine) {
        ag0 += w * node[GridDof::F];
        ag1 += w * node[GridDof::F + 1];
      }
      if (vel && Affine) {
        const double wv0 = w * nv0, wv1 = w * nv1, rx = S.rx[a], ry = S.ry[b];
        Bn[0] += wv0 * rx;
        Bn[1] += wv0 * ry;
        Bn[2] += wv1 * rx;
        Bn[3] += wv1 * ry;
      }
      if (kin) {
        const double gx = S.dwx[a] * wy, gy = S.wx[a] * dwy;
        L0 += nv0 * gx;
        L1 += nv0 * gy;
        L2 += nv1 * gx;
        L3 += nv1 * gy;
      }
    }
  }
}

// Particle p's kinematics from the gathered sums: its position (eq. 5), L dt (into the fused
// stress update when el, else into dudx), the hoop increment and stretch (Axi), F <- (I + L dt) F
// and the volume; returns the volume ratio J.
template <bool Axi>
__attribute__((always_inline)) inline double
g2p_deform(const ParticleView &P, PetscInt p, double *x, double vg0, double vg1, double L0,
           double L1, double L2, double L3, double dt, const double *el, double *hoop,
           double *dudx) {
  const double dhoop = Axi ? dt * vg0 / x[0] : 0.0; // at the step's start, where L is taken
  x[0] += dt * vg0;                                 // eq. 5
  x[1] += dt * vg1;
  double dul[DIM * DIM] = {L0 * dt, L1 * dt, L2 * dt, L3 * dt}, *F = P.F + p * DIM * DIM;
  const double *du = dul;
  if (el) { // the stress update fused (one pass over the particles, no dudx round trip)
    const double *e = el + 2 * P.mat[p];
    elastic_rate_update(e[0], e[1], du, du[0], du[3], dhoop, P.stress + p * NSTRESS);
  } else
    for (int k = 0; k < DIM * DIM; ++k) dudx[p * DIM * DIM + k] = dul[k];
  const double Fhoop = Axi ? x[0] / P.x0[p * DIM] : 1.0;
  if (Axi && hoop) {
    hoop[2 * p] = dhoop;
    hoop[2 * p + 1] = Fhoop;
  }
  // F <- (I + L dt) F
  const double F0 = F[0], F1 = F[1], F2 = F[2], F3 = F[3];
  F[0] = (1.0 + du[0]) * F0 + du[1] * F2;
  F[1] = (1.0 + du[0]) * F1 + du[1] * F3;
  F[2] = du[2] * F0 + (1.0 + du[3]) * F2;
  F[3] = du[2] * F1 + (1.0 + du[3]) * F3;
  const double J = Axi ? (F[0] * F[3] - F[1] * F[2]) * Fhoop : F[0] * F[3] - F[1] * F[2];
  P.vol[p] = J * P.vol0[p];
  return J;
}

// APIC's kinetic energy of particle p beyond the grid velocity's: its affine part, with the D_p
// that B_p was just taken at (affine.hpp).
template <class Shape>
__attribute__((always_inline)) inline double g2p_affine_kinetic(const ParticleView &P, PetscInt p,
                                                                const Stencil<Shape> &S) {
  double D[DIM] = {0, 0};
  for (int a = 0; a < S.nx; ++a) D[0] += S.wx[a] * S.rx[a] * S.rx[a];
  for (int b = 0; b < S.ny; ++b) D[1] += S.wy[b] * S.ry[b] * S.ry[b];
  return affine_kinetic(P.mass[p], P.B + p * DIM * DIM, D);
}

template <class Shape, G2PMode mode, bool Multi, bool Affine, bool Axi = false>
void g2p_one(const ParticleView &P, const GridView &G0_, const GridView *G1_, const Grid *grid,
             const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats *st) {
  // local copies of the views, as in p2g_impl (the particle stores may alias the caller's)
  const GridView G0 = G0_;
  GridView G1v;
  if (G1_) G1v = *G1_;
  const GridView *G1 = G1_ ? &G1v : nullptr;
  const int ND = Multi ? G0.nd : GridDof::NDOF;
  constexpr bool vel = mode != G2PMode::Kinematics, kin = mode != G2PMode::Velocity;
  const double dt = prm.dt, pic = prm.pic;
  const PetscInt row = G0.row() * ND; // G1 shares G0's layout
  constexpr bool bodies = Multi;      // each particle reads its own body's block
  const double hx = G0.origin[0] + G0.ncell[0] * G0.h, hy = G0.origin[1] + G0.ncell[1] * G0.h;
  const double invh = 1.0 / G0.h;
  const double ox = G0.origin[0], oy = G0.origin[1];
  const double gd0 = prm.gdir[0], gd1 = prm.gdir[1];
  const double *el = prm.elastic, *en = prm.elastic ? prm.energy : nullptr;
  double *const hoop = prm.hoop;
  // the sums in registers (through st they were stored and reloaded every particle: the stores
  // into the particle arrays may alias them); the same order, the same sums
  double c2max = 0, v2max = 0, kinetic = 0, weight_power = 0, elastic = 0;
  PetscInt left = 0;
  Stencil<Shape> S;
  for (PetscInt p = 0; p < P.n; ++p) {
    double *x = P.x + p * DIM, *v = P.v + p * DIM;
    const GridView &G = (G1 && P.colour[p] > 0.5) ? *G1 : G0; // interface body field
    double lb[DIM];
    stencil<Shape, Affine && vel>(G, x, Shape::half(P.lp + p * DIM, P.F + p * DIM * DIM, lb), S);
    if (bodies) S.node0 += P.body[p] * GridDof::NDOF;
    double vg0 = 0, vg1 = 0, ag0 = 0, ag1 = 0, L0 = 0, L1 = 0, L2 = 0, L3 = 0;
    double Bn[DIM * DIM] = {0, 0, 0, 0};
    g2p_gather<Shape, vel, kin, Affine>(S, row, ND, vg0, vg1, ag0, ag1, L0, L1, L2, L3, Bn);
    if (vel && Affine) { // APIC
      v[0] = vg0;
      v[1] = vg1;
      for (int k = 0; k < DIM * DIM; ++k) P.B[p * DIM * DIM + k] = Bn[k];
    } else if (vel) { // FLIP (eq. 4) with an optional PIC blend
      v[0] = (1.0 - pic) * (v[0] + dt * ag0) + pic * vg0;
      v[1] = (1.0 - pic) * (v[1] + dt * ag1) + pic * vg1;
    }
    if (!kin) continue;
    const double J = g2p_deform<Axi>(P, p, x, vg0, vg1, L0, L1, L2, L3, dt, el, hoop, dudx);
    if (en) { // every particle, in order, as ElasticEnergy (relaxation.cpp)
      const double *c = en + 2 * P.mat[p];
      elastic += elastic_energy(c[0], c[1], P.vol[p], P.stress + p * NSTRESS);
    }
    const double speed2 = v[0] * v[0] + v[1] * v[1];
    kinetic += 0.5 * P.mass[p] * speed2;
    if (Affine && vel) kinetic += g2p_affine_kinetic(P, p, S);
    weight_power += P.weight[p] * (gd0 * v[0] + gd1 * v[1]);
    // Instability and escape checks, reported by the caller with the particle's id. The centre
    // must stay on the grid (the ghosted DMDA has room for the support beyond it). (Written out:
    // as a helper, another branch layout cost 0.3 % of a run's instructions.)
    const char *what = nullptr;
    if (!(J > 0.0) || !std::isfinite(J))
      what = "non-positive or non-finite volume ratio J";
    else if (!std::isfinite(x[0] + x[1] + v[0] + v[1]))
      what = "non-finite position or velocity";
    else if (!(x[0] >= ox && x[0] < hx && x[1] >= oy && x[1] < hy))
      what = "particle left the grid";
    else if (Axi && !(x[0] > 0.0))
      what = "particle reached the axis r = 0";
    if (what) {
      if (st->bad++ == 0) {
        st->bad_pid = P.pid[p];
        st->bad_x[0] = x[0];
        st->bad_x[1] = x[1];
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
    const PetscInt cell[DIM] = {static_cast<PetscInt>((x[0] - ox) * invh),
                                static_cast<PetscInt>((x[1] - oy) * invh)};
    if (!grid->owns_cell(cell)) ++left;
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
template <class Shape, G2PMode mode>
void g2p_impl(const ParticleView &P, const GridView &G0, const GridView *G1, const Grid *grid,
              const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats *st) {
  const bool multi = G0.nbody > 1, affine = P.B != nullptr;
  // axisymmetric runs have one body (GeometryCheck refuses chains)
  if (G0.axisymmetric && affine)
    g2p_one<Shape, mode, false, true, true>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
  else if (G0.axisymmetric)
    g2p_one<Shape, mode, false, false, true>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
  else if (multi && affine)
    g2p_one<Shape, mode, true, true>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
  else if (multi)
    g2p_one<Shape, mode, true, false>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
  else if (affine)
    g2p_one<Shape, mode, false, true>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
  else
    g2p_one<Shape, mode, false, false>(P, G0, G1, grid, prm, wave_modulus, dudx, st);
}
} // namespace

template <class Shape>
void g2p_velocity(const ParticleView &P, const GridView &G, const GridView *G1,
                  const G2PParams &prm) {
  g2p_impl<Shape, G2PMode::Velocity>(P, G, G1, nullptr, prm, nullptr, nullptr, nullptr);
}

template <class Shape>
void g2p_kinematics(const ParticleView &P, const GridView &G, const GridView *G1, const Grid &grid,
                    const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats &st) {
  g2p_impl<Shape, G2PMode::Kinematics>(P, G, G1, &grid, prm, wave_modulus, dudx, &st);
}

template <class Shape>
void g2p(const ParticleView &P, const GridView &G, const GridView *G1, const Grid &grid,
         const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats &st) {
  g2p_impl<Shape, G2PMode::Fused>(P, G, G1, &grid, prm, wave_modulus, dudx, &st);
}

// (no affine term: SimulationSetup refuses -musl with -transfer apic)
template <class Shape> void p2g_momentum(const ParticleView &P, const GridView &G) {
  constexpr int NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    double lb[DIM];
    weights<Shape>(P.x + p * DIM, Shape::half(P.lp + p * DIM, P.F + p * DIM * DIM, lb), G.origin,
                   G.h, W);
    const double m = P.mass[p], *v = P.v + p * DIM;
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        double *node = G.node(W.base[0] + a, W.base[1] + b);
        const double wm = W.w[b * NS + a] * m;
        node[GridDof::M] += wm;
        node[GridDof::P + 0] += wm * v[0];
        node[GridDof::P + 1] += wm * v[1];
      }
  }
}

void grid_velocity(const GridView &G, const FaceBC face[2 * DIM],
                   const PrescribedVelocity *prescribed) {
  PrescribedCursor cur{prescribed && !prescribed->empty() ? prescribed : nullptr};
  for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j)
    for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
      double *node = G.node(i, j);
      const double m = node[GridDof::M];
      if (m <= 0.0) continue;
      bool held[DIM];
      held_dofs(i, j, G.ncell, face, held);
      long pi[DIM];
      cur.at(i, j, G.ncell, pi);
      for (int d = 0; d < DIM; ++d)
        node[GridDof::P + d] =
            pi[d] >= 0 ? cur.pv->v[pi[d]] : (held[d] ? 0.0 : node[GridDof::P + d] / m);
    }
}

#define PMPM_INSTANTIATE(S)                                                                        \
  template void p2g_traction<S>(const ParticleView &, const std::vector<ParticleLoad> &,           \
                                const std::vector<PetscInt> &, double, const GridView &);          \
  template void p2g<S>(const ParticleView &, const Load &, const GridView &, const PetscInt *,     \
                       PetscInt, const double *);                                                  \
  template void p2g_colour_gradient<S>(const ParticleView &, const PetscInt *, PetscInt,           \
                                       const GridView &);                                          \
  template void g2p_velocity<S>(const ParticleView &, const GridView &, const GridView *,          \
                                const G2PParams &);                                                \
  template void p2g_momentum<S>(const ParticleView &, const GridView &);                           \
  template void g2p<S>(const ParticleView &, const GridView &, const GridView *, const Grid &,     \
                       const G2PParams &, const double *, double *, G2PStats &);                   \
  template void g2p_kinematics<S>(const ParticleView &, const GridView &, const GridView *,        \
                                  const Grid &, const G2PParams &, const double *, double *,       \
                                  G2PStats &);
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
PMPM_INSTANTIATE(CPGIMPShape)
#undef PMPM_INSTANTIATE

} // namespace pmpm
