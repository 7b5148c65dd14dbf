// Unit tests of the stacked multi-velocity contact kernel (contact_stack.hpp) at one node:
//   two bodies: approaching ones take the mass-weighted mean normal velocity with N = m0 (vn0 -
//     vcm), separating ones are left alone (not in contact); frictionless keeps the tangential
//     velocities, a large mu sticks, an intermediate mu slips with |S| = mu N exactly, reducing
//     (not reversing) the relative sliding; adhesion alone sticks up to its capacity and slips at
//     it beyond, and does not act across a gap;
//   bonded faces give one velocity even when separating; paper faces join the normal velocity
//     even when separating (tension, N < 0) with friction capacity mu max(N, 0) (zero in tension);
//   heavy / light (1e-6) / heavy: the normal impulse passes through the light body (N0 = N1 to
//     1e-6), the stack sticks below the weaker capacity, the weaker face slips above it, both
//     faces slip at equal mu;
//   random stacks (nb 2..5, random face types, masses 1e-6..1e3, random normals): momentum is
//     conserved, kinetic energy does not increase, no interpenetration, no tensile contact
//     impulse, |S| <= C, Coulomb's KKT conditions, and the enumeration never needs its fallback;
//     on well-conditioned stacks (masses 0.1..10) the result equals brute-force projected
//     Gauss-Seidel (20000 sweeps) on the normal and the tangential problems, and so does the
//     kernel's own fallback solver.
#include "check.hpp"
#include "pmpm/contact/contact_stack.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

using namespace pmpm;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Stack {
  int nb = 2;
  double m[8] = {};
  double v[16] = {};
  StackFace f[7];
  double n[2] = {0, 1};
  StackFaceResult res[7];
  bool fallback = false;
  void set(int i, double vn, double vt) { // body i's velocity from its components
    v[2 * i] = vn * n[0] - vt * n[1];
    v[2 * i + 1] = vn * n[1] + vt * n[0];
  }
  double vn(int i) const { return v[2 * i] * n[0] + v[2 * i + 1] * n[1]; }
  double vt(int i) const { return -v[2 * i] * n[1] + v[2 * i + 1] * n[0]; }
  void run() { contact_stack(nb, m, v, f, n, res, &fallback); }
};

double momentum(const Stack &s, int c) {
  double p = 0;
  for (int i = 0; i < s.nb; ++i) p += s.m[i] * s.v[2 * i + c];
  return p;
}
double momentum_scale(const Stack &s) {
  double p = 0;
  for (int i = 0; i < s.nb; ++i) p += s.m[i] * std::hypot(s.v[2 * i], s.v[2 * i + 1]);
  return p;
}
double energy(const Stack &s) {
  double e = 0;
  for (int i = 0; i < s.nb; ++i)
    e += 0.5 * s.m[i] * (s.v[2 * i] * s.v[2 * i] + s.v[2 * i + 1] * s.v[2 * i + 1]);
  return e;
}

// Brute force: min sum_i m_i/2 (w_i + (x_i - x_{i-1}) / m_i)^2, lo_k <= x_k <= hi_k, x_k acting
// +x on body k and -x on body k+1, by projected Gauss-Seidel over the faces (w: in trial, out new).
void chain_pgs(int nb, const double *m, double *w, const double *lo, const double *hi, double *x,
               int sweeps) {
  for (int k = 0; k < nb - 1; ++k) x[k] = 0;
  for (int s = 0; s < sweeps; ++s) {
    double change = 0;
    for (int k = 0; k < nb - 1; ++k) {
      const double d = (w[k + 1] - w[k]) / (1 / m[k] + 1 / m[k + 1]);
      const double xn = std::min(std::max(x[k] + d, lo[k]), hi[k]), dx = xn - x[k];
      w[k] += dx / m[k];
      w[k + 1] -= dx / m[k + 1];
      x[k] = xn;
      change = std::max(change, std::fabs(dx));
    }
    if (change == 0) break; // a fixed point in floating point
  }
}

double capacity(const StackFace &f, const StackFaceResult &r) {
  if (f.type == FaceType::Bonded) return kInf;
  return r.contact ? f.mu * std::max(r.normal, 0.0) + f.adhesion : 0.0;
}

