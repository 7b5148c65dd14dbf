// Linear elastic and neo-Hookean: no options of their own (-E and -nu are every material's), and
// their Newton tangents (materials/tangent.hpp).
#include "pmpm/materials/elastic.hpp"
#include "pmpm/materials/tangent.hpp"

namespace pmpm {

PetscErrorCode LinearElastic::Create(MPI_Comm, const std::string &, const ElasticConstants &el,
                                     const Options &, std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  model = std::make_unique<LinearElastic>(el);
  PetscFunctionReturn(0);
}

// The Jaumann update is linear in Gm: ds = dW s - s dW + lambda tr(dGm) I + 2 mu sym(dGm), with s
// the committed stress.
template <int D> void LinearElastic::tangent(const TangentPoint &pt, double *A) const {
  using M = MatD<D>;
  const TangentKinematicsT<D> k(pt);
  const double lam = c_.lambda(), mu = c_.G();
  piola_directions<D>(
      [&](const M &dG) {
        const M dGm = k.Hi * dG * k.Hi;
        const M dW = 0.5 * (dGm - dGm.transpose()), de = 0.5 * (dGm + dGm.transpose());
        const M ds = dW * k.so - k.so * dW + lam * dGm.trace() * k.I + 2.0 * mu * de;
        return k.rate_form_dP(dG, ds);
      },
      A);
}

PetscErrorCode NeoHookean::Create(MPI_Comm, const std::string &, const ElasticConstants &el,
                                  const Options &, std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  model = std::make_unique<NeoHookean>(el);
  PetscFunctionReturn(0);
}

// P = tau f^-T / J^n: dP = (dtau - tau f^-T dG^T) f^-T / J^n, dtau = mu (dF F^T + F dF^T) +
// lambda tr(f^-1 dG) I, dF = dG F^n.
template <int D> void NeoHookean::tangent(const TangentPoint &pt, double *A) const {
  using M = MatD<D>;
  const TangentKinematicsT<D> k(pt);
  const double lam = c_.lambda(), mu = c_.G();
  const M Fo = mat_of<D>(pt.Fn), Ft = k.f * Fo;
  const double Jn = Fo.determinant();
  const M tau = mu * (Ft * Ft.transpose() - k.I) + lam * std::log(Ft.determinant()) * k.I;
  piola_directions<D>(
      [&](const M &dG) {
        const M dF = dG * Fo;
        const M dtau = mu * (dF * Ft.transpose() + Ft * dF.transpose()) + lam * k.dtr(dG) * k.I;
        return M((dtau - tau * k.fiT * dG.transpose()) * k.fiT / Jn);
      },
      A);
}

template void LinearElastic::tangent<2>(const TangentPoint &, double *) const;
template void LinearElastic::tangent<3>(const TangentPoint &, double *) const;
template void NeoHookean::tangent<2>(const TangentPoint &, double *) const;
template void NeoHookean::tangent<3>(const TangentPoint &, double *) const;

} // namespace pmpm
