#include "pmpm/implicit_kernels.hpp"
#include <cmath>

namespace pmpm {

namespace {
inline MatN mat_of(const double *a) {
  MatN m;
  m << a[0], a[1], a[2], a[3];
  return m;
}
inline MatN in_plane(const double *s) { // Cauchy stress xx yy zz xy -> in-plane 2x2
  MatN m;
  m << s[0], s[3], s[3], s[1];
  return m;
}
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

void implicit_deformation(PetscInt n, const double *G, const double *F, double *Fnew) {
  for (PetscInt p = 0; p < n; ++p) {
    const MatN f = MatN::Identity() + mat_of(G + p * DIM * DIM);
    const MatN Fn = f * mat_of(F + p * DIM * DIM);
    for (int a = 0; a < DIM; ++a)
      for (int b = 0; b < DIM; ++b) Fnew[p * DIM * DIM + a * DIM + b] = Fn(a, b);
  }
}

void implicit_midpoint_gradient(PetscInt n, const double *G, double *Gm) {
  for (PetscInt p = 0; p < n; ++p) {
    const MatN g = mat_of(G + p * DIM * DIM);
    const MatN gm = (MatN::Identity() + 0.5 * g).inverse() * g;
    for (int a = 0; a < DIM; ++a)
      for (int b = 0; b < DIM; ++b) Gm[p * DIM * DIM + a * DIM + b] = gm(a, b);
  }
}

void implicit_piola(PetscInt n, const double *G, const double *stress, double *Pk) {
  for (PetscInt p = 0; p < n; ++p) {
    const MatN f = MatN::Identity() + mat_of(G + p * DIM * DIM);
    const MatN Pm = f.determinant() * in_plane(stress + p * NSTRESS) * f.inverse().transpose();
    for (int a = 0; a < DIM; ++a)
      for (int b = 0; b < DIM; ++b) Pk[p * DIM * DIM + a * DIM + b] = Pm(a, b);
  }
}

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

// Directional derivatives dP[dG] for the DIM^2 unit directions dG = e_b (x) e_l, with
// f = I + G, J = det f, dJ = J tr(f^-1 dG), d(f^-T) = -f^-T dG^T f^-T:
//   linear elastic:  P = J s' f^-T, ds' = dW s - s dW + lambda tr(dG) I + 2 mu sym(dG),
//                    dW = skew(dG) (the Jaumann update is linear in G; s the committed stress)
//                    dP = J (tr(f^-1 dG) s' + ds' - s' f^-T dG^T) f^-T
//   plastic (von Mises, Drucker-Prager): s' = return(s_tr), s_tr = s + W s - s W + C : (sym(G) -
//   e*)
//                    (3 x 3: sigma_zz is part of the trial state and of the return), so
//                    ds' = D : ds_tr with D the return's derivative at s_tr (ReturnDerivative),
//                    ds_tr = dW s - s dW + lambda tr(dG) I + 2 mu sym(dG); dP as above
//   neo-Hookean:     P = tau f^-T / J^n, tau = mu (B - I) + lambda ln(J_tot) I, F_tot = f F^n
//                    dtau = mu (dF F_tot^T + F_tot dF^T) + lambda tr(f^-1 dG) I, dF = dG F^n
//                    dP = (dtau - tau f^-T dG^T) f^-T / J^n
void piola_tangent(const TangentModel &tm, const double *G, const double *s_old,
                   const double *s_new, const double *Fn, double eps_p, double *A,
                   const double *eigen) {
  const TangentKind kind = tm.kind;
  const ElasticConstants &el = tm.el;
  const MatN I = MatN::Identity();
  const MatN f = I + mat_of(G), fi = f.inverse(), fiT = fi.transpose();
  // the rate-form update reads the midpoint gradient Gm = (I + G/2)^-1 G, dGm = Hi dG Hi
  const MatN Hi = (I + 0.5 * mat_of(G)).inverse(), Gm = Hi * mat_of(G);
  const double gm[DIM * DIM] = {Gm(0, 0), Gm(0, 1), Gm(1, 0), Gm(1, 1)};
  const double J = f.determinant(), lam = el.lambda(), mu = el.G();
  const MatN sn = in_plane(s_new), so = in_plane(s_old);
  const MatN Fo = mat_of(Fn), Ft = f * Fo;
  const double Jn = Fo.determinant();
  const MatN tau = mu * (Ft * Ft.transpose() - I) + lam * std::log(Ft.determinant()) * I;
  const bool plastic = kind == TangentKind::VonMises || kind == TangentKind::DruckerPrager;
  ReturnDerivative D;
  Mat3 so3 = Mat3::Zero();
  if (plastic) { // the trial stress exactly as predictor_corrector forms it
    so3 = stress_to_tensor(s_old);
    Mat3 de, dw;
    strain_and_spin(gm, de, dw);
    if (eigen)
      for (int d = 0; d < 3; ++d) de(d, d) -= eigen[d];
    const Mat3 s_tr = jaumann_rotate(so3, dw) + elastic_increment(el, de);
    D = kind == TangentKind::VonMises
            ? von_mises_return_derivative(tm.vm, s_tr, eps_p)
            : drucker_prager_return_derivative(tm.dp, tm.dpk, s_tr, eps_p);
  }
  for (int b = 0; b < DIM; ++b)
    for (int l = 0; l < DIM; ++l) {
      MatN dG = MatN::Zero();
      dG(b, l) = 1.0;
      const double dtr = (fi * dG).trace();
      MatN dP;
      if (kind == TangentKind::NeoHookean) {
        const MatN dF = dG * Fo;
        const MatN dtau = mu * (dF * Ft.transpose() + Ft * dF.transpose()) + lam * dtr * I;
        dP = (dtau - tau * fiT * dG.transpose()) * fiT / Jn;
      } else if (plastic) {
        const MatN dGm = Hi * dG * Hi;
        const double g[DIM * DIM] = {dGm(0, 0), dGm(0, 1), dGm(1, 0), dGm(1, 1)};
        Mat3 de, dw;
        strain_and_spin(g, de, dw);
        const Mat3 ds3 = D.apply(dw * so3 - so3 * dw + elastic_increment(el, de));
        MatN ds;
        ds << ds3(0, 0), ds3(0, 1), ds3(1, 0), ds3(1, 1);
        dP = J * (dtr * sn + ds - sn * fiT * dG.transpose()) * fiT;
      } else {
        const MatN dGm = Hi * dG * Hi;
        const MatN dW = 0.5 * (dGm - dGm.transpose()), de = 0.5 * (dGm + dGm.transpose());
        const MatN ds = dW * so - so * dW + lam * dGm.trace() * I + 2.0 * mu * de;
        dP = J * (dtr * sn + ds - sn * fiT * dG.transpose()) * fiT;
      }
      for (int a = 0; a < DIM; ++a)
        for (int j = 0; j < DIM; ++j) A[(a * DIM + j) * DIM * DIM + (b * DIM + l)] = dP(a, j);
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