void test_two_bodies_normal() {
  Stack s;
  s.n[0] = 0.6;
  s.n[1] = 0.8;
  s.m[0] = 2;
  s.m[1] = 3;
  s.set(0, 1.0, 0.3);
  s.set(1, -0.5, -0.2);
  const double p0[2] = {momentum(s, 0), momentum(s, 1)}, scale = momentum_scale(s);
  s.run();
  const double vcm = (2 * 1.0 + 3 * -0.5) / 5; // 0.1
  // velocities recovered through n and t: a few ulps of |v| ~ 1
  CHECK_CLOSE(s.vn(0), vcm, 1e-15);
  CHECK_CLOSE(s.vn(1), vcm, 1e-15);
  CHECK_CLOSE(s.vt(0), 0.3, 1e-15); // mu = 0: tangential untouched
  CHECK_CLOSE(s.vt(1), -0.2, 1e-15);
  CHECK_CLOSE(s.res[0].normal, 2 * (1.0 - vcm), 1e-15); // N = m0 (vn0 - vcm) = 1.8
  CHECK(s.res[0].contact);
  CHECK(s.res[0].slip); // frictionless: free sliding
  CHECK(s.res[0].tangential == 0.0);
  CHECK(!s.fallback);
  CHECK_CLOSE(momentum(s, 0), p0[0], 1e-14 * scale);
  CHECK_CLOSE(momentum(s, 1), p0[1], 1e-14 * scale);

  // separating: untouched to the bit, not in contact
  Stack q = s;
  q.set(0, -1.0, 0.3);
  q.set(1, 0.5, -0.2);
  q.f[0].mu = 0.8;
  q.f[0].adhesion = 5; // no adhesion across a gap
  double v0[4];
  std::copy(q.v, q.v + 4, v0);
  q.run();
  CHECK(std::equal(v0, v0 + 4, q.v));
  CHECK(!q.res[0].contact);
  CHECK(!q.res[0].slip);
  CHECK(q.res[0].normal == 0.0);
  CHECK(q.res[0].tangential == 0.0);

  // one body: nothing to do
  Stack one;
  one.nb = 1;
  one.m[0] = 1;
  one.v[0] = 0.25;
  one.v[1] = -3;
  one.run();
  CHECK(one.v[0] == 0.25 && one.v[1] == -3);
  bool threw = false;
  try {
    contact_stack(9, one.m, one.v, one.f, one.n, one.res);
  } catch (const std::invalid_argument &) {
    threw = true;
  }
  CHECK(threw);
}

// m = (2, 3), vn = (1, -0.5): N = 1.8; vt = (0, 1): the impulse that sticks is m0 m1 / (m0 + m1)
// * 1 = 1.2 on the lower body, leaving both at vt_cm = 0.6.
Stack friction_pair(double mu, double adhesion) {
  Stack s;
  const double a = 0.3;
  s.n[0] = std::sin(a);
  s.n[1] = std::cos(a);
  s.m[0] = 2;
  s.m[1] = 3;
  s.set(0, 1.0, 0.0);
  s.set(1, -0.5, 1.0);
  s.f[0].mu = mu;
  s.f[0].adhesion = adhesion;
  s.run();
  return s;
}

