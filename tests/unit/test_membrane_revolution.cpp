// Unit test of a chain as a sheet of revolution (chain.hpp; -geometry axisymmetric; docs/method.md,
// section 9.2), without the grid:
//  - its forces are the gradient of its energy: with the linear law and no projection, f_i =
//    -dU/dx_i for U = sum_k l0_k R_k W(eps_k, th_k), W = J/2 (eps^2 + 2 nu eps th + th^2)
//    (chain_elastic_energy), by central differences on a curved 5-point meridian away from the
//    axis (step 1e-6, relative tolerance 1e-6 of the largest force: the difference's truncation
//    is (1e-6)^2 of the curvature terms, round-off 1e-16 / 1e-6);
//  - the tensions of one segment in each state of the tension-field law (tension_only): taut
//    (both tensile: the biaxial law), wrinkled around the hoop (the hoop tension would compress:
//    N = E t eps, N_th = 0), wrinkled along the meridian (N_th = E t th, N = 0) and slack (both
//    strains shortening: nothing), each against the formula to 1e-12;
//  - the linear law on the same wrinkled geometry keeps a compressive hoop tension (the two laws
//    differ exactly where the sheet would wrinkle).
#include "check.hpp"
#include "chain_fixture.hpp"
#include "pmpm/contact/chain.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

using pmpm::DIM;
using pmpm_test::make_chain;

int main() {
  const double J = 2.0e5, nu = 0.45, Et = J * (1 - nu * nu);
  const int linear = pmpm::MembraneLawId<pmpm::LinearMembrane>;
  const int field = pmpm::MembraneLawId<pmpm::TensionOnlyMembrane>;

  // 1. forces = -grad U (linear law, no projection), a curved meridian moved off its rest state
  {
    pmpm::Chain c = make_chain({0.5, 1.0, 0.9, 1.1, 1.4, 1.15, 1.8, 1.1, 2.3, 0.95}, J, nu, linear);
    const double u[] = {0.01, -0.02, -0.015, 0.01, 0.02, -0.03, -0.01, 0.02, 0.005, 0.01};
    for (int q = 0; q < 2 * c.n; ++q) c.x[q] += u[q];
    pmpm::chain_update_tension(c);
    const std::vector<double> f = c.f;
    double fmax = 0;
    for (double v : f) fmax = std::fmax(fmax, std::fabs(v));
    const double d = 1e-6;
    for (int q = 0; q < 2 * c.n; ++q) {
      pmpm::Chain a = c, b = c;
      a.x[q] += d;
      b.x[q] -= d;
      pmpm::chain_update_tension(a);
      pmpm::chain_update_tension(b);
      const double dU = (pmpm::chain_elastic_energy(a) - pmpm::chain_elastic_energy(b)) / (2 * d);
      CHECK_CLOSE(f[q], -dU, 1e-6 * fmax);
    }
    // a hoop strain is there: the test exercises the hoop terms
    double thmax = 0;
    for (double t : c.eps_hoop) thmax = std::fmax(thmax, std::fabs(t));
    CHECK(thmax > 1e-3);
  }

  // 2. one segment from R = 1..2 on y = 0 in each state of the tension field
  struct Case {
    double x0, x1; // its ends' current radii
    int state;     // 0 taut, 1 wrinkled around the hoop, 2 wrinkled along the meridian, 3 slack
  };
  const Case cases[] = {{1.01, 2.03, 0}, {0.95, 1.97, 1}, {1.05, 2.02, 2}, {0.99, 1.98, 3}};
  for (const Case &k : cases) {
    pmpm::Chain c = make_chain({1.0, 0.0, 2.0, 0.0}, J, nu, field);
    c.x[0] = k.x0;
    c.x[2] = k.x1;
    pmpm::chain_update_tension(c);
    const double e = (k.x1 - k.x0) - 1.0, th = 0.5 * (k.x0 + k.x1) / 1.5 - 1.0;
    CHECK_CLOSE(c.eps[0], e, 1e-12);
    CHECK_CLOSE(c.eps_hoop[0], th, 1e-12);
    double N = 0, Nh = 0;
    if (k.state == 0) N = J * (e + nu * th), Nh = J * (th + nu * e);
    if (k.state == 1) N = Et * e;
    if (k.state == 2) Nh = Et * th;
    CHECK_CLOSE(c.T[0], N, 1e-12 * J);
    CHECK_CLOSE(c.T_hoop[0], Nh, 1e-12 * J);
    CHECK(bool(c.slack[0]) == (k.state == 3));
    // the state is the one the case names: the biaxial trial tensions say so
    const double Nb = J * (e + nu * th), Nhb = J * (th + nu * e);
    if (k.state == 0) CHECK(Nb >= 0 && Nhb >= 0);
    if (k.state == 1) CHECK(Nhb < 0 && e > th);
    if (k.state == 2) CHECK(Nb < 0 && th > e);
    if (k.state == 3) CHECK(e <= 0 && th <= 0);
    // the forces: the meridional tension on a ring of radius 1.5, the hoop pulling inward
    const double l = k.x1 - k.x0;
    CHECK_CLOSE(c.f[0], 1.5 * N * l / l - 0.5 * Nh, 1e-12 * J);
    CHECK_CLOSE(c.f[2], -1.5 * N - 0.5 * Nh, 1e-12 * J);
    if (k.state == 1) { // the linear law keeps the compressive hoop tension there
      pmpm::Chain g = make_chain({1.0, 0.0, 2.0, 0.0}, J, nu, linear);
      g.x[0] = k.x0;
      g.x[2] = k.x1;
      pmpm::chain_update_tension(g);
      CHECK(g.T_hoop[0] < 0);
      CHECK_CLOSE(g.T_hoop[0], J * (th + nu * e), 1e-12 * J);
    }
  }
  return pmpm_test::report("test_membrane_revolution");
}
