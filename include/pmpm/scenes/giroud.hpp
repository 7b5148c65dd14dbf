// Closed-form geomembrane-over-void solution: Terzaghi trapdoor arching in the cover soil plus a
// tensioned membrane spanning the void (Giroud, Bonaparte, Beech & Gross 1990, "Design of
// soil layer-geosynthetic systems overlying voids", Geotextiles and Geomembranes 9:11-50).
// This is the analytical solution the seed paper compares against in section 4, eqs. (21)-(24).
// See docs/method.md, section 1.3 (corrected sign of eq. 21).
//
// Geometry: a long (plane-strain) void of width b under a membrane of thickness t, covered by
// soil of height H and unit weight gamma, with surface load q. The membrane over the void is a
// circular arc with chord b and sag y at mid-span; outside the void it does not move.
// SI units throughout (m, N/m^3, Pa); strains are fractions, not per cent.
//
// Plain functions, header-only, no PETSc. Invalid arguments throw std::invalid_argument.
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>

namespace pmpm {
namespace giroud {

constexpr double pi = 3.14159265358979323846;

namespace detail {
inline void require_positive(double v, const char *what) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw std::invalid_argument(std::string("pmpm::giroud: ") + what + " must be positive");
}
inline void require_nonnegative(double v, const char *what) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw std::invalid_argument(std::string("pmpm::giroud: ") + what + " must be >= 0");
}
} // namespace detail

// Pressure on the membrane over the void from Terzaghi trapdoor arching with K tan(phi) = 0.25
// (Giroud et al. 1990), seed paper eq. (21) with its sign typo corrected (docs/method.md,
// section 1.3):
//   p = 2 gamma b (1 - exp(-0.5 H/b)) + q exp(-0.5 H/b)
// The printed form has exp(+0.5 H/b) in the first term, which makes p negative.
inline double arching_pressure(double gamma, double b, double H, double q) {
  detail::require_nonnegative(gamma, "gamma");
  detail::require_positive(b, "b");
  detail::require_nonnegative(H, "H");
  const double e = std::exp(-0.5 * H / b);
  return 2.0 * gamma * b * (1.0 - e) + q * e;
}

// Terzaghi's arching pressure on a long void (trapdoor) of width B under cover H (docs/method.md,
// section 6.4):
//   sigma_v = (gamma B / 2 - c) / (K tan phi) (1 - exp(-2 K tan phi H / B))
//             + q exp(-2 K tan phi H / B)
// with ktan = K tan(phi) > 0 (K = 1 and K = Ka bracket what trapdoor tests show; Giroud's 0.25 is
// arching_pressure above), cohesion c (Pa), surcharge q (Pa). Never below zero.
inline double terzaghi_pressure(double gamma, double B, double H, double ktan, double c = 0,
                                double q = 0) {
  detail::require_positive(B, "B");
  detail::require_positive(ktan, "K tan(phi)");
  detail::require_nonnegative(H, "H");
  const double e = std::exp(-2.0 * ktan * H / B);
  return std::fmax(0.0, (gamma * B / 2.0 - c) / ktan * (1.0 - e) + q * e);
}
// Tension factor, seed paper eq. (23) (Giroud et al. 1990):
//   Omega = (1/4) (2y/b + b/(2y))
// For a circular arc of chord b and sag y, the radius is R = b Omega, so T = p R = p b Omega.
// Omega >= 1/2, with the minimum at y/b = 1/2 (semicircle).
inline double omega(double y, double b) {
  detail::require_positive(y, "sag y");
  detail::require_positive(b, "b");
  return 0.25 * (2.0 * y / b + b / (2.0 * y));
}

// Half-angle subtended by the arc at its centre: theta = 2 atan(2y/b), theta in (0, pi).
// Then sin(theta) = 1/(2 Omega), R = b/(2 sin theta), arc length = 2 R theta.
inline double half_angle(double y, double b) {
  detail::require_positive(y, "sag y");
  detail::require_positive(b, "b");
  return 2.0 * std::atan(2.0 * y / b);
}

// Membrane strain (arc length / chord - 1), seed paper eq. (24) with both branches
// (Giroud et al. 1990):
//   eps = 2 Omega asin(1/(2 Omega)) - 1          (y/b <= 0.5, arc less than a semicircle)
//   eps = 2 Omega (pi - asin(1/(2 Omega))) - 1   (y/b >  0.5, arc more than a semicircle)
// Both equal theta/sin(theta) - 1 with theta = half_angle(y, b); they meet at y/b = 0.5 with
// eps = pi/2 - 1. The paper prints only the first branch. Small y loses relative accuracy to
// cancellation (eps ~ (8/3)(y/b)^2); irrelevant for the sags of interest here.
inline double strain(double y, double b) {
  const double Om = omega(y, b);
  const double a = std::asin(std::fmin(1.0, 1.0 / (2.0 * Om)));
  if (y / b <= 0.5) return 2.0 * Om * a - 1.0;
  return 2.0 * Om * (pi - a) - 1.0;
}

