// Unit test of the chains' strain projection (chain.hpp, ChainProjection; -chain_strain_projection)
// on a curved sheet crossing a grid of unit cells, 4 segments a cell (the default spacing):
//  - it keeps a uniform strain (the blocks' weights are a partition of unity inside the box);
//  - it keeps the sheet's elongation, sum_k l0_k (P e)_k = sum_k l0_k e_k (the nodes' l0-weighted
//    means go back with the same weights): the projected strain stretches the sheet as the chord
//    strain does;
//  - l0_k P_kj is symmetric, sum l0 u (P v) = sum l0 v (P u): the projected tension is the gradient
//    of an energy and Newton's tangent (chain_implicit.hpp) is symmetric for a linear law;
//  - it removes the cell-period oscillation. A node's weight of a point is the hat of the nodes
//    (transform sinc^2(f h)) averaged over a block one cell long (sinc(f h)), zero at f = 1 / h,
//    so a strain cos(2 pi x / h) has no nodal part; the segments' midpoint sums and the sheet's
//    curvature leave a residue (measured 3.4e-3 of the amplitude), bound 5e-2 (the projected
//    runs' oscillation index is 1-4 % of the peak, the chord strain's 23-86 %).
//    A strain with a period of 10 cells keeps most of its amplitude: node and back, sinc^6(0.1) =
//    0.905 (measured 0.912), bound 0.8.
// Tolerances: round-off over some 60 terms per sum, 1e-13 relative.
#include "check.hpp"
#include "pmpm/contact/chain.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

int main() {
  using pmpm::DIM;
  pmpm::Chain c;
  c.grid_h = 1.0;
  c.grid_origin[0] = c.grid_origin[1] = 0.0;
  c.grid_ncell[0] = 30;
  c.grid_ncell[1] = 12;
  // the sheet: x from 3.1 to 26.9 at 4 points a cell, y = 6.3 + 0.8 sin(x / 4)
  const double x0 = 3.1, x1 = 26.9;
  c.n = static_cast<int>(std::round((x1 - x0) * 4.0)) + 1;
  c.x.resize(static_cast<size_t>(c.n) * DIM);
  for (int i = 0; i < c.n; ++i) {
    const double x = x0 + (x1 - x0) * i / (c.n - 1);
    c.x[i * DIM] = x;
    c.x[i * DIM + 1] = 6.3 + 0.8 * std::sin(x / 4.0);
  }
  const int ns = c.n - 1;
  c.l0.resize(ns);
  std::vector<double> xm(ns);
  for (int k = 0; k < ns; ++k) {
    // a laid length a little off the current one (the sheet is strained)
    const double dx = c.x[(k + 1) * DIM] - c.x[k * DIM],
                 dy = c.x[(k + 1) * DIM + 1] - c.x[k * DIM + 1];
    c.l0[k] = std::hypot(dx, dy) * (1.0 - 0.01 * std::cos(0.3 * k));
    xm[k] = 0.5 * (c.x[k * DIM] + c.x[(k + 1) * DIM]);
  }
  pmpm::ChainProjection P;
  pmpm::chain_projection(c, c.x.data(), P);
  CHECK(static_cast<int>(P.start.size()) == ns + 1);

  auto l0dot = [&](const std::vector<double> &a, const std::vector<double> &b) {
    double s = 0;
    for (int k = 0; k < ns; ++k) s += c.l0[k] * a[k] * b[k];
    return s;
  };
  std::vector<double> one(ns, 1.0), e(ns), pe(ns);

  // uniform strain
  std::vector<double> u(ns, 0.0123);
  pmpm::chain_project(c, P, u.data(), pe.data());
  double worst = 0;
  for (int k = 0; k < ns; ++k) worst = std::max(worst, std::fabs(pe[k] - 0.0123));
  CHECK_CLOSE(worst, 0.0, 1e-13 * 0.0123);

  // elongation and symmetry, random strains
  pmpm_test::Lcg rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> a(ns), b(ns), pa(ns), pb(ns);
    for (int k = 0; k < ns; ++k) {
      a[k] = rng.uniform(-0.01, 0.02);
      b[k] = rng.uniform(-0.01, 0.02);
    }
    pmpm::chain_project(c, P, a.data(), pa.data());
    pmpm::chain_project(c, P, b.data(), pb.data());
    double scale = 0;
    for (int k = 0; k < ns; ++k) scale += c.l0[k] * std::fabs(a[k]);
    CHECK_CLOSE(l0dot(one, pa), l0dot(one, a), 1e-13 * scale);
    CHECK_CLOSE(l0dot(a, pb), l0dot(b, pa), 1e-13 * scale * 0.02);
  }

  // the cell-period oscillation, away from the sheet's ends (3 cells)
  auto amplitude_kept = [&](double period) {
    for (int k = 0; k < ns; ++k) e[k] = 0.01 + 0.005 * std::cos(2 * M_PI * xm[k] / period);
    pmpm::chain_project(c, P, e.data(), pe.data());
    double got = 0, had = 0;
    for (int k = 0; k < ns; ++k)
      if (xm[k] > x0 + 3 && xm[k] < x1 - 3) {
        got = std::max(got, std::fabs(pe[k] - 0.01));
        had = std::max(had, std::fabs(e[k] - 0.01));
      }
    return got / had;
  };
  const double cell = amplitude_kept(1.0), ten = amplitude_kept(10.0);
  std::printf("amplitude kept: cell period %.3g, ten cells %.3g\n", cell, ten);
  CHECK(cell <= 5e-2);
  CHECK(ten >= 0.8);
  return pmpm_test::report("chain_projection");
}
