// A chain laid through given points, without the grid, for the unit tests of the chain's
// kernels (test_membrane_revolution.cpp, test_sheet.cpp).
#pragma once
#include "pmpm/contact/chain.hpp"
#include <cmath>
#include <vector>

namespace pmpm_test {

// A chain through the given points (x, y pairs), laid there (rest lengths and radii), as a sheet
// of revolution with stiffness J and Poisson's ratio nu under the given law.
inline pmpm::Chain make_chain(const std::vector<double> &pts, double J, double nu, int law) {
  pmpm::Chain c;
  c.n = static_cast<int>(pts.size()) / pmpm::DIM;
  c.x = pts;
  c.x0 = pts;
  c.axisymmetric = true;
  c.strain_projection = false;
  c.nu = nu;
  c.law.kind = law;
  c.law.J = J;
  const int ns = c.n - 1;
  c.l0.resize(ns);
  c.r0.resize(ns);
  for (int k = 0; k < ns; ++k) {
    c.l0[k] = std::hypot(pts[(k + 1) * pmpm::DIM] - pts[k * pmpm::DIM],
                         pts[(k + 1) * pmpm::DIM + 1] - pts[k * pmpm::DIM + 1]);
    c.r0[k] = 0.5 * (pts[k * pmpm::DIM] + pts[(k + 1) * pmpm::DIM]);
  }
  c.eps.assign(ns, 0.0);
  c.eps_p.assign(ns, 0.0);
  c.alpha.assign(ns, 0.0);
  c.T.assign(ns, 0.0);
  c.T_hoop.assign(ns, 0.0);
  c.eps_hoop.assign(ns, 0.0);
  c.slack.assign(ns, 0);
  c.f.assign(pts.size(), 0.0);
  return c;
}
} // namespace pmpm_test
