#include "pmpm/transfers.hpp"
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

template <class Shape>
void p2g(const ParticleView &P, const Load &load, const GridView &G, const PetscInt *idx,
         PetscInt nidx) {
  constexpr int NS = Shape::NS;
  Weights<Shape> W;
  const PetscInt n = idx ? nidx : P.n;
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt p = idx ? idx[k] : k;
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, G.origin, G.h, W);
    const double m = P.mass[p], V = P.vol[p];
    const double *v = P.v + p * DIM, *s = P.stress + p * NSTRESS;
    const double fb[DIM] = {load.factor * P.weight[p] * load.gdir[0],
                            load.factor * P.weight[p] * load.gdir[1]};
    for (int b = 0; b < NS; ++b) {
      for (int a = 0; a < NS; ++a) {
        const int q = b * NS + a;
        const double w = W.w[q], gx = W.grad[q][0], gy = W.grad[q][1];
        double *node = G.node(W.base[0] + a, W.base[1] + b);
        node[GridDof::M] += w * m;
        node[GridDof::P + 0] += w * m * v[0];
        node[GridDof::P + 1] += w * m * v[1];
        // internal force -V sigma . grad S (eq. 9; with PMPM weights eq. 14)
        node[GridDof::F + 0] += w * fb[0] - V * (s[0] * gx + s[3] * gy);
        node[GridDof::F + 1] += w * fb[1] - V * (s[3] * gx + s[1] * gy);
        node[GridDof::FEXT + 0] += w * fb[0];
        node[GridDof::FEXT + 1] += w * fb[1];
      }
    }
  }
}

void p2g_traction(const ParticleView &P, const std::vector<PetscInt> &idx, double factor,
                  const GridView &G) {
  Weights<LinearShape> W;
  const double zero[DIM] = {0.0, 0.0};
  for (const PetscInt p : idx) {
    // The face sits at the undeformed offset: PMPM blocks keep their initial size, so this is
    // the face the body's weights see (consistent with eq. 14).
    const double *o = P.tface + p * DIM;
    const double xf[DIM] = {P.x[p * DIM] + o[0], P.x[p * DIM + 1] + o[1]};
    weights<LinearShape>(xf, zero, G.origin, G.h, W);
    const double t[DIM] = {factor * P.traction[p * DIM], factor * P.traction[p * DIM + 1]};
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        double *node = G.node(W.base[0] + a, W.base[1] + b);
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
  constexpr int NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt k = 0; k < nidx; ++k) {
    const PetscInt p = idx[k];
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, G.origin, G.h, W);
    const double vc = P.vol[p] * P.colour[p];
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        double *node = G.node(W.base[0] + a, W.base[1] + b);
        node[GridDof::FEXT + 0] += vc * W.grad[b * NS + a][0];
        node[GridDof::FEXT + 1] += vc * W.grad[b * NS + a][1];
      }
  }
}

void grid_update(const GridView &G, const GridUpdateParams &prm, GridStats &st) {
  const double dt = prm.dt, alpha = prm.damping_alpha;
  for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j) {
    for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
      double *node = G.node(i, j);
      const double m = node[GridDof::M];
      if (m <= 0.0) continue; // empty node: nothing to update (its slots stay zero)
      bool held[DIM];
      held_dofs(i, j, G.ncell, prm.face, held);
      double fext2 = 0.0;
      for (int d = 0; d < DIM; ++d) fext2 += node[GridDof::FEXT + d] * node[GridDof::FEXT + d];
      if (fext2 > 0.0) {
        st.sum_ext += std::sqrt(fext2);
        st.n_ext += 1.0;
      }
      double f2 = 0.0; // |f_int + f_ext|^2 over the free dofs
      for (int d = 0; d < DIM; ++d) {
        double v = node[GridDof::P + d] / m;
        double f = node[GridDof::F + d];
        if (held[d]) {
          node[GridDof::P + d] = 0.0;
          node[GridDof::F + d] = 0.0;
          continue;
        }
        f2 += f * f;
        if (alpha > 0.0 && v != 0.0) f -= alpha * std::fabs(f) * (v > 0.0 ? 1.0 : -1.0);
        const double a = f / m;
        v += dt * a;
        node[GridDof::P + d] = v;
        node[GridDof::F + d] = a;
        st.kinetic += 0.5 * m * v * v;
      }
      st.max_unbalanced = std::fmax(st.max_unbalanced, std::sqrt(f2));
    }
  }
}

template <class Shape>
void g2p_velocity(const ParticleView &P, const GridView &G0, const GridView *G1,
                  const G2PParams &prm) {
  constexpr int NS = Shape::NS;
  const double dt = prm.dt, pic = prm.pic;
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    double *v = P.v + p * DIM;
    const GridView &G = (G1 && P.colour[p] > 0.5) ? *G1 : G0; // interface body field
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, G.origin, G.h, W);
    double vg[DIM] = {0, 0}, ag[DIM] = {0, 0};
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        const double *node = G.node(W.base[0] + a, W.base[1] + b);
        const double w = W.w[b * NS + a];
        for (int d = 0; d < DIM; ++d) {
          vg[d] += w * node[GridDof::P + d];
          ag[d] += w * node[GridDof::F + d];
        }
      }
    // FLIP (eq. 4) with an optional PIC blend
    for (int d = 0; d < DIM; ++d) v[d] = (1.0 - pic) * (v[d] + dt * ag[d]) + pic * vg[d];
  }
}

