// Von Mises (J2) elastoplasticity with linear isotropic hardening, closed-form radial return.
//
// Simo & Hughes (1998), ch. 3 (radial return); de Souza Neto, Peric & Owen (2008), ch. 7.
//   q = sqrt(3 J2),  Phi = q - sigma_y(eps_p),  sigma_y = sigma_y0 + H eps_p.
// Associated flow d(eps^p) = dgamma (3/2) s/q, so the equivalent plastic strain
// eps_p = int sqrt(2/3 d(eps^p):d(eps^p)) increases by exactly dgamma. With linear hardening
// the consistency condition q_tr - 3G dgamma - sigma_y0 - H (eps_p + dgamma) = 0 is linear:
//   dgamma = Phi_tr / (3G + H),  s = (1 - 3G dgamma / q_tr) s_tr,  p = p_tr.
#pragma once
#include "pmpm/materials/material.hpp"
#include "pmpm/materials/return_map.hpp"
#include <petscsys.h>
#include <memory>
#include <string>

namespace pmpm {

struct VonMisesParams {
  ElasticConstants el;
  double sigma_y0 = 0;  // initial uniaxial yield stress
  double hardening = 0; // H = d(sigma_y)/d(eps_p); expected H > -3G
};

// sigma: in = trial stress (3x3 symmetric, tension positive), out = returned stress.
// eps_p: equivalent plastic strain (accumulated, += dgamma). On an elastic step sigma and eps_p
// are left untouched (bit for bit).
inline ReturnResult von_mises_return(const VonMisesParams &prm, Mat3 &sigma, double &eps_p) {
  ReturnResult r;
  const double p_tr = stress_inv::mean(sigma);
  const Mat3 s_tr = sigma - p_tr * Mat3::Identity();
  const double q_tr = std::sqrt(3.0) * stress_inv::sqrt_j2(s_tr);
  const double phi_tr = q_tr - (prm.sigma_y0 + prm.hardening * eps_p);
  if (phi_tr <= 0.0) return r;
  const double G = prm.el.G();
  const double dgamma = phi_tr / (3.0 * G + prm.hardening);
  // phi_tr > 0 implies q_tr > 0 whenever sigma_y >= 0, so the division is safe.
  sigma = (1.0 - 3.0 * G * dgamma / q_tr) * s_tr + p_tr * Mat3::Identity();
  eps_p += dgamma;
  r.yielded = true;
  r.dgamma = dgamma;
  return r;
}

// d sigma / d sigma_tr of von_mises_return at the trial stress sigma_tr and the committed eps_p
// (the consistent tangent, Simo & Hughes 1998 box 3.2; de Souza Neto et al. 2008 eq. 7.120):
// elastic: the identity; plastic, with n = s_tr / |s_tr| and dgamma = Phi_tr / (3G + H):
//   D : ds = (1 - 3G dgamma / q_tr) dev(ds) - 3G (1 / (3G + H) - dgamma / q_tr) n (n : ds)
//            + I tr(ds) / 3,
// so that D : C = C - 6G^2 dgamma / q_tr I_dev + 6G^2 (dgamma / q_tr - 1 / (3G + H)) n (x) n.
// A trial stress on the yield surface (Phi_tr within kOnSurface of sigma_y: a particle that
// yielded in the last load step, at the next one's start) takes the loading side's derivative,
// dgamma = 0 (the return is not differentiable there; this is the continuum tangent).
// (src/materials/von_mises_derivative.cpp)
ReturnDerivative von_mises_return_derivative(const VonMisesParams &prm, const Mat3 &sigma_tr,
                                             double eps_p);

// Hypoelastic-plastic von Mises material: Jaumann-rotate the old stress, add the elastic
// increment C:de (trial), then return (same as LinearElastic plus the return map).
class VonMises final : public Material {
public:
  static constexpr const char *kName = "von_mises";
  static constexpr bool kRateForm = true, kPlastic = true;
  using Options = VonMisesParams; // its el is not an option (set by Create)
  // -yield_stress, -hardening (src/materials/von_mises.cpp)
  static PetscErrorCode ReadOptions(PetscOptionItems *items, Options &o);
  static PetscErrorCode Create(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                               const Options &o, std::unique_ptr<Material> &model);
  explicit VonMises(const VonMisesParams &prm) : prm_(prm) {}
  const char *model() const override { return kName; }
  bool has_tangent() const override { return true; }
  void piola_tangent(const TangentPoint &pt, double *A) const override { tangent<DIM>(pt, A); }
  void piola_tangent3(const TangentPoint &pt, double *A) const override { tangent<3>(pt, A); }
  double wave_modulus() const override { return prm_.el.M(); }
  bool rate_form() const override { return kRateForm; }
  bool plastic() const override { return kPlastic; }
  const VonMisesParams &params() const { return prm_; }
  void update_stress(const StressBatch &b) const override {
    predictor_corrector(b, prm_.el, [this](Mat3 &s, double &ep) { von_mises_return(prm_, s, ep); });
  }

private:
  // the consistent tangent in D dimensions (piola_tangent, piola_tangent3)
  template <int D> void tangent(const TangentPoint &pt, double *A) const;
  VonMisesParams prm_;
};

} // namespace pmpm
