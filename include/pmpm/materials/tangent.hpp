// What the material laws' consistent tangents (Material::piola_tangent) share: the step's
// kinematics at one particle and the loop over the DIM^2 unit directions dG = e_b (x) e_l.
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

// One particle's kinematics at a TangentPoint.
struct TangentKinematics {
  MatN I, f, fi, fiT;   // f = I + G, its inverse and inverse transpose
  MatN Hi;              // (I + G/2)^-1: dGm = Hi dG Hi
  double gm[DIM * DIM]; // the midpoint gradient Gm = Hi G, row-major
  double J;             // det f
  MatN sn, so;          // in-plane s_new and s_old
  explicit TangentKinematics(const TangentPoint &pt) {
    I = MatN::Identity();
    f = I + mat_of(pt.G);
    fi = f.inverse();
    fiT = fi.transpose();
    Hi = (I + 0.5 * mat_of(pt.G)).inverse();
    const MatN Gm = Hi * mat_of(pt.G);
    gm[0] = Gm(0, 0);
    gm[1] = Gm(0, 1);
    gm[2] = Gm(1, 0);
    gm[3] = Gm(1, 1);
    J = f.determinant();
    sn = in_plane(pt.s_new);
    so = in_plane(pt.s_old);
  }
  // tr(f^-1 dG): the relative volume change dJ / J along dG
  double dtr(const MatN &dG) const { return (fi * dG).trace(); }
  // the rate-form laws' dP given the stress derivative ds along dG (above)
  MatN rate_form_dP(const MatN &dG, const MatN &ds) const {
    return J * (dtr(dG) * sn + ds - sn * fiT * dG.transpose()) * fiT;
  }
};

// A[(a DIM + j) DIM^2 + (b DIM + l)] = dP(e_b (x) e_l)_aj, dP(dG) a law's directional derivative.
template <class DP> inline void piola_directions(DP &&dP, double *A) {
  for (int b = 0; b < DIM; ++b)
    for (int l = 0; l < DIM; ++l) {
      MatN dG = MatN::Zero();
      dG(b, l) = 1.0;
      const MatN d = dP(dG);
      for (int a = 0; a < DIM; ++a)
        for (int j = 0; j < DIM; ++j) A[(a * DIM + j) * DIM * DIM + (b * DIM + l)] = d(a, j);
    }
}

// The rate-form plastic laws (von Mises, Drucker-Prager): the trial stress exactly as
// predictor_corrector forms it at the point (Jaumann-rotated s_old + C : (sym(Gm) - e*)).
Mat3 trial_stress(const ElasticConstants &el, const TangentKinematics &k, const TangentPoint &pt);
// Their tangent, D the return's derivative at trial_stress (above).
void plastic_piola_tangent(const ElasticConstants &el, const TangentKinematics &k,
                           const TangentPoint &pt, const ReturnDerivative &D, double *A);

} // namespace pmpm
