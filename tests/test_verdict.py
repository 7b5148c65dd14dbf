"""Verdicts only from converged states, and the error estimate behind them (issue 21).

The test cover (tests/cover_void.opts: a 1 m void under 1 m of soil on an HDPE sheet) at h = 0.5 m:
1. Stopped by -max_steps before equilibrium: exit 3, verdict NOT CONVERGED naming the stages in
   the log's last line, in summary.json and in stages.csv; the outputs are still written.
2. -estimate_error (meshes 0.5 and 0.25 m): every design answer with its error, which is the GCI of
   two meshes (3 |f_0.25 - f_0.5|, order 1 assumed) of the two meshes' own values; the coarse mesh
   in DIR/mesh_h0.5 is the same run as a standalone one (its answers equal to the last digit); the
   verdict is value +- error against the allowable, and the exit code follows it.
3. The allowable set inside the error bar: INCONCLUSIVE: refine, exit 4. Set far below the answer
   on one mesh: EXCEEDED, exit 0.
4. -estimate_error refuses what it cannot do (exit 1, one line naming the option).

usage: test_verdict.py EXE NP OUTDIR
"""
import json
import os
import sys

from pmpmtest import (EXIT_BAD_INPUT, EXIT_INCONCLUSIVE, EXIT_NOT_CONVERGED, EXIT_OK, Checks,
                      expected_verdict, run, stages, summary)

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"verdict_np{np_}")
SCENE = ["-options_file", "tests/cover_void.opts", "-cell_size", "0.5"]


def last_line(text):
    """pmpm's last line (mpiexec appends a banner when a rank exits non-zero)."""
    text = text.split("\n-----")[0]
    lines = [l for l in text.splitlines() if l.strip()]
    return lines[-1] if lines else ""


# 1. a run stopped before equilibrium
d = f"{out}/capped"
code, text = run(exe, np_, SCENE + ["-max_steps", "300"], d, expect_ok=False)
s = summary(d)
rows = stages(d)
capped = [int(r["stage"]) for r in rows if r["converged"] == "0"]
c.check("capped run: exit 3", code == EXIT_NOT_CONVERGED, f"(exit {code})")
c.check("capped run: summary verdict NOT CONVERGED", s["verdict"] == "NOT CONVERGED")
c.check("capped run: summary names the capped stages",
        s["not_converged"] == [{"h": 0.5, "stages": capped}] and capped, f"({s['not_converged']})")
c.check("capped run: last log line is the verdict naming the stages",
        last_line(text).startswith("verdict: NOT CONVERGED (stage") and "h = 0.5 m" in text,
        f"[{last_line(text)[:90]}]")
first = min(capped) if capped else 0
c.check("capped run: stages.csv says NOT CONVERGED from the first capped stage on",
        all((r["verdict"] == "NOT CONVERGED") == (int(r["stage"]) >= first) for r in rows))
c.check("capped run: no PASS or EXCEEDED anywhere",
        "PASS" not in text and "EXCEEDED" not in text and
        not any(r["verdict"] in ("PASS", "EXCEEDED") for r in rows))
c.check("capped run: outputs written", all(os.path.isfile(f"{d}/{f}") for f in
                                           ("particles.h5", "stages.csv", "chains.h5")))

# 2. the error estimate over two meshes
d = f"{out}/estimate"
code, text = run(exe, np_, SCENE + ["-estimate_error"], d, expect_ok=False)
s = summary(d)
coarse = summary(f"{d}/mesh_h0.5")
est = s["design"]["error_estimate"]
ans = s["design"]["answers"]
c.check("estimate: both meshes ran to equilibrium", s["not_converged"] == [] and
        coarse["not_converged"] == [], f"({s['not_converged']}, {coarse['not_converged']})")
c.check("estimate: meshes 0.5 and 0.25 m", est["meshes"] == [0.5, 0.25] and s["h"] == 0.25 and
        coarse["h"] == 0.5)
