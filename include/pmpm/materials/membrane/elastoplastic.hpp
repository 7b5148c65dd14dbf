// Membrane law "elastoplastic": 1D von Mises with linear isotropic hardening and its closed-form
// return map (Simo & Hughes 1998, ch. 1; de Souza Neto, Peric & Owen 2008, ch. 6):
//   T_tr = J (eps - eps_p),  f = |T_tr| - (yield_T + hardening alpha)
//   f > 0:  dg = f / (J + hardening),  eps_p += dg sign(T_tr),  alpha += dg,
//           T = T_tr - J dg sign(T_tr)
// Linear hardening makes the consistency condition linear in dg, so the return is exact for any
// strain increment; its derivative is the consistent tangent J hardening / (J + hardening).
#pragma once

namespace pmpm {

struct ElastoplasticMembrane {
  static constexpr const char *name = "elastoplastic";
  static constexpr const char *description = "1D von Mises, linear hardening";
  static constexpr bool plastic = true; // reads -mat_<name>_yield_stress, _hardening
  template <class Law>
  static double tension(const Law &m, double eps, double &eps_p, double &alpha, bool &slack) {
    slack = false;
    const double T_tr = m.J * (eps - eps_p);
    const double f = (T_tr < 0.0 ? -T_tr : T_tr) - (m.yield_T + m.hardening * alpha);
    if (!(f > 0.0)) return T_tr;
    const double sgn = T_tr < 0.0 ? -1.0 : 1.0;
    const double dg = f / (m.J + m.hardening);
    eps_p += dg * sgn;
    alpha += dg;
    return T_tr - m.J * dg * sgn;
  }
  template <class Law> static double tangent(const Law &m, double eps, double eps_p, double alpha) {
    const double T_tr = m.J * (eps - eps_p);
    const double f = (T_tr < 0.0 ? -T_tr : T_tr) - (m.yield_T + m.hardening * alpha);
    return f > 0.0 ? m.J * m.hardening / (m.J + m.hardening) : m.J;
  }
};

} // namespace pmpm