template <class Shape> void p2g_momentum(const ParticleView &P, const GridView &G) {
  constexpr int NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, G.origin, G.h, W);
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

void grid_velocity(const GridView &G, const FaceBC face[2 * DIM]) {
  for (PetscInt j = G.gs[1]; j < G.gs[1] + G.gm[1]; ++j)
    for (PetscInt i = G.gs[0]; i < G.gs[0] + G.gm[0]; ++i) {
      double *node = G.node(i, j);
      const double m = node[GridDof::M];
      if (m <= 0.0) continue;
      bool held[DIM];
      held_dofs(i, j, G.ncell, face, held);
      for (int d = 0; d < DIM; ++d) node[GridDof::P + d] = held[d] ? 0.0 : node[GridDof::P + d] / m;
    }
}

template <class Shape>
void g2p_kinematics(const ParticleView &P, const GridView &G0, const GridView *G1, const Grid &grid,
                    const G2PParams &prm, const double *wave_modulus, double *dudx, G2PStats &st) {
  const GridView &G = G0;
  constexpr int NS = Shape::NS;
  const double dt = prm.dt;
  const double lo[DIM] = {G.origin[0], G.origin[1]};
  const double hi[DIM] = {G.origin[0] + G.ncell[0] * G.h, G.origin[1] + G.ncell[1] * G.h};
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    double *x = P.x + p * DIM, *v = P.v + p * DIM, *F = P.F + p * DIM * DIM;
    const GridView &Gp = (G1 && P.colour[p] > 0.5) ? *G1 : G0; // interface body field
    weights<Shape>(x, P.lp + p * DIM, G.origin, G.h, W);
    double vg[DIM] = {0, 0}, L[DIM * DIM] = {0, 0, 0, 0};
    for (int b = 0; b < NS; ++b) {
      for (int a = 0; a < NS; ++a) {
        const int k = b * NS + a;
        const double *node = Gp.node(W.base[0] + a, W.base[1] + b);
        const double w = W.w[k], gx = W.grad[k][0], gy = W.grad[k][1];
        const double nvx = node[GridDof::P], nvy = node[GridDof::P + 1];
        vg[0] += w * nvx;
        vg[1] += w * nvy;
        L[0] += nvx * gx; // velocity gradient, eq. 20 with PMPM weights
        L[1] += nvx * gy;
        L[2] += nvy * gx;
        L[3] += nvy * gy;
      }
    }
    for (int d = 0; d < DIM; ++d) x[d] += dt * vg[d]; // eq. 5
    double *du = dudx + p * DIM * DIM;
    for (int q = 0; q < DIM * DIM; ++q) du[q] = L[q] * dt;
    // F <- (I + L dt) F
    const double F0 = F[0], F1 = F[1], F2 = F[2], F3 = F[3];
    F[0] = (1.0 + du[0]) * F0 + du[1] * F2;
    F[1] = (1.0 + du[0]) * F1 + du[1] * F3;
    F[2] = du[2] * F0 + (1.0 + du[3]) * F2;
    F[3] = du[2] * F1 + (1.0 + du[3]) * F3;
    const double J = F[0] * F[3] - F[1] * F[2];
    P.vol[p] = J * P.vol0[p];
    const double speed2 = v[0] * v[0] + v[1] * v[1];
    st.kinetic += 0.5 * P.mass[p] * speed2;
    const double c = std::sqrt(wave_modulus[P.mat[p]] * P.vol[p] / P.mass[p]);
    st.max_speed = std::fmax(st.max_speed, c + std::sqrt(speed2));
    // Instability and escape checks, reported by the caller with the particle's id.
    const char *what = nullptr;
    if (!(J > 0.0) || !std::isfinite(J))
      what = "non-positive or non-finite volume ratio J";
    else if (!std::isfinite(x[0] + x[1] + v[0] + v[1]))
      what = "non-finite position or velocity";
    // The centre must stay on the grid (the ghosted DMDA has room for the support beyond it).
    for (int d = 0; d < DIM && !what; ++d)
      if (!(x[d] >= lo[d] && x[d] < hi[d])) what = "particle left the grid";
    if (what) {
      if (st.bad++ == 0) {
        st.bad_pid = P.pid[p];
        st.bad_x[0] = x[0];
        st.bad_x[1] = x[1];
        st.bad_what = what;
      }
      continue;
    }
    PetscInt c_idx[DIM];
    for (int d = 0; d < DIM; ++d)
      c_idx[d] = static_cast<PetscInt>(std::floor((x[d] - G.origin[d]) / G.h));
    if (!grid.owns_cell(c_idx)) ++st.left_rank;
  }
}

#define PMPM_INSTANTIATE(S)                                                                        \
  template void p2g<S>(const ParticleView &, const Load &, const GridView &, const PetscInt *,     \
                       PetscInt);                                                                  \
  template void p2g_colour_gradient<S>(const ParticleView &, const PetscInt *, PetscInt,           \
                                       const GridView &);                                          \
  template void g2p_velocity<S>(const ParticleView &, const GridView &, const GridView *,          \
                                const G2PParams &);                                                \
  template void p2g_momentum<S>(const ParticleView &, const GridView &);                           \
  template void g2p_kinematics<S>(const ParticleView &, const GridView &, const GridView *,        \
                                  const Grid &, const G2PParams &, const double *, double *,       \
                                  G2PStats &);
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
#undef PMPM_INSTANTIATE

} // namespace pmpm
