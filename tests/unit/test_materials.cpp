// Unit tests of the plastic materials: von Mises and Drucker-Prager return maps and their
// Material::update_stress drivers. Tension positive; p = tr(sigma)/3, q = sqrt(J2) for DP.
#include "check.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/materials/von_mises.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

using namespace pmpm;

namespace {

const double INF = std::numeric_limits<double>::infinity();
// Round-off tolerance factor for closed-form returns: a handful of flops on numbers of size
// `scale` give errors of a few 1e-16 * scale; 1e-10 leaves six orders of margin.
const double RTOL = 1e-10;

// Deterministic generator (64-bit LCG), uniform in [-1, 1).
struct Lcg {
  std::uint64_t s = 0x9E3779B97F4A7C15ull;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / double(1ull << 53) * 2.0 - 1.0;
  }
};

Mat3 random_sym(Lcg &g, double amp) {
  Mat3 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) = amp * g.next();
  return 0.5 * (a + a.transpose());
}

double dp_phi(const DPCoefficients &k, double c, const Mat3 &sig) {
  const Mat3 s = stress_inv::deviator(sig);
  return stress_inv::sqrt_j2(s) + k.eta * stress_inv::mean(sig) - k.xi * c;
}

// Distance of deviator a from the line spanned by deviator b (0 when parallel).
double off_parallel(const Mat3 &a, const Mat3 &b) {
  const double bb = b.squaredNorm();
  if (bb == 0.0) return a.norm();
  return (a - (a.cwiseProduct(b).sum() / bb) * b).norm();
}

ElasticConstants elastic() {
  ElasticConstants el;
  el.E = 2.6e7; // G = 1e7, K = 2.1666...e7 with nu = 0.3
  el.nu = 0.3;
  return el;
}

// ---------------------------------------------------------------------------------------------
void test_coefficients() {
  // phi = 30 deg: sin = 1/2, cos = sqrt3/2, tan = 1/sqrt3 (hand values).
  const double s3 = std::sqrt(3.0);
  DruckerPragerParams prm;
  prm.phi_deg = 30;
  prm.psi_deg = 30;
  prm.match = DPMatch::Outer; // eta = 3/(sqrt3 * 2.5) = 0.4 sqrt3, xi = 3 sqrt3/(2.5 sqrt3) = 1.2
  DPCoefficients k = dp_coefficients(prm);
  CHECK_CLOSE(k.eta, 0.4 * s3, 1e-15);
  CHECK_CLOSE(k.xi, 1.2, 1e-15);
  CHECK_CLOSE(k.etabar, 0.4 * s3, 1e-15);
  prm.match = DPMatch::Inner; // eta = 3/(3.5 sqrt3) = 2 sqrt3/7, xi = 6/7
  k = dp_coefficients(prm);
  CHECK_CLOSE(k.eta, 2.0 * s3 / 7.0, 1e-15);
  CHECK_CLOSE(k.xi, 6.0 / 7.0, 1e-15);
  prm.match = DPMatch::PlaneStrain; // sqrt(9 + 12/3) = sqrt13: eta = sqrt(3/13), xi = 3/sqrt13
  k = dp_coefficients(prm);
  CHECK_CLOSE(k.eta, std::sqrt(3.0 / 13.0), 1e-15);
  CHECK_CLOSE(k.xi, 3.0 / std::sqrt(13.0), 1e-15);
  // etabar from psi with the same formula; psi = 0 -> 0 (no dilation).
  prm.psi_deg = 0;
  CHECK_CLOSE(dp_coefficients(prm).etabar, 0.0, 0.0);
  prm.psi_deg = 30;
  prm.phi_deg = 40; // etabar independent of phi
  CHECK_CLOSE(dp_coefficients(prm).etabar, std::sqrt(3.0 / 13.0), 1e-15);
}

