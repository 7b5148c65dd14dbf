// Design answers, their error estimate and the verdict (design.hpp).
#include "pmpm/model/design.hpp"
#include "pmpm/util/json.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pmpm {

namespace {
std::string fmt(const char *f, double x) {
  char b[64];
  snprintf(b, sizeof(b), f, x);
  return b;
}
// "2.74 %", "0.153 m": an answer's value in its printing unit
std::string show(const DesignAnswer &a, double v) {
  return fmt("%.4g", v * a.scale) + (a.unit.empty() ? "" : " " + a.unit);
}
const DesignAnswer *checked_answer(const DesignRecord &r) {
  for (const DesignAnswer &a : r.answers)
    if (a.checked) return &a;
  return nullptr;
}
} // namespace

ErrorEstimate estimate_error(const std::vector<double> &f, double assumed_order) {
  ErrorEstimate e;
  const size_t n = f.size();
  e.value = f.back();
  e.extrapolated = e.value;
  if (n < 2) return e;
  const double e21 = f[n - 1] - f[n - 2];
  e.order = assumed_order;
  e.safety = 3.0;
  if (n >= 3) {
    const double e32 = f[n - 2] - f[n - 3];
    e.monotone = e21 * e32 > 0 || (e21 == 0 && e32 == 0);
    if (e21 * e32 > 0) {
      // f_h = f + C h^p: successive differences shrink by 2^p
      const double p = std::log(std::fabs(e32) / std::fabs(e21)) / std::log(2.0);
      e.order = std::clamp(p, 0.5, 2.0);
      e.order_clamped = e.order != p;
      e.order_observed = true;
      e.safety = 1.25;
    }
  }
  const double d = std::pow(2.0, e.order) - 1.0;
  e.error = e.safety * std::fabs(e21) / d;
  e.extrapolated = e.value + e21 / d;
  return e;
}

const char *verdict_name(Verdict v) {
  switch (v) {
  case Verdict::Pass:
    return "PASS";
  case Verdict::Exceeded:
    return "EXCEEDED";
  case Verdict::Inconclusive:
    return "INCONCLUSIVE: refine";
  case Verdict::NotConverged:
    return "NOT CONVERGED";
  default:
    return "none";
  }
}

Verdict judge(double value, double error, double allowable) {
  if (value + error <= allowable) return Verdict::Pass;
  if (value - error > allowable) return Verdict::Exceeded;
  return Verdict::Inconclusive;
}

std::string capped_text(const std::vector<CappedStages> &capped) {
  std::string s;
  for (const CappedStages &c : capped) {
    if (c.stages.empty()) continue;
    if (!s.empty()) s += "; ";
    s += c.stages.size() > 1 ? "stages " : "stage ";
    for (size_t k = 0; k < c.stages.size(); ++k) s += (k ? ", " : "") + std::to_string(c.stages[k]);
    s += " at h = " + fmt("%.6g", c.h) + " m";
  }
  return s;
}

Assessment assess(const std::vector<double> &h, const std::vector<DesignRecord> &meshes,
                  const std::vector<CappedStages> &capped, double assumed_order) {
  Assessment a;
  a.h = h;
  a.meshes = meshes;
  for (const CappedStages &c : capped)
    if (!c.stages.empty()) a.not_converged.push_back(c);
  const DesignRecord &fine = meshes.back();
  a.has_check = fine.has_check;
  a.allowable = fine.allowable;
  if (meshes.size() >= 2)
    for (size_t k = 0; k < fine.answers.size(); ++k) {
      std::vector<double> f;
      for (const DesignRecord &m : meshes) f.push_back(m.answers[k].value);
      a.estimates.push_back(estimate_error(f, assumed_order));
    }
  if (!a.not_converged.empty()) {
    a.verdict = Verdict::NotConverged;
    const bool newton = a.not_converged.back().newton; // one solver over the meshes
    a.reason = capped_text(a.not_converged) +
               (newton ? " stopped at the last load-step halving (-newton_max_cuts) before "
                         "converging: not an equilibrium, no design answer (a collapse, or raise "
                         "-newton_max_cuts; docs/newton.md)"
                       : " stopped at the step cap before reaching -tol: not an equilibrium, no "
                         "design answer (raise -max_steps or the stage's step cap, or "
                         "docs/method.md, section 3)");
    return a;
  }
  const DesignAnswer *c = checked_answer(fine);
  if (!a.has_check || !c) return a;
  const size_t k = static_cast<size_t>(c - fine.answers.data());
  const double err = a.estimates.empty() ? 0.0 : a.estimates[k].error;
  a.verdict = judge(c->value, err, a.allowable);
  const std::string allow = "allowable " + show(*c, a.allowable);
  const std::string v = show(*c, c->value), e = show(*c, err);
  switch (a.verdict) {
  case Verdict::Pass:
    a.reason = c->label + " " + v + (err > 0 ? " + " + e : "") + " <= " + allow;
    break;
  case Verdict::Exceeded:
    a.reason = c->label + " " + v + (err > 0 ? " - " + e : "") + " > " + allow;
    break;
  default:
    a.reason = c->label + " " + v + " +- " + e + " brackets the " + allow +
               ": refine (a smaller -cell_size) to decide";
  }
  if (a.estimates.empty()) a.reason += " (no error estimate: -estimate_error gives one)";
  return a;
}

