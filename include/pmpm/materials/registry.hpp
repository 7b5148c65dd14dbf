// The material laws: one class each (a Material), and one line each in the table of
// src/materials/registry.cpp. The table gives -mat_<name>_model its values, -help and
// docs/options.md their lists, and the error messages their allowed names; nothing else lists
// the laws (scenes whose closed forms need one law's parameters ask for that class).
//
// A law class provides, besides the Material methods (model(), wave_modulus(), update_stress(),
// tangent() for -solver newton):
//   static constexpr const char *kName;   the value of -mat_<name>_model
//   static constexpr bool kRateForm, kPlastic;
//       what its rate_form() and plastic() return (MaterialLawList lists the laws with either)
//   struct Options { ... };               what its own options set (default-constructed = defaults)
//   static PetscErrorCode ReadOptions(PetscOptionItems *, Options &);
//       its options, read inside the material's block -mat_<name>_ (after -model, -E, -nu,
//       -gamma, -density); under -help every law's are read, so that all are listed
//   static PetscErrorCode Create(MPI_Comm, const std::string &prefix, const ElasticConstants &,
//                                const Options &, std::unique_ptr<Material> &);
//       its options' checks (PmpmCheckInput: skipped under -help), then the model
// (docs/developer-guide.md, "Adding a material").
#pragma once
#include "pmpm/materials/material.hpp"
#include <petscsys.h>
#include <memory>
#include <string>
#include <vector>

namespace pmpm {

// Moduli, strengths and hardening above this (Pa) are typos: the stiffest solids are near 1e12.
inline constexpr double kMaxModulus = 1e13;

// One law's options between reading them (inside the material's options block) and making the
// model (after the block's common checks), so a material's errors come in its block's order.
class LawOptions {
public:
  virtual ~LawOptions() = default;
  virtual PetscErrorCode read(PetscOptionItems *items) = 0;
  virtual PetscErrorCode make(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                              std::unique_ptr<Material> &model) const = 0;
};

template <class Law> class LawOptionsOf final : public LawOptions {
public:
  PetscErrorCode read(PetscOptionItems *items) override { return Law::ReadOptions(items, o_); }
  PetscErrorCode make(MPI_Comm comm, const std::string &prefix, const ElasticConstants &el,
                      std::unique_ptr<Material> &model) const override {
    return Law::Create(comm, prefix, el, o_, model);
  }

private:
  typename Law::Options o_;
};

struct MaterialLaw {
  const char *name;        // -mat_<name>_model's value
  const char *description; // one line: -help, docs/options.md
  std::unique_ptr<LawOptions> (*options)();
  bool rate_form, plastic; // Material::rate_form(), plastic() of its models
};

// One entry of the table.
template <class Law> MaterialLaw RegisterLaw(const char *description) {
  return {Law::kName, description,
          [] { return std::unique_ptr<LawOptions>(new LawOptionsOf<Law>); }, Law::kRateForm,
          Law::kPlastic};
}

// The table, in -mat_<name>_model's order (the first is the default).
const std::vector<MaterialLaw> &MaterialLaws();
// -mat_<name>_model's list as PmpmOptionsEnum takes it: the names, "MaterialModel", "MODEL_", null.
const char *const *MaterialLawNames();
// The names joined by ", " (error messages); with a trait (&MaterialLaw::plastic), only the laws
// that have it.
std::string MaterialLawList(bool MaterialLaw::*trait = nullptr);

} // namespace pmpm
