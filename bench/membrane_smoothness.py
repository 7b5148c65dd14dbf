#!/usr/bin/python3
"""Membrane chains: the cell-period oscillation of the sheet's segment strain, with and without
-chain_strain_projection, on the shipped cover and trench examples, three meshes each.

    /usr/bin/python3 bench/membrane_smoothness.py                 # every example, 2 ranks
    /usr/bin/python3 bench/membrane_smoothness.py --only void,trench --np 1
    /usr/bin/python3 bench/membrane_smoothness.py --quick         # the 1 m test void only
    /usr/bin/python3 bench/membrane_smoothness.py --only degradation --meshes 1   # coarsest only

For each run the segment strains e_k come from chain_<name>.csv (its point strain is the mean of
the two adjacent segments; the first point's is its segment's, so the segments follow exactly).
The oscillation index is max_k |e_k - (e_{k-1} + e_{k+1}) / 2| / max_k e_k over the interior
segments (the two end segments excluded); the peak is the largest segment strain (no gauge).
The table gives per example, mesh and variant: steps, wall time, whether every stage converged,
the segment peak and its x, the index, the peak's change from the next coarser mesh and the
largest mean over a 1 m window (a measure that does not shrink with the cell). Writes
bench/out/membrane_smoothness/{table,results}_<examples>.{md,csv}.
"""
# Measured (this 2-core machine, shared; 1 rank unless said; segment peak %, index %):
#   test void (tests/cover_void.opts), h = 0.5 / 0.25 / 0.125 m:
#     chord      0.81 / 1.18 / 1.55, index 86 / 50 / 55
#     projected  0.43 / 0.67 / 0.80, index 3.5 / 1.7 / 1.3 (peak at the finest two 18 % apart);
#       --meshes 4 adds h = 0.0625 m: 0.94, index 0.8, 1 m gauge 0.40 / 0.63 / 0.78 / 0.89
#       (not converged: docs/benchmarks/membrane_smoothness.md, "The test void")
#   trench (options/trench.opts, its 8000 steps, not at -tol 1e-4), h = 0.25 / 0.125 / 0.0625 m:
#     chord      6.35 / 6.14 / 5.47, index 34 / 39 / 50
#     projected  4.91 / 4.65 / 4.60, index 2.5 / 3.6 / 1.7 (the largest at the support edges)
#   trench since 2026-12-05 (the shipped -tol 1e-3, reached at every mesh; 1 rank):
#     projected  4.656 / 4.652 / 4.599, index 3.07 / 2.64 / 2.43, beyond a cell of the edges
#       1.51 / 1.22 / 1.56 (at the edges the strain jumps by the capstan factor)
#   degradation (options/cover_degradation.opts), h = 1 / 0.5 m:
#     chord      8.37 / 8.28, index 2.9 / 7.0;  projected 8.26 / 8.24, index 1.1 / 1.7
#   sinkhole (options/cover_sinkhole.opts, 2 ranks), h = 0.5 m only (17 min a run here):
#     chord 1.86, index 23.8;  projected 1.50, index 2.5
import argparse
import csv
import glob
from pathlib import Path

import numpy as np

from benchmarks_md import run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "membrane_smoothness"

# example: (options file, cell sizes coarse to fine, extra options for every run, the x of the
# sharp support edges the sheet turns over: the last column leaves out a cell either side of them)
EXAMPLES = {
    "void": ("tests/cover_void.opts", [0.5, 0.25, 0.125, 0.0625], [], []),  # --meshes 4: 0.0625
    "sinkhole": ("options/cover_sinkhole.opts", [0.5, 0.25, 0.125], [], []),
    "degradation": ("options/cover_degradation.opts", [1.0, 0.5, 0.25], [], []),
    "trench": ("options/trench.opts", [0.25, 0.125, 0.0625], [], [2.25, 4.25]),
}
VARIANTS = {"chord": ["-chain_strain_projection", "0"], "projected": []}  # projected: default


