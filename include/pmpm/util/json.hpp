// Small JSON helpers for summary.json and the scenes' results: numbers written so they read back
// exactly (%.17g), non-finite values as null.
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

namespace pmpm {

inline std::string json_num(double v) {
  if (!std::isfinite(v)) return "null";
  char b[64];
  snprintf(b, sizeof(b), "%.17g", v);
  return b;
}
inline std::string json_kv(const std::string &k, double v) {
  return "\"" + k + "\": " + json_num(v);
}
inline std::string json_kv(const std::string &k, const std::string &raw) {
  return "\"" + k + "\": " + raw;
}

} // namespace pmpm