void test_friction_pair() {
  const double N = 1.8, stick = 1.2;
  Stack s = friction_pair(0.0, 0.0); // frictionless
  CHECK_CLOSE(s.vt(0), 0.0, 1e-15);
  CHECK_CLOSE(s.vt(1), 1.0, 1e-15);
  CHECK(s.res[0].slip);

  s = friction_pair(10.0, 0.0); // capacity 18 > 1.2: stick at the centre-of-mass velocity
  CHECK_CLOSE(s.res[0].normal, N, 1e-15);
  CHECK_CLOSE(s.res[0].tangential, stick, 1e-15);
  CHECK_CLOSE(s.vt(0), 0.6, 1e-15);
  CHECK_CLOSE(s.vt(1), 0.6, 1e-15);
  CHECK(s.res[0].contact && !s.res[0].slip);

  const double mu = 0.5; // capacity 0.9 < 1.2: slip with S = mu N
  s = friction_pair(mu, 0.0);
  // S = C = mu N + 0: exactly, up to an ulp where the compiler fuses the multiply-add
  CHECK_CLOSE(s.res[0].tangential, mu * s.res[0].normal, 1e-16);
  CHECK_CLOSE(s.res[0].tangential, 0.9, 1e-15);
  CHECK(s.res[0].slip);
  CHECK_CLOSE(s.vt(0), 0.9 / 2, 1e-15);
  CHECK_CLOSE(s.vt(1), 1.0 - 0.9 / 3, 1e-15);
  const double rel = s.vt(1) - s.vt(0); // 1 - 0.9 (1/2 + 1/3) = 0.25: reduced, not reversed
  CHECK_CLOSE(rel, 0.25, 1e-15);
  CHECK(rel > 0 && rel < 1);
  CHECK(!s.fallback);

  // adhesion alone: stick while 1.2 <= a, slip with |S| = a beyond
  s = friction_pair(0.0, 1.5);
  CHECK_CLOSE(s.res[0].tangential, stick, 1e-15);
  CHECK(!s.res[0].slip);
  CHECK_CLOSE(s.vt(1) - s.vt(0), 0.0, 1e-15);
  s = friction_pair(0.0, 0.7);
  CHECK_CLOSE(s.res[0].tangential, 0.7, 0.0); // 0 * N + 0.7
  CHECK(s.res[0].slip);
  CHECK_CLOSE(s.vt(1) - s.vt(0), 1.0 - 0.7 * (1.0 / 2 + 1.0 / 3), 1e-15);
  s = friction_pair(0.5, 0.2); // both: capacity mu N + a = 1.1
  CHECK_CLOSE(s.res[0].tangential, 0.5 * s.res[0].normal + 0.2, 1e-15);
}

void test_bonded_paper() {
  // three bonded bodies flying apart: one velocity, the centre of mass's
  Stack s;
  s.nb = 3;
  s.n[0] = -0.8;
  s.n[1] = 0.6;
  const double m[3] = {1, 2, 3}, vn[3] = {-1, 0.5, 2}, vt[3] = {0.4, -0.3, 0.7};
  double pn = 0, pt = 0;
  for (int i = 0; i < 3; ++i) {
    s.m[i] = m[i];
    s.set(i, vn[i], vt[i]);
    s.f[i].type = FaceType::Bonded;
    pn += m[i] * vn[i];
    pt += m[i] * vt[i];
  }
  s.run();
  for (int i = 0; i < 3; ++i) {
    CHECK_CLOSE(s.vn(i), pn / 6, 1e-15);
    CHECK_CLOSE(s.vt(i), pt / 6, 1e-15);
  }
  // N_k = sum_{i <= k} m_i (vn_i - V): tension here
  CHECK_CLOSE(s.res[0].normal, 1 * (-1 - pn / 6), 1e-15);
  CHECK_CLOSE(s.res[1].normal, 1 * (-1 - pn / 6) + 2 * (0.5 - pn / 6), 1e-15);
  CHECK(s.res[0].contact && s.res[1].contact && !s.res[0].slip && !s.res[1].slip);

  // paper, separating: normal joined (N = -1 < 0), friction capacity mu max(N, 0) = 0
  Stack p;
  p.m[0] = p.m[1] = 1;
  p.f[0].type = FaceType::Paper;
  p.f[0].mu = 0.5;
  p.set(0, -1.0, 0.0);
  p.set(1, 1.0, 1.0);
  p.run();
  CHECK_CLOSE(p.vn(0), 0.0, 1e-15);
  CHECK_CLOSE(p.vn(1), 0.0, 1e-15);
  CHECK_CLOSE(p.res[0].normal, -1.0, 1e-15);
  CHECK(p.res[0].contact);
  CHECK(p.res[0].tangential == 0.0);
  CHECK_CLOSE(p.vt(0), 0.0, 1e-15);
  CHECK_CLOSE(p.vt(1), 1.0, 1e-15);
  CHECK(p.res[0].slip); // free: no capacity in tension
  // ... with adhesion 0.3 the capacity in tension is the adhesion (stick would need 0.5)
  p.f[0].adhesion = 0.3;
  p.set(0, -1.0, 0.0);
  p.set(1, 1.0, 1.0);
  p.run();
  CHECK_CLOSE(p.res[0].tangential, 0.3, 0.0);
  // paper pressed: like contact, capacity mu N = 0.4 * 1 < 0.5 needed to stick: slips at it
  p.f[0].adhesion = 0;
  p.set(0, 1.0, 0.0);
  p.set(1, -1.0, 1.0);
  p.f[0].mu = 0.4;
  p.run();
  CHECK_CLOSE(p.res[0].normal, 1.0, 1e-15);
  CHECK_CLOSE(p.res[0].tangential, 0.4, 1e-15);
  CHECK(p.res[0].slip);
  // contact type, same separating state: released
  p.f[0].type = FaceType::Contact;
  p.set(0, -1.0, 0.0);
  p.set(1, 1.0, 1.0);
  p.run();
  CHECK(!p.res[0].contact && p.res[0].normal == 0.0);
  CHECK_CLOSE(p.vn(0), -1.0, 1e-15);
}

