// Axial law of a geomembrane modelled as a chain of points (docs/method.md, sections 6.7 and 7.1):
// each segment carries a force per unit width T (N/m) from its engineering strain
//   eps = current length / initial length - 1.
// The laws are one header each in materials/membrane/ (a struct with its name, description,
// tension and consistent tangent) and one entry of MembraneLaws below; -mat_<name>_law, its help,
// its allowed list and docs/options.md come from that list. The dispatch is a chain of compares
// the compiler folds like a switch: no virtual call per segment.
//
// J is the sheet's axial stiffness per width: E t for a uniaxial sheet, E t / (1 - nu^2) with the
// out-of-plane strain held at zero (the caller chooses and says which). yield_T = sigma_y t,
// hardening = H t with H = d(sigma_y)/d(alpha). Expected J > 0, yield_T >= 0, J + hardening > 0.
//
// Header-only, no PETSc: usable from the kernels and from the unit tests.
#pragma once
#include "pmpm/materials/membrane/elastoplastic.hpp"
#include "pmpm/materials/membrane/linear.hpp"
#include "pmpm/materials/membrane/tension_only.hpp"
#include <string>
#include <type_traits>

namespace pmpm {

template <class... L> struct MembraneLawList {
  static constexpr int size = sizeof...(L);
  // PETSc enum-list layout (values, enum name, prefix, null) for PetscOptionsEnum.
  static constexpr const char *names[] = {L::name..., "MembraneLawKind", "MEMBRANE_", nullptr};
  static std::string help() {
    std::string s = "Membrane law:";
    int k = 0;
    ((s += std::string(k++ ? ", " : " ") + L::name + " (" + L::description + ")"), ...);
    return s;
  }
  template <class Law> static constexpr int id() {
    int k = 0, found = -1;
    ((found = (found < 0 && std::is_same_v<Law, L>) ? k : found, ++k), ...);
    return found;
  }
};

// The membrane-law table: one entry per law, its position its -law value.
using MembraneLaws = MembraneLawList<LinearMembrane, TensionOnlyMembrane, ElastoplasticMembrane>;
inline constexpr const char *const *MembraneLawNames = MembraneLaws::names;
template <class Law> inline constexpr int MembraneLawId = MembraneLaws::id<Law>();

struct MembraneLaw {
  int kind = 0;         // the law's position in MembraneLaws (PetscEnum)
  double J = 0;         // axial stiffness (N/m)
  double yield_T = 0;   // initial yield force per width (N/m) (plastic laws): sigma_y * t
  double hardening = 0; // plastic hardening modulus per width (N/m): H * t, dT/d(alpha)

  // Tension (N/m) for the total engineering strain eps. Plastic laws only: eps_p (plastic
  // strain) and alpha (accumulated plastic strain, sum of |d eps_p|) are updated in place; an
  // elastic step leaves them untouched bit for bit. The other laws never touch them.
  // slack: true where the sheet carries no force because it is in compression (tension_only);
  // always false for the other laws.
  double tension(double eps, double &eps_p, double &alpha, bool &slack) const {
    return Tension(MembraneLaws{}, eps, eps_p, alpha, slack);
  }
  // The consistent tangent dT/d(eps) of tension() at the total strain eps from the committed
  // state (eps_p, alpha) of the step's start (the implicit solver's bar stiffness).
  double tangent(double eps, double eps_p, double alpha) const {
    return Tangent(MembraneLaws{}, eps, eps_p, alpha);
  }
  // Whether the law reads the yield options.
  bool plastic() const { return Plastic(MembraneLaws{}); }

private:
  template <class... L>
  double Tension(MembraneLawList<L...>, double eps, double &eps_p, double &alpha,
                 bool &slack) const {
    double T = 0.0;
    int k = 0;
    slack = false;
    (void)((kind == k++ ? (T = L::tension(*this, eps, eps_p, alpha, slack), true) : false) || ...);
    return T;
  }
  template <class... L>
  double Tangent(MembraneLawList<L...>, double eps, double eps_p, double alpha) const {
    double D = 0.0;
    int k = 0;
    (void)((kind == k++ ? (D = L::tangent(*this, eps, eps_p, alpha), true) : false) || ...);
    return D;
  }
  template <class... L> bool Plastic(MembraneLawList<L...>) const {
    bool p = false;
    int k = 0;
    (void)((kind == k++ ? (p = L::plastic, true) : false) || ...);
    return p;
  }
};

} // namespace pmpm