// ---------------------------------------------------------------------------------------------
void test_elastic_path() {
  DruckerPragerParams dp;
  dp.el = elastic();
  dp.cohesion = 1e4;
  dp.tension_cutoff = 5e3;
  VonMisesParams vm;
  vm.el = elastic();
  vm.sigma_y0 = 2e4;
  vm.hardening = 1e5;
  Lcg g;
  int n_dp = 0, n_vm = 0;
  for (int it = 0; it < 200; ++it) {
    const Mat3 sig0 = random_sym(g, 1e4) - 2e4 * g.next() * Mat3::Identity();
    const DPCoefficients k = dp_coefficients(dp);
    if (dp_phi(k, dp.cohesion, sig0) < 0 && stress_inv::mean(sig0) < dp.tension_cutoff) {
      Mat3 sig = sig0;
      double ep = 0.3;
      const ReturnResult r = drucker_prager_return(dp, sig, ep);
      CHECK(!r.yielded);
      CHECK((sig.array() == sig0.array()).all()); // bit for bit
      CHECK(ep == 0.3);
      ++n_dp;
    }
    const double q = std::sqrt(3.0) * stress_inv::sqrt_j2(stress_inv::deviator(sig0));
    if (q < vm.sigma_y0 + vm.hardening * 0.3) {
      Mat3 sig = sig0;
      double ep = 0.3;
      const ReturnResult r = von_mises_return(vm, sig, ep);
      CHECK(!r.yielded);
      CHECK((sig.array() == sig0.array()).all());
      CHECK(ep == 0.3);
      ++n_vm;
    }
  }
  CHECK(n_dp > 20); // the sample really exercised the elastic branch
  CHECK(n_vm > 20);
}

// ---------------------------------------------------------------------------------------------
// Drucker-Prager: trial states all around the cone, every matching, associated and not, with
// and without hardening. For each returned state check admissibility, the active surface(s)
// and the flow rule, the latter through the plastic strain recovered from the elastic law:
//   d(eps^p) = C^-1 : (sigma_tr - sigma) = dev(sigma_tr - sigma)/(2G) + (p_tr - p)/(3K) I
// which on the cone must equal dgamma (s/(2 sqrt(J2)) + etabar/3 I).
void test_dp_returns() {
  const DPMatch matches[3] = {DPMatch::Outer, DPMatch::Inner, DPMatch::PlaneStrain};
  const double psis[3] = {30.0, 10.0, 0.0}; // associated, non-associated, non-dilatant
  const double hards[2] = {0.0, 2e6};
  int n_cone = 0, n_apex = 0, n_tension = 0, n_corner = 0;
  for (DPMatch m : matches)
    for (double psi : psis)
      for (double H : hards)
        for (double tcut : {INF, 2e3}) {
          DruckerPragerParams prm;
          prm.el = elastic();
          prm.cohesion = 1e4;
          prm.phi_deg = 30;
          prm.psi_deg = psi;
          prm.hardening = H;
          prm.tension_cutoff = tcut;
          prm.match = m;
          const DPCoefficients k = dp_coefficients(prm);
          const double G = prm.el.G(), K = prm.el.K();
          Lcg g;
          for (int it = 0; it < 300; ++it) {
            // deviators up to 1e5, mean stress in [-1e5, 1e5]: cone, apex and cut-off regions
            const Mat3 sig_tr =
                random_sym(g, 1e5 * std::fabs(g.next())) + 1e5 * g.next() * Mat3::Identity();
            const double ep0 = 0.01;
            Mat3 sig = sig_tr;
            double ep = ep0;
            const ReturnResult r = drucker_prager_return(prm, sig, ep);
            const double scale = std::max(sig_tr.norm(), prm.cohesion);
            const double tol = RTOL * scale;
            const double c = prm.cohesion + H * ep;
            const double p = stress_inv::mean(sig), p_tr = stress_inv::mean(sig_tr);
            const Mat3 s = stress_inv::deviator(sig), s_tr = stress_inv::deviator(sig_tr);
            const double q = stress_inv::sqrt_j2(s);
            // admissible: on or inside the cone and below the cut-off
            CHECK(dp_phi(k, c, sig) <= tol);
            CHECK(p <= tcut + tol);
            if (!r.yielded) continue;
            CHECK(r.dgamma >= 0.0);
            CHECK_CLOSE(ep - ep0, k.xi * r.dgamma, RTOL * ep0); // eps_p += xi dgamma
            CHECK(off_parallel(s, s_tr) <= RTOL * s_tr.norm()); // radial in the deviatoric plane
            const Mat3 depsp = (s_tr - s) / (2.0 * G) + (p_tr - p) / (3.0 * K) * Mat3::Identity();
            if (r.apex) {
              ++n_apex;
              CHECK(s.norm() <= tol);
              if (!r.tension) {
                CHECK_CLOSE(p, k.xi * c / k.eta, tol); // apex of the (hardened) cone
                // volumetric plastic strain etabar dgamma (psi > 0 or H > 0)
                if (psi > 0 || H > 0) CHECK_CLOSE(depsp.trace(), k.etabar * r.dgamma, RTOL);
                // the apex needs at least the deviatoric flow that removes s_tr
                CHECK(r.dgamma >= stress_inv::sqrt_j2(s_tr) / G * (1 - 1e-12));
              }
            } else if (r.tension && r.dgamma == 0.0) {
              ++n_tension; // cut-off alone: p = t, deviator untouched, eps_p unchanged
              CHECK_CLOSE(p, tcut, tol);
              CHECK((s - s_tr).norm() <= tol);
              CHECK(p_tr > tcut);
            } else if (r.tension) {
              ++n_corner; // cone and cut-off active
              CHECK_CLOSE(p, tcut, tol);
              CHECK_CLOSE(dp_phi(k, c, sig), 0.0, tol);
              // cut-off share of the volumetric plastic strain is non-negative
              CHECK(depsp.trace() - k.etabar * r.dgamma >= -RTOL);
            } else {
              ++n_cone;
              CHECK_CLOSE(dp_phi(k, c, sig), 0.0, tol);             // on the surface
              CHECK_CLOSE(p - p_tr, -K * k.etabar * r.dgamma, tol); // p = p_tr - K etabar dgamma
              // full flow rule d(eps^p) = dgamma (s/(2 sqrt J2) + etabar/3 I)
              const Mat3 n = s / (2.0 * q) + k.etabar / 3.0 * Mat3::Identity();
              CHECK((depsp - r.dgamma * n).norm() <= RTOL * (std::fabs(r.dgamma) + 1e-3));
            }
          }
        }
  // every branch was exercised
  CHECK(n_cone > 100);
  CHECK(n_apex > 20);
  CHECK(n_tension > 20);
  CHECK(n_corner > 20);
}