// Heavy (1) / light (1e-6) / heavy (1): the top comes down at 1 and slides along t at u over the
// bottom at rest; the membrane is at rest.
Stack hlh(double mu_b, double mu_t, double u) {
  Stack s;
  s.nb = 3;
  s.n[0] = std::sin(-0.4);
  s.n[1] = std::cos(-0.4);
  s.m[0] = 1;
  s.m[1] = 1e-6;
  s.m[2] = 1;
  s.set(0, 0, 0);
  s.set(1, 0, 0);
  s.set(2, -1, u);
  s.f[0].mu = mu_b;
  s.f[1].mu = mu_t;
  s.run();
  return s;
}

void test_heavy_light_heavy() {
  const double M = 2 + 1e-6, V = -1 / M; // all three join at the centre-of-mass velocity
  Stack s = hlh(0.4, 0.6, 0.3);
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(s.vn(i), V, 1e-15);
  CHECK(s.res[0].contact && s.res[1].contact);
  const double N0 = s.res[0].normal, N1 = s.res[1].normal;
  CHECK_CLOSE(N0, 1 / M, 1e-15);
  CHECK_CLOSE(N1, N0, 1e-5 * N0);        // through the light body: differ by m1 |V| = 5e-7
  CHECK_CLOSE(N1 - N0, 1e-6 / M, 1e-15); // exactly that (round-off of N0 ~ 1e-16)
  // demand u / M ~ 0.15 < min capacity 0.4 N0 ~ 0.2: the stack sticks
  for (int i = 0; i < 3; ++i) CHECK_CLOSE(s.vt(i), 0.3 / M, 1e-15);
  CHECK(!s.res[0].slip && !s.res[1].slip && !s.fallback);
  CHECK_CLOSE(s.res[0].tangential, 0.3 / M, 1e-15);

  // demand ~0.5 > 0.4 N0: the weaker bottom face slips, the membrane rides with the top
  s = hlh(0.4, 0.6, 1.0);
  CHECK(s.res[0].slip && !s.res[1].slip && !s.fallback);
  const double S0 = 0.4 * N0;
  CHECK_CLOSE(s.res[0].tangential, S0, 1e-16); // = C0 to an ulp (fused multiply-add)
  CHECK_CLOSE(s.vt(0), S0, 1e-15);
  CHECK_CLOSE(s.vt(1), (1.0 - S0) / (1 + 1e-6), 1e-15);
  CHECK_CLOSE(s.vt(2), s.vt(1), 1e-15);
  CHECK(std::fabs(s.res[1].tangential) <= 0.6 * s.res[1].normal);
  // weaker top face: the membrane stays with the bottom, the top face slips
  s = hlh(0.6, 0.4, 1.0);
  CHECK(!s.res[0].slip && s.res[1].slip && !s.fallback);
  CHECK_CLOSE(s.res[1].tangential, 0.4 * N1, 1e-16); // = C1 to an ulp
  CHECK_CLOSE(s.vt(0), s.vt(1), 1e-15);
  CHECK_CLOSE(s.vt(0), 0.4 * N1 / (1 + 1e-6), 1e-15);
  CHECK_CLOSE(s.vt(2), 1.0 - 0.4 * N1, 1e-15);
  // equal mu, demand above: the top face slips (S1 = mu N1); the membrane, driven by mu N1 from
  // above, could slide on the bottom only if mu N1 - mu N0 exceeded what keeps it level with the
  // bottom; N1 - N0 = m1 |V| makes that an exact tie: the membrane and the bottom both move at
  // mu N0 / m0 = mu |V|, the bottom face at its capacity (stuck or slipping: the same impulses).
  // Round-off: impulses ~0.2 over the membrane's mass 1e-6 ~ 1e-10 in its velocity.
  s = hlh(0.4, 0.4, 1.0);
  CHECK(s.res[1].slip && !s.fallback);
  CHECK_CLOSE(s.res[1].tangential, 0.4 * s.res[1].normal, 1e-16);
  CHECK_CLOSE(std::fabs(s.res[0].tangential), 0.4 * s.res[0].normal, 1e-15);
  CHECK_CLOSE(s.vt(0), 0.4 / M, 1e-15);
  CHECK_CLOSE(s.vt(1), 0.4 / M, 1e-9);
  CHECK_CLOSE(s.vt(2), 1.0 - 0.4 * s.res[1].normal, 1e-15);
}