def segment_strains(d):
    """Segment strains and midpoints x of the run's (first) chain, from its point strains."""
    f = sorted(glob.glob(str(d / "chain_*.csv")))[0]
    a = np.genfromtxt(f, delimiter=",", names=True)
    p = a["strain"]
    e = np.empty(len(p) - 1)
    e[0] = p[0]
    for k in range(1, len(e)):
        e[k] = 2 * p[k] - e[k - 1]
    return e, 0.5 * (a["x"][1:] + a["x"][:-1])


def gauge_peak(e, xm, g=1.0):
    """The largest mean strain over a window g long (laid length ~ x): a measure independent of
    the cell size."""
    best = -np.inf
    for c in xm:
        m = np.abs(xm - c) <= 0.5 * g
        best = max(best, e[m].mean())
    return best


def oscillation(e, xm=None, edges=(), h=0.0):
    """max |e_k - (e_{k-1} + e_{k+1}) / 2| over interior segments, over the peak; with edges,
    leaving out the segments within h of them (where the strain jumps: a second difference
    measures the jump there, not an oscillation)."""
    r = np.abs(e[2:-2] - 0.5 * (e[1:-3] + e[3:-1]))
    if len(edges):
        keep = np.min([np.abs(xm[2:-2] - x) for x in edges], axis=0) > h
        r = r[keep]
    return r.max() / np.abs(e).max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", default="")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--variants", default="chord,projected")
    ap.add_argument("--meshes", type=int, default=3, help="the first N meshes only (coarse first)")
    ap.add_argument("extra", nargs="*", help="pmpm options for every run (e.g. -max_steps 5000)")
    a = ap.parse_args()
    names = ["void"] if a.quick else (a.only.split(",") if a.only else list(EXAMPLES))
    OUT.mkdir(parents=True, exist_ok=True)
    lines = ["| example | variant | h (m) | steps | wall (s) | converged | segment peak (%) | "
             "at x (m) | oscillation index (%) | peak change from coarser | 1 m gauge peak (%) | "
             "index beyond a cell of the edges (%) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    rows = []
    print("\n".join(lines), flush=True)
    for n in names:
        opts, hs, more, edges = EXAMPLES[n]
        hs = hs[:a.meshes]
        for v in a.variants.split(","):
            prev = None
            for h in hs:
                d = OUT / f"{n}_{v}_h{h}"
                s = run_pmpm(ROOT / "build" / "pmpm", a.np,
                             ["-options_file", opts, "-cell_size", str(h)] + more + VARIANTS[v] +
                             a.extra, d)
                if s is None:
                    lines.append(f"| {n} | {v} | {h} | failed | | | | | | | | |")
                    print(lines[-1], flush=True)
                    continue
                e, xm = segment_strains(d)
                k = int(np.argmax(e))
                osc = oscillation(e)
                change = "" if prev is None else f"{100 * (e[k] / prev - 1):+.1f} %"
                conv = s.get("converged")
                lines.append(f"| {n} | {v} | {h} | {s.get('steps', '')} | "
                             f"{s.get('wall_seconds', 0):.0f} | {conv} | {100 * e[k]:.3f} | "
                             f"{xm[k]:.2f} | {100 * osc:.1f} | {change} | "
                             f"{100 * gauge_peak(e, xm):.3f} | "
                             f"{100 * oscillation(e, xm, edges, h):.1f} |")
                print(lines[-1], flush=True)
                rows.append([n, v, h, s.get("steps", ""), conv, e[k], xm[k], osc])
                prev = e[k]
    tag = "_".join(names)
    (OUT / f"table_{tag}.md").write_text("\n".join(lines) + "\n")
    with open(OUT / f"results_{tag}.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["example", "variant", "h", "steps", "converged", "segment_peak", "peak_x",
                    "oscillation_index"])
        w.writerows(rows)


if __name__ == "__main__":
    main()