// Apex by hand: hydrostatic tension trial, no deviator. p_tr = 5e4, c = 1e4, outer phi = 30,
// psi = 30: eta = 0.4 sqrt3, xi = 1.2, apex p = xi c / eta = 1.2e4 / (0.4 sqrt3) = 1e4 sqrt3.
// With hardening H: dgamma = (eta p_tr - xi c)/(K eta etabar + xi^2 H), p = p_tr - K eta dgamma.
void test_dp_apex_and_cutoff() {
  DruckerPragerParams prm;
  prm.el = elastic();
  prm.cohesion = 1e4;
  prm.phi_deg = prm.psi_deg = 30;
  prm.tension_cutoff = INF;
  const double K = prm.el.K(), eta = 0.4 * std::sqrt(3.0), xi = 1.2;
  const double tol = RTOL * 5e4;
  {
    Mat3 sig = 5e4 * Mat3::Identity();
    double ep = 0;
    const ReturnResult r = drucker_prager_return(prm, sig, ep);
    CHECK(r.yielded && r.apex && !r.tension);
    CHECK_CLOSE(sig(0, 0), 1e4 * std::sqrt(3.0), tol);
    CHECK_CLOSE(sig(2, 2), 1e4 * std::sqrt(3.0), tol);
    CHECK_CLOSE(sig(0, 1), 0.0, 0.0);
    CHECK_CLOSE(r.dgamma, (eta * 5e4 - xi * 1e4) / (K * eta * eta), 1e-12 * r.dgamma);
  }
  {
    prm.hardening = 5e6;
    const double H = prm.hardening;
    Mat3 sig = 5e4 * Mat3::Identity();
    double ep = 1e-3; // c_n = 1e4 + 5e3
    const ReturnResult r = drucker_prager_return(prm, sig, ep);
    const double dg = (eta * 5e4 - xi * 1.5e4) / (K * eta * eta + xi * xi * H);
    CHECK(r.yielded && r.apex);
    CHECK_CLOSE(r.dgamma, dg, 1e-12 * dg);
    CHECK_CLOSE(ep, 1e-3 + xi * dg, 1e-15);
    CHECK_CLOSE(sig(1, 1), 5e4 - K * eta * dg, tol);
    CHECK_CLOSE(sig(1, 1), xi * (1e4 + H * ep) / eta, tol); // on the hardened apex
    prm.hardening = 0;
  }
  {
    // Non-dilatant perfectly plastic (psi = 0): no apex of the potential; p = xi c/eta.
    prm.psi_deg = 0;
    Mat3 sig = 5e4 * Mat3::Identity();
    sig(0, 1) = sig(1, 0) = 1e3;
    double ep = 0;
    const ReturnResult r = drucker_prager_return(prm, sig, ep);
    CHECK(r.apex);
    CHECK_CLOSE(sig(0, 0), 1e4 * std::sqrt(3.0), tol);
    CHECK_CLOSE(sig(0, 1), 0.0, tol);
    CHECK_CLOSE(r.dgamma, 1e3 / prm.el.G(), 1e-15); // sqrt(J2_tr) / G
    prm.psi_deg = 30;
  }
  {
    // Default cut-off t = 0 with c > 0: hydrostatic tension is cut to p = 0 (below the apex).
    DruckerPragerParams d0;
    d0.el = elastic();
    d0.cohesion = 1e4;
    Mat3 sig = 5e4 * Mat3::Identity();
    double ep = 0;
    const ReturnResult r = drucker_prager_return(d0, sig, ep);
    CHECK(r.yielded && r.tension && !r.apex);
    CHECK_CLOSE(sig.norm(), 0.0, tol);
    CHECK_CLOSE(ep, 0.0, 0.0);
    // cut-off alone: small deviator kept, p -> 0
    sig = 5e4 * Mat3::Identity();
    sig(0, 1) = sig(1, 0) = 1e3;
    const ReturnResult r2 = drucker_prager_return(d0, sig, ep);
    CHECK(r2.tension && r2.dgamma == 0.0);
    CHECK_CLOSE(sig.trace(), 0.0, tol);
    CHECK_CLOSE(sig(0, 1), 1e3, 0.0);
    // corner: large deviator (sqrt J2 = 4e4 > xi c = 1.2e4 at p = 0): p = 0, sqrt(J2) = xi c
    sig = 5e4 * Mat3::Identity();
    sig(0, 1) = sig(1, 0) = 4e4;
    const ReturnResult r3 = drucker_prager_return(d0, sig, ep);
    CHECK(r3.tension && r3.dgamma > 0.0 && !r3.apex);
    CHECK_CLOSE(sig.trace(), 0.0, tol);
    CHECK_CLOSE(sig(0, 1), 1.2e4, tol);
    CHECK_CLOSE(r3.dgamma, (4e4 - 1.2e4) / d0.el.G(), 1e-15);
  }
}