// A random stack: nb 2..5, a random normal, masses log-uniform in 1e-6..1e3 (0.1..10 if
// well_conditioned), velocities in [-1, 1]^2, face types, mu and adhesion at random.
void random_stack(pmpm_test::Lcg &r, Stack &s, bool well_conditioned) {
  s.nb = 2 + static_cast<int>(r.next() * 4); // 2..5
  const double a = r.uniform(0, 2 * 3.14159265358979);
  s.n[0] = std::cos(a);
  s.n[1] = std::sin(a);
  for (int i = 0; i < s.nb; ++i) {
    s.m[i] = well_conditioned ? r.uniform(0.1, 10) : std::pow(10.0, r.uniform(-6, 3));
    s.v[2 * i] = r.uniform(-1, 1);
    s.v[2 * i + 1] = r.uniform(-1, 1);
  }
  for (int k = 0; k < s.nb - 1; ++k) {
    const double c = r.next();
    s.f[k].type = c < 0.2 ? FaceType::Bonded : c < 0.4 ? FaceType::Paper : FaceType::Contact;
    s.f[k].mu = r.next() < 0.2 ? 0.0 : r.uniform(0, 1.2);
    // adhesion on the scale of the lighter neighbour's momentum (sometimes much more)
    const double ml = std::min(s.m[k], s.m[k + 1]);
    s.f[k].adhesion = r.next() < 0.5 ? 0.0 : ml * std::pow(10.0, r.uniform(-2, 1));
  }
}

