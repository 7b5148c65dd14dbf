// Drucker-Prager elastoplasticity (associated or not) with linear isotropic hardening of the
// cohesion and a tension cut-off on the mean stress. Closed-form return map, no iteration.
//
// Sources: de Souza Neto, Peric & Owen (2008), ch. 8 (DP return mapping, cone and apex);
// Simo & Hughes (1998), ch. 3; docs/method.md, section 4. Tension positive throughout:
//   p = tr(sigma)/3, s = dev(sigma), J2 = s:s/2, q = sqrt(J2) (NOT sqrt(3 J2) here)
//   yield      Phi = sqrt(J2) + eta p - xi c(eps_p),       c = cohesion + H eps_p
//   potential  Psi = sqrt(J2) + etabar p                   (etabar from psi; = eta if psi = phi)
//   flow       d(eps^p) = dgamma (s / (2 sqrt(J2)) + etabar/3 I)   (smooth part of the cone)
//
// Equivalent plastic strain (the hardening variable, as in de Souza Neto et al. ch. 8):
//   cone : eps_p += xi dgamma
//   apex : eps_p += (xi / etabar) d(eps_v^p) = xi dgamma, where dgamma := d(eps_v^p) / etabar
// i.e. always eps_p += xi dgamma. The tension cut-off flow (purely volumetric, p = t) does NOT
// contribute to eps_p: the cut-off is a separate, perfectly plastic mechanism.
//
// Tension cut-off: second surface Phi_t = p - t <= 0, t = DruckerPragerParams::tension_cutoff,
// associated (purely volumetric) flow. Together with the cone apex this enforces
//   p <= min(t, xi c / eta).
// Note the default t = 0: no tensile mean stress is carried, even with c > 0. Set t = +infinity
// (std::numeric_limits<double>::infinity()) to disable the cut-off.
//
// Valid parameter range assumed (not checked): 0 <= psi <= phi < 90 deg, H >= 0, c >= 0.
#pragma once
#include "pmpm/materials/material.hpp"
#include "pmpm/materials/return_map.hpp"
#include <petscsys.h>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace pmpm {

// Matching of the DP cone to the Mohr-Coulomb pyramid (de Souza Neto et al. 2008, ch. 6):
//   Outer (compressive meridians coincide):  eta = 6 sin(phi) / (sqrt3 (3 - sin(phi)))
//                                            xi  = 6 cos(phi) / (sqrt3 (3 - sin(phi)))
//   Inner (tensile meridians coincide):      same with (3 + sin(phi))
//   PlaneStrain (same plane-strain collapse load, associated flow):
//                                            eta = 3 tan(phi) / sqrt(9 + 12 tan^2(phi))
//                                            xi  = 3 / sqrt(9 + 12 tan^2(phi))
// etabar uses the same formula as eta with phi -> psi.
enum class DPMatch { Outer, Inner, PlaneStrain };

struct DruckerPragerParams {
  ElasticConstants el;
  double cohesion = 0;       // c at eps_p = 0
  double phi_deg = 30;       // friction angle
  double psi_deg = 0;        // dilation angle (non-associated when != phi)
  double hardening = 0;      // H = dc/d(eps_p), linear isotropic hardening of the cohesion
  double tension_cutoff = 0; // t: max mean stress p (tension positive); p <= min(t, xi c/eta)
  DPMatch match = DPMatch::Outer;
};

struct DPCoefficients {
  double eta, xi, etabar;
};

// eta-type coefficient of the chosen matching for an angle in radians (friction or dilation).
inline double dp_eta_of(double angle, DPMatch m) {
  const double sq3 = std::sqrt(3.0);
  switch (m) {
  case DPMatch::Outer:
    return 6.0 * std::sin(angle) / (sq3 * (3.0 - std::sin(angle)));
  case DPMatch::Inner:
    return 6.0 * std::sin(angle) / (sq3 * (3.0 + std::sin(angle)));
  case DPMatch::PlaneStrain:
  default: {
    const double t = std::tan(angle);
    return 3.0 * t / std::sqrt(9.0 + 12.0 * t * t);
  }
  }
}

inline DPCoefficients dp_coefficients(const DruckerPragerParams &prm) {
  const double deg = 3.14159265358979323846 / 180.0;
  const double phi = prm.phi_deg * deg, psi = prm.psi_deg * deg;
  const double sq3 = std::sqrt(3.0);
  double xi = 0;
  switch (prm.match) {
  case DPMatch::Outer:
    xi = 6.0 * std::cos(phi) / (sq3 * (3.0 - std::sin(phi)));
    break;
  case DPMatch::Inner:
    xi = 6.0 * std::cos(phi) / (sq3 * (3.0 + std::sin(phi)));
    break;
  case DPMatch::PlaneStrain: {
    const double t = std::tan(phi);
    xi = 3.0 / std::sqrt(9.0 + 12.0 * t * t);
    break;
  }
  }
  return {dp_eta_of(phi, prm.match), xi, dp_eta_of(psi, prm.match)};
}

