// Minimal assertion helpers for the unit-test executables (no framework needed).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace pmpm_test {
inline int &failures() {
  static int n = 0;
  return n;
}
inline int &checks() {
  static int n = 0;
  return n;
}
inline void check_close(double got, double want, double tol, const char *what, const char *file,
                        int line) {
  ++checks();
  const double err = std::fabs(got - want);
  if (!(err <= tol)) {
    ++failures();
    std::printf("FAIL %s:%d %s: got %.15g want %.15g |diff| %.3g > tol %.3g\n", file, line, what,
                got, want, err, tol);
  }
}
inline void check_true(bool ok, const char *what, const char *file, int line) {
  ++checks();
  if (!ok) {
    ++failures();
    std::printf("FAIL %s:%d %s\n", file, line, what);
  }
}
// Deterministic generator (64-bit LCG), uniform in [0, 1); the seed picks the sequence.
struct Lcg {
  std::uint64_t s;
  explicit Lcg(std::uint64_t seed) : s(seed) {}
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / double(1ull << 53);
  }
  double uniform(double a, double b) { return a + (b - a) * next(); }
};

inline int report(const char *suite) {
  std::printf("%s: %d checks, %d passed, %d failed\n", suite, checks(), checks() - failures(),
              failures());
  return failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
} // namespace pmpm_test

#define CHECK_CLOSE(got, want, tol)                                                                \
  pmpm_test::check_close((got), (want), (tol), #got, __FILE__, __LINE__)
#define CHECK(cond) pmpm_test::check_true((cond), #cond, __FILE__, __LINE__)
