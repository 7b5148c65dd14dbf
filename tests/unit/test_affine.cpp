// Unit tests of the APIC algebra (affine.hpp) for one particle, for LinearShape and UGIMPShape:
//   D_p against its closed form (linear: h^2 r (1 - r); uGIMP: l^2 / 3 + the block average of
//   h^2 r (1 - r), by quadrature); the affine weights' moments sum_a a_a = 0 and
//   sum_a a_a (x_a - x_p) = 1 (what the angular momentum argument needs); for linear hats the
//   affine weight w D^-1 (x_i - x_p) equals the hat's gradient; and a round trip of one particle
//   (P2G of m, v, B as the kernels do it; nodal velocities p / m; G2P v = sum w v_i,
//   B = sum w v_i (x_i - x_p)^T) returns v and B, and the grid holds the particle's linear and
//   angular momentum m (x_p x v_p + B_yx - B_xy).
// Tolerances: the quantities are O(1) sums of a few O(1) products (cells, m/s); 1e-12 leaves
// room for the eps / w_min amplification where a node's weight is small (w >= 1e-3 drawn).
#include "check.hpp"
#include "pmpm/core/affine.hpp"
#include <cmath>

using namespace pmpm;

namespace {

const double H = 0.37;
const double ORIGIN[DIM] = {-1.3, 0.7};
const int NSAMPLE = 2000;

struct Lcg : pmpm_test::Lcg {
  Lcg() : pmpm_test::Lcg(0x9E3779B97F4A7C15ull) {}
};

// One direction of one particle: weights, offsets (m), affine weights (per m), D (m^2).
template <class Shape> struct Dir {
  double w[Shape::NS], dw[Shape::NS], r[Shape::NS], a[Shape::NS], D;
  int base;
};
template <class Shape> void eval_dir(double x, double l, double origin, Dir<Shape> &d) {
  const double xi = (x - origin) / H;
  Shape::eval1d(xi, l / H, d.base, d.w, d.dw);
  affine1d<Shape>(xi, d.base, d.w, d.dw, H, d.r, d.a);
}

// h^2 r (1 - r) at y (m), r the position in its cell
double hat_inertia(double y, double origin) {
  const double s = (y - origin) / H, r = s - std::floor(s);
  return H * H * r * (1.0 - r);
}

template <class Shape> void random_particle(Lcg &g, double x[DIM], double l[DIM]) {
  for (int d = 0; d < DIM; ++d) {
    l[d] = g.uniform(0.05, 0.5) * H;
    // keep every nonzero weight >= 1e-3 (see the tolerances): not too close to a node or a face
    double xi;
    Dir<Shape> t;
    do {
      xi = g.uniform(2.0, 12.0);
      eval_dir<Shape>(ORIGIN[d] + xi * H, l[d], ORIGIN[d], t);
      bool ok = true;
      for (int k = 0; k < Shape::NS; ++k) ok = ok && (t.w[k] == 0.0 || t.w[k] >= 1e-3);
      if (ok) break;
    } while (true);
    x[d] = ORIGIN[d] + xi * H;
  }
}

template <class Shape> void test_inertia_and_moments(Lcg &g, bool linear) {
  constexpr int NS = Shape::NS;
  double worst_lin = 0;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM], D[DIM];
    random_particle<Shape>(g, x, l);
    affine_inertia<Shape>(x, l, ORIGIN, H, D);
    for (int d = 0; d < DIM; ++d) {
      Dir<Shape> t;
      eval_dir<Shape>(x[d], l[d], ORIGIN[d], t);
      // closed form
      double want;
      if (linear) {
        want = hat_inertia(x[d], ORIGIN[d]);
      } else { // l^2 / 3 + block average of h^2 r (1 - r): midpoint rule, 20000 points (the
               // integrand is a parabola per cell; the error is < 1e-9 h^2)
        const int M = 20000;
        double s = 0;
        for (int k = 0; k < M; ++k)
          s += hat_inertia(x[d] - l[d] + (k + 0.5) * 2 * l[d] / M, ORIGIN[d]);
        want = l[d] * l[d] / 3 + s / M;
      }
      CHECK_CLOSE(D[d] / (H * H), want / (H * H), 1e-8);
      // moments of the affine weights
      double s0 = 0, s1 = 0;
      for (int k = 0; k < NS; ++k) {
        s0 += t.a[k];
        s1 += t.a[k] * t.r[k];
      }
      CHECK_CLOSE(s0 * H, 0.0, 1e-12);
      CHECK_CLOSE(s1, 1.0, 1e-12);
      if (linear) // the general formula w r / D gives the hat's gradient
        for (int k = 0; k < NS; ++k)
          worst_lin = std::fmax(worst_lin, std::fabs(t.w[k] * t.r[k] / D[d] - t.dw[k] / H) * H);
    }
  }
  if (linear) CHECK_CLOSE(worst_lin, 0.0, 1e-12);
}

