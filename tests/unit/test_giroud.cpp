// Unit test of the closed-form geomembrane-over-void solution (include/pmpm/scenes/giroud.hpp):
// Terzaghi arching + tensioned membrane (Giroud et al. 1990), seed paper eqs. (21)-(24).
// Expected values from docs/method.md, section 1.3. Each tolerance is half a unit in the last
// printed digit of the reference value, so the check is "rounds to the printed number".
#include "check.hpp"
#include "pmpm/scenes/giroud.hpp"
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace g = pmpm::giroud;

int main() {
  // Geometry and materials of the seed paper, section 4 / Table I (docs/method.md,
  // sections 1.1, 1.2).
  const double b = 6e-3, H = 8e-3, t = 1e-3, q = 0.0;
  const double E = 0.207e9;      // geomembrane Young's modulus [Pa]
  const double gamma_II = 1.5e9; // soil unit weight, load II [N/m^3]
  const double gamma_I = 7.5e8;  // soil unit weight, load I [N/m^3] (printed 7.5e9 is a typo)

  // Arching pressure, eq. (21) corrected: p = 8.758 MPa (printed to 0.001 MPa).
  const double p = g::arching_pressure(gamma_II, b, H, q);
  CHECK_CLOSE(p, 8.758e6, 0.5e3);
  CHECK(p > 0.0);
  // Surface load alone decays as q exp(-0.5 H/b); H = 0 gives p = q.
  CHECK_CLOSE(g::arching_pressure(0.0, b, H, 1e5), 1e5 * std::exp(-0.5 * H / b), 1e-9);
  CHECK_CLOSE(g::arching_pressure(gamma_II, b, 0.0, 1e5), 1e5, 1e-9);

  // Paper form with the paper's numerical sag y = 2 mm (load II): the paper's 27 % / 28.5 MPa.
  const g::Result pf = g::paper_form(gamma_II, b, H, q, t, 2e-3);
  CHECK_CLOSE(g::omega(2e-3, b), 0.5417, 0.5e-4);
  CHECK_CLOSE(pf.strain, 0.2740, 0.5e-4); // 27.40 %
  CHECK_CLOSE(pf.stress, 28.47e6, 0.5e4); // 28.47 MPa
  CHECK_CLOSE(pf.sag, 2e-3, 0.0);
  CHECK_CLOSE(pf.pressure, p, 0.0);
  CHECK_CLOSE(pf.tension, pf.stress * t, 1e-9 * pf.tension);

  // Omega is minimal (1/2) at y/b = 1/2 (semicircle); there eps = pi/2 - 1 on both branches.
  CHECK_CLOSE(g::omega(0.5 * b, b), 0.5, 1e-15);
  CHECK_CLOSE(g::strain(0.5 * b, b), g::pi / 2.0 - 1.0, 1e-15);
  // strain() continuous across the branch switch at y/b = 0.5.
  {
    const double y0 = 0.5 * b, dy = 1e-9 * b;
    const double below = g::strain(y0 - dy, b), above = g::strain(y0 + dy, b);
    // slope d eps/dy at the semicircle is 2/b (from eps = theta/sin theta - 1, theta = 2atan(2y/b))
    CHECK_CLOSE(above - below, 2.0 / b * 2.0 * dy, 1e-6);
    CHECK_CLOSE(below, g::pi / 2.0 - 1.0, 1e-8);
    CHECK_CLOSE(above, g::pi / 2.0 - 1.0, 1e-8);
  }
  // Both branches equal the arc-length form theta/sin(theta) - 1, theta = 2 atan(2y/b).
  for (double r : {0.05, 0.2, 0.333, 0.49, 0.51, 0.8, 1.5, 4.0}) {
    const double th = g::half_angle(r * b, b);
    CHECK_CLOSE(g::strain(r * b, b), th / std::sin(th) - 1.0, 1e-12);
  }
  // strain increases with sag on both branches.
  {
    bool mono = true;
    double prev = g::strain(1e-3 * b, b);
    for (int i = 2; i <= 3000; ++i) {
      const double e = g::strain(1e-3 * i * b, b);
      mono = mono && e > prev;
      prev = e;
    }
    CHECK(mono);
  }

  // Self-consistent solution (T = J eps, J = E t), load II: y = 1.498 mm, eps = 15.9 %,
  // sigma = 32.9 MPa.
  const g::Result s2 = g::self_consistent(gamma_II, b, H, q, t, E);
  CHECK_CLOSE(s2.sag, 1.498e-3, 0.5e-6);
  CHECK_CLOSE(s2.strain, 0.159, 0.5e-3);
  CHECK_CLOSE(s2.stress, 32.9e6, 0.05e6);
  // Load I: y = 1.149 mm, eps = 9.5 %, sigma = 19.7 MPa.
  const g::Result s1 = g::self_consistent(gamma_I, b, H, q, t, E);
  CHECK_CLOSE(s1.sag, 1.149e-3, 0.5e-6);
  CHECK_CLOSE(s1.strain, 0.095, 0.5e-3);
  CHECK_CLOSE(s1.stress, 19.7e6, 0.05e6);

  // The root satisfies p b Omega(y) = E t eps(y) to 1e-10 relative, and sigma = p b Omega / t.
  for (const g::Result *s : {&s2, &s1}) {
    const double lhs = s->pressure * b * g::omega(s->sag, b);
    const double rhs = E * t * g::strain(s->sag, b);
    CHECK_CLOSE(lhs / rhs, 1.0, 1e-10);
    CHECK_CLOSE(s->stress / (lhs / t), 1.0, 1e-10);
    CHECK_CLOSE(s->tension, s->stress * t, 1e-9 * s->tension);
  }
  // Small load: sag tiny but still a root to 1e-10 (tests the small-angle branch of the solver).
  {
    const g::Result s = g::self_consistent(1e3, b, H, q, t, E);
    const double th = g::half_angle(s.sag, b);
    CHECK_CLOSE((th - std::sin(th)) / (s.pressure * b / (2.0 * E * t)), 1.0, 1e-10);
  }
  // No equilibrium for a linear membrane when p b / (2 E t) >= pi.
  {
    bool threw = false;
    try {
      g::self_consistent(gamma_II, b, H, q, t, 1e4);
    } catch (const std::invalid_argument &) {
      threw = true;
    }
    CHECK(threw);
  }

  // A round void of diameter D: the pressure of a long void of width D / 2 (area over perimeter
  // D / 4 for both) and a spherical cap, T = p D Omega(y, D) / 2 = E t eps(y, D) at the root.
  {
    const double D = 2.0, Hr = 1.2, gr = 19e3, tr = 1.5e-3, Er = 500e6;
    const g::Result r = g::self_consistent_round(gr, D, Hr, 0.0, tr, Er);
    CHECK_CLOSE(r.pressure / g::arching_pressure(gr, 0.5 * D, Hr, 0.0), 1.0, 1e-14);
    CHECK_CLOSE(0.5 * r.pressure * D * g::omega(r.sag, D) / (Er * tr * g::strain(r.sag, D)), 1.0,
                1e-9);
    CHECK_CLOSE(r.tension, Er * tr * r.strain, 1e-9 * r.tension);
    // half the long void's tension factor: the cap sags less than the cylinder at one pressure
    const g::Result l = g::self_consistent(gr, D, Hr, 0.0, tr, Er);
    CHECK(r.sag < l.sag * g::arching_pressure(gr, 0.5 * D, Hr, 0.0) / l.pressure);
  }

  std::printf("load II paper form (y = 2 mm): p = %.4f MPa, Omega = %.4f, eps = %.2f %%, "
              "sigma = %.2f MPa\n",
              p / 1e6, g::omega(2e-3, b), 100 * pf.strain, pf.stress / 1e6);
  std::printf("load II self-consistent: y = %.4f mm, eps = %.3f %%, sigma = %.3f MPa\n",
              s2.sag * 1e3, 100 * s2.strain, s2.stress / 1e6);
  std::printf("load I  self-consistent: y = %.4f mm, eps = %.3f %%, sigma = %.3f MPa\n",
              s1.sag * 1e3, 100 * s1.strain, s1.stress / 1e6);
  return pmpm_test::report("test_giroud");
}
