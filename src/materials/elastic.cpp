// Linear elastic and neo-Hookean: no options of their own (-E and -nu are every material's), and
// what their Newton tangents need.
#include "pmpm/materials/elastic.hpp"
#include "pmpm/implicit_kernels.hpp"

namespace pmpm {

PetscErrorCode LinearElastic::Create(MPI_Comm, const std::string &, const ElasticConstants &el,
                                     const Options &, std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  model = std::make_unique<LinearElastic>(el);
  PetscFunctionReturn(0);
}

bool LinearElastic::tangent(TangentModel &tm) const {
  tm.kind = TangentKind::LinearElastic;
  tm.el = c_;
  return true;
}

PetscErrorCode NeoHookean::Create(MPI_Comm, const std::string &, const ElasticConstants &el,
                                  const Options &, std::unique_ptr<Material> &model) {
  PetscFunctionBeginUser;
  model = std::make_unique<NeoHookean>(el);
  PetscFunctionReturn(0);
}

bool NeoHookean::tangent(TangentModel &tm) const {
  tm.kind = TangentKind::NeoHookean;
  tm.el = c_;
  return true;
}

} // namespace pmpm