for k in ("peak_strain", "peak_tension", "surface_settlement", "membrane_settlement",
          "differential_settlement"):
    e = est[k]
    f0, f1 = coarse["design"]["answers"][k], ans[k]
    c.check(f"estimate {k}: per-mesh values are the meshes' own", e["per_mesh"] == [f0, f1],
            f"({e['per_mesh']} vs {[f0, f1]})")
    # GCI of two meshes: Fs = 3, p = 1 assumed (2^1 - 1 = 1); round-off of one subtraction
    c.check(f"estimate {k}: error = 3 |f1 - f0|", abs(e["error"] - 3 * abs(f1 - f0)) <=
            1e-12 * abs(f1) and e["order"] == 1 and not e["order_observed"],
            f"({e['error']:.6g} vs {3 * abs(f1 - f0):.6g})")
    c.check(f"estimate {k}: Richardson extrapolation f1 + (f1 - f0)",
            abs(e["extrapolated"] - (2 * f1 - f0)) <= 1e-12 * abs(f1))
v, err, allow = ans["peak_strain"], est["peak_strain"]["error"], s["design"]["allowable"]
want = expected_verdict(v, err, allow)
c.check("estimate: verdict from value +- error", s["verdict"] == want, f"({s['verdict']})")
c.check("estimate: exit code follows the verdict",
        code == (EXIT_INCONCLUSIVE if want.startswith("INCONCLUSIVE") else EXIT_OK), f"({code})")
c.check("estimate: the log gives the strain with its error",
        f"peak membrane strain {100 * v:.4g} % +- {100 * err:.4g} % (estimated" in text)
c.check("estimate: verdict is the log's last line", last_line(text).startswith("verdict: " + want))

# the coarse mesh of -estimate_error is the standalone run at that cell size, to the last digit
d1 = f"{out}/exceeded"
code1, text1 = run(exe, np_, SCENE + ["-cover_allowable_strain", f"{v / 10:.6g}"], d1,
                   expect_ok=False)
s1 = summary(d1)
c.check("standalone coarse mesh = -estimate_error's coarse mesh",
        s1["design"]["answers"] == coarse["design"]["answers"])
c.check("allowable a tenth of the answer: EXCEEDED, exit 0", s1["verdict"] == "EXCEEDED" and
        code1 == EXIT_OK and "error_estimate" not in s1["design"], f"({s1['verdict']}, {code1})")

# 3. the allowable inside the error bar
d2 = f"{out}/inconclusive"
code2, text2 = run(exe, np_, SCENE + ["-estimate_error", "-cover_allowable_strain", f"{v:.6g}"],
                   d2, expect_ok=False)
s2 = summary(d2)
c.check("allowable = the answer: INCONCLUSIVE: refine, exit 4",
        s2["verdict"] == "INCONCLUSIVE: refine" and code2 == EXIT_INCONCLUSIVE and err > 0,
        f"({s2['verdict']}, exit {code2})")
c.check("the same meshes give the same answers", s2["design"]["answers"] == ans)

# 4. refusals
for what, args, needle in [
        ("levels out of range", ["-estimate_error", "-estimate_error_levels", "5"],
         "-estimate_error_levels"),
        ("order out of range", ["-estimate_error", "-estimate_error_order", "0.1"],
         "-estimate_error_order"),
        ("a scene without design answers", ["-options_file", "options/bar.opts", "-estimate_error"],
         "-estimate_error"),
        ("after -restart", SCENE + ["-estimate_error", "-restart", "nothing.h5"], "-restart")]:
    dd = f"{out}/bad_{what.replace(' ', '_')}"
    code, text = run(exe, np_, (SCENE if args[0] != "-options_file" and "-restart" not in args
                                else []) + args, dd, expect_ok=False)
    lines = [l for l in text.splitlines() if l.startswith("pmpm: error")]
    c.check(f"refused, {what}: exit 1, one line naming {needle}",
            code == EXIT_BAD_INPUT and len(lines) == 1 and needle in lines[0],
            f"(exit {code}: {lines[:1]})")
    c.check(f"refused, {what}: nothing written", not os.path.exists(dd))
c.done()