// ---------------------------------------------------------------------------------------------
void test_vm_returns() {
  for (double H : {0.0, 3e6}) {
    VonMisesParams prm;
    prm.el = elastic();
    prm.sigma_y0 = 2e4;
    prm.hardening = H;
    const double G = prm.el.G();
    Lcg g;
    int n_pl = 0;
    for (int it = 0; it < 300; ++it) {
      const Mat3 sig_tr =
          random_sym(g, 1e5 * std::fabs(g.next())) + 1e5 * g.next() * Mat3::Identity();
      Mat3 sig = sig_tr;
      const double ep0 = 0.02;
      double ep = ep0;
      const ReturnResult r = von_mises_return(prm, sig, ep);
      const double tol = RTOL * std::max(sig_tr.norm(), prm.sigma_y0);
      const Mat3 s = stress_inv::deviator(sig), s_tr = stress_inv::deviator(sig_tr);
      const double q = std::sqrt(3.0) * stress_inv::sqrt_j2(s);
      const double sy = prm.sigma_y0 + H * ep;
      CHECK(q <= sy + tol);
      if (!r.yielded) continue;
      ++n_pl;
      CHECK_CLOSE(q, sy, tol);                                           // on the surface
      CHECK_CLOSE(stress_inv::mean(sig), stress_inv::mean(sig_tr), tol); // isochoric flow
      CHECK(off_parallel(s, s_tr) <= RTOL * s_tr.norm());                // radial return
      CHECK_CLOSE(ep - ep0, r.dgamma, 1e-15);                            // eps_p += dgamma
      // flow rule: (s_tr - s)/(2G) = dgamma (3/2) s/q
      CHECK(((s_tr - s) / (2.0 * G) - 1.5 * r.dgamma * s / q).norm() <= RTOL * r.dgamma + 1e-16);
    }
    CHECK(n_pl > 100);
  }
}

