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

template <class Shape>
void implicit_gradient(const ParticleView &P, const NodalView &U, const NodalView &mask, double *G,
                       double *up) {
  constexpr int NN = Weights<Shape>::NN, NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, U.origin, U.h, W);
    double g[DIM * DIM] = {0, 0, 0, 0}, v[DIM] = {0, 0};
    for (int k = 0; k < NN; ++k) {
      const PetscInt i = W.base[0] + k % NS, j = W.base[1] + k / NS;
      const double *u = U.node(i, j), *m = mask.node(i, j);
      for (int a = 0; a < DIM; ++a) {
        v[a] += W.w[k] * m[a] * u[a];
        for (int d = 0; d < DIM; ++d) g[a * DIM + d] += m[a] * u[a] * W.grad[k][d];
      }
    }
    for (int q = 0; q < DIM * DIM; ++q) G[p * DIM * DIM + q] = g[q];
    if (up)
      for (int a = 0; a < DIM; ++a) up[p * DIM + a] = v[a];
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

template <class Shape>
void implicit_internal_force(const ParticleView &P, const double *Pk, const NodalView &R) {
  constexpr int NN = Weights<Shape>::NN, NS = Shape::NS;
  Weights<Shape> W;
  for (PetscInt p = 0; p < P.n; ++p) {
    weights<Shape>(P.x + p * DIM, P.lp + p * DIM, R.origin, R.h, W);
    const double V = P.vol[p], *Pm = Pk + p * DIM * DIM;
    for (int k = 0; k < NN; ++k) {
      double *r = R.node(W.base[0] + k % NS, W.base[1] + k / NS);
      for (int a = 0; a < DIM; ++a)
        for (int d = 0; d < DIM; ++d) r[a] += V * Pm[a * DIM + d] * W.grad[k][d];
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

template <class Shape>
void particle_stiffness(const Weights<Shape> &W, double V, const double *A, double *K) {
  constexpr int NN = Weights<Shape>::NN, ND = NN * DIM;
  for (int k = 0; k < NN; ++k)
    for (int a = 0; a < DIM; ++a)
      for (int m = 0; m < NN; ++m)
        for (int b = 0; b < DIM; ++b) {
          double s = 0;
          for (int j = 0; j < DIM; ++j)
            for (int l = 0; l < DIM; ++l)
              s += W.grad[k][j] * A[(a * DIM + j) * DIM * DIM + (b * DIM + l)] * W.grad[m][l];
          K[(k * DIM + a) * ND + (m * DIM + b)] = V * s;
        }
}

template <class Shape>
void add_particle_blocks(const Weights<Shape> &W, const double *K, const NodeBlocks &B) {
  constexpr int NN = Weights<Shape>::NN, NS = Shape::NS, ND = NN * DIM;
  for (int k = 0; k < NN; ++k) {
    const PetscInt i = W.base[0] + k % NS, j = W.base[1] + k / NS;
    for (int m = 0; m < NN; ++m) {
      double *b = B.block(i, j, m % NS - k % NS, m / NS - k / NS);
      for (int a = 0; a < DIM; ++a)
        for (int c = 0; c < DIM; ++c) b[a * DIM + c] += K[(k * DIM + a) * ND + (m * DIM + c)];
    }
  }
}

#define PMPM_INSTANTIATE(S)                                                                        \
  template void implicit_gradient<S>(const ParticleView &, const NodalView &, const NodalView &,   \
                                     double *, double *);                                          \
  template void implicit_internal_force<S>(const ParticleView &, const double *,                   \
                                           const NodalView &);                                     \
  template int reset_internal_force<S>(const ParticleView &, const double *, const double *,       \
                                       const double *, const double *, const double *,             \
                                       const NodalView &);                                         \
  template void particle_reset_stiffness<S>(const Weights<S> &, const double[][3], double,         \
                                            const double *, const double *, double,                \
                                            const double *, double *);                             \
  template void particle_stiffness<S>(const Weights<S> &, double, const double *, double *);       \
  template void add_particle_blocks<S>(const Weights<S> &, const double *, const NodeBlocks &);
PMPM_INSTANTIATE(LinearShape)
PMPM_INSTANTIATE(UGIMPShape)
#undef PMPM_INSTANTIATE

} // namespace pmpm
