// Waste degradation's eigenstrain increment (degradation.hpp) in 2D and 3D: the modes, the
// zone's grading and taper, the materials that degrade, and the power on the current stresses,
// against values written out by hand; a 3D particle gives its 2D parent's increment and power.
#include "check.hpp"
#include "pmpm/core/degradation.hpp"
#include <cmath>
#include <vector>

using namespace pmpm;

namespace {

// n particles of dimension D: initial positions, stresses, volumes, materials
template <int D> struct Cloud {
  std::vector<double> x0, stress, vol;
  std::vector<PetscInt> mat;
  ParticleView P;
  explicit Cloud(int n) : x0(D * n), stress(NStress<D> * n), vol(n, 1.0), mat(n, 0) {
    P.n = n;
    P.x0 = x0.data();
    P.stress = stress.data();
    P.vol = vol.data();
    P.mat = mat.data();
  }
};

Shrinkage Zone(ShrinkMode mode) {
  Shrinkage s;
  s.mode = mode;
  s.x_lo = 2.0, s.x_hi = 4.0, s.taper = 1.0; // full over [2, 4], 0 beyond 1 m outside
  s.y_lo = 0.0, s.y_hi = 10.0;
  s.grade_bottom = 1.0, s.grade_top = 0.5; // linear in y: 1 at the base, 0.5 at y = 10
  s.degrades = {1, 0};                     // material 0 degrades, material 1 does not
  return s;
}

// five particles: inside, in the taper, outside, above the zone, a material that does not degrade
const double kX[5][2] = {{3.0, 0.0}, {4.5, 5.0}, {6.0, 1.0}, {3.0, 11.0}, {3.0, 0.0}};
// the zone's grade at each (the taper's 1/2 times the y grading's 0.75 at y = 5), and the share
// of the shrinkage each takes (the last one's material does not degrade)
const double kGrade[5] = {1.0, 0.5 * 0.75, 0.0, 0.0, 1.0};
const double kShare[5] = {1.0, 0.5 * 0.75, 0.0, 0.0, 0.0};

template <int D> void fill(Cloud<D> &c) {
  for (int p = 0; p < 5; ++p) {
    c.x0[D * p] = kX[p][0];
    c.x0[D * p + 1] = kX[p][1];
    if (D == 3) c.x0[D * p + 2] = 0.7 * p; // z: the zone is a prism along it
    double *s = &c.stress[NStress<D> * p];
    s[0] = -10.0 - p, s[1] = -20.0 - 2 * p, s[2] = -5.0 - p, s[3] = 3.0; // xx yy zz xy
    if (D == 3) s[4] = 1.0, s[5] = -2.0;                                 // yz xz: no power
    c.vol[p] = 0.5 + 0.1 * p;
  }
  c.mat[4] = 1;
}

template <int D> void test_mode(ShrinkMode mode) {
  Cloud<D> c(5);
  fill(c);
  const Shrinkage s = Zone(mode);
  std::vector<double> e;
  const double amount = 0.01;
  const double power = shrinkage_increment<D>(c.P, s, amount, e);
  CHECK(e.size() == 15);
  double want_power = 0;
  for (int p = 0; p < 5; ++p) {
    const double ev = amount * kShare[p];
    CHECK_CLOSE(shrinkage_grade(s, &c.x0[D * p]), kGrade[p], 1e-15);
    const double want[3] = {mode == ShrinkMode::Vertical ? 0.0 : -ev / 3,
                            mode == ShrinkMode::Vertical ? -ev : -ev / 3,
                            mode == ShrinkMode::Vertical ? 0.0 : -ev / 3};
    for (int d = 0; d < 3; ++d) CHECK_CLOSE(e[3 * p + d], want[d], 1e-18);
    const double *sg = &c.stress[NStress<D> * p];
    want_power -= c.vol[p] * (sg[0] * want[0] + sg[1] * want[1] + sg[2] * want[2]);
  }
  CHECK_CLOSE(power, want_power, 1e-15);
  CHECK(power < 0); // shrinking under compression: the stresses do negative work on it
}

// a 3D particle (its 2D parent's x, y, any z, the same normal stresses) gives the 2D increment
void test_3d_against_2d() {
  for (ShrinkMode mode : {ShrinkMode::Vertical, ShrinkMode::Isotropic}) {
    Cloud<2> a(5);
    Cloud<3> b(5);
    fill(a);
    fill(b);
    const Shrinkage s = Zone(mode);
    std::vector<double> ea, eb;
    const double pa = shrinkage_increment<2>(a.P, s, 0.02, ea);
    const double pb = shrinkage_increment<3>(b.P, s, 0.02, eb);
    CHECK(ea == eb);
    CHECK(pa == pb);
  }
}

// 3D, a zone round in plan (radius 2 about (x, z) = (1, 3), taper 1 m beyond it, graded in y as
// Zone's): full inside the circle at any azimuth, half in the middle of the taper, none beyond
// it; the increment of a particle is amount times that grade.
void test_round_zone() {
  Shrinkage s = Zone(ShrinkMode::Vertical);
  s.x_lo = 100, s.x_hi = 101; // an x range that would exclude every particle: the circle wins
  s.cx = 1, s.cz = 3, s.radius = 2;
  const double c = std::cos(0.3), d = std::sin(0.3);
  // (x, y, z) and the grade: inside (r = 1.9), in the taper (r = 2.5), beyond (r = 3.2), on the
  // circle above the zone's top (y = 11)
  const double X[4][3] = {{1 + 1.9 * c, 0, 3 + 1.9 * d},
                          {1 - 2.5 * d, 5, 3 + 2.5 * c},
                          {1 + 3.2, 2, 3},
                          {1, 11, 3 + 2}};
  const double want[4] = {1.0, 0.5 * 0.75, 0.0, 0.0};
  Cloud<3> cl(4);
  for (int p = 0; p < 4; ++p) {
    for (int k = 0; k < 3; ++k) cl.x0[3 * p + k] = X[p][k];
    CHECK_CLOSE(shrinkage_grade3(s, X[p]), want[p], 1e-14);
  }
  std::vector<double> e;
  shrinkage_increment<3>(cl.P, s, 0.01, e);
  for (int p = 0; p < 4; ++p) CHECK_CLOSE(e[3 * p + 1], -0.01 * want[p], 1e-16);
  s.radius = 0; // no circle: the x range's prism (nothing degrades at x < 100)
  for (int p = 0; p < 4; ++p) CHECK(shrinkage_grade3(s, X[p]) == 0.0);
}

} // namespace

int main() {
  test_round_zone();
  test_mode<2>(ShrinkMode::Vertical);
  test_mode<2>(ShrinkMode::Isotropic);
  test_mode<3>(ShrinkMode::Vertical);
  test_mode<3>(ShrinkMode::Isotropic);
  test_3d_against_2d();
  return pmpm_test::report("degradation");
}
