#!/usr/bin/python3
"""The 3D sheet divided among the ranks (docs/method.md, section 10): the clamped circular sheet of
options/sheet.opts at h = 0.25 m (4,921 points) on 1 and 2 ranks, where the
sheet's time goes by its -log_view events: SheetForces (the triangles a rank computes), SheetShare
(the points sent to the neighbouring ranks) and Chain (the sheet's whole share of the step, both
of those included), the slowest rank's seconds.

    /usr/bin/python3 bench/sheet_ranks.py          # ~2 min on 2 cores; rewrites
                                                   # docs/benchmarks/sheet_ranks.md
    /usr/bin/python3 bench/sheet_ranks.py --quick  # h = 0.5 m; bench/out/ only
"""
import argparse
import re
from pathlib import Path

from benchmarks_md import launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "sheet_ranks"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- sheet_ranks.py begin -->", "<!-- sheet_ranks.py end -->"
EVENTS = ("Chain", "SheetForces", "SheetShare")


def event_seconds(log, name):
    """An event's max time over the ranks (s) from -log_view's table, or nan."""
    m = re.search(rf"^{name}\s+\d+\s+[\d.]+\s+([\d.e+-]+)", log, re.M)
    return float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="h = 0.5 m; no docs update")
    ap.add_argument("--exe", default=str(EXE), help="the pmpm binary (default build/pmpm)")
    a = ap.parse_args()
    h = 0.5 if a.quick else 0.25
    rows = []
    for n in (1, 2):
        s, log = launch(a.exe, n, ["-options_file", "options/sheet.opts", "-cell_size", h,
                                   "-log_view"], OUT / f"np{n}")
        if not s:
            print(log)
            continue
        ev = {e: event_seconds(log, e) for e in EVENTS}
        rows.append((n, s["steps"], s["results"]["sag"], s["elapsed"], ev))
    lines = [MARK_BEGIN, "## The 3D sheet on 1 and 2 ranks (bench/sheet_ranks.py)", "",
             f"options/sheet.opts at h = {h} m, one core per rank. Seconds are the slowest "
             "rank's (-log_view); SheetForces and SheetShare are inside Chain.", "",
             "| ranks | steps | sag (m) | run (s) | Chain (s) | SheetForces (s) | SheetShare (s) |",
             "|---|---|---|---|---|---|---|"]
    for n, steps, sag, wall, ev in rows:
        share = "-" if n == 1 else f"{ev['SheetShare']:.2f}"  # one rank sends nothing
        lines.append(f"| {n} | {steps:,} | {sag:.6f} | {wall:.1f} | {ev['Chain']:.1f} | "
                     f"{ev['SheetForces']:.1f} | {share} |")
    if len(rows) == 2:
        lines += ["", f"The triangles on 2 ranks: {rows[1][4]['SheetForces'] / rows[0][4]['SheetForces']:.0%} "
                  "of one rank's per rank (half the disc and the band of cells at the cut); the sag "
                  f"on 2 ranks against 1: {rows[1][2] / rows[0][2] - 1:+.1e}."]
    lines.append(MARK_END)
    publish("\n".join(lines) + "\n", OUT / "table.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