void test_random() {
  pmpm_test::Lcg r(0xC0FFEEull);
  int fallbacks = 0, cases = 0, slips = 0, sticks = 0, separations = 0;
  double worst_pgs = 0, worst_fallback = 0;
  for (int c = 0; c < 6000; ++c) {
    const bool well = c % 3 == 0;
    Stack s0;
    random_stack(r, s0, well);
    Stack s = s0;
    s.run();
    ++cases;
    if (s.fallback) ++fallbacks;
    const int nb = s.nb;
    double vmax = 0, pscale = momentum_scale(s0) + momentum_scale(s);
    for (int i = 0; i < nb; ++i)
      vmax = std::max(
          {vmax, std::hypot(s0.v[2 * i], s0.v[2 * i + 1]), std::hypot(s.v[2 * i], s.v[2 * i + 1])});
    // momentum: each impulse acts on two bodies with opposite signs; round-off of the sums
    for (int d = 0; d < 2; ++d) CHECK_CLOSE(momentum(s, d), momentum(s0, d), 1e-12 * pscale);
    // energy: both steps are projections; round-off relative to the energy moved about
    CHECK(energy(s) <= energy(s0) * (1 + 1e-12) + 1e-13 * pscale * vmax);
    for (int k = 0; k < nb - 1; ++k) {
      const StackFace &f = s.f[k];
      const StackFaceResult &q = s.res[k];
      // round-off: velocities are recovered through n and t (ulps of vmax); impulses of size
      // `imp` acting on the lighter body perturb its velocity by ulps of imp / m
      double imp = 0;
      for (int j = std::max(k - 1, 0); j <= std::min(k + 1, nb - 2); ++j)
        imp = std::max({imp, std::fabs(s.res[j].normal), std::fabs(s.res[j].tangential)});
      const double tolv = 1e-12 * (vmax + imp / std::min(s.m[k], s.m[k + 1]));
      const double reln = s.vn(k + 1) - s.vn(k), relt = s.vt(k + 1) - s.vt(k);
      if (f.type == FaceType::Contact) {
        CHECK(reln >= -1e-13 * vmax); // no interpenetration
        CHECK(q.normal >= -1e-13 * pscale);
        if (q.contact)
          CHECK_CLOSE(reln, 0.0, 1e-13 * vmax);
        else
          separations++;
      } else {
        CHECK(q.contact);
        CHECK_CLOSE(reln, 0.0, 1e-13 * vmax);
      }
      if (!q.contact) {
        CHECK(q.normal == 0.0 && q.tangential == 0.0 && !q.slip);
        continue;
      }
      const double C = capacity(f, q), S = q.tangential;
      if (f.type == FaceType::Bonded) {
        CHECK(!q.slip);
        CHECK_CLOSE(relt, 0.0, tolv);
        continue;
      }
      CHECK(std::fabs(S) <= C * (1 + 1e-12));
      if (C == 0) {
        CHECK(S == 0.0 && q.slip);
      } else if (!q.slip) { // stuck: common velocity
        ++sticks;
        CHECK_CLOSE(relt, 0.0, tolv);
      } else { // slipping at the capacity, against the sliding
        ++slips;
        CHECK_CLOSE(std::fabs(S), C, 1e-15 * C);
        CHECK(S > 0 ? relt >= -tolv : relt <= tolv);
      }
    }
    if (!well) continue;

    // Brute force on the same stack: normal, then tangential over the kernel's capacities.
    double wn[8], wt[8], m[8], lo[7], hi[7], x[7];
    for (int i = 0; i < nb; ++i) {
      wn[i] = s0.vn(i);
      wt[i] = s0.vt(i);
      m[i] = s0.m[i];
    }
    for (int k = 0; k < nb - 1; ++k) { // x = -N: compression <= 0 at contact faces
      lo[k] = -kInf;
      hi[k] = s0.f[k].type == FaceType::Contact ? 0.0 : kInf;
    }
    chain_pgs(nb, m, wn, lo, hi, x, 20000);
    double err = 0;
    for (int k = 0; k < nb - 1; ++k) err = std::max(err, std::fabs(-x[k] - s.res[k].normal));
    double cap[7], S[7];
    for (int k = 0; k < nb - 1; ++k) {
      cap[k] = capacity(s.f[k], s.res[k]);
      lo[k] = -cap[k];
      hi[k] = cap[k];
    }
    double wt2[8];
    std::copy(wt, wt + nb, wt2);
    chain_pgs(nb, m, wt, lo, hi, x, 20000);
    for (int i = 0; i < nb; ++i)
      err = std::max({err, std::fabs(wn[i] - s.vn(i)), std::fabs(wt[i] - s.vt(i))});
    worst_pgs = std::max(worst_pgs, err);
    CHECK(err <= 1e-8); // velocities ~1, impulses ~10
    // the kernel's own fallback solver agrees with its enumeration
    FaceState st[7];
    stack_friction_pgs(nb, m, wt2, cap, S, st, 200000);
    double errf = 0;
    for (int i = 0; i < nb; ++i) errf = std::max(errf, std::fabs(wt2[i] - s.vt(i)));
    for (int k = 0; k < nb - 1; ++k) errf = std::max(errf, std::fabs(S[k] - s.res[k].tangential));
    worst_fallback = std::max(worst_fallback, errf);
    CHECK(errf <= 1e-8);
  }
  CHECK(fallbacks == 0); // the enumeration always found the consistent state
  CHECK(sticks > 500 && slips > 500 && separations > 500); // all regimes were exercised
  std::printf("random stacks: %d cases, %d fallbacks, %d stuck / %d slipping friction faces, %d "
              "separations; worst |kernel - PGS| %.2g, |kernel - own fallback| %.2g\n",
              cases, fallbacks, sticks, slips, separations, worst_pgs, worst_fallback);
}

} // namespace

int main() {
  test_two_bodies_normal();
  test_friction_pair();
  test_bonded_paper();
  test_heavy_light_heavy();
  test_random();
  return pmpm_test::report("contact_stack");
}
