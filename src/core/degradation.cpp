// Waste degradation: the eigenstrain increment per particle (degradation.hpp).
#include "pmpm/core/degradation.hpp"
#include <algorithm>
#include <cmath>

namespace pmpm {

namespace {
// The plan factor a distance d > 0 beyond the zone: linear to 0 over the taper (none: 0).
double taper_factor(const Shrinkage &s, double d) {
  return s.taper > 0 ? std::max(0.0, 1 - d / s.taper) : 0.0;
}
// The grade at height y inside [y_lo, y_hi], times the plan factor g: linear from the base's
// factor to the top's.
double graded(const Shrinkage &s, double y, double g) {
  const double span = s.y_hi - s.y_lo;
  const double r = span > 0 && std::isfinite(span) ? (y - s.y_lo) / span : 0.5;
  return g * (s.grade_bottom + r * (s.grade_top - s.grade_bottom));
}
} // namespace

double shrinkage_grade(const Shrinkage &s, const double X[DIM]) {
  const double x = X[0], y = X[1];
  if (y < s.y_lo || y > s.y_hi) return 0;
  double gx = 1;
  if (x < s.x_lo) gx = taper_factor(s, s.x_lo - x);
  if (x > s.x_hi) gx = taper_factor(s, x - s.x_hi);
  return graded(s, y, gx);
}

double shrinkage_grade3(const Shrinkage &s, const double X[3]) {
  if (!(s.radius > 0)) return shrinkage_grade(s, X);
  const double y = X[1];
  if (y < s.y_lo || y > s.y_hi) return 0;
  const double r = std::hypot(X[0] - s.cx, X[2] - s.cz);
  return graded(s, y, r > s.radius ? taper_factor(s, r - s.radius) : 1.0);
}

template <int D>
double shrinkage_increment(const ParticleView &P, const Shrinkage &s, double amount,
                           std::vector<double> &eigen) {
  constexpr int NS = NStress<D>; // xx yy zz first in both layouts
  eigen.assign(static_cast<size_t>(P.n) * 3, 0.0);
  double power = 0;
  for (PetscInt p = 0; p < P.n; ++p) {
    if (!s.degrades[P.mat[p]]) continue;
    const double ev = amount * (D == 3 ? shrinkage_grade3(s, P.x0 + p * D)
                                       : shrinkage_grade(s, P.x0 + p * D)); // the initial point
    if (ev == 0) continue;
    double *e = &eigen[3 * p];
    if (s.mode == ShrinkMode::Vertical) {
      e[1] = -ev;
    } else {
      e[0] = e[1] = e[2] = -ev / 3;
    }
    const double *sg = P.stress + p * NS;
    power -= P.vol[p] * (sg[0] * e[0] + sg[1] * e[1] + sg[2] * e[2]);
  }
  return power;
}
template double shrinkage_increment<2>(const ParticleView &, const Shrinkage &, double,
                                       std::vector<double> &);
template double shrinkage_increment<3>(const ParticleView &, const Shrinkage &, double,
                                       std::vector<double> &);

} // namespace pmpm