// Return map with precomputed coefficients (the Material caches them). Algorithm, each
// candidate accepted only if its Kuhn-Tucker conditions hold (closest-point structure, so the
// first admissible candidate is the solution for H >= 0):
//  0. elastic   : Phi_tr <= 0 and p_tr <= t -> sigma unchanged.
//  1. cone      : dgamma = Phi_tr / (G + K eta etabar + xi^2 H)
//                 s = (1 - G dgamma / sqrt(J2_tr)) s_tr,  p = p_tr - K etabar dgamma
//                 valid if sqrt(J2_tr) - G dgamma >= 0 and p <= t.
//  2. cut-off   : p = t, s = s_tr; valid if p_tr > t and sqrt(J2_tr) + eta t - xi c_n <= 0.
//  3. corner    : cone and cut-off both active, p = t, sqrt(J2) = xi c - eta t:
//                 sqrt(J2_tr) - G dgamma = xi (c_n + H xi dgamma) - eta t
//                 => dgamma = (sqrt(J2_tr) + eta t - xi c_n) / (G + xi^2 H);
//                 cut-off volumetric plastic strain (p_tr - t)/K - etabar dgamma must be >= 0,
//                 and sqrt(J2) >= 0 (the cut-off lies below the apex).
//  4. apex      : s = 0, p = xi c / eta with c = c_n + H xi dgamma and
//                 p = p_tr - K etabar dgamma (volumetric plastic strain etabar dgamma), so
//                 dgamma = (eta p_tr - xi c_n) / (K eta etabar + xi^2 H)   (exact, closed form;
//                 de Souza Neto ch. 8 apex return with d(eps_v^p) = etabar dgamma). If K eta etabar
//                 + xi^2 H = 0 (psi = 0, H = 0) the potential has no apex: p = xi c_n / eta and
//                 dgamma = sqrt(J2_tr)/G, the least multiplier that removes the deviator. If the
//                 apex lies above the cut-off (possible only through hardening within the step), p
//                 is finally clamped to t.
inline ReturnResult drucker_prager_return(const DruckerPragerParams &prm, const DPCoefficients &k,
                                          Mat3 &sigma, double &eps_p) {
  ReturnResult r;
  const Mat3 I = Mat3::Identity();
  const double G = prm.el.G(), K = prm.el.K(), H = prm.hardening, t = prm.tension_cutoff;
  const double eta = k.eta, xi = k.xi, etabar = k.etabar;
  const double c_n = prm.cohesion + H * eps_p;
  const double p_tr = stress_inv::mean(sigma);
  const Mat3 s_tr = sigma - p_tr * I;
  const double q_tr = stress_inv::sqrt_j2(s_tr);
  const double phi_tr = q_tr + eta * p_tr - xi * c_n;
  if (phi_tr <= 0.0 && p_tr <= t) return r; // 0. elastic
  r.yielded = true;

  if (phi_tr > 0.0) { // 1. smooth part of the cone
    const double dgamma = phi_tr / (G + K * eta * etabar + xi * xi * H);
    const double q = q_tr - G * dgamma;
    const double p = p_tr - K * etabar * dgamma;
    if (q >= 0.0 && p <= t) {
      // dgamma > 0 and q >= 0 imply q_tr > 0.
      sigma = (q / q_tr) * s_tr + p * I;
      eps_p += xi * dgamma;
      r.dgamma = dgamma;
      return r;
    }
  }
  if (p_tr > t) {
    const double phi_t = q_tr + eta * t - xi * c_n; // cone at p = t, trial deviator
    if (phi_t <= 0.0) {                             // 2. cut-off alone
      sigma = s_tr + t * I;
      r.tension = true;
      return r;
    }
    const double dgamma = phi_t / (G + xi * xi * H); // 3. corner cone / cut-off
    const double q = q_tr - G * dgamma;
    const double dev_t = (p_tr - t) / K - etabar * dgamma;
    if (q >= 0.0 && dev_t >= 0.0) {
      sigma = (q / q_tr) * s_tr + t * I;
      eps_p += xi * dgamma;
      r.dgamma = dgamma;
      r.tension = true;
      return r;
    }
  }
  // 4. apex
  const double denom = K * eta * etabar + xi * xi * H;
  double dgamma, p;
  if (denom > 0.0) {
    dgamma = (eta * p_tr - xi * c_n) / denom;
    p = p_tr - K * etabar * dgamma;
  } else {
    dgamma = q_tr / G;
    p = xi * c_n / eta;
  }
  if (p > t) {
    p = t;
    r.tension = true;
  }
  sigma = p * I;
  eps_p += xi * dgamma;
  r.apex = true;
  r.dgamma = dgamma;
  return r;
}

