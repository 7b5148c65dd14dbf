// Unit tests of the geomembrane's axial law (include/pmpm/materials/membrane_law.hpp): linear,
// tension-only and 1D elastoplastic with linear isotropic hardening, against hand solutions.
// Forces per unit width (N/m), engineering strain (dimensionless).
#include "check.hpp"
#include "pmpm/materials/membrane_law.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>

using namespace pmpm;

namespace {

// A 1.5 mm HDPE sheet (docs/method.md, section 7.2): E = 600 MPa, sigma_y = 15 MPa (yield
// strain 2.5 %), H = 30 MPa (5 % of E), uniaxial J = E t.
const double t_sheet = 1.5e-3;
const double J = 600e6 * t_sheet;                    // 9e5 N/m
const double YIELD_T = 15e6 * t_sheet;               // 2.25e4 N/m
const double HARDENING = 30e6 * t_sheet;             // 4.5e4 N/m
const double EPS_Y = YIELD_T / J;                    // 0.025
const double J_EP = J * HARDENING / (J + HARDENING); // elastoplastic tangent
// The return map is closed form: a few flops per call, errors of a few 1e-16 relative.
const double RTOL = 1e-12;

MembraneLaw law(int kind, double hardening = HARDENING) {
  MembraneLaw m;
  m.kind = kind;
  m.J = J;
  m.yield_T = YIELD_T;
  m.hardening = hardening;
  return m;
}

// Hand bilinear curve of monotonic loading from the virgin state (eps >= 0).
double bilinear(double eps, double hardening) {
  if (eps <= YIELD_T / J) return J * eps;
  return YIELD_T + (J * hardening / (J + hardening)) * (eps - YIELD_T / J);
}

// ---------------------------------------------------------------------------------------------
void test_names() {
  CHECK(std::strcmp(MembraneLawNames[int(MembraneLawId<LinearMembrane>)], "linear") == 0);
  CHECK(std::strcmp(MembraneLawNames[int(MembraneLawId<TensionOnlyMembrane>)], "tension_only") ==
        0);
  CHECK(std::strcmp(MembraneLawNames[int(MembraneLawId<ElastoplasticMembrane>)], "elastoplastic") ==
        0);
  CHECK(std::strcmp(MembraneLawNames[3], "MembraneLawKind") == 0);
  CHECK(std::strcmp(MembraneLawNames[4], "MEMBRANE_") == 0);
  CHECK(MembraneLawNames[5] == nullptr);
  const MembraneLaw def;
  CHECK(def.kind == MembraneLawId<LinearMembrane>);
}

// Linear: T = J eps exactly, in tension and compression; state untouched; never slack.
void test_linear() {
  const MembraneLaw m = law(MembraneLawId<LinearMembrane>);
  pmpm_test::Lcg g(1);
  for (int i = 0; i < 200; ++i) {
    const double eps = g.uniform(-0.2, 0.2);
    double ep = 0.125, al = 0.5; // arbitrary state: must be ignored and left as is
    bool slack = true;
    const double T = m.tension(eps, ep, al, slack);
    CHECK_CLOSE(T, J * eps, 0.0);
    CHECK(!slack);
    CHECK(ep == 0.125 && al == 0.5);
  }
}

// Tension only: J eps in tension, exactly zero and slack in compression, zero and taut at 0.
void test_tension_only() {
  const MembraneLaw m = law(MembraneLawId<TensionOnlyMembrane>);
  pmpm_test::Lcg g(2);
  int n_slack = 0;
  for (int i = 0; i < 200; ++i) {
    const double eps = g.uniform(-0.2, 0.2);
    double ep = 0, al = 0;
    bool slack = eps >= 0; // opposite of the expected value, so the call must set it
    const double T = m.tension(eps, ep, al, slack);
    if (eps < 0) {
      ++n_slack;
      CHECK(slack);
      CHECK(T == 0.0 && !std::signbit(T));
    } else {
      CHECK(!slack);
      CHECK_CLOSE(T, J * eps, 0.0);
    }
    CHECK(ep == 0 && al == 0);
  }
  CHECK(n_slack > 50 && n_slack < 150); // both branches were exercised
  double ep = 0, al = 0;
  bool slack = true;
  CHECK(m.tension(0.0, ep, al, slack) == 0.0);
  CHECK(!slack);
  CHECK(m.tension(-1e-300, ep, al, slack) == 0.0);
  CHECK(slack);
}

// Elastoplastic, monotonic loading from the virgin state to 12 % (HDPE's yield elongation) along
// the hand bilinear curve, in n equal increments. Plastic strain in closed form: on the hardening
// branch J (eps - eps_p) = yield_T + H alpha with alpha = eps_p, so
// eps_p = (J eps - yield_T) / (J + H).
void monotonic(int n, double hardening) {
  const MembraneLaw m = law(MembraneLawId<ElastoplasticMembrane>, hardening);
  const double eps_max = 0.12;
  double ep = 0, al = 0;
  for (int i = 1; i <= n; ++i) {
    const double eps = eps_max * i / n;
    bool slack = true;
    const double T = m.tension(eps, ep, al, slack);
    const double want = bilinear(eps, hardening);
    CHECK_CLOSE(T, want, RTOL * want);
    CHECK(!slack);
    const double ep_want = eps <= EPS_Y ? 0.0 : (J * eps - YIELD_T) / (J + hardening);
    CHECK_CLOSE(ep, ep_want, RTOL * eps_max);
    CHECK_CLOSE(al, ep, RTOL * eps_max);
    CHECK(T <= YIELD_T + hardening * al + RTOL * YIELD_T); // on or inside the yield surface
  }
}

void test_monotonic() {
  monotonic(1, HARDENING);    // one jump 0 -> 12 %: the return map is exact
  monotonic(7, HARDENING);    // a step that straddles the yield point
  monotonic(1000, HARDENING); // small increments
  monotonic(1, 0.0);          // perfectly plastic: T = yield_T beyond yield
  monotonic(1000, 0.0);
  monotonic(1, 10 * J); // stiff hardening (tangent close to J)
  // Elastic below the yield strain: state untouched bit for bit.
  const MembraneLaw m = law(MembraneLawId<ElastoplasticMembrane>);
  double ep = 0, al = 0;
  bool slack = false;
  const double T = m.tension(0.999 * EPS_Y, ep, al, slack);
  CHECK_CLOSE(T, J * 0.999 * EPS_Y, 0.0);
  CHECK(ep == 0.0 && al == 0.0);
  // Compression from the virgin state mirrors tension (symmetric yield).
  ep = al = 0;
  const double Tc = m.tension(-0.08, ep, al, slack);
  CHECK_CLOSE(Tc, -bilinear(0.08, HARDENING), RTOL * bilinear(0.08, HARDENING));
  CHECK_CLOSE(ep, -(J * 0.08 - YIELD_T) / (J + HARDENING), RTOL * 0.08);
  CHECK(!slack);
}

// Load to a peak, unload elastically with slope J, yield in reverse at -(yield_T + H alpha_peak),
// then harden along the reverse bilinear branch of slope J H / (J + H). Done with fine
// increments and again with one jump per stage.
void cycle(int n) {
  const MembraneLaw m = law(MembraneLawId<ElastoplasticMembrane>);
  const double eps_peak = 0.08;
  double ep = 0, al = 0;
  bool slack = false;
  double T = 0;
  for (int i = 1; i <= n; ++i) T = m.tension(eps_peak * i / n, ep, al, slack);
  const double T_peak = bilinear(eps_peak, HARDENING);
  CHECK_CLOSE(T, T_peak, RTOL * T_peak);
  const double ep_peak = ep, al_peak = al;
  CHECK_CLOSE(T_peak, J * (eps_peak - ep_peak), RTOL * T_peak);

  // Elastic unloading: T = T_peak - J (eps_peak - eps) until T = -Y_peak, i.e. down to
  // eps_rev = ep_peak - Y_peak / J. Stop just short of it; the state must not move.
  const double Y_peak = YIELD_T + HARDENING * al_peak;
  const double eps_rev = ep_peak - Y_peak / J;
  const double eps_unl = eps_rev + 1e-6;
  for (int i = 1; i <= n; ++i) {
    const double eps = eps_peak + (eps_unl - eps_peak) * i / n;
    T = m.tension(eps, ep, al, slack);
    CHECK_CLOSE(T, T_peak - J * (eps_peak - eps), RTOL * T_peak);
    CHECK(ep == ep_peak && al == al_peak);
  }
  // Slope J from the peak, by finite difference over the whole unloading.
  CHECK_CLOSE((T_peak - T) / (eps_peak - eps_unl), J, 1e-9 * J);
  CHECK_CLOSE(T, -Y_peak + J * 1e-6, RTOL * T_peak); // just inside the reverse yield point

  // Reverse plastic loading to eps_end: T = -Y_peak + J_EP (eps - eps_rev) (negative slope
  // side), with eps_p = (yield_T + H (al_peak + ep_peak) + J eps) / (J + H) and alpha grown by
  // the plastic strain reversed.
  const double eps_end = -0.05;
  for (int i = 1; i <= n; ++i) {
    const double eps = eps_unl + (eps_end - eps_unl) * i / n;
    T = m.tension(eps, ep, al, slack);
    const double want =
        eps >= eps_rev ? -Y_peak + J * (eps - eps_rev) : -Y_peak + J_EP * (eps - eps_rev);
    CHECK_CLOSE(T, want, RTOL * T_peak);
    CHECK(!slack);
  }
  const double ep_want =
      (YIELD_T + HARDENING * (al_peak + ep_peak) + J * eps_end) / (J + HARDENING);
  CHECK_CLOSE(ep, ep_want, RTOL * eps_peak);
  CHECK_CLOSE(al, al_peak + (ep_peak - ep), RTOL * eps_peak);
  CHECK_CLOSE(-T, YIELD_T + HARDENING * al, RTOL * T_peak); // on the (expanded) yield surface
  CHECK(-T > Y_peak); // the reverse branch hardened beyond the peak's yield force
}

void test_unload_reverse() {
  cycle(1);
  cycle(400);
}

// Random strain walk: the state always satisfies T = J (eps - eps_p), |T| <= yield_T + H alpha,
// alpha never decreases and grows by exactly |d eps_p|, and each step's plastic work is >= 0.
void test_consistency() {
  for (double hardening : {HARDENING, 0.0}) {
    const MembraneLaw m = law(MembraneLawId<ElastoplasticMembrane>, hardening);
    pmpm_test::Lcg g(3);
    double ep = 0, al = 0, eps = 0;
    int n_plastic = 0, n_elastic = 0;
    for (int i = 0; i < 20000; ++i) {
      eps = std::clamp(eps + g.uniform(-0.004, 0.004), -0.15, 0.15);
      const double ep0 = ep, al0 = al;
      bool slack = true;
      const double T = m.tension(eps, ep, al, slack);
      const double Y = YIELD_T + hardening * al;
      CHECK(!slack);
      CHECK(std::fabs(T) <= Y + RTOL * Y);
      CHECK_CLOSE(T, J * (eps - ep), RTOL * Y);
      CHECK(al >= al0);
      CHECK_CLOSE(al - al0, std::fabs(ep - ep0), RTOL * 0.15);
      CHECK(T * (ep - ep0) >= 0.0); // dissipation T d(eps_p) >= 0
      if (al > al0 || ep != ep0) {  // a plastic step (dg may be below alpha's ulp)
        ++n_plastic;
        CHECK_CLOSE(std::fabs(T), Y, RTOL * Y); // plastic step ends on the surface
      } else {
        ++n_elastic;
        CHECK(std::fabs(T) <= Y); // elastic only if the trial force is inside, no tolerance
      }
    }
    CHECK(n_plastic > 100 && n_elastic > 100); // both regimes exercised
  }
}

// The consistent tangent (the implicit solver's bar stiffness) against central differences of
// tension() from the same committed state, every kind, at random states of a strain walk: elastic
// J, slack 0, plastic J H / (J + H). Differences of the closed-form return are exact but for
// round-off and the kink: states within the step of the surface are skipped.
void test_tangent() {
  for (int kind : {MembraneLawId<LinearMembrane>, MembraneLawId<TensionOnlyMembrane>,
                   MembraneLawId<ElastoplasticMembrane>}) {
    const MembraneLaw m = law(kind);
    pmpm_test::Lcg g(7);
    double ep = 0, al = 0, eps = 0;
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
      eps = std::clamp(eps + g.uniform(-0.004, 0.004), -0.15, 0.15);
      const double d = 1e-7;
      double ep1 = ep, al1 = al, ep2 = ep, al2 = al;
      bool slack;
      const double Tp = m.tension(eps + d, ep1, al1, slack);
      const double Tm = m.tension(eps - d, ep2, al2, slack);
      const bool kink = (ep1 == ep) != (ep2 == ep) || (eps + d > 0) != (eps - d > 0);
      if (!kink) {
        CHECK_CLOSE(m.tangent(eps, ep, al), (Tp - Tm) / (2 * d), 1e-6 * J);
        ++checked;
      }
      bool s;
      m.tension(eps, ep, al, s); // commit
    }
    CHECK(checked > 1900);
  }
  const MembraneLaw e = law(MembraneLawId<ElastoplasticMembrane>);
  CHECK_CLOSE(e.tangent(2 * EPS_Y, 0, 0), J_EP, RTOL * J);
  CHECK(law(MembraneLawId<TensionOnlyMembrane>).tangent(-0.01, 0, 0) == 0.0);
}

} // namespace

int main() {
  test_tangent();
  test_names();
  test_linear();
  test_tension_only();
  test_monotonic();
  test_unload_reverse();
  test_consistency();
  return pmpm_test::report("membrane_law");
}