template <class Shape> void test_round_trip(Lcg &g) {
  constexpr int NS = Shape::NS;
  double worst_v = 0, worst_B = 0, worst_P = 0, worst_L = 0;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM], v[DIM], B[DIM * DIM];
    random_particle<Shape>(g, x, l);
    for (int d = 0; d < DIM; ++d) v[d] = g.uniform(-1, 1);
    for (int k = 0; k < DIM * DIM; ++k) B[k] = g.uniform(-1, 1) * H; // |C| ~ 1 / s
    const double m = g.uniform(0.5, 2.0);
    Dir<Shape> X, Y;
    eval_dir<Shape>(x[0], l[0], ORIGIN[0], X);
    eval_dir<Shape>(x[1], l[1], ORIGIN[1], Y);
    // P2G (transfers.cpp, Affine), nodal velocities, G2P
    double mi[NS][NS], pi[NS][NS][DIM];
    double P[DIM] = {0, 0}, L = 0, vb[DIM] = {0, 0}, Bb[DIM * DIM] = {0, 0, 0, 0};
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        const double w = X.w[a] * Y.w[b], a0 = X.a[a] * Y.w[b], a1 = X.w[a] * Y.a[b];
        mi[a][b] = m * w;
        pi[a][b][0] = m * (w * v[0] + B[0] * a0 + B[1] * a1);
        pi[a][b][1] = m * (w * v[1] + B[2] * a0 + B[3] * a1);
        // grid momentum and angular momentum about the particle (x_i - x_p = (r_a, r_b))
        P[0] += pi[a][b][0];
        P[1] += pi[a][b][1];
        L += X.r[a] * pi[a][b][1] - Y.r[b] * pi[a][b][0];
        if (mi[a][b] <= 0) continue;
        const double vi[DIM] = {pi[a][b][0] / mi[a][b], pi[a][b][1] / mi[a][b]};
        for (int d = 0; d < DIM; ++d) {
          vb[d] += w * vi[d];
          Bb[d * DIM + 0] += w * vi[d] * X.r[a];
          Bb[d * DIM + 1] += w * vi[d] * Y.r[b];
        }
      }
    for (int d = 0; d < DIM; ++d) {
      worst_v = std::fmax(worst_v, std::fabs(vb[d] - v[d]));
      worst_P = std::fmax(worst_P, std::fabs(P[d] / m - v[d]));
    }
    for (int k = 0; k < DIM * DIM; ++k) worst_B = std::fmax(worst_B, std::fabs(Bb[k] - B[k]) / H);
    // about the particle's centre the grid's angular momentum is the particle's spin
    worst_L = std::fmax(worst_L, std::fabs(L - affine_spin(m, B)) / (m * H));
  }
  CHECK_CLOSE(worst_v, 0.0, 1e-12);
  CHECK_CLOSE(worst_B, 0.0, 1e-12);
  CHECK_CLOSE(worst_P, 0.0, 1e-12);
  CHECK_CLOSE(worst_L, 0.0, 1e-12);
}

// The affine kinetic energy equals 1/2 m sum_i w_i |C (x_i - x_p)|^2, C = B D^-1.
template <class Shape> void test_kinetic(Lcg &g) {
  constexpr int NS = Shape::NS;
  double worst = 0;
  for (int n = 0; n < NSAMPLE; ++n) {
    double x[DIM], l[DIM], B[DIM * DIM], D[DIM];
    random_particle<Shape>(g, x, l);
    for (int k = 0; k < DIM * DIM; ++k) B[k] = g.uniform(-1, 1) * H;
    affine_inertia<Shape>(x, l, ORIGIN, H, D);
    Dir<Shape> X, Y;
    eval_dir<Shape>(x[0], l[0], ORIGIN[0], X);
    eval_dir<Shape>(x[1], l[1], ORIGIN[1], Y);
    const double C[DIM * DIM] = {B[0] / D[0], B[1] / D[1], B[2] / D[0], B[3] / D[1]};
    double e = 0;
    for (int b = 0; b < NS; ++b)
      for (int a = 0; a < NS; ++a) {
        const double u0 = C[0] * X.r[a] + C[1] * Y.r[b], u1 = C[2] * X.r[a] + C[3] * Y.r[b];
        e += 0.5 * X.w[a] * Y.w[b] * (u0 * u0 + u1 * u1);
      }
    const double k = affine_kinetic(1.0, B, D);
    worst = std::fmax(worst, std::fabs(k - e) / e);
  }
  CHECK_CLOSE(worst, 0.0, 1e-10); // relative; C = B / D amplifies by D's smallness (linear hats)
}

} // namespace

int main() {
  Lcg g;
  test_inertia_and_moments<LinearShape>(g, true);
  test_inertia_and_moments<UGIMPShape>(g, false);
  test_round_trip<LinearShape>(g);
  test_round_trip<UGIMPShape>(g);
  test_kinetic<LinearShape>(g);
  test_kinetic<UGIMPShape>(g);
  return pmpm_test::report("test_affine");
}