// sigma: in = trial stress (3x3 symmetric, tension positive), out = returned stress.
// eps_p accumulates xi dgamma (see the header comment). On an elastic step sigma and eps_p are
// left untouched (bit for bit).
inline ReturnResult drucker_prager_return(const DruckerPragerParams &prm, Mat3 &sigma,
                                          double &eps_p) {
  return drucker_prager_return(prm, dp_coefficients(prm), sigma, eps_p);
}

// d sigma / d sigma_tr of drucker_prager_return at the trial stress sigma_tr and the committed
// eps_p, branch by branch (the branch is the return map's own, read from its ReturnResult; de
// Souza Neto et al. 2008 box 8.7 written on the trial stress instead of the trial strain). With
// n = s_tr / |s_tr|, q_tr = sqrt(J2_tr) = |s_tr| / sqrt2, d q_tr = n : ds / sqrt2,
// d p_tr = tr(ds) / 3 and ReturnDerivative's form a dev + b n n: + c n tr/3 + d I n: + e I tr/3:
//   elastic : a = e = 1
//   cone    : A = G + K eta etabar + xi^2 H, d dgamma = (d q_tr + eta d p_tr) / A,
//             sigma = (q / q_tr) s_tr + p I, q = q_tr - G dgamma, p = p_tr - K etabar dgamma:
//             a = q / q_tr, b = G (dgamma / q_tr - 1 / A), c = -sqrt2 G eta / A,
//             d = -K etabar / (sqrt2 A), e = 1 - K eta etabar / A
//   cut-off : sigma = s_tr + t I: a = 1
//   corner  : A = G + xi^2 H, d dgamma = d q_tr / A: a = q / q_tr, b = G (dgamma / q_tr - 1 / A)
//   apex    : sigma = p I, p = p_tr - K etabar (eta p_tr - xi c_n) / (K eta etabar + xi^2 H):
//             e = xi^2 H / (K eta etabar + xi^2 H) (= 1 - K eta etabar / denominator); 0 when the
//             apex is fixed (psi = 0 and H = 0: p = xi c_n / eta) or clamped to the cut-off.
//             D : C = K (1 - K eta etabar / (K eta etabar + xi^2 H)) 1 (x) 1, no deviatoric part.
// A trial stress on the cone to round-off (kOnSurface; the return leaves it elastic) takes the
// cone's derivative with dgamma = 0, the loading side (as von_mises_return_derivative).
// (src/materials/drucker_prager_derivative.cpp)
ReturnDerivative drucker_prager_return_derivative(const DruckerPragerParams &prm,
                                                  const DPCoefficients &k, const Mat3 &sigma_tr,
                                                  double eps_p);

// Hypoelastic-plastic Drucker-Prager material: Jaumann-rotate the old stress, add the elastic
// increment C:de (trial), then return (same as LinearElastic plus the return map).
class DruckerPrager final : public Material {
public:
  static constexpr const char *kName = "drucker_prager";
  static constexpr bool kRateForm = true, kPlastic = true;
  // its el is not an option (set by Create); no tension cut-off unless -tension_cutoff is given
  struct Options : DruckerPragerParams {
    Options() { tension_cutoff = std::numeric_limits<double>::infinity(); }
  };
  // -cohesion, -friction_angle, -dilation_angle, -hardening, -tension_cutoff, -match
  // (src/materials/drucker_prager.cpp)
  static PetscErrorCode ReadOptions(PetscOptionItems *items, Options &o);
  static PetscErrorCode Create(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                               const Options &o, std::unique_ptr<Material> &model);
  explicit DruckerPrager(const DruckerPragerParams &prm) : prm_(prm), k_(dp_coefficients(prm)) {}
  const char *model() const override { return kName; }
  bool has_tangent() const override { return true; }
  void piola_tangent(const TangentPoint &pt, double *A) const override { tangent<DIM>(pt, A); }
  void piola_tangent3(const TangentPoint &pt, double *A) const override { tangent<3>(pt, A); }
  double wave_modulus() const override { return prm_.el.M(); }
  bool rate_form() const override { return kRateForm; }
  bool plastic() const override { return kPlastic; }
  bool dilatant() const override { return prm_.psi_deg > 0; }
  const DruckerPragerParams &params() const { return prm_; }
  const DPCoefficients &coefficients() const { return k_; }
  void update_stress(const StressBatch &b) const override {
    predictor_corrector(b, prm_.el,
                        [this](Mat3 &s, double &ep) { drucker_prager_return(prm_, k_, s, ep); });
  }

private:
  // the consistent tangent in D dimensions (piola_tangent, piola_tangent3)
  template <int D> void tangent(const TangentPoint &pt, double *A) const;
  DruckerPragerParams prm_;
  DPCoefficients k_;
};

} // namespace pmpm
