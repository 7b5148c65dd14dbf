#include "pmpm/solvers/implicit_kernels.hpp"
#include "pmpm/materials/tangent.hpp"
#include <cmath>

namespace pmpm {

namespace {
// V^n J sigma' of the reset grid's force (implicit_kernels.hpp), J = det(I + G)
template <int D>
inline MatD<D> current_stress_volume(double V, const double *G, const double *stress) {
  return V * (MatD<D>::Identity() + mat_of<D>(G)).determinant() * in_plane<D>(stress);
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

template <class Shape, int D>
int reset_internal_force(const ParticleView &P, const double *G, const double *stress,
                         const double *Pk, const double *u, const double *gw,
                         const NodalViewT<D> &R) {
  constexpr int NN = Weights<Shape, D>::NN, NS = Shape::NS;
  Weights<Shape, D> W0, W;
  int outside = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    const double V = P.vol[p];
    weights<Shape, D>(P.x + p * D, P.lp + p * D, R.origin, R.h, W0);
    double xt[D];
    for (int d = 0; d < D; ++d) xt[d] = P.x[p * D + d] + u[p * D + d];
    weights<Shape, D>(xt, P.lp + p * D, R.origin, R.h, W);
    bool in = true;
    for (int d = 0; d < D; ++d)
      in = in && W.base[d] >= R.gs[d] && W.base[d] + NS <= R.gs[d] + R.gm[d];
    if (!in) {
      ++outside;
      const double *Pm = Pk + p * D * D;
      for (int k = 0; k < NN; ++k) {
        double *r = R.node(W0, k);
        for (int a = 0; a < D; ++a)
          for (int d = 0; d < D; ++d) r[a] += V * Pm[a * D + d] * W0.grad[k][d];
      }
      continue;
    }
    const MatD<D> s = current_stress_volume<D>(V, G + p * D * D, stress + p * NStress<D>);
    double wg[D];
    for (int d = 0; d < D; ++d) wg[d] = P.weight[p] * gw[d];
    for (int k = 0; k < NN; ++k) {
      double *r = R.node(W, k);
      for (int a = 0; a < D; ++a) {
        if constexpr (D == 2) {
          r[a] += s(a, 0) * W.grad[k][0] + s(a, 1) * W.grad[k][1] - wg[a] * W.w[k];
        } else {
          r[a] += s(a, 0) * W.grad[k][0] + s(a, 1) * W.grad[k][1] + s(a, 2) * W.grad[k][2] -
                  wg[a] * W.w[k];
        }
      }
      double *r0 = R.node(W0, k);
      for (int a = 0; a < D; ++a) r0[a] += wg[a] * W0.w[k];
    }
  }
  return outside;
}

template <class Shape, int D>
void particle_reset_stiffness(const Weights<Shape, D> &W, const double H[][NHess<D>], double V,
                              const double *G, const double *stress, double weight,
                              const double *gw, double *K) {
  constexpr int NN = Weights<Shape, D>::NN, ND = NN * D;
  const MatD<D> Vs = current_stress_volume<D>(V, G, stress);
  double wg[D];
  for (int d = 0; d < D; ++d) wg[d] = weight * gw[d];
  for (int k = 0; k < NN; ++k) {
    double Hk[D][D];
    for (int b = 0; b < D; ++b)
      for (int c = 0; c < D; ++c) Hk[b][c] = H[k][hessian_index<D>(b, c)];
    for (int a = 0; a < D; ++a)
      for (int m = 0; m < NN; ++m)
        for (int c = 0; c < D; ++c) {
          double v = -wg[a] * W.grad[k][c] * W.w[m];
          for (int b = 0; b < D; ++b)
            v += Vs(a, b) * (Hk[b][c] * W.w[m] + W.grad[k][c] * W.grad[m][b]);
          K[(k * D + a) * ND + (m * D + c)] += v;
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
  template int reset_internal_force<S, D>(const ParticleView &, const double *, const double *,    \
                                          const double *, const double *, const double *,          \
                                          const NodalViewT<D> &);                                  \
  template void particle_reset_stiffness<S, D>(const Weights<S, D> &, const double[][NHess<D>],    \
                                               double, const double *, const double *, double,     \
                                               const double *, double *);                          \
  template void particle_stiffness<S, D>(const Weights<S, D> &, double, const double *, double *); \
  template void add_particle_blocks<S, D>(const Weights<S, D> &, const double *,                   \
                                          const NodeBlocksT<D> &);
#define PMPM_INSTANTIATE(S)                                                                        \
  PMPM_INSTANTIATE_D(S, 2)                                                                         \
  PMPM_INSTANTIATE_D(S, 3)
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
#undef PMPM_INSTANTIATE
#undef PMPM_INSTANTIATE_D

} // namespace pmpm
