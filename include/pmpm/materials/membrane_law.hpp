// Axial law of a geomembrane modelled as a chain of points (docs/method.md, sections 6.7 and 7.1):
// each segment carries a force per unit width T (N/m) from its engineering strain
//   eps = current length / initial length - 1.
// Three kinds:
//   linear         T = J eps                      (the catenary check, docs/method.md, section 6.1)
//   tension_only   T = max(J eps, 0)              (a sheet buckles instead of carrying
//                                                   compression; docs/method.md, section 7.1
//                                                   "Wrinkles")
//   elastoplastic  1D von Mises, linear isotropic hardening, closed-form return map
//                  (Simo & Hughes 1998, ch. 1; de Souza Neto, Peric & Owen 2008, ch. 6):
//                    T_tr = J (eps - eps_p),  f = |T_tr| - (yield_T + hardening alpha)
//                    f > 0:  dg = f / (J + hardening),  eps_p += dg sign(T_tr),  alpha += dg,
//                            T = T_tr - J dg sign(T_tr)
//                  Linear hardening makes the consistency condition linear in dg, so the return
//                  is exact for any strain increment. Path dependent: call with the new total
//                  strain each step and keep (eps_p, alpha) per segment.
// J is the sheet's axial stiffness per width: E t for a uniaxial sheet, E t / (1 - nu^2) with the
// out-of-plane strain held at zero (the caller chooses and says which). yield_T = sigma_y t,
// hardening = H t with H = d(sigma_y)/d(alpha). Expected J > 0, yield_T >= 0, J + hardening > 0.
//
// Header-only, no PETSc: usable from the kernels and from the unit tests.
#pragma once

namespace pmpm {

enum class MembraneLawKind { Linear = 0, TensionOnly = 1, Elastoplastic = 2 };
// PETSc enum-list layout (values, enum name, prefix, null) for PetscOptionsEnum.
inline constexpr const char *MembraneLawNames[] = {
    "linear", "tension_only", "elastoplastic", "MembraneLawKind", "MEMBRANE_", nullptr};

struct MembraneLaw {
  MembraneLawKind kind = MembraneLawKind::Linear;
  double J = 0;         // axial stiffness (N/m)
  double yield_T = 0;   // initial yield force per width (N/m) (elastoplastic): sigma_y * t
  double hardening = 0; // plastic hardening modulus per width (N/m): H * t, dT/d(alpha)

  // Tension (N/m) for the total engineering strain eps. Elastoplastic only: eps_p (plastic
  // strain) and alpha (accumulated plastic strain, sum of |d eps_p|) are updated in place; an
  // elastic step leaves them untouched bit for bit. The other kinds never touch them.
  // slack: true where the sheet carries no force because it is in compression (tension_only);
  // always false for the other kinds.
  double tension(double eps, double &eps_p, double &alpha, bool &slack) const {
    slack = false;
    switch (kind) {
    case MembraneLawKind::Linear:
      return J * eps;
    case MembraneLawKind::TensionOnly: {
      const double T = J * eps;
      slack = T < 0.0;
      return slack ? 0.0 : T;
    }
    case MembraneLawKind::Elastoplastic: {
      const double T_tr = J * (eps - eps_p);
      const double f = (T_tr < 0.0 ? -T_tr : T_tr) - (yield_T + hardening * alpha);
      if (!(f > 0.0)) return T_tr;
      const double sgn = T_tr < 0.0 ? -1.0 : 1.0;
      const double dg = f / (J + hardening);
      eps_p += dg * sgn;
      alpha += dg;
      return T_tr - J * dg * sgn;
    }
    }
    return 0.0;
  }

  // The consistent tangent dT/d(eps) of tension() at the total strain eps from the committed
  // state (eps_p, alpha) of the step's start (the implicit solver's bar stiffness): J where
  // elastic (linear, a taut tension_only sheet), 0 where slack, J hardening / (J + hardening)
  // where the return map is active (the closed-form return is exact, so this is its derivative).
  double tangent(double eps, double eps_p, double alpha) const {
    switch (kind) {
    case MembraneLawKind::Linear:
      return J;
    case MembraneLawKind::TensionOnly:
      return J * eps < 0.0 ? 0.0 : J;
    case MembraneLawKind::Elastoplastic: {
      const double T_tr = J * (eps - eps_p);
      const double f = (T_tr < 0.0 ? -T_tr : T_tr) - (yield_T + hardening * alpha);
      return f > 0.0 ? J * hardening / (J + hardening) : J;
    }
    }
    return 0.0;
  }
};

} // namespace pmpm
