// Unit tests of F-bar (antilock.hpp) on plain arrays:
//   fbar_groups: cell and body of each particle among the owned cells, -1 outside them;
//   fbar_apply: every particle of a group ends the step with the group's volume ratio
//   (sum of new volumes / sum of old volumes), the group's total volume is unchanged, each
//   particle's isochoric increment (I + du) / sqrt(det) is its own, F and vol follow the
//   increment, and groups (cells, bodies) do not mix. A uniform increment is left untouched;
//   fbar_pressure_shift: p + shift is the group's volume-averaged pressure, and the force's power
//   with it equals the stress power of F-bar's averaged volume rate (conjugacy), for any rates;
//   in 3D (-dim 3): the groups of a 3D box of cells, the group's volume ratio with the cube root
//   (I + du_bar = (dJ_bar / dJ)^(1/3) (I + du)), and the pressure from the six-component stress.
#include "check.hpp"
#include "pmpm/core/antilock.hpp"
#include <cmath>
#include <vector>

using namespace pmpm;

namespace {

struct Particles {
  std::vector<double> x, F, vol, du, stress;
  std::vector<PetscInt> body;
  ParticleView P;
  explicit Particles(int n)
      : x(2 * n), F(4 * n), vol(n), du(4 * n), stress(NSTRESS * n), body(n, 0) {
    P.n = n;
    P.stress = stress.data();
    P.x = x.data();
    P.F = F.data();
    P.vol = vol.data();
    P.body = body.data();
  }
};

double det(const double *a) {
  return a[0] * a[3] - a[1] * a[2];
}

void test_groups() {
  Particles s(5);
  const double origin[2] = {-1.0, 0.0}, h = 0.5;
  const PetscInt lo[2] = {2, 1}, hi[2] = {5, 3}; // owned cells i 2..4, j 1..2
  const double pts[5][2] = {{0.1, 0.6}, {0.4, 0.9}, {1.4, 1.4}, {-0.9, 0.6}, {0.1, 1.6}};
  for (int p = 0; p < 5; ++p) {
    s.x[2 * p] = pts[p][0];
    s.x[2 * p + 1] = pts[p][1];
  }
  s.body[1] = 2;
  std::vector<int> g;
  fbar_groups<2>(s.P, origin, h, lo, hi, 3, g);
  // particle 0: cell (2, 1) -> ((1-1)*3 + 0)*3 + 0 = 0; particle 1: cell (2, 1), body 2 -> 2
  CHECK(g[0] == 0);
  CHECK(g[1] == 2);
  // particle 2: cell (4, 2) -> ((2-1)*3 + 2)*3 = 15
  CHECK(g[2] == 15);
  CHECK(g[3] == -1); // cell (0, 1): not owned
  CHECK(g[4] == -1); // cell (2, 3): not owned
}

void test_apply() {
  // group 0: three particles with different increments; group 1: one particle; group -1: one
  Particles s(5);
  pmpm_test::Lcg r(7);
  std::vector<int> g = {0, 0, 0, 1, -1};
  double old_vol[5], du0[5][4], F0[5][4];
  for (int p = 0; p < 5; ++p) {
    double *du = &s.du[4 * p], *F = &s.F[4 * p];
    for (int k = 0; k < 4; ++k) du[k] = r.uniform(-0.02, 0.02);
    F[0] = 1.0 + r.uniform(-0.1, 0.1);
    F[1] = r.uniform(-0.1, 0.1);
    F[2] = r.uniform(-0.1, 0.1);
    F[3] = 1.0 + r.uniform(-0.1, 0.1);
    old_vol[p] = r.uniform(0.5, 1.5);
    // the state g2p leaves: vol already times the particle's own step ratio
    const double I_du[4] = {1 + du[0], du[1], du[2], 1 + du[3]};
    s.vol[p] = old_vol[p] * det(I_du);
    for (int k = 0; k < 4; ++k) du0[p][k] = du[k], F0[p][k] = F[k];
  }
  double new_sum = 0, old_sum = 0;
  for (int p = 0; p < 3; ++p) new_sum += s.vol[p], old_sum += old_vol[p];
  const double vol_untouched = s.vol[4], vol_alone = s.vol[3];
  std::vector<double> sums;
  const double change = fbar_apply<2>(s.P, g, sums, s.du.data());
  CHECK(change > 1e-4); // the increments differed: the average moved them
  const double ratio = new_sum / old_sum;
  double after = 0;
  for (int p = 0; p < 3; ++p) {
    const double *du = &s.du[4 * p];
    const double I_du[4] = {1 + du[0], du[1], du[2], 1 + du[3]};
    CHECK_CLOSE(det(I_du), ratio, 1e-14); // the group's volume ratio
    CHECK_CLOSE(s.vol[p] / old_vol[p], ratio, 1e-14);
    after += s.vol[p];
    // isochoric part kept: (I + du_bar) = s (I + du)
    const double I0[4] = {1 + du0[p][0], du0[p][1], du0[p][2], 1 + du0[p][3]};
    const double sc = std::sqrt(ratio / det(I0));
    for (int k = 0; k < 4; ++k) CHECK_CLOSE(I_du[k], sc * I0[k], 1e-14);
    for (int k = 0; k < 4; ++k) CHECK_CLOSE(s.F[4 * p + k], sc * F0[p][k], 1e-14);
  }
  CHECK_CLOSE(after, new_sum, 1e-13); // the group's volume is conserved
  // a group of one and a particle outside every group are unchanged
  CHECK_CLOSE(s.vol[3], vol_alone, 1e-15);
  CHECK_CLOSE(s.vol[4], vol_untouched, 0.0);
  for (int k = 0; k < 4; ++k) {
    CHECK_CLOSE(s.du[12 + k], du0[3][k], 1e-15);
    CHECK_CLOSE(s.du[16 + k], du0[4][k], 0.0);
  }
}

void test_uniform() {
  // the same increment everywhere: F-bar changes nothing
  Particles s(4);
  std::vector<int> g = {0, 0, 0, 0};
  const double du[4] = {0.01, -0.004, 0.003, -0.02};
  const double d = (1 + du[0]) * (1 + du[3]) - du[1] * du[2];
  for (int p = 0; p < 4; ++p) {
    for (int k = 0; k < 4; ++k) s.du[4 * p + k] = du[k];
    s.F[4 * p] = s.F[4 * p + 3] = 1.0;
    s.vol[p] = (1.0 + 0.1 * p) * d;
  }
  std::vector<double> sums;
  CHECK_CLOSE(fbar_apply<2>(s.P, g, sums, s.du.data()), 0.0, 1e-15);
  for (int p = 0; p < 4; ++p)
    for (int k = 0; k < 4; ++k) CHECK_CLOSE(s.du[4 * p + k], du[k], 1e-15);
}

void test_pressure_shift() {
  // groups 0 (three particles) and 2 (two), one particle outside; random stresses and volumes
  Particles s(6);
  pmpm_test::Lcg r(11);
  std::vector<int> g = {0, 2, 0, 2, -1, 0};
  for (int p = 0; p < 6; ++p) {
    s.vol[p] = r.uniform(0.5, 1.5);
    for (int k = 0; k < NSTRESS; ++k) s.stress[NSTRESS * p + k] = r.uniform(-2e4, 1e3);
  }
  std::vector<double> sums, shift;
  fbar_pressure_shift<2>(s.P, g, sums, shift);
  auto pressure = [&](int p) {
    const double *t = &s.stress[NSTRESS * p];
    return (t[0] + t[1] + t[2]) / 3.0;
  };
  for (int grp : {0, 2}) {
    double vp = 0, v = 0;
    for (int p = 0; p < 6; ++p)
      if (g[p] == grp) vp += s.vol[p] * pressure(p), v += s.vol[p];
    for (int p = 0; p < 6; ++p)
      if (g[p] == grp) CHECK_CLOSE(pressure(p) + shift[p], vp / v, 1e-12 * 2e4);
  }
  CHECK_CLOSE(shift[4], 0.0, 0.0); // outside every group: its own pressure
  // conjugacy: sum_p V (sigma_p + shift_p I) : D_p = sum_p V (sigma_p : D_p + p_p (trD_bar -
  // trD_p)) in plane strain (D_zz = 0), trD_bar the group's volume average, for random rates D
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> D(4 * 6);
    for (double &d : D) d = r.uniform(-1.0, 1.0);
    auto tr = [&](int p) { return D[4 * p] + D[4 * p + 3]; };
    double lhs = 0, rhs = 0;
    for (int p = 0; p < 6; ++p) {
      if (g[p] < 0) continue;
      const double *t = &s.stress[NSTRESS * p], *d = &D[4 * p];
      const double sd = t[0] * d[0] + t[1] * d[3] + t[3] * (d[1] + d[2]);
      lhs += s.vol[p] * (sd + shift[p] * tr(p));
      double vt = 0, v = 0;
      for (int q = 0; q < 6; ++q)
        if (g[q] == g[p]) vt += s.vol[q] * tr(q), v += s.vol[q];
      rhs += s.vol[p] * (sd + pressure(p) * (vt / v - tr(p)));
    }
    CHECK_CLOSE(lhs, rhs, 1e-10 * 2e4);
  }
}

