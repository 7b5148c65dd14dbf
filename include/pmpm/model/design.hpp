// Design answers and the verdict a run may give about them.
//
// A scene with a design check (the cover: the geomembrane's peak strain against an allowable)
// reports its answers as a DesignRecord. The verdict is earned, not printed:
//   NOT CONVERGED         some stage ended at its step cap, out of equilibrium: no answer of
//                         that run is a design answer (this overrides everything below)
//   PASS / EXCEEDED       the checked answer against its allowable; with an error estimate,
//                         PASS needs answer + error <= allowable and EXCEEDED answer - error >
//                         allowable
//   INCONCLUSIVE: refine  the allowable lies inside answer +- error
// The error estimate (-estimate_error) is Richardson extrapolation over meshes refined by 2,
// reported as Roache's grid convergence index (P. J. Roache, Verification and Validation in
// Computational Science and Engineering, Hermosa 1998; I. B. Celik et al., J. Fluids Eng. 130,
// 078001, 2008): with two meshes the order p is assumed and the safety factor is 3; with three or
// more the order is observed from the three finest and the factor is 1.25.
// Everything here is a plain function of numbers, tested in tests/unit/test_design.cpp.
#pragma once
#include <string>
#include <vector>

namespace pmpm {

struct DesignAnswer {
  std::string key;      // summary.json key, e.g. "peak_strain"
  std::string label;    // for the log, e.g. "peak membrane strain"
  double value = 0;     // SI units
  double scale = 1;     // printed as value * scale ...
  std::string unit;     // ... followed by this unit ("%", "m", "kN/m")
  bool checked = false; // the answer compared with the allowable
};

struct DesignRecord {
  bool has_check = false; // an allowable to compare with
  double allowable = 0;
  std::vector<DesignAnswer> answers;
};

// One answer's error estimate from its values on meshes h, h/2, h/4, ... (coarse first).
struct ErrorEstimate {
  double value = 0;            // the finest mesh's value
  double error = 0;            // GCI: Fs |f_fine - f_next| / (2^p - 1), an error bar on `value`
  double extrapolated = 0;     // Richardson: f_fine + (f_fine - f_next) / (2^p - 1)
  double order = 1;            // p used
  double safety = 3;           // Fs used
  bool order_observed = false; // p observed from three meshes (else assumed)
  bool monotone = true;        // the three finest values change in one direction
  bool order_clamped = false;  // the observed p fell outside [0.5, 2] and was clamped
};
// values: coarse to fine, at least two. assumed_order: p for two meshes, or when three are not
// monotone (then Fs = 3 too: the data do not support the smaller factor).
ErrorEstimate estimate_error(const std::vector<double> &values, double assumed_order);

enum class Verdict { None = 0, Pass, Exceeded, Inconclusive, NotConverged };
const char *verdict_name(Verdict v); // "none", "PASS", "EXCEEDED", "INCONCLUSIVE: refine", ...
// The checked answer's verdict: value +- error against the allowable (error 0: no estimate).
Verdict judge(double value, double error, double allowable);

// Stages of one mesh's run that ended at their step cap.
struct CappedStages {
  double h = 0;
  std::vector<int> stages;
  bool newton = false; // -solver newton: a stage ends unconverged at its last load-step halving
};
// "stages 2, 3 at h = 0.5 m; stage 1 at h = 0.25 m"
std::string capped_text(const std::vector<CappedStages> &capped);

// The run's answers over its meshes (coarse first; one mesh without -estimate_error) and the
// verdict they earn, with its one-line reason.
struct Assessment {
  Verdict verdict = Verdict::None;
  std::string reason;
  std::vector<double> h;                // cell sizes, coarse first
  std::vector<DesignRecord> meshes;     // one per h
  std::vector<ErrorEstimate> estimates; // one per answer of the finest mesh (empty: one mesh)
  std::vector<CappedStages> not_converged;
  double allowable = 0;
  bool has_check = false;
};
Assessment assess(const std::vector<double> &h, const std::vector<DesignRecord> &meshes,
                  const std::vector<CappedStages> &capped, double assumed_order);

// summary.json's top-level entries: "verdict", "not_converged" and, with a design, "design"
// (answers, allowable, the error estimate per answer). Without a trailing comma.
std::string design_json(const Assessment &a);
// The log's closing lines: each answer (with its error when estimated), then "verdict: ..."
// last (nothing for a converged run without a check).
std::string design_log(const Assessment &a);

} // namespace pmpm
