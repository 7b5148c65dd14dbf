// von Mises: its options, their checks, and its Newton tangent.
#include "pmpm/materials/von_mises.hpp"
#include "pmpm/materials/registry.hpp"
#include "pmpm/materials/tangent.hpp"
#include "pmpm/util/options.hpp"

namespace pmpm {

PetscErrorCode VonMises::ReadOptions(PetscOptionItems *PetscOptionsObject, Options &vm) {
  PetscFunctionBeginUser;
  PetscCall(PmpmOptionsReal("-yield_stress", "von_mises: initial yield stress (Pa), > 0", nullptr,
                            vm.sigma_y0, &vm.sigma_y0, nullptr));
  PetscCall(PmpmOptionsReal("-hardening",
                            "von_mises: linear isotropic hardening modulus H (Pa), >= 0", nullptr,
                            vm.hardening, &vm.hardening, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode VonMises::Create(MPI_Comm comm, const std::string &prefix,
                                const ElasticConstants &el, const Options &o,
                                std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  PmpmCheckInput(o.sigma_y0 > 0 && o.sigma_y0 <= kMaxModulus, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%syield_stress must be in (0, %g] Pa (got %g)", prefix.c_str(), kMaxModulus,
                 o.sigma_y0);
  PmpmCheckInput(o.hardening >= 0 && o.hardening <= kMaxModulus, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%shardening must be in [0, %g] Pa (got %g)", prefix.c_str(), kMaxModulus,
                 o.hardening);
  VonMisesParams vm = o;
  vm.el = el;
  model = std::make_unique<VonMises>(vm);
  PetscFunctionReturn(0);
}

template <int D> void VonMises::tangent(const TangentPoint &pt, double *A) const {
  const TangentKinematicsT<D> k(pt);
  const ReturnDerivative R =
      von_mises_return_derivative(prm_, trial_stress<D>(prm_.el, k, pt), pt.eps_p);
  plastic_piola_tangent<D>(prm_.el, k, pt, R, A);
}

template void VonMises::tangent<2>(const TangentPoint &, double *) const;
template void VonMises::tangent<3>(const TangentPoint &, double *) const;

} // namespace pmpm