// 3D: particles with positions, increments and F of three dimensions.
struct Particles3 {
  std::vector<double> x, F, vol, du, stress;
  std::vector<PetscInt> body;
  ParticleView P;
  explicit Particles3(int n)
      : x(3 * n), F(9 * n), vol(n), du(9 * n), stress(NStress<3> * n), body(n, 0) {
    P.n = n;
    P.stress = stress.data();
    P.x = x.data();
    P.F = F.data();
    P.vol = vol.data();
    P.body = body.data();
  }
};

double det3(const double *a) {
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
         a[2] * (a[3] * a[7] - a[4] * a[6]);
}

void test_groups_3d() {
  Particles3 s(4);
  const double origin[3] = {0.0, -1.0, 2.0}, h = 0.5;
  const PetscInt lo[3] = {1, 0, 2}, hi[3] = {3, 2, 5}; // owned: i 1..2, j 0..1, k 2..4
  const double pts[4][3] = {{0.6, -0.9, 3.1}, {1.4, -0.2, 4.6}, {0.4, -0.9, 3.1}, {0.6, -0.9, 4.6}};
  for (int p = 0; p < 4; ++p)
    for (int d = 0; d < 3; ++d) s.x[3 * p + d] = pts[p][d];
  s.body[1] = 1;
  std::vector<int> g;
  fbar_groups<3>(s.P, origin, h, lo, hi, 2, g);
  // particle 0: cell (1, 0, 2) -> ((0 * 2 + 0) * 2 + 0) * 2 + 0 = 0
  CHECK(g[0] == 0);
  // particle 1: cell (2, 1, 5)? z = 4.6 -> k = 5, not owned
  CHECK(g[1] == -1);
  CHECK(g[2] == -1); // i = 0: not owned
  // particle 3: cell (1, 0, 5): not owned either; move it to k = 4 (z = 4.1)
  s.x[3 * 3 + 2] = 4.1;
  s.x[3 * 1 + 2] = 4.1; // particle 1: cell (2, 1, 4), body 1
  fbar_groups<3>(s.P, origin, h, lo, hi, 2, g);
  CHECK(g[3] == ((2 * 2 + 0) * 2 + 0) * 2 + 0);
  CHECK(g[1] == ((2 * 2 + 1) * 2 + 1) * 2 + 1);
}