std::string design_json(const Assessment &a) {
  std::string s = "\"verdict\": \"" + std::string(verdict_name(a.verdict)) + "\",\n  ";
  s += "\"not_converged\": [";
  for (size_t j = 0; j < a.not_converged.size(); ++j) {
    const CappedStages &c = a.not_converged[j];
    s += (j ? ", {" : "{") + json_kv("h", c.h) + ", \"stages\": [";
    for (size_t k = 0; k < c.stages.size(); ++k) s += (k ? ", " : "") + std::to_string(c.stages[k]);
    s += "]}";
  }
  s += "]";
  const DesignRecord &fine = a.meshes.back();
  if (fine.answers.empty()) return s;
  s += ",\n  \"design\": {\n    \"checked\": ";
  const DesignAnswer *c = checked_answer(fine);
  s += c ? "\"" + c->key + "\"" : std::string("null");
  s += ",\n    " + json_kv("allowable", a.has_check ? a.allowable : std::nan(""));
  s += ",\n    \"answers\": {";
  for (size_t k = 0; k < fine.answers.size(); ++k)
    s += (k ? ", " : "") + json_kv(fine.answers[k].key, fine.answers[k].value);
  s += "}";
  if (!a.estimates.empty()) {
    s += ",\n    \"error_estimate\": {\n      \"meshes\": [";
    for (size_t j = 0; j < a.h.size(); ++j) s += (j ? ", " : "") + json_num(a.h[j]);
    s += "]";
    for (size_t k = 0; k < fine.answers.size(); ++k) {
      const ErrorEstimate &e = a.estimates[k];
      s += ",\n      \"" + fine.answers[k].key + "\": {" + json_kv("value", e.value) + ", " +
           json_kv("error", e.error) + ", " + json_kv("extrapolated", e.extrapolated) + ", " +
           json_kv("order", e.order) + ", " + json_kv("safety_factor", e.safety) +
           ", \"order_observed\": " + (e.order_observed ? "true" : "false") +
           ", \"monotone\": " + (e.monotone ? "true" : "false") +
           ", \"order_clamped\": " + (e.order_clamped ? "true" : "false") + ", \"per_mesh\": [";
      for (size_t j = 0; j < a.meshes.size(); ++j)
        s += (j ? ", " : "") + json_num(a.meshes[j].answers[k].value);
      s += "]}";
    }
    s += "\n    }";
  }
  s += "\n  }";
  return s;
}

std::string design_log(const Assessment &a) {
  std::string s;
  const DesignRecord &fine = a.meshes.back();
  for (size_t k = 0; k < fine.answers.size(); ++k) {
    const DesignAnswer &d = fine.answers[k];
    s += d.label + " " + show(d, d.value);
    if (!a.estimates.empty()) {
      const ErrorEstimate &e = a.estimates[k];
      s += " +- " + show(d, e.error) + " (estimated; order " + fmt("%.2g", e.order) +
           (e.order_observed ? " observed" : " assumed") + (e.monotone ? "" : ", not monotone") +
           ")";
    }
    s += "\n";
  }
  if (a.verdict != Verdict::None)
    s += std::string("verdict: ") + verdict_name(a.verdict) + " (" + a.reason + ")\n";
  return s;
}

} // namespace pmpm
