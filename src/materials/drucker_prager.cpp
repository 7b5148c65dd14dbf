// Drucker-Prager: its options, their checks, and its Newton tangent.
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/registry.hpp"
#include "pmpm/materials/tangent.hpp"
#include "pmpm/util/options.hpp"

namespace pmpm {

namespace {
const char *const DPMatchNames[] = {"outer", "inner", "plane_strain", "DPMatch", "DP_", nullptr};
}

PetscErrorCode DruckerPrager::ReadOptions(PetscOptionItems *PetscOptionsObject, Options &dp) {
  PetscFunctionBeginUser;
  PetscCall(PmpmOptionsReal("-cohesion", "drucker_prager: cohesion c (Pa), >= 0", nullptr,
                            dp.cohesion, &dp.cohesion, nullptr));
  PetscCall(PmpmOptionsReal("-friction_angle",
                            "drucker_prager: friction angle phi (degrees), 0..60", nullptr,
                            dp.phi_deg, &dp.phi_deg, nullptr));
  PetscCall(PmpmOptionsReal("-dilation_angle",
                            "drucker_prager: dilation angle psi (degrees), 0..phi", nullptr,
                            dp.psi_deg, &dp.psi_deg, nullptr));
  PetscCall(PmpmOptionsReal("-hardening",
                            "drucker_prager: linear hardening of the cohesion dc/deps_p (Pa), >= 0",
                            nullptr, dp.hardening, &dp.hardening, nullptr));
  PetscCall(PmpmOptionsReal("-tension_cutoff",
                            "drucker_prager: largest mean stress p (Pa, tension > 0); "
                            "default none",
                            nullptr, dp.tension_cutoff, &dp.tension_cutoff, nullptr));
  PetscCall(
      PmpmOptionsEnum("-match", "drucker_prager: Mohr-Coulomb matching: outer, inner, plane_strain",
                      nullptr, DPMatchNames, (PetscEnum)dp.match, (PetscEnum *)&dp.match, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode DruckerPrager::Create(MPI_Comm comm, const std::string &prefix,
                                     const ElasticConstants &el, const Options &o,
                                     std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  PmpmCheckInput(o.cohesion >= 0 && o.cohesion <= kMaxModulus, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%scohesion must be in [0, %g] Pa (got %g)", prefix.c_str(), kMaxModulus,
                 o.cohesion);
  PmpmCheckInput(o.phi_deg >= 0 && o.phi_deg <= 60, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sfriction_angle must be in [0, 60] degrees (got %g)", prefix.c_str(),
                 o.phi_deg);
  PmpmCheckInput(o.psi_deg >= 0 && o.psi_deg <= o.phi_deg, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sdilation_angle must be in [0, friction_angle] (got %g)", prefix.c_str(),
                 o.psi_deg);
  PmpmCheckInput(o.hardening >= 0 && o.hardening <= kMaxModulus, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%shardening must be in [0, %g] Pa (got %g)", prefix.c_str(), kMaxModulus,
                 o.hardening);
  PmpmCheckInput(o.phi_deg > 0 || o.cohesion > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%scohesion and -%sfriction_angle cannot both be 0", prefix.c_str(),
                 prefix.c_str());
  DruckerPragerParams dp = o;
  dp.el = el;
  model = std::make_unique<DruckerPrager>(dp);
  PetscFunctionReturn(0);
}

template <int D> void DruckerPrager::tangent(const TangentPoint &pt, double *A) const {
  const TangentKinematicsT<D> k(pt);
  const ReturnDerivative R =
      drucker_prager_return_derivative(prm_, k_, trial_stress<D>(prm_.el, k, pt), pt.eps_p);
  plastic_piola_tangent<D>(prm_.el, k, pt, R, A);
}

template void DruckerPrager::tangent<2>(const TangentPoint &, double *) const;
template void DruckerPrager::tangent<3>(const TangentPoint &, double *) const;

} // namespace pmpm