// ---------------------------------------------------------------------------------------------
// Single-particle driver of Material::update_stress: one step with dudx (row-major DIM x DIM).
struct OneParticle {
  double dudx[DIM * DIM] = {0, 0, 0, 0};
  double F[DIM * DIM] = {1, 0, 0, 1};
  double stress[NSTRESS] = {0, 0, 0, 0};
  double eps_p = 0;
  int idx = 0;
  void step(const Material &m, double g00, double g01, double g10, double g11) {
    dudx[0] = g00;
    dudx[1] = g01;
    dudx[2] = g10;
    dudx[3] = g11;
    // F <- (I + L dt) F
    const double F0[4] = {F[0], F[1], F[2], F[3]};
    F[0] = (1 + g00) * F0[0] + g01 * F0[2];
    F[1] = (1 + g00) * F0[1] + g01 * F0[3];
    F[2] = g10 * F0[0] + (1 + g11) * F0[2];
    F[3] = g10 * F0[1] + (1 + g11) * F0[3];
    StressBatch b;
    b.n = 1;
    b.idx = &idx;
    b.dudx = dudx;
    b.F = F;
    b.stress = stress;
    b.eps_p = &eps_p;
    m.update_stress(b);
  }
};

// Uniaxial strain (plane strain, de = d(eps) e_x e_x) through VonMises::update_stress.
// Derivation: the elastic volumetric response is exact since the flow is isochoric: p = K eps.
// Deviatoric strain e_xx = 2 eps/3, and by symmetry s = (q/3) diag(2, -1, -1) for loading,
// with plastic strain eps^p = eps_p diag(1, -1/2, -1/2) (flow (3/2) s/q). Then
//   s_xx = 2G (2 eps/3 - eps_p)  =>  q = 3 s_xx / 2 = 2G eps - 3G eps_p.
// Elastic while 2G eps <= sigma_y0; after that q = sigma_y0 + H eps_p gives
//   eps_p = (2G eps - sigma_y0) / (3G + H),  q = sigma_y0 + H eps_p,
//   sigma_xx = K eps + 2q/3,  sigma_yy = sigma_zz = K eps - q/3,
// tangent d(sigma_xx)/d(eps) = K + (4/3) G H / (3G + H) (= M elastically, K when H = 0).
// The path is proportional (fixed deviatoric direction), so the backward-Euler radial return
// reproduces it exactly for any increment size: round-off tolerance.
void test_vm_uniaxial_strain() {
  for (double H : {0.0, 4e6}) {
    VonMisesParams prm;
    prm.el = elastic();
    prm.sigma_y0 = 2e4;
    prm.hardening = H;
    const VonMises mat(prm);
    const double G = prm.el.G(), K = prm.el.K();
    OneParticle pt;
    const double deps = 1e-4; // eps_y = sigma_y0 / 2G = 1e-3: ten elastic steps
    for (int n = 1; n <= 40; ++n) {
      pt.step(mat, deps, 0, 0, 0);
      const double eps = n * deps;
      double sxx, syy;
      if (2 * G * eps <= prm.sigma_y0) {
        sxx = prm.el.M() * eps;
        syy = prm.el.lambda() * eps;
        CHECK_CLOSE(pt.eps_p, 0.0, 0.0);
      } else {
        const double ep = (2 * G * eps - prm.sigma_y0) / (3 * G + H);
        const double q = prm.sigma_y0 + H * ep;
        sxx = K * eps + 2 * q / 3;
        syy = K * eps - q / 3;
        CHECK_CLOSE(pt.eps_p, ep, RTOL * eps);
      }
      const double tol = RTOL * std::fabs(sxx);
      CHECK_CLOSE(pt.stress[0], sxx, tol);
      CHECK_CLOSE(pt.stress[1], syy, tol);
      CHECK_CLOSE(pt.stress[2], syy, tol); // sigma_zz evolves in plane strain
      CHECK_CLOSE(pt.stress[3], 0.0, tol);
    }
  }
}

