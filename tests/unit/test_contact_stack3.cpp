// Unit tests of the stacked contact in 3D (contact_stack.hpp, contact_stack3: the friction cone):
//   planar motion (every tangential velocity along one direction of the plane) gives the 2D
//     kernel's answer to round-off, on 3,000 random stacks;
//   the answer turns with the stack: velocities rotated about the normal give the rotated answer;
//   two bodies sliding obliquely: the impulse is mu N along the relative sliding, which it reduces
//     and does not reverse (the closed form of two bodies: the relative tangential velocity
//     shrinks by mu N (1/m0 + 1/m1) along itself);
//   heavy / light (1e-6) / heavy with the top body pushed along (1, 0, 1) in the plane: pushed
//     gently the stack sticks; pushed hard the weaker face (below or above the sheet) slides at
//     its capacity along the push and the sheet moves with the body across the stronger face;
//   random stacks (nb 2..5, random face types, masses 1e-6..1e3, random normals, velocities in
//     3D): momentum conserved, kinetic energy not increased, no interpenetration, |S| <= C,
//     Coulomb's law as a cone (stuck faces move together, sliding ones carry |S| = C along the
//     relative sliding velocity), and the enumeration never needs its fallback; on
//     well-conditioned stacks (masses 0.1..10) the tangential answer equals projected block
//     Gauss-Seidel run to convergence, an independent solve of the same energy.
#include "check.hpp"
#include "pmpm/contact/contact_stack.hpp"
#include <algorithm>
#include <cmath>

using namespace pmpm;