void test_apply_3d() {
  Particles3 s(4);
  pmpm_test::Lcg r(5);
  std::vector<int> g = {0, 0, 0, -1};
  double old_vol[4], du0[4][9], F0[4][9];
  for (int p = 0; p < 4; ++p) {
    double *du = &s.du[9 * p], *F = &s.F[9 * p];
    for (int k = 0; k < 9; ++k) {
      du[k] = r.uniform(-0.02, 0.02);
      F[k] = (k % 4 == 0 ? 1.0 : 0.0) + r.uniform(-0.1, 0.1);
    }
    old_vol[p] = r.uniform(0.5, 1.5);
    double I_du[9];
    for (int k = 0; k < 9; ++k) I_du[k] = (k % 4 == 0 ? 1.0 : 0.0) + du[k];
    s.vol[p] = old_vol[p] * det3(I_du);
    for (int k = 0; k < 9; ++k) du0[p][k] = du[k], F0[p][k] = F[k];
  }
  double new_sum = 0, old_sum = 0;
  for (int p = 0; p < 3; ++p) new_sum += s.vol[p], old_sum += old_vol[p];
  std::vector<double> sums;
  CHECK(fbar_apply<3>(s.P, g, sums, s.du.data()) > 1e-4);
  const double ratio = new_sum / old_sum;
  for (int p = 0; p < 3; ++p) {
    double I_du[9], I0[9];
    for (int k = 0; k < 9; ++k) {
      I_du[k] = (k % 4 == 0 ? 1.0 : 0.0) + s.du[9 * p + k];
      I0[k] = (k % 4 == 0 ? 1.0 : 0.0) + du0[p][k];
    }
    CHECK_CLOSE(det3(I_du), ratio, 1e-14);
    CHECK_CLOSE(s.vol[p] / old_vol[p], ratio, 1e-14);
    const double sc = std::cbrt(ratio / det3(I0)); // the isochoric part is the particle's own
    for (int k = 0; k < 9; ++k) CHECK_CLOSE(I_du[k], sc * I0[k], 1e-14);
    for (int k = 0; k < 9; ++k) CHECK_CLOSE(s.F[9 * p + k], sc * F0[p][k], 1e-14);
  }
  for (int k = 0; k < 9; ++k) CHECK_CLOSE(s.du[27 + k], du0[3][k], 0.0); // outside: untouched
}

void test_pressure_shift_3d() {
  Particles3 s(3);
  pmpm_test::Lcg r(3);
  std::vector<int> g = {1, 1, -1};
  for (int p = 0; p < 3; ++p) {
    s.vol[p] = r.uniform(0.5, 1.5);
    for (int k = 0; k < NStress<3>; ++k) s.stress[NStress<3> * p + k] = r.uniform(-2e4, 1e3);
  }
  std::vector<double> sums, shift;
  fbar_pressure_shift<3>(s.P, g, sums, shift);
  auto pressure = [&](int p) {
    const double *t = &s.stress[NStress<3> * p];
    return (t[0] + t[1] + t[2]) / 3.0;
  };
  const double pbar = (s.vol[0] * pressure(0) + s.vol[1] * pressure(1)) / (s.vol[0] + s.vol[1]);
  for (int p = 0; p < 2; ++p) CHECK_CLOSE(pressure(p) + shift[p], pbar, 1e-12 * 2e4);
  CHECK_CLOSE(shift[2], 0.0, 0.0);
}

} // namespace

int main() {
  test_groups();
  test_apply();
  test_uniform();
  test_pressure_shift();
  test_groups_3d();
  test_apply_3d();
  test_pressure_shift_3d();
  return pmpm_test::report("antilock");
}
