#!/usr/bin/python3
"""Design answers with error bars (issue 21): -estimate_error on every shipped cover example.

    /usr/bin/python3 bench/estimate_error.py              # shipped cells h and h/2, 2 ranks:
                                                          # about 25 min idle; rewrites its
                                                          # section of docs/benchmarks/estimate_error.md
    /usr/bin/python3 bench/estimate_error.py --coarse 2   # cells 2h and h (a quick look, ~4 min)
    /usr/bin/python3 bench/estimate_error.py --only slope --levels 3

Each example runs once with -estimate_error (its meshes one after the other in one process); the
table gives the verdict, the exit code, every design answer with its error bar (Roache's GCI of
the finest mesh) and the Richardson extrapolation, and the wall time of the whole process.
"""
import argparse
from pathlib import Path

from benchmarks_md import publish, run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "estimate_error"
MARK_BEGIN, MARK_END = "<!-- estimate_error.py begin -->", "<!-- estimate_error.py end -->"
EXAMPLES = {  # example: (options file, shipped cell size m)
    "slope": ("options/cover_slope.opts", 0.5),
    "degradation": ("options/cover_degradation.opts", 0.5),
    "sinkhole": ("options/cover_sinkhole.opts", 0.25),
}
ANSWERS = [("peak_strain", "peak strain", 100, "%"), ("peak_tension", "peak tension", 1e-3, "kN/m"),
           ("surface_settlement", "surface settlement", 1, "m"),
           ("differential_settlement", "differential settlement", 1, "m")]


def study(name, coarse, levels):
    opts, h = EXAMPLES[name]
    h *= coarse
    s = run_pmpm(ROOT / "build" / "pmpm", 2, ["-options_file", opts, "-cell_size", h,
                                              "-estimate_error", "-estimate_error_levels", levels],
                 OUT / name, timeout=4 * 3600)
    if s is None:
        return [f"| {name} | {h} | failed | | | | | | |"]
    est = s["design"].get("error_estimate", {})
    cells = []
    for key, _, scale, unit in ANSWERS:
        e = est.get(key)
        if e is None:
            cells.append("")
            continue
        cells.append(f"{e['value'] * scale:.4g} +- {e['error'] * scale:.3g} "
                     f"(-> {e['extrapolated'] * scale:.4g}; p {e['order']:.2g}"
                     f"{' obs.' if e['order_observed'] else ''}"
                     f"{', not monotone' if not e['monotone'] else ''})")
    meshes = ", ".join(f"{x:g}" for x in est.get("meshes", []))
    nc = "; ".join(f"h {q['h']:g}: stages {q['stages']}" for q in s["not_converged"])
    row = (f"| {name} | {meshes} | {s['verdict']}{' (' + nc + ')' if nc else ''} | "
           f"{s['exit_code']} | " + " | ".join(cells) + f" | {s['elapsed']:.0f} |")
    print(row, flush=True)
    return [row]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--coarse", type=float, default=1.0, help="cell size factor on the shipped h")
    ap.add_argument("--levels", type=int, default=2)
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    names = a.only.split(",") if a.only else list(EXAMPLES)
    md = [MARK_BEGIN, "## Design answers with error bars (bench/estimate_error.py)", "",
          f"2 ranks, this 2-core machine; each example with `-estimate_error -estimate_error_levels "
          f"{a.levels}` from {a.coarse:g} x its shipped cell size. Each answer is the finest mesh's "
          "value +- its GCI (-> the Richardson extrapolation; p the order, assumed unless "
          "`obs.`). Allowable strain 3 %.", "",
          "| example | meshes (m) | verdict | exit | " +
          " | ".join(f"{lab} ({u})" for _, lab, _, u in ANSWERS) + " | wall (s) |",
          "|---|---|---|---|" + "---|" * len(ANSWERS) + "---|"]
    for n in names:
        md += study(n, a.coarse, a.levels)
    md += ["", MARK_END]
    publish("\n".join(md) + "\n", OUT / "ESTIMATE_ERROR.md", MARK_BEGIN, MARK_END,
            a.coarse == 1.0 and not a.only and a.levels == 2)


if __name__ == "__main__":
    main()