namespace {

struct Stack3 {
  int nb = 2;
  double m[8] = {}, v[24] = {}, n[3] = {0, 1, 0};
  StackFace f[7];
  StackFaceResult3 res[7];
  bool fallback = false;
  void run() { contact_stack3(nb, m, v, f, n, res, &fallback); }
  double dot(int i, const double *a) const {
    return v[3 * i] * a[0] + v[3 * i + 1] * a[1] + v[3 * i + 2] * a[2];
  }
  double vn(int i) const { return dot(i, n); }
  // the tangential velocity of body i (3 components)
  void vt(int i, double t[3]) const {
    for (int d = 0; d < 3; ++d) t[d] = v[3 * i + d] - vn(i) * n[d];
  }
};

double norm3(const double *a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

double capacity(const StackFace &f, const StackFaceResult3 &q) {
  return f.mu * std::max(q.normal, 0.0) + f.adhesion;
}

void random_stack(pmpm_test::Lcg &r, Stack3 &s, bool well) {
  s.nb = 2 + static_cast<int>(r.next() * 4);
  const double a = r.uniform(0, 2 * M_PI), z = r.uniform(-1, 1);
  s.n[0] = std::sqrt(1 - z * z) * std::cos(a);
  s.n[1] = std::sqrt(1 - z * z) * std::sin(a);
  s.n[2] = z;
  for (int i = 0; i < s.nb; ++i) {
    s.m[i] = well ? r.uniform(0.1, 10) : std::pow(10.0, r.uniform(-6, 3));
    for (int d = 0; d < 3; ++d) s.v[3 * i + d] = r.uniform(-1, 1);
  }
  for (int k = 0; k < s.nb - 1; ++k) {
    const double c = r.next();
    s.f[k].type = c < 0.2 ? FaceType::Bonded : c < 0.4 ? FaceType::Paper : FaceType::Contact;
    s.f[k].mu = r.next() < 0.2 ? 0.0 : r.uniform(0, 1.2);
    const double ml = std::min(s.m[k], s.m[k + 1]);
    s.f[k].adhesion = r.next() < 0.5 ? 0.0 : ml * std::pow(10.0, r.uniform(-2, 1));
  }
}

// 1. planar motion: the 2D kernel's answer
void test_planar() {
  pmpm_test::Lcg r(0xBEEFull);
  double worst = 0;
  for (int c = 0; c < 3000; ++c) {
    Stack3 s;
    random_stack(r, s, c % 2 == 0);
    // the normal in the x-y plane, the motion in it too (z components 0)
    const double a = r.uniform(0, 2 * M_PI);
    s.n[0] = std::cos(a);
    s.n[1] = std::sin(a);
    s.n[2] = 0;
    double v2[16], n2[2] = {s.n[0], s.n[1]}, vmax = 0;
    StackFaceResult r2[7];
    for (int i = 0; i < s.nb; ++i) {
      s.v[3 * i + 2] = 0;
      v2[2 * i] = s.v[3 * i];
      v2[2 * i + 1] = s.v[3 * i + 1];
      vmax = std::max(vmax, std::hypot(v2[2 * i], v2[2 * i + 1]));
    }
    contact_stack(s.nb, s.m, v2, s.f, n2, r2);
    s.run();
    double pscale = 0; // the momenta summed: the impulses' round-off scale
    for (int i = 0; i < s.nb; ++i) pscale += s.m[i] * std::hypot(v2[2 * i], v2[2 * i + 1]);
    for (int i = 0; i < s.nb; ++i) {
      // an impulse of size I moves the lightest body by I / m: the round-off scale
      const double tol = 1e-9 * (vmax + pscale / s.m[i]);
      const double e =
          std::max({std::fabs(s.v[3 * i] - v2[2 * i]), std::fabs(s.v[3 * i + 1] - v2[2 * i + 1]),
                    std::fabs(s.v[3 * i + 2])});
      CHECK(e <= tol);
      worst = std::max(worst, e / tol);
    }
    for (int k = 0; k + 1 < s.nb; ++k) {
      CHECK(s.res[k].contact == r2[k].contact);
      CHECK_CLOSE(s.res[k].normal, r2[k].normal, 1e-12 * pscale);
      // the 2D impulse is along t = (-n_y, n_x) on the lower body
      const double t[2] = {-n2[1], n2[0]}, T = r2[k].tangential;
      const double scale = 1e-10 * pscale;
      CHECK_CLOSE(s.res[k].tangential[0], T * t[0], scale);
      CHECK_CLOSE(s.res[k].tangential[1], T * t[1], scale);
    }
  }
  std::printf("planar: worst velocity difference %.2g of its bound\n", worst);
}

// 2. rotation about the normal
void test_rotation() {
  pmpm_test::Lcg r(0x5EEDull);
  for (int c = 0; c < 500; ++c) {
    Stack3 s;
    random_stack(r, s, true);
    s.n[0] = s.n[2] = 0;
    s.n[1] = 1;
    Stack3 q = s;
    const double a = r.uniform(0, 2 * M_PI), ca = std::cos(a), sa = std::sin(a);
    for (int i = 0; i < s.nb; ++i) { // rotate about y
      const double x = s.v[3 * i], z = s.v[3 * i + 2];
      q.v[3 * i] = ca * x + sa * z;
      q.v[3 * i + 2] = -sa * x + ca * z;
    }
    s.run();
    q.run();
    for (int i = 0; i < s.nb; ++i) {
      const double x = s.v[3 * i], z = s.v[3 * i + 2];
      CHECK_CLOSE(q.v[3 * i], ca * x + sa * z, 1e-10);
      CHECK_CLOSE(q.v[3 * i + 1], s.v[3 * i + 1], 1e-10);
      CHECK_CLOSE(q.v[3 * i + 2], -sa * x + ca * z, 1e-10);
    }
  }
}

// 3. two bodies sliding obliquely
void test_two_bodies() {
  Stack3 s;
  s.m[0] = 2;
  s.m[1] = 1;
  s.f[0].type = FaceType::Contact;
  s.f[0].mu = 0.3;
  // approaching along y (N = m0 m1 / (m0 + m1) * 1 = 2/3), sliding along (3, 0, 4) / 5 at 1
  const double v0[3] = {0, 0.5, 0}, v1[3] = {0.6, -0.5, 0.8};
  for (int d = 0; d < 3; ++d) {
    s.v[d] = v0[d];
    s.v[3 + d] = v1[d];
  }
  s.run();
  CHECK(!s.fallback && s.res[0].contact && s.res[0].slip);
  const double N = 2.0 / 3.0, C = 0.3 * N;
  CHECK_CLOSE(s.res[0].normal, N, 1e-15);
  // the impulse on the lower body: C along the sliding (0.6, 0, 0.8)
  CHECK_CLOSE(s.res[0].tangential[0], C * 0.6, 1e-14);
  CHECK_CLOSE(s.res[0].tangential[1], 0.0, 1e-14);
  CHECK_CLOSE(s.res[0].tangential[2], C * 0.8, 1e-14);
  // the relative sliding shrinks along itself by C (1/m0 + 1/m1) = 0.3
  const double rel = 1.0 - C * (0.5 + 1.0);
  CHECK_CLOSE(s.v[3] - s.v[0], rel * 0.6, 1e-14);
  CHECK_CLOSE(s.v[5] - s.v[2], rel * 0.8, 1e-14);
  CHECK_CLOSE(s.v[1], s.v[4], 1e-15);
  // a large mu sticks: one tangential velocity, the mass-weighted mean
  s = Stack3();
  s.m[0] = 2;
  s.m[1] = 1;
  s.f[0].mu = 5;
  for (int d = 0; d < 3; ++d) {
    s.v[d] = v0[d];
    s.v[3 + d] = v1[d];
  }
  s.run();
  CHECK(!s.res[0].slip);
  CHECK_CLOSE(s.v[0], 0.2, 1e-15);
  CHECK_CLOSE(s.v[3], 0.2, 1e-15);
  CHECK_CLOSE(s.v[2], 0.8 / 3, 1e-15);
  CHECK_CLOSE(s.v[5], 0.8 / 3, 1e-15);
}

// 4. heavy / light / heavy: the top body presses down (vn -1, N = 0.5 through the light sheet)
//    and is pushed along (1, 0, 1) / sqrt 2 in the plane
void test_sheet_between() {
  struct Case {
    double push, mu_lo, mu_hi;
  };
  for (const Case k : {Case{0.1, 0.2, 0.5}, Case{10, 0.2, 0.5}, Case{10, 0.5, 0.2}}) {
    Stack3 s;
    s.nb = 3;
    s.m[0] = 1;
    s.m[1] = 1e-6;
    s.m[2] = 1;
    s.f[0].mu = k.mu_lo;
    s.f[1].mu = k.mu_hi;
    s.v[6] = k.push / std::sqrt(2.0);
    s.v[7] = -1;
    s.v[8] = k.push / std::sqrt(2.0);
    s.run();
    CHECK(!s.fallback);
    const double N = s.res[0].normal;
    CHECK_CLOSE(N, 0.5, 1e-6); // the light sheet passes the normal impulse on
    CHECK_CLOSE(s.res[1].normal, N, 1e-6);
    if (k.push < 1) {
      // 0.1: sticking needs about m_red push = 0.05 < 0.2 N = 0.1: one velocity, the mean
      CHECK(!s.res[0].slip && !s.res[1].slip);
      const double mean = 0.1 / std::sqrt(2.0) / (2 + 1e-6);
      for (int i = 0; i < 3; ++i) {
        CHECK_CLOSE(s.v[3 * i], mean, 1e-11); // the sheet: round-off of 0.1 over 1e-6
        CHECK_CLOSE(s.v[3 * i + 2], mean, 1e-11);
      }
      continue;
    }
    // 10: the weaker face slides at its capacity along (1, 0, 1) / sqrt 2, the sheet stays with
    // the body across the stronger one, both faces carry the same impulse (the sheet is light)
    const int weak = k.mu_lo < k.mu_hi ? 0 : 1, strong = 1 - weak;
    const double Cw = std::min(k.mu_lo, k.mu_hi) * s.res[weak].normal;
    CHECK(s.res[weak].slip && !s.res[strong].slip);
    CHECK_CLOSE(norm3(s.res[weak].tangential), Cw, 1e-12 * Cw);
    CHECK_CLOSE(s.res[weak].tangential[0], s.res[weak].tangential[2], 1e-12 * Cw);
    CHECK(s.res[weak].tangential[0] > 0);
    // the sheet's own momentum change (1e-6 x 9.9 m/s) is the difference
    CHECK_CLOSE(norm3(s.res[strong].tangential), Cw, 1e-6 * 10);
    const int with = weak == 0 ? 2 : 0; // the body the sheet moves with
    CHECK_CLOSE(s.v[3], s.v[3 * with], 1e-9);
    CHECK_CLOSE(s.v[5], s.v[3 * with + 2], 1e-9);
  }
}

// 5. random stacks
void test_random() {
  pmpm_test::Lcg r(0xC0FFEEull);
  int fallbacks = 0, slips = 0, sticks = 0;
  double worst_pgs = 0;
  for (int c = 0; c < 6000; ++c) {
    const bool well = c % 3 == 0;
    Stack3 s0;
    random_stack(r, s0, well);
    Stack3 s = s0;
    s.run();
    fallbacks += s.fallback;
    const int nb = s.nb;
    double vmax = 0, pscale = 0, e0 = 0, e1 = 0;
    for (int i = 0; i < nb; ++i) {
      vmax = std::max({vmax, norm3(&s0.v[3 * i]), norm3(&s.v[3 * i])});
      pscale += s0.m[i] * (norm3(&s0.v[3 * i]) + norm3(&s.v[3 * i]));
      e0 += 0.5 * s0.m[i] * std::pow(norm3(&s0.v[3 * i]), 2);
      e1 += 0.5 * s.m[i] * std::pow(norm3(&s.v[3 * i]), 2);
    }
    for (int d = 0; d < 3; ++d) {
      double p0 = 0, p1 = 0;
      for (int i = 0; i < nb; ++i) {
        p0 += s0.m[i] * s0.v[3 * i + d];
        p1 += s.m[i] * s.v[3 * i + d];
      }
      CHECK_CLOSE(p1, p0, 1e-12 * pscale);
    }
    CHECK(e1 <= e0 * (1 + 1e-12) + 1e-13 * pscale * vmax);
    for (int k = 0; k < nb - 1; ++k) {
      const StackFace &f = s.f[k];
      const StackFaceResult3 &q = s.res[k];
      double imp = 0;
      for (int j = std::max(k - 1, 0); j <= std::min(k + 1, nb - 2); ++j)
        imp = std::max({imp, std::fabs(s.res[j].normal), norm3(s.res[j].tangential)});
      // impulses are sums of the stack's momenta: their round-off moves a light body by it over
      // its mass
      const double tolv = 1e-9 * (vmax + pscale / std::min(s.m[k], s.m[k + 1]));
      const double reln = s.vn(k + 1) - s.vn(k);
      double ta[3], tb[3], rel[3];
      s.vt(k, ta);
      s.vt(k + 1, tb);
      for (int d = 0; d < 3; ++d) rel[d] = tb[d] - ta[d];
      if (f.type == FaceType::Contact) {
        CHECK(reln >= -1e-12 * (vmax + imp / std::min(s.m[k], s.m[k + 1])));
        CHECK(q.normal >= -1e-13 * pscale);
      } else {
        CHECK(q.contact);
      }
      if (!q.contact) {
        CHECK(q.normal == 0.0 && norm3(q.tangential) == 0.0 && !q.slip);
        continue;
      }
      const double C = capacity(f, q), S = norm3(q.tangential);
      if (f.type == FaceType::Bonded) {
        CHECK(!q.slip);
        CHECK(norm3(rel) <= tolv);
        continue;
      }
      CHECK(S <= C * (1 + 1e-9) + 1e-300);
      if (C == 0) {
        CHECK(S == 0.0 && q.slip);
      } else if (!q.slip) {
        ++sticks;
        CHECK(norm3(rel) <= tolv);
      } else { // sliding: |S| = C along the relative sliding (the lower body pulled along)
        ++slips;
        CHECK_CLOSE(S, C, 1e-9 * C);
        const double along =
            (q.tangential[0] * rel[0] + q.tangential[1] * rel[1] + q.tangential[2] * rel[2]);
        CHECK(along >= (1 - 1e-6) * S * norm3(rel) - tolv * S);
      }
    }
    if (!well) continue;
    // an independent solve: projected block Gauss-Seidel on the same capacities
    const double N[3] = {s.n[0], s.n[1], s.n[2]};
    double t1[3], t2[3];
    {
      const double a[3] = {std::fabs(N[0]) < 0.9 ? 1.0 : 0.0, std::fabs(N[0]) < 0.9 ? 0.0 : 1.0,
                           0.0};
      const double dn = a[0] * N[0] + a[1] * N[1] + a[2] * N[2];
      for (int d = 0; d < 3; ++d) t1[d] = a[d] - dn * N[d];
      const double l = norm3(t1);
      for (int d = 0; d < 3; ++d) t1[d] /= l;
      t2[0] = N[1] * t1[2] - N[2] * t1[1];
      t2[1] = N[2] * t1[0] - N[0] * t1[2];
      t2[2] = N[0] * t1[1] - N[1] * t1[0];
    }
    double vt[16], cap[7], S[14];
    for (int i = 0; i < nb; ++i) {
      vt[2 * i] = s0.v[3 * i] * t1[0] + s0.v[3 * i + 1] * t1[1] + s0.v[3 * i + 2] * t1[2];
      vt[2 * i + 1] = s0.v[3 * i] * t2[0] + s0.v[3 * i + 1] * t2[1] + s0.v[3 * i + 2] * t2[2];
    }
    for (int k = 0; k < nb - 1; ++k)
      cap[k] = s.f[k].type == FaceType::Bonded ? INFINITY
               : s.res[k].contact              ? capacity(s.f[k], s.res[k])
                                               : 0.0;
    stack_friction_cone_pgs(nb, s.m, vt, cap, S, nullptr, 400000);
    for (int i = 0; i < nb; ++i) {
      double ta[3];
      s.vt(i, ta);
      const double a = ta[0] * t1[0] + ta[1] * t1[1] + ta[2] * t1[2],
                   b = ta[0] * t2[0] + ta[1] * t2[1] + ta[2] * t2[2];
      const double e = std::hypot(a - vt[2 * i], b - vt[2 * i + 1]);
      CHECK(e <= 1e-7 * (vmax + 1));
      worst_pgs = std::max(worst_pgs, e);
    }
  }
  CHECK(fallbacks == 0);
  CHECK(slips > 500 && sticks > 500);
  std::printf("random: %d sliding and %d stuck faces, %d fallbacks, worst against Gauss-Seidel "
              "%.2g\n",
              slips, sticks, fallbacks, worst_pgs);
}
} // namespace

int main() {
  test_planar();
  test_rotation();
  test_two_bodies();
  test_sheet_between();
  test_random();
  return pmpm_test::report("test_contact_stack3");
}
