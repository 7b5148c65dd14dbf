// Membrane law "tension_only": T = max(J eps, 0). A sheet buckles instead of carrying compression
// (docs/method.md, section 7.1, "Wrinkles"); where it would, it is slack.
#pragma once

namespace pmpm {

struct TensionOnlyMembrane {
  static constexpr const char *name = "tension_only";
  static constexpr const char *description = "slack in compression";
  static constexpr bool plastic = false;
  template <class Law>
  static double tension(const Law &m, double eps, double &, double &, bool &slack) {
    const double T = m.J * eps;
    slack = T < 0.0;
    return slack ? 0.0 : T;
  }
  template <class Law> static double tangent(const Law &m, double eps, double, double) {
    return m.J * eps < 0.0 ? 0.0 : m.J;
  }
};

} // namespace pmpm
