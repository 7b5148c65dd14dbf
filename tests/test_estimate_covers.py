"""-estimate_error on every shipped cover example (issue 21), at coarse cells so that CI can afford
it (the shipped cells are bench/estimate_error.py's): the slope and the degradation at 2 and 1 m,
the sinkhole at 0.5 and 0.25 m (its first void, 0.5 m wide, needs two particle columns; its
voids to 1.5 m), on 2 ranks. For each: the process ends with a verdict and the exit code that goes with it; every design answer has an error bar that is the GCI of the two meshes'
own values (3 |f_h - f_2h|, order 1 assumed); the verdict is the peak strain +- its error against
the example's allowable, or NOT CONVERGED naming the stages that stopped at their cap.

usage: test_estimate_covers.py EXE OUTDIR
"""
import sys

from pmpmtest import (EXIT_INCONCLUSIVE, EXIT_NOT_CONVERGED, EXIT_OK, Checks, expected_verdict,
                      run, summary)

exe, out = sys.argv[1], sys.argv[2]
c = Checks("estimate_covers")
# the sinkhole's 0.5 m void needs two particle columns: h <= 0.5; its voids stop at 1.5 m here
# (at h = 0.25 m the 2 m void took 11,425 of its 19,406 steps); the degradation's stages at
# h = 2 m stop at their step cap (the NOT CONVERGED path), so its cap is 5,000 steps here, twice
# the most its 1 m mesh needs (2,557), instead of the example's 30,000
EXAMPLES = [("slope", 2.0, []), ("degradation", 2.0, ["-max_steps", "5000"]),
            ("sinkhole", 0.5, ["-cover_void_widths", "0.5,1,1.5"])]
KEYS = ("peak_strain", "peak_tension", "surface_settlement", "membrane_settlement",
        "differential_settlement")

for name, h, extra in EXAMPLES:
    d = f"{out}/{name}"
    code, text = run(exe, 2, ["-options_file", f"options/cover_{name}.opts", "-cell_size", str(h),
                              "-estimate_error"] + extra, d, expect_ok=False)
    s = summary(d)
    coarse = summary(f"{d}/mesh_h{h:g}")
    est, ans = s["design"]["error_estimate"], s["design"]["answers"]
    c.check(f"{name}: meshes {h:g} and {h / 2:g} m", est["meshes"] == [h, h / 2])
    for k in KEYS:
        e = est[k]
        f0, f1 = coarse["design"]["answers"][k], ans[k]
        c.check(f"{name} {k}: GCI of the two meshes' values",
                e["per_mesh"] == [f0, f1] and abs(e["error"] - 3 * abs(f1 - f0)) <=
                1e-12 * max(abs(f1), 1e-30), f"({f1:.5g} +- {e['error']:.3g})")
    c.check(f"{name}: a sheet that stretches and a cover that settles",
            ans["peak_strain"] > 0 and ans["surface_settlement"] > 0)
    capped = [q for q in s["not_converged"]]
    if capped:
        want, want_code = "NOT CONVERGED", EXIT_NOT_CONVERGED
    else:
        v, err, allow = ans["peak_strain"], est["peak_strain"]["error"], s["design"]["allowable"]
        want = expected_verdict(v, err, allow)
        want_code = EXIT_INCONCLUSIVE if want.startswith("INCONCLUSIVE") else EXIT_OK
    c.check(f"{name}: verdict {want}, exit {want_code}", s["verdict"] == want and code == want_code,
            f"({s['verdict']}, exit {code}; not converged: {capped})")
    c.check(f"{name}: the log ends with the verdict", f"verdict: {want}" in text)
c.done()
