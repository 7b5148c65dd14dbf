// The Drucker-Prager return's derivative (materials/drucker_prager.hpp), out of line like
// von_mises_derivative.cpp: its one caller is the consistent tangent, and the return's copy for
// it stays out of drucker_prager.cpp, whose explicit update keeps its own specialised copy.
#include "pmpm/materials/drucker_prager.hpp"

namespace pmpm {

ReturnDerivative drucker_prager_return_derivative(const DruckerPragerParams &prm,
                                                  const DPCoefficients &k, const Mat3 &sigma_tr,
                                                  double eps_p) {
  ReturnDerivative D;
  Mat3 sig = sigma_tr;
  double ep = eps_p;
  const ReturnResult r = drucker_prager_return(prm, k, sig, ep);
  const double G = prm.el.G(), K = prm.el.K(), H = prm.hardening, sq2 = std::sqrt(2.0);
  const double eta = k.eta, xi = k.xi, etabar = k.etabar;
  if (!r.yielded) { // elastic, unless on the cone to round-off (see kOnSurface): dgamma = 0
    const double p_tr = stress_inv::mean(sigma_tr);
    const double q_tr = stress_inv::sqrt_j2(stress_inv::deviator(sigma_tr));
    const double scale = xi * (prm.cohesion + H * eps_p) + std::fabs(eta * p_tr);
    if (!(q_tr > 0.0 && q_tr + eta * p_tr - xi * (prm.cohesion + H * eps_p) >= -kOnSurface * scale))
      return D;
  }
  if (r.apex) {
    const double denom = K * eta * etabar + xi * xi * H;
    const bool clamped = r.tension; // the apex path sets tension only when p was clamped to t
    D.a = 0.0;
    D.e = denom > 0.0 && !clamped ? xi * xi * H / denom : 0.0;
    return D;
  }
  if (r.tension && r.dgamma == 0.0) { // cut-off alone
    D.e = 0.0;
    return D;
  }
  const Mat3 s_tr = stress_inv::deviator(sigma_tr);
  const double norm = s_tr.norm(), q_tr = norm / sq2, q = q_tr - G * r.dgamma;
  D.n = s_tr / norm;
  D.a = q / q_tr;
  if (r.tension) { // corner of the cone and the cut-off: p = t
    const double A = G + xi * xi * H;
    D.b = G * (r.dgamma / q_tr - 1.0 / A);
    D.e = 0.0;
    return D;
  }
  const double A = G + K * eta * etabar + xi * xi * H; // smooth part of the cone
  D.b = G * (r.dgamma / q_tr - 1.0 / A);
  D.c = -sq2 * G * eta / A;
  D.d = -K * etabar / (sq2 * A);
  D.e = 1.0 - K * eta * etabar / A;
  return D;
}

} // namespace pmpm
