// Shared pieces of the closed-form return maps (von Mises, Drucker-Prager).
//
// Conventions (docs/method.md, section 4): Cauchy stress, tension positive, always the full 3x3
// tensor (plane strain keeps sigma_zz, which evolves with plastic flow).
//   p = tr(sigma)/3,  s = sigma - p I,  J2 = s:s/2.
#pragma once
#include "pmpm/util/config.hpp"
#include <cmath>

namespace pmpm {

// Outcome of one return map. yielded: the trial state was outside the elastic domain and was
// modified. apex: returned to the Drucker-Prager apex. tension: the tension cut-off p <= t was
// active (alone or at its corner with the cone). dgamma: plastic multiplier of the yield
// surface (cone / apex / von Mises), 0 on an elastic step.
struct ReturnResult {
  bool yielded = false;
  bool apex = false;
  bool tension = false;
  double dgamma = 0;
};

namespace stress_inv {
inline double mean(const Mat3 &sigma) {
  return sigma.trace() / 3.0;
}
inline Mat3 deviator(const Mat3 &sigma) {
  return sigma - mean(sigma) * Mat3::Identity();
}
// sqrt(J2) of a deviator s: sqrt(s:s/2).
inline double sqrt_j2(const Mat3 &s) {
  return std::sqrt(0.5 * s.squaredNorm());
}
} // namespace stress_inv

// The derivative of a return map with respect to its trial stress (the algorithmic tangent of
// the stress update is this map after the elastic predictor: d sigma = D : d sigma_tr, with
// d sigma_tr = C : de + the Jaumann terms). Every branch of the closed-form returns has the form
//   D : ds = a dev(ds) + b n (n : ds) + c n tr(ds)/3 + d I (n : ds) + e I tr(ds)/3,
// n = s_tr / |s_tr| the unit trial deviator (0 when s_tr = 0). Elastic: a = e = 1.
// A trial stress with Phi_tr >= -kOnSurface x (the yield stress) counts as on the yield surface
// in the derivative (the return leaves it elastic, bit for bit): returned states sit on the
// surface to a few 1e-16 of it.
constexpr double kOnSurface = 1e-10;
struct ReturnDerivative {
  double a = 1, b = 0, c = 0, d = 0, e = 1;
  Mat3 n = Mat3::Zero();
  Mat3 apply(const Mat3 &ds) const {
    const Mat3 I = Mat3::Identity();
    const double pt = ds.trace() / 3.0, nd = (n.array() * ds.array()).sum();
    return a * (ds - pt * I) + (b * nd + c * pt) * n + (d * nd + e * pt) * I;
  }
};

} // namespace pmpm
