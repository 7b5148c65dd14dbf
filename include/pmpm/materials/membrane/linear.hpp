// Membrane law "linear": T = J eps (the catenary check, docs/method.md, section 6.1).
#pragma once

namespace pmpm {

struct LinearMembrane {
  static constexpr const char *name = "linear";
  static constexpr const char *description = "T = J eps";
  static constexpr bool plastic = false;
  template <class Law>
  static double tension(const Law &m, double eps, double &, double &, bool &slack) {
    slack = false;
    return m.J * eps;
  }
  template <class Law> static double tangent(const Law &m, double, double, double) { return m.J; }
};

} // namespace pmpm