// Uniaxial stress (3D strain path, sigma_yy = sigma_zz = 0) with von_mises_return directly:
// each increment d(eps_xx) is given and the lateral strain d(eps_yy) = d(eps_zz) = x is solved
// (secant iteration, sigma_yy is piecewise linear in x) so that sigma_yy = 0. Hand solution:
// sigma = sigma_y0 + H eps_p and eps = sigma/E + eps_p (eps^p_xx = eps_p for tension), so
//   eps <= sigma_y0/E:  sigma = E eps
//   otherwise:          sigma = sigma_y0 + E H / (E + H) (eps - sigma_y0/E),  eps_p = (sigma -
//   sigma_y0)/H
// The stress stays proportional to diag(1,0,0), so the radial return is exact at any step.
void test_vm_uniaxial_stress() {
  VonMisesParams prm;
  prm.el = elastic();
  prm.sigma_y0 = 2e4;
  prm.hardening = 5e6;
  const double E = prm.el.E, H = prm.hardening;
  Mat3 sig = Mat3::Zero();
  double ep = 0, eps = 0;
  const double deps = 2.5e-4; // eps_y = sigma_y0 / E = 7.7e-4
  for (int n = 1; n <= 20; ++n) {
    auto trial = [&](double x, Mat3 &out, double &ep_out) {
      Mat3 de = Mat3::Zero();
      de(0, 0) = deps;
      de(1, 1) = de(2, 2) = x;
      out = sig + elastic_increment(prm.el, de);
      ep_out = ep;
      von_mises_return(prm, out, ep_out);
      return out(1, 1);
    };
    Mat3 s_new;
    double ep_new;
    double x0 = -prm.el.nu * deps, x1 = -0.5 * deps;
    double f0 = trial(x0, s_new, ep_new), f1 = trial(x1, s_new, ep_new);
    for (int it = 0; it < 50 && std::fabs(f1) > 1e-12 * prm.sigma_y0 && f1 != f0; ++it) {
      const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
      x0 = x1;
      f0 = f1;
      x1 = x2;
      f1 = trial(x1, s_new, ep_new);
    }
    trial(x1, s_new, ep_new);
    sig = s_new;
    ep = ep_new;
    eps += deps;
    const double want = eps <= prm.sigma_y0 / E
                            ? E * eps
                            : prm.sigma_y0 + E * H / (E + H) * (eps - prm.sigma_y0 / E);
    CHECK_CLOSE(sig(1, 1), 0.0, 1e-11 * prm.sigma_y0);
    CHECK_CLOSE(sig(2, 2), 0.0, 1e-11 * prm.sigma_y0);
    CHECK_CLOSE(sig(0, 0), want, 1e-9 * want);
    CHECK_CLOSE(ep, std::max(0.0, (want - prm.sigma_y0) / H), 1e-9 * eps);
  }
  CHECK(ep > 0.0); // the path went well into the plastic range
}

// ---------------------------------------------------------------------------------------------
// Plane-strain simple shear through Material::update_stress: dudx = [[0, dg], [0, 0]] per step,
// so de = dg/2 (e_x e_y + e_y e_x) and the spin dw = dg/2 (e_x e_y - e_y e_x) is not zero.
// In small strain only s_xy = tau develops, sqrt(J2) = |tau|, q_vm = sqrt3 |tau|. The Jaumann
// rotation adds tau dg to sigma_xx (and removes it from sigma_yy) each step: elastically this is
// the classical tau = G sin(gamma), sigma_xx = G (1 - cos gamma), i.e. relative deviations of
// O(gamma^2) from the small-strain curve; on the plateau the normal deviator reaches
// ~ tau^2/G, again a relative O((tau/G)^2) effect on tau through J2 = tau^2 + s_xx^2 + ...
// Hence the tolerance tau_ref * gamma^2 (gamma >= tau/G throughout), plus round-off.
//
// Hand curves (gamma = n dg, gamma_y = tau_y / G):
//  VM perfectly plastic: tau = G gamma up to tau_y = sigma_y / sqrt3, then tau = tau_y.
//  DP (p0 = 0): the surface is tau + eta p = xi c. With plastic multiplier Gamma (total),
//    tau = G (gamma - Gamma), p = -K etabar Gamma  =>  Gamma = (G gamma - xi c)/(G + K eta etabar)
//    tau = xi c + h (gamma - gamma_y),  h = G K eta etabar / (G + K eta etabar),  gamma_y = xi c/G
//    eps_p = xi Gamma. psi = 0: plateau tau = xi c, p = 0.
struct ShearCurve {
  std::vector<double> tau, p, ep;
};

