#include "pmpm/solvers/implicit_kernels.hpp"
#include "pmpm/materials/tangent.hpp"
#include <cmath>

namespace pmpm {

namespace {
// V^n J sigma' of the reset grid's force (implicit_kernels.hpp), J = det(I + G)
inline MatN current_stress_volume(double V, const double *G, const double *stress) {
  return V * (MatN::Identity() + mat_of(G)).determinant() * in_plane(stress);
}
} // namespace

template <class Shape, int D>
void implicit_gradient(const ParticleView &P, const NodalViewT<D> &U, const NodalViewT<D> &mask,
                       double *G, double *up) {
  constexpr int NN = Weights<Shape, D>::NN;
  Weights<Shape, D> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape, D>(P.x + p * D, P.lp + p * D, U.origin, U.h, W);
    double g[D * D] = {}, v[D] = {};
    for (int k = 0; k < NN; ++k) {
      const double *u = U.node(W, k), *m = mask.node(W, k);
      for (int a = 0; a < D; ++a) {
        v[a] += W.w[k] * m[a] * u[a];
        for (int d = 0; d < D; ++d) g[a * D + d] += m[a] * u[a] * W.grad[k][d];
      }
    }
    for (int q = 0; q < D * D; ++q) G[p * D * D + q] = g[q];
    if (up)
      for (int a = 0; a < D; ++a) up[p * D + a] = v[a];
  }
}

template <int D>
void implicit_deformation(PetscInt n, const double *G, const double *F, double *Fnew) {
  using M = MatD<D>;
  for (PetscInt p = 0; p < n; ++p) {
    const M f = M::Identity() + mat_of<D>(G + p * D * D);
    const M Fn = f * mat_of<D>(F + p * D * D);
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) Fnew[p * D * D + a * D + b] = Fn(a, b);
  }
}

template <int D> void implicit_midpoint_gradient(PetscInt n, const double *G, double *Gm) {
  using M = MatD<D>;
  for (PetscInt p = 0; p < n; ++p) {
    const M g = mat_of<D>(G + p * D * D);
    const M gm = (M::Identity() + 0.5 * g).inverse() * g;
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) Gm[p * D * D + a * D + b] = gm(a, b);
  }
}

template <int D>
void implicit_piola(PetscInt n, const double *G, const double *stress, double *Pk) {
  using M = MatD<D>;
  for (PetscInt p = 0; p < n; ++p) {
    const M f = M::Identity() + mat_of<D>(G + p * D * D);
    const M Pm = f.determinant() * in_plane<D>(stress + p * NStress<D>) * f.inverse().transpose();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) Pk[p * D * D + a * D + b] = Pm(a, b);
  }
}

template void implicit_deformation<2>(PetscInt, const double *, const double *, double *);
template void implicit_deformation<3>(PetscInt, const double *, const double *, double *);
template void implicit_midpoint_gradient<2>(PetscInt, const double *, double *);
template void implicit_midpoint_gradient<3>(PetscInt, const double *, double *);
template void implicit_piola<2>(PetscInt, const double *, const double *, double *);
template void implicit_piola<3>(PetscInt, const double *, const double *, double *);

template <class Shape, int D>
void implicit_internal_force(const ParticleView &P, const double *Pk, const NodalViewT<D> &R) {
  constexpr int NN = Weights<Shape, D>::NN;
  Weights<Shape, D> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape, D>(P.x + p * D, P.lp + p * D, R.origin, R.h, W);
    const double V = P.vol[p], *Pm = Pk + p * D * D;
    for (int k = 0; k < NN; ++k) {
      double *r = R.node(W, k);
      for (int a = 0; a < D; ++a)
        for (int d = 0; d < D; ++d) r[a] += V * Pm[a * D + d] * W.grad[k][d];
    }
  }
}

template <class Shape>
int reset_internal_force(const ParticleView &P, const double *G, const double *stress,
                         const double *Pk, const double *u, const double gw[DIM],
                         const NodalView &R) {
  constexpr int NN = Weights<Shape>::NN, NS = Shape::NS;
  Weights<Shape> W0, W;
  int outside = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    const double V = P.vol[p];
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, R.origin, R.h, W0);
    const double xt[DIM] = {P.x[p * DIM] + u[p * DIM], P.x[p * DIM + 1] + u[p * DIM + 1]};
    weights<Shape>(xt, P.lp + p * DIM, R.origin, R.h, W);
    bool in = true;
    for (int d = 0; d < DIM; ++d)
      in = in && W.base[d] >= R.gs[d] && W.base[d] + NS <= R.gs[d] + R.gm[d];
    if (!in) {
      ++outside;
      const double *Pm = Pk + p * DIM * DIM;
      for (int k = 0; k < NN; ++k) {
        double *r = R.node(W0.base[0] + k % NS, W0.base[1] + k / NS);
        for (int a = 0; a < DIM; ++a)
          for (int d = 0; d < DIM; ++d) r[a] += V * Pm[a * DIM + d] * W0.grad[k][d];
      }
      continue;
    }
    const MatN s = current_stress_volume(V, G + p * DIM * DIM, stress + p * NSTRESS);
    const double wg[DIM] = {P.weight[p] * gw[0], P.weight[p] * gw[1]};
    for (int k = 0; k < NN; ++k) {
      double *r = R.node(W.base[0] + k % NS, W.base[1] + k / NS);
      for (int a = 0; a < DIM; ++a)
        r[a] += s(a, 0) * W.grad[k][0] + s(a, 1) * W.grad[k][1] - wg[a] * W.w[k];
      double *r0 = R.node(W0.base[0] + k % NS, W0.base[1] + k / NS);
      for (int a = 0; a < DIM; ++a) r0[a] += wg[a] * W0.w[k];
    }
  }
  return outside;
}