struct Result {
  double sag;      // y: mid-span deflection of the membrane over the void [m]
  double strain;   // eps: uniform membrane strain over the void [-]
  double stress;   // sigma = T / t: axial membrane stress [Pa]
  double pressure; // p: arching pressure on the membrane, eq. (21) corrected [Pa]
  double tension;  // T = p b Omega: membrane tension per unit length [N/m]
};

// The paper's use of the solution (section 4): plug a given sag y (the paper used its numerical
// 2 mm for load II) into eqs. (21)-(24): p from arching, T = p b Omega(y), sigma = T / t
// (eq. 22), eps(y) from the geometry (eq. 24). Stress and strain are not linked by a modulus.
inline Result paper_form(double gamma, double b, double H, double q, double t, double y) {
  detail::require_positive(t, "t");
  const double p = arching_pressure(gamma, b, H, q);
  const double T = p * b * omega(y, b);
  return Result{y, strain(y, b), T / t, p, T};
}

// Self-consistent Giroud solution: close eqs. (21)-(24) with a linear membrane, T = J eps,
// J = E t (Giroud et al. 1990 use the geosynthetic's tension-strain curve the same way), and
// solve for the sag y:
//   G(y) = p b Omega(y) - J eps(y) = 0.
// One root. With theta = 2 atan(2y/b) (strictly increasing map of y in (0, inf) onto
// (0, pi)), Omega = 1/(2 sin theta) and eps = theta/sin(theta) - 1 on both branches, so
//   G = [ p b / 2 - J (theta - sin theta) ] / sin(theta),   sin(theta) > 0.
// h(theta) = theta - sin(theta) is strictly increasing on (0, pi) (h' = 1 - cos theta > 0) from
// 0 to pi, hence sign(G) = sign(kappa - h(theta)) with kappa = p b / (2 J): G is positive then
// negative and has exactly one root iff 0 < kappa < pi (for kappa >= pi the linear membrane
// cannot carry the load at any finite sag; we throw). The root is bracketed by theta in (0, pi)
// and found by bisection to machine precision, which is bisection on G(y) over y in (0, inf)
// after the monotone change of variable; y = (b/2) tan(theta/2). Returned stress = J eps / t
// (= E eps), which equals p b Omega / t at the root.
namespace detail {
// The sheet over a void of chord b under pressure p, closed with T = J eps (J = E t): its tension
// is p b Omega(y) / k (k = 1 a long void's cylinder, k = 2 a round void's spherical cap), so
// kappa = p b / (2 k J) must be below pi; bisection on theta as explained above.
inline Result solve_sag(double p, double b, double k, double t, double E, const char *who) {
  require_positive(p, "arching pressure p");
  const double J = E * t;
  const double kappa = p * b / (2.0 * k * J);
  if (!(kappa < pi))
    throw std::invalid_argument(std::string("pmpm::giroud::") + who +
                                ": no equilibrium sag for a linear membrane (kappa >= pi)");
  // h(theta) - kappa, with the small-angle series for h to keep relative accuracy near 0.
  auto f = [kappa](double th) {
    const double h = th < 1e-3 ? th * th * th / 6.0 * (1.0 - th * th / 20.0) : th - std::sin(th);
    return h - kappa;
  };
  double lo = 0.0, hi = pi; // f(lo) = -kappa < 0, f(hi) = pi - kappa > 0
  for (int it = 0; it < 200 && hi - lo > 4.0 * 2.220446049250313e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (f(mid) < 0.0)
      lo = mid;
    else
      hi = mid;
  }
  const double theta = 0.5 * (lo + hi);
  const double y = 0.5 * b * std::tan(0.5 * theta);
  const double eps = strain(y, b);
  return Result{y, eps, J * eps / t, p, J * eps};
}
} // namespace detail

inline Result self_consistent(double gamma, double b, double H, double q, double t, double E) {
  detail::require_positive(t, "t");
  detail::require_positive(E, "E");
  return detail::solve_sag(arching_pressure(gamma, b, H, q), b, 1.0, t, E, "self_consistent");
}

// A round void of diameter D (Giroud et al. 1990 treat it alongside the long one): the arching
// over a round trapdoor is the long void's with the same area over perimeter, D / 4, i.e. width
// D / 2 (p = arching_pressure(gamma, D / 2, H, q)); the sheet is a spherical cap of chord D and
// sag y, whose tension is half a cylinder's, T = p D Omega(y, D) / 2, with the same arc strain
// eps(y, D). Closed with T = J eps as self_consistent: kappa = p D / (4 J) < pi.
inline Result self_consistent_round(double gamma, double D, double H, double q, double t,
                                    double E) {
  detail::require_positive(t, "t");
  detail::require_positive(E, "E");
  detail::require_positive(D, "D");
  return detail::solve_sag(arching_pressure(gamma, 0.5 * D, H, q), D, 2.0, t, E,
                           "self_consistent_round");
}

} // namespace giroud
} // namespace pmpm
