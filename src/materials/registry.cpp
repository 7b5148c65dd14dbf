// The material law table: one line per law (materials/registry.hpp).
#include "pmpm/materials/registry.hpp"
#include "pmpm/materials/drucker_prager.hpp"
#include "pmpm/materials/elastic.hpp"
#include "pmpm/materials/von_mises.hpp"

namespace pmpm {

const std::vector<MaterialLaw> &MaterialLaws() {
  static const std::vector<MaterialLaw> laws = {
      RegisterLaw<LinearElastic>("linear elasticity in rate form (Jaumann), small strain"),
      RegisterLaw<NeoHookean>("compressible neo-Hookean hyperelasticity, large strain"),
      RegisterLaw<DruckerPrager>("Drucker-Prager elastoplasticity with a tension cut-off"),
      RegisterLaw<VonMises>("von Mises (J2) elastoplasticity, linear hardening"),
  };
  return laws;
}

const char *const *MaterialLawNames() {
  static const std::vector<const char *> names = [] {
    std::vector<const char *> v;
    for (const MaterialLaw &l : MaterialLaws()) v.push_back(l.name);
    v.insert(v.end(), {"MaterialModel", "MODEL_", nullptr});
    return v;
  }();
  return names.data();
}

std::string MaterialLawList(bool MaterialLaw::*trait) {
  std::string s;
  for (const MaterialLaw &l : MaterialLaws())
    if (!trait || l.*trait) s += (s.empty() ? "" : ", ") + std::string(l.name);
  return s;
}

} // namespace pmpm
