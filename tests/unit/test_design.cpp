// The design answers' error estimate and verdict (design.hpp) against exact sequences: values
// f_h = f + C h^p on meshes h, h/2, h/4 have differences that shrink by exactly 2^p, so the
// observed order, the Richardson extrapolation and the GCI are known in closed form.
#include "check.hpp"
#include "pmpm/model/design.hpp"
#include <string>

using namespace pmpm;

static DesignRecord record(double strain, double settlement, double allowable) {
  DesignRecord r;
  r.has_check = true;
  r.allowable = allowable;
  r.answers = {{"peak_strain", "peak membrane strain", strain, 100, "%", true},
               {"surface_settlement", "surface settlement", settlement, 1, "m", false}};
  return r;
}

int main() {
  const double tight = 1e-14; // sums of a few O(1) numbers: round-off only
  // two meshes, order 1 assumed: the GCI is 3 |f2 - f1| / (2 - 1)
  {
    const ErrorEstimate e = estimate_error({0.020, 0.021}, 1.0);
    CHECK_CLOSE(e.value, 0.021, tight);
    CHECK_CLOSE(e.error, 3 * 0.001, tight);
    CHECK_CLOSE(e.extrapolated, 0.022, tight);
    CHECK(!e.order_observed);
    CHECK_CLOSE(e.safety, 3.0, 0.0);
  }
  // two meshes, order 2 assumed: 3 |d| / 3
  {
    const ErrorEstimate e = estimate_error({1.0, 1.3}, 2.0);
    CHECK_CLOSE(e.error, 0.3, tight);
    CHECK_CLOSE(e.extrapolated, 1.4, tight);
  }
  // three meshes of an exact second-order sequence: p = 2 observed, Fs = 1.25, f recovered
  {
    const double f = 1.0, C = 0.16;
    const ErrorEstimate e = estimate_error({f + C, f + C / 4, f + C / 16}, 1.0);
    CHECK(e.order_observed && e.monotone && !e.order_clamped);
    CHECK_CLOSE(e.order, 2.0, 1e-12);
    CHECK_CLOSE(e.safety, 1.25, 0.0);
    CHECK_CLOSE(e.extrapolated, f, 1e-14);
    CHECK_CLOSE(e.error, 1.25 * (3 * C / 16) / 3, 1e-14);
    // the error bar covers the true error of the finest value (C / 16), by the factor 1.25
    CHECK(e.error >= std::fabs(e.value - f));
  }
  // first order, decreasing: p = 1, f recovered
  {
    const ErrorEstimate e = estimate_error({2 - 0.4, 2 - 0.2, 2 - 0.1}, 2.0);
    CHECK_CLOSE(e.order, 1.0, 1e-12);
    CHECK_CLOSE(e.extrapolated, 2.0, 1e-14);
    CHECK_CLOSE(e.error, 1.25 * 0.1, 1e-14);
  }
  // differences shrinking by 8 (p = 3) are clamped to p = 2 (no more is credited)
  {
    const ErrorEstimate e = estimate_error({1.64, 1.08, 1.01}, 1.0);
    CHECK(e.order_observed && e.order_clamped);
    CHECK_CLOSE(e.order, 2.0, 0.0);
    CHECK_CLOSE(e.error, 1.25 * 0.07 / 3, 1e-14);
  }
  // oscillating values: no order can be observed; the assumed order and Fs = 3 are used
  {
    const ErrorEstimate e = estimate_error({1.0, 1.1, 1.05}, 1.0);
    CHECK(!e.monotone && !e.order_observed);
    CHECK_CLOSE(e.safety, 3.0, 0.0);
    CHECK_CLOSE(e.error, 3 * 0.05, 1e-14);
  }
  // meshes that agree exactly: no error
  {
    const ErrorEstimate e = estimate_error({0.5, 0.5, 0.5}, 1.0);
    CHECK(e.monotone);
    CHECK_CLOSE(e.error, 0.0, 0.0);
  }
  // the verdict: the allowable against value +- error, boundaries included on the PASS side
  CHECK(judge(0.02, 0.0, 0.03) == Verdict::Pass);
  CHECK(judge(0.03, 0.0, 0.03) == Verdict::Pass);
  CHECK(judge(0.031, 0.0, 0.03) == Verdict::Exceeded);
  CHECK(judge(0.024, 0.005, 0.03) == Verdict::Pass);
  CHECK(judge(0.028, 0.003, 0.03) == Verdict::Inconclusive);
  CHECK(judge(0.032, 0.003, 0.03) == Verdict::Inconclusive);
  CHECK(judge(0.034, 0.003, 0.03) == Verdict::Exceeded);
  CHECK(std::string(verdict_name(Verdict::Inconclusive)) == "INCONCLUSIVE: refine");
  // one mesh: PASS from the value alone, and the reason says there is no estimate
  {
    const Assessment a = assess({0.5}, {record(0.028, 0.1, 0.03)}, {{0.5, {}}}, 1.0);
    CHECK(a.verdict == Verdict::Pass);
    CHECK(a.estimates.empty());
    CHECK(a.reason.find("no error estimate") != std::string::npos);
  }
  // two meshes: 2.8 % +- 3 x 0.2 % brackets 3 %: INCONCLUSIVE
  {
    const Assessment a = assess({0.5, 0.25}, {record(0.026, 0.10, 0.03), record(0.028, 0.11, 0.03)},
                                {{0.5, {}}, {0.25, {}}}, 1.0);
    CHECK(a.verdict == Verdict::Inconclusive);
    CHECK(a.estimates.size() == 2);
    CHECK_CLOSE(a.estimates[0].error, 0.006, 1e-15);
    CHECK_CLOSE(a.estimates[1].error, 0.03, 1e-15);
    const std::string j = design_json(a), log = design_log(a);
    CHECK(j.find("\"verdict\": \"INCONCLUSIVE: refine\"") != std::string::npos);
    CHECK(j.find("\"per_mesh\": [0.025999999999999999, 0.028000000000000001]") !=
          std::string::npos);
    CHECK(log.find("peak membrane strain 2.8 % +- 0.6 % (estimated; order 1 assumed)") !=
          std::string::npos);
    // the verdict is the log's last line
    const size_t last = log.rfind('\n', log.size() - 2);
    CHECK(log.compare(last + 1, 9, "verdict: ") == 0);
  }
  // a stage at its step cap on any mesh: NOT CONVERGED, whatever the answers say
  {
    const std::vector<CappedStages> capped = {{0.5, {}}, {0.25, {2, 3}}};
    const Assessment a =
        assess({0.5, 0.25}, {record(0.010, 0.1, 0.03), record(0.010, 0.1, 0.03)}, capped, 1.0);
    CHECK(a.verdict == Verdict::NotConverged);
    CHECK(capped_text(capped) == "stages 2, 3 at h = 0.25 m");
    CHECK(a.reason.find("stages 2, 3 at h = 0.25 m") == 0);
    CHECK(design_json(a).find("\"not_converged\": [{\"h\": 0.25, \"stages\": [2, 3]}]") !=
          std::string::npos);
  }
  // a scene without a design check: no verdict unless a stage was capped
  {
    const Assessment a = assess({0.1}, {DesignRecord{}}, {{0.1, {}}}, 1.0);
    CHECK(a.verdict == Verdict::None);
    CHECK(design_log(a).empty());
    CHECK(design_json(a) == "\"verdict\": \"none\",\n  \"not_converged\": []");
    const Assessment b = assess({0.1}, {DesignRecord{}}, {{0.1, {0}}}, 1.0);
    CHECK(b.verdict == Verdict::NotConverged);
    CHECK(design_log(b).rfind("verdict: NOT CONVERGED (stage 0 at h = 0.1 m", 0) == 0);
    // the reason names how the stage ended: relaxation's step cap or Newton's last halving
    CHECK(b.reason.find("at the step cap before reaching -tol") != std::string::npos);
    CHECK(b.reason.find("halving") == std::string::npos);
    const Assessment n = assess({0.1}, {DesignRecord{}}, {{0.1, {1}, true}}, 1.0);
    CHECK(n.verdict == Verdict::NotConverged);
    CHECK(n.reason.find("stage 1 at h = 0.1 m stopped at the last load-step halving") == 0);
    CHECK(n.reason.find("-tol") == std::string::npos);
  }
  return pmpm_test::report("design");
}