ShearCurve run_shear(const Material &m, double dg, int nsteps) {
  ShearCurve c;
  OneParticle pt;
  for (int n = 0; n < nsteps; ++n) {
    pt.step(m, 0, dg, 0, 0);
    c.tau.push_back(pt.stress[3]);
    c.p.push_back((pt.stress[0] + pt.stress[1] + pt.stress[2]) / 3.0);
    c.ep.push_back(pt.eps_p);
  }
  CHECK_CLOSE(pt.F[1], nsteps * dg, 1e-15); // F = [[1, gamma], [0, 1]]
  return c;
}

void test_simple_shear() {
  const double dg = 1e-4;
  const int nsteps = 60; // gamma up to 6e-3, several times gamma_y ~ 1e-3
  {
    VonMisesParams prm;
    prm.el = elastic();
    prm.sigma_y0 = 2e4 * std::sqrt(3.0); // tau_y = 2e4, gamma_y = 2e-3
    const VonMises mat(prm);
    const double G = prm.el.G(), tau_y = 2e4;
    const ShearCurve c = run_shear(mat, dg, nsteps);
    for (int n : {4, 9, 19, 24, 39, 59}) {
      const double gam = (n + 1) * dg;
      const double want = std::min(G * gam, tau_y);
      CHECK_CLOSE(c.tau[n], want, want * gam * gam + RTOL * tau_y);
      CHECK_CLOSE(c.p[n], 0.0, RTOL * tau_y); // Jaumann rotation and J2 flow keep tr(sigma)
    }
    CHECK(c.ep[15] == 0.0);
    CHECK(c.ep[59] > 0.0);
  }
  for (double psi : {0.0, 10.0, 30.0}) {
    DruckerPragerParams prm;
    prm.el = elastic();
    prm.cohesion = 1e4;
    prm.phi_deg = 30;
    prm.psi_deg = psi;
    prm.match = DPMatch::PlaneStrain;
    prm.tension_cutoff = INF;
    const DruckerPrager mat(prm);
    const DPCoefficients k = mat.coefficients();
    const double G = prm.el.G(), K = prm.el.K();
    const double tau_y = k.xi * prm.cohesion, gam_y = tau_y / G;
    const double h = G * K * k.eta * k.etabar / (G + K * k.eta * k.etabar);
    const ShearCurve c = run_shear(mat, dg, nsteps);
    double p_sum = 0; // accumulated -K etabar dgamma, dgamma = d(eps_p)/xi per step
    for (int n = 0; n < nsteps; ++n) {
      const double gam = (n + 1) * dg;
      const double dgam = (c.ep[n] - (n ? c.ep[n - 1] : 0.0)) / k.xi;
      p_sum += -K * k.etabar * dgam;
      CHECK_CLOSE(c.p[n], p_sum, RTOL * tau_y);
      const double Gam = std::max(0.0, (G * gam - tau_y) / (G + K * k.eta * k.etabar));
      const double tau = gam <= gam_y ? G * gam : tau_y + h * (gam - gam_y);
      const double tol = tau * gam * gam + RTOL * tau_y;
      CHECK_CLOSE(c.tau[n], tau, tol);
      CHECK_CLOSE(c.p[n], -K * k.etabar * Gam, K * k.etabar * tol / G + RTOL * tau_y);
      CHECK_CLOSE(c.ep[n], k.xi * Gam, tol / G);
    }
    // plateau xi c; tolerance gamma_max^2 = 3.6e-5 relative (see the comment above)
    if (psi == 0.0) CHECK_CLOSE(c.tau[nsteps - 1], tau_y, tau_y * 4e-5);
    CHECK(c.ep[nsteps - 1] > 0.0);
  }
}

void test_material_interface() {
  VonMisesParams vm;
  vm.el = elastic();
  DruckerPragerParams dp;
  dp.el = elastic();
  const VonMises a(vm);
  const DruckerPrager b(dp);
  CHECK(std::string(a.model()) == "von_mises");
  CHECK(std::string(b.model()) == "drucker_prager");
  CHECK(a.plastic() && b.plastic());
  CHECK_CLOSE(a.wave_modulus(), vm.el.M(), 0.0);
  CHECK_CLOSE(b.wave_modulus(), dp.el.M(), 0.0);
}

} // namespace

int main() {
  test_coefficients();
  test_elastic_path();
  test_dp_returns();
  test_dp_apex_and_cutoff();
  test_vm_returns();
  test_vm_uniaxial_strain();
  test_vm_uniaxial_stress();
  test_simple_shear();
  test_material_interface();
  return pmpm_test::report("test_materials");
}
