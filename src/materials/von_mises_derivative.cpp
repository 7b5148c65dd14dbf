// The von Mises return's derivative (materials/von_mises.hpp), out of line: its one caller is
// the consistent tangent (VonMises::piola_tangent), and the return is inlined into it alone,
// apart from von_mises.cpp's explicit update.
#include "pmpm/materials/von_mises.hpp"

namespace pmpm {

ReturnDerivative von_mises_return_derivative(const VonMisesParams &prm, const Mat3 &sigma_tr,
                                             double eps_p) {
  ReturnDerivative D;
  Mat3 s = sigma_tr;
  const ReturnResult r = von_mises_return(prm, s, eps_p);
  const double G = prm.el.G();
  const Mat3 s_tr = stress_inv::deviator(sigma_tr);
  const double norm = s_tr.norm(), q_tr = std::sqrt(1.5) * norm;
  if (!r.yielded) { // elastic, unless on the yield surface to round-off (see kOnSurface)
    const double sy = prm.sigma_y0 + prm.hardening * eps_p;
    if (!(q_tr > 0.0 && q_tr - sy >= -kOnSurface * sy)) return D;
  }
  D.n = s_tr / norm;
  D.a = 1.0 - 3.0 * G * r.dgamma / q_tr;
  D.b = -3.0 * G * (1.0 / (3.0 * G + prm.hardening) - r.dgamma / q_tr);
  return D;
}

} // namespace pmpm
