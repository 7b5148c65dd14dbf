// Cover soil on a geomembrane on a slope (veneer stability), docs/method.md, section 6.3: the
// infinite-slope factor of safety and Koerner and Soong's (1998) two-wedge factor of safety for a
// finite slope with a passive toe wedge (cohesion and adhesion zero). Limit-equilibrium estimates,
// reported beside the simulation. Plain functions, header-only; angles in radians.
#pragma once
#include <cmath>

namespace pmpm {
namespace veneer {

// tan(delta) / tan(beta): the cover slides on the sheet when below 1.
inline double fs_infinite(double beta, double delta) {
  return std::tan(delta) / std::tan(beta);
}

// Acceleration of a sliding infinite veneer (m/s^2, along the slope; 0 when it holds).
inline double acceleration(double beta, double delta, double g = 9.81) {
  return std::fmax(0.0, g * (std::sin(beta) - std::tan(delta) * std::cos(beta)));
}

// Koerner-Soong FS: unit weight gamma (N/m^3), cover thickness h perpendicular to the slope (m),
// slope length L along the slope (m), slope angle beta, soil friction phi, interface friction
// delta. NaN when the slope is too short for the wedge geometry (W_A <= 0).
inline double fs_koerner_soong(double gamma, double h, double L, double beta, double phi,
                               double delta) {
  const double sb = std::sin(beta), cb = std::cos(beta), tp = std::tan(phi), td = std::tan(delta);
  const double WA = gamma * h * h * (L / h - 1.0 / sb - std::tan(beta) / 2.0);
  if (!(WA > 0)) return std::nan("");
  const double NA = WA * cb, WP = gamma * h * h / std::sin(2.0 * beta);
  const double a = (WA - NA * cb) * cb;
  const double b = -((WA - NA * cb) * sb * tp + NA * td * sb * cb + WP * tp * sb);
  const double c = NA * td * sb * sb * tp;
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

} // namespace veneer
} // namespace pmpm