template <class Shape>
void particle_reset_stiffness(const Weights<Shape> &W, const double H[][3], double V,
                              const double *G, const double *stress, double weight,
                              const double gw[DIM], double *K) {
  constexpr int NN = Weights<Shape>::NN, ND = NN * DIM;
  const MatN Vs = current_stress_volume(V, G, stress);
  const double wg[DIM] = {weight * gw[0], weight * gw[1]};
  for (int k = 0; k < NN; ++k) {
    const double Hk[DIM][DIM] = {{H[k][0], H[k][1]}, {H[k][1], H[k][2]}};
    for (int a = 0; a < DIM; ++a)
      for (int m = 0; m < NN; ++m)
        for (int c = 0; c < DIM; ++c) {
          double v = -wg[a] * W.grad[k][c] * W.w[m];
          for (int b = 0; b < DIM; ++b)
            v += Vs(a, b) * (Hk[b][c] * W.w[m] + W.grad[k][c] * W.grad[m][b]);
          K[(k * DIM + a) * ND + (m * DIM + c)] += v;
        }
  }
}

template <class Shape, int D>
void particle_stiffness(const Weights<Shape, D> &W, double V, const double *A, double *K) {
  constexpr int NN = Weights<Shape, D>::NN, ND = NN * D;
  for (int k = 0; k < NN; ++k)
    for (int a = 0; a < D; ++a)
      for (int m = 0; m < NN; ++m)
        for (int b = 0; b < D; ++b) {
          double s = 0;
          for (int j = 0; j < D; ++j)
            for (int l = 0; l < D; ++l)
              s += W.grad[k][j] * A[(a * D + j) * D * D + (b * D + l)] * W.grad[m][l];
          K[(k * D + a) * ND + (m * D + b)] = V * s;
        }
}

template <class Shape, int D>
void add_particle_blocks(const Weights<Shape, D> &W, const double *K, const NodeBlocksT<D> &B) {
  constexpr int NN = Weights<Shape, D>::NN, NS = Shape::NS, ND = NN * D;
  for (int k = 0; k < NN; ++k) {
    for (int m = 0; m < NN; ++m) {
      double *b;
      if constexpr (D == 2) {
        b = B.block(W.base[0] + k % NS, W.base[1] + k / NS, m % NS - k % NS, m / NS - k / NS);
      } else {
        const int ki = k % NS, kj = (k / NS) % NS, kk = k / (NS * NS);
        const int mi = m % NS, mj = (m / NS) % NS, mk = m / (NS * NS);
        b = B.block(W.base[0] + ki, W.base[1] + kj, W.base[2] + kk, mi - ki, mj - kj, mk - kk);
      }
      for (int a = 0; a < D; ++a)
        for (int c = 0; c < D; ++c) b[a * D + c] += K[(k * D + a) * ND + (m * D + c)];
    }
  }
}

#define PMPM_INSTANTIATE_D(S, D)                                                                   \
  template void implicit_gradient<S, D>(const ParticleView &, const NodalViewT<D> &,               \
                                        const NodalViewT<D> &, double *, double *);                \
  template void implicit_internal_force<S, D>(const ParticleView &, const double *,                \
                                              const NodalViewT<D> &);                              \
  template void particle_stiffness<S, D>(const Weights<S, D> &, double, const double *, double *); \
  template void add_particle_blocks<S, D>(const Weights<S, D> &, const double *,                   \
                                          const NodeBlocksT<D> &);
#define PMPM_INSTANTIATE(S)                                                                        \
  PMPM_INSTANTIATE_D(S, 2)                                                                         \
  PMPM_INSTANTIATE_D(S, 3)                                                                         \
  template int reset_internal_force<S>(const ParticleView &, const double *, const double *,       \
                                       const double *, const double *, const double *,             \
                                       const NodalView &);                                         \
  template void particle_reset_stiffness<S>(const Weights<S> &, const double[][3], double,         \
                                            const double *, const double *, double,                \
                                            const double *, double *);
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
#undef PMPM_INSTANTIATE
#undef PMPM_INSTANTIATE_D

} // namespace pmpm
