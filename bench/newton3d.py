#!/usr/bin/python3
"""-solver newton in 3D against relaxation on a problem only 3D has: the quarter circular footing
(options/footing.opts with -footing_shape circle; bench/footing_circle.py's 3D case: B = 1 m,
soil 2 x 2 x 1.5 m, h = B/8, 24,576 particles) without F-bar (Newton has none yet), so both
solvers solve the same locked discretisation.

    /usr/bin/python3 bench/newton3d.py          # ~15 min on 2 cores; rewrites
                                                # docs/benchmarks/newton3d.md
    /usr/bin/python3 bench/newton3d.py --quick  # 0.9 only; bench/out/ only

Relaxation runs the pressures as stages of one run (-tol 1e-4, kinetic damping, as shipped);
Newton runs each pressure as its own run (a pressure stage after the first is not a Newton load
path yet) with its default load steps (10, halved on failure) and 3D linear solver (GMRES with
BoomerAMG). Pressures in units of Shield's 5.69 k. Both on 1 rank, so the wall times compare the
methods, not the partitions.
"""
import argparse
import math
from pathlib import Path

from benchmarks_md import launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "newton3d"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- newton3d.py begin -->", "<!-- newton3d.py end -->"
SHIELD = 5.69 * 17320.508 / math.sqrt(3.0)
BASE = ["-options_file", "options/footing.opts", "-footing_shape", "circle", "-cell_size", "0.125",
        "-footing_soil_width", "2", "-footing_soil_depth", "1.5", "-dim", "3", "-depth", "2",
        "-fbar", "0"]


def pressures(fs):
    return ["-footing_pressures", ",".join(f"{f * SHIELD:.6f}" for f in fs)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="0.9 only; no docs update")
    ap.add_argument("--exe", default=str(EXE), help="the pmpm binary (default build/pmpm)")
    a = ap.parse_args()
    fs = (0.9,) if a.quick else (0.9, 1.0, 1.1, 1.2)
    rows = {f: {} for f in fs}
    s, out = launch(a.exe, 1, BASE + pressures(fs), OUT / "relaxation")
    relax_wall = s["elapsed"] if s else float("nan")
    if s:
        for st in s["results"]["stages"]:
            f = round(st["pressure"] / SHIELD, 3)
            if f in rows:
                rows[f]["relax"] = st
    for f in fs:
        s, out = launch(a.exe, 1, BASE + pressures((f,)) + ["-solver", "newton"], OUT / f"newton_{f}")
        if s:
            rows[f]["newton"] = (s["results"]["stages"][0], s.get("newton", {}), s["elapsed"])
    lines = [MARK_BEGIN, "## Newton in 3D: the quarter circular footing (bench/newton3d.py)", "",
             "B/8, no F-bar, 1 rank. Relaxation: one run through the stages (its wall time for "
             f"all of them: {relax_wall:.0f} s; steps per stage below). Newton: one run per "
             "pressure. Settlements in mm; a stage that does not reach equilibrium is a collapse.",
             "", "| q / Shield | relaxation: holds, settlement, steps | Newton: holds, settlement "
             "| Newton: load steps, Newton its, linear its, halvings | Newton wall (s) |",
             "|---|---|---|---|---|"]
    for f in fs:
        r, n = rows[f].get("relax"), rows[f].get("newton")
        rc = (f"{'holds' if r['holds'] else 'collapses'}, {1e3 * r['settlement']:.2f}, "
              f"{r['steps']:,}" if r else "not reached")
        if n:
            st, nw, wall = n
            nc = f"{'holds' if st['holds'] else 'collapses'}, {1e3 * st['settlement']:.2f}"
            ni = (f"{nw.get('load_steps', '')}, {nw.get('nonlinear_iterations', '')}, "
                  f"{nw.get('linear_iterations', '')}, {nw.get('halvings', '')}")
            lines.append(f"| {f:.2f} | {rc} | {nc} | {ni} | {wall:.0f} |")
        else:
            lines.append(f"| {f:.2f} | {rc} | failed | | |")
        print(lines[-1], flush=True)
    lines += ["", "Command: `/usr/bin/python3 bench/newton3d.py`.", MARK_END]
    OUT.mkdir(parents=True, exist_ok=True)
    publish("\n".join(lines) + "\n", OUT / "newton3d.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
