#!/usr/bin/python3
"""The circular footing's capacity brackets: a uniform pressure on a disc of diameter B = 1 m on
weightless von Mises soil (options/footing.opts with -footing_shape circle, F-bar), run round
(-geometry axisymmetric) at h = B/16, B/32, B/64, and as a quarter in 3D at B/8 beside the
axisymmetric run of the same smaller soil (2 m in radius, 1.5 m deep).

    /usr/bin/python3 bench/footing_circle.py          # ~16 min on 2 cores; rewrites the
                                                      # "Circular footing" section of
                                                      # docs/benchmarks/footing.md
    /usr/bin/python3 bench/footing_circle.py --quick  # the B/8 pair only; bench/out/ only

Pressures are fractions of Shield's 5.69 k (the smooth rigid circular punch on Tresca soil, an
upper bound for the uniform load on von Mises soil); the load's edge gives the smaller upper bound
(2 + pi) k = 0.904 of it (docs/method.md, section 2.6). A stage holds when it reaches -tol 1e-4
within its 20,000 steps; the run stops at the first that does not.
"""
import argparse
import math
from pathlib import Path

from benchmarks_md import launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "footing_circle"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- footing_circle.py begin -->", "<!-- footing_circle.py end -->"
SHIELD = 5.69 * 17320.508 / math.sqrt(3.0)
FINE = (0.90, 0.95, 0.975, 1.00, 1.025, 1.05, 1.075, 1.10, 1.15, 1.20)
SMALL = ["-footing_soil_width", "2", "-footing_soil_depth", "1.5"]

# name, ranks, cell, extra arguments, stages
RUNS = [
    ("axisymmetric", 1, 0.0625, ["-geometry", "axisymmetric"], FINE),
    ("axisymmetric", 1, 0.03125, ["-geometry", "axisymmetric"], FINE),
    ("axisymmetric", 1, 0.015625, ["-geometry", "axisymmetric"], FINE),
    ("axisymmetric, soil 2 x 1.5 m", 1, 0.125, ["-geometry", "axisymmetric"] + SMALL,
     (0.9, 1.0, 1.1, 1.2)),
    ("3D quarter, soil 2 x 2 x 1.5 m", 2, 0.125, ["-dim", "3", "-depth", "2"] + SMALL,
     (0.9, 1.0, 1.1, 1.2)),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="the B/8 pair only; no docs update")
    a = ap.parse_args()
    lines = [MARK_BEGIN, "## Circular footing (bench/footing_circle.py)", "",
             f"Stages in units of Shield's 5.69 k = {SHIELD / 1e3:.2f} kPa (the edge bound "
             "(2 + pi) k is 0.904 of it); each stage: holds (settlement, mm, steps) or the stage "
             "that did not reach equilibrium.", "",
             "| run | h / B | particles | stages held: fraction (settlement mm, steps) | "
             "not in equilibrium at | loaded area / disc | wall (s) |",
             "|---|---|---|---|---|---|---|"]
    for name, np_, h, extra, stages in RUNS[3:] if a.quick else RUNS:
        args = ["-options_file", "options/footing.opts", "-footing_shape", "circle",
                "-cell_size", repr(h), "-footing_pressures",
                ",".join(f"{f * SHIELD:.6f}" for f in stages)] + extra
        tag = f"{name.split(',')[0].replace(' ', '_')}_{h}"
        s, output = launch(EXE, np_, args, OUT / tag)
        if s is None:
            lines.append(f"| {name} | 1/{round(1 / h)} | failed | | | | |")
            continue
        r = s["results"]
        held = [st for st in r["stages"] if st["holds"]]
        failed = [st for st in r["stages"] if not st["holds"]]
        row = (f"| {name} | 1/{round(1 / h)} | {s['particles']:,} | "
               + ", ".join(f"{st['pressure'] / SHIELD:.3f} ({1e3 * st['settlement']:.1f}, "
                           f"{st['steps']:,})" for st in held)
               + (f" | {failed[0]['pressure'] / SHIELD:.3f} "
                  f"({1e3 * failed[0]['settlement']:.1f}) " if failed else " | none "))
        row += f"| {r['loaded_area_ratio']:.4f} | {s['wall_seconds']:.0f} |"
        print(row, flush=True)
        lines.append(row)
    lines += ["", "Command: `/usr/bin/python3 bench/footing_circle.py`.", MARK_END]
    OUT.mkdir(parents=True, exist_ok=True)
    publish("\n".join(lines) + "\n", OUT / "footing_circle.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
