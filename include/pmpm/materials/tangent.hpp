// What the material laws' consistent tangents (Material::piola_tangent, piola_tangent3) share: the
// step's kinematics at one particle and the loop over the D^2 unit directions dG = e_b (x) e_l,
// in 2D (plane strain, D = 2) and 3D (D = 3).
//
// With f = I + G, J = det f, dJ = J tr(f^-1 dG), d(f^-T) = -f^-T dG^T f^-T, each law gives the
// directional derivative dP[dG] of P = J sigma' f^-T:
//   rate-form laws (sigma' from the Jaumann update with the midpoint gradient Gm = H^-1 G,
//   H = I + G/2, dGm = H^-1 dG H^-1):
//                    dP = J (tr(f^-1 dG) s' + ds' - s' f^-T dG^T) f^-T   (rate_form_dP)
//     linear elastic: ds' = dW s - s dW + lambda tr(dGm) I + 2 mu sym(dGm), dW = skew(dGm)
//     plastic (von Mises, Drucker-Prager): s' = return(s_tr), s_tr = s + W s - s W +
//       C : (sym(Gm) - e*) (3 x 3: sigma_zz is part of the trial state and of the return), so
//       ds' = D : ds_tr with D the return's derivative at s_tr (ReturnDerivative),
//       ds_tr = dW s - s dW + C : sym(dGm)   (plastic_piola_tangent)
//   neo-Hookean:     P = tau f^-T / J^n, tau = mu (B - I) + lambda ln(J_tot) I, F_tot = f F^n
//                    dtau = mu (dF F_tot^T + F_tot dF^T) + lambda tr(f^-1 dG) I, dF = dG F^n
//                    dP = (dtau - tau f^-T dG^T) f^-T / J^n
#pragma once
#include "pmpm/materials/material.hpp"
#include "pmpm/materials/return_map.hpp"

namespace pmpm {

// A D x D matrix (Eigen, fixed size): MatN in 2D, Mat3 in 3D.
template <int D> using MatD = Eigen::Matrix<double, D, D>;

template <int D = DIM> inline MatD<D> mat_of(const double *a) { // row-major D x D
  MatD<D> m;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) m(i, j) = a[i * D + j];
  return m;
}
// The Cauchy stress's D x D block: in 2D (xx yy zz xy) the in-plane 2x2 (zz does not enter P),
// in 3D (xx yy zz xy yz xz) the whole tensor.
template <int D = DIM> inline MatD<D> in_plane(const double *s) {
  return stress_to_tensor<D>(s).template topLeftCorner<D, D>();
}

// One particle's kinematics at a TangentPoint (G, F: D x D row-major; stresses NStress<D>).
template <int D> struct TangentKinematicsT {
  using M = MatD<D>;
  M I, f, fi, fiT;  // f = I + G, its inverse and inverse transpose
  M Hi;             // (I + G/2)^-1: dGm = Hi dG Hi
  double gm[D * D]; // the midpoint gradient Gm = Hi G, row-major
  double J;         // det f
  M sn, so;         // the stresses' D x D blocks: s_new and s_old
  explicit TangentKinematicsT(const TangentPoint &pt) {
    I = M::Identity();
    f = I + mat_of<D>(pt.G);
    fi = f.inverse();
    fiT = fi.transpose();
    Hi = (I + 0.5 * mat_of<D>(pt.G)).inverse();
    const M Gm = Hi * mat_of<D>(pt.G);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) gm[i * D + j] = Gm(i, j);
    J = f.determinant();
    sn = in_plane<D>(pt.s_new);
    so = in_plane<D>(pt.s_old);
  }
  // tr(f^-1 dG): the relative volume change dJ / J along dG
  double dtr(const M &dG) const { return (fi * dG).trace(); }
  // the rate-form laws' dP given the stress derivative ds along dG (above)
  M rate_form_dP(const M &dG, const M &ds) const {
    return J * (dtr(dG) * sn + ds - sn * fiT * dG.transpose()) * fiT;
  }
};

// A[(a D + j) D^2 + (b D + l)] = dP(e_b (x) e_l)_aj, dP(dG) a law's directional derivative.
template <int D = DIM, class DP> inline void piola_directions(DP &&dP, double *A) {
  for (int b = 0; b < D; ++b)
    for (int l = 0; l < D; ++l) {
      MatD<D> dG = MatD<D>::Zero();
      dG(b, l) = 1.0;
      const MatD<D> d = dP(dG);
      for (int a = 0; a < D; ++a)
        for (int j = 0; j < D; ++j) A[(a * D + j) * D * D + (b * D + l)] = d(a, j);
    }
}

// The rate-form plastic laws (von Mises, Drucker-Prager): the trial stress exactly as
// predictor_corrector forms it at the point (Jaumann-rotated s_old + C : (sym(Gm) - e*)).
template <int D>
Mat3 trial_stress(const ElasticConstants &el, const TangentKinematicsT<D> &k,
                  const TangentPoint &pt);
// Their tangent, R the return's derivative at trial_stress (above).
template <int D>
void plastic_piola_tangent(const ElasticConstants &el, const TangentKinematicsT<D> &k,
                           const TangentPoint &pt, const ReturnDerivative &R, double *A);

} // namespace pmpm
