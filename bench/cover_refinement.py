#!/usr/bin/python3
"""Field covers (issue 9): what resolution each shipped example needs for its answer to hold.

    /usr/bin/python3 bench/cover_refinement.py            # ~75 min on 2 cores; rewrites the
                                                          # "Field covers" section of docs/benchmarks/cover_refinement.md
    /usr/bin/python3 bench/cover_refinement.py --quick    # the slope only, two meshes, ~4 min;
                                                          # writes bench/out/cover_refinement/ only
    /usr/bin/python3 bench/cover_refinement.py --only slope,sinkhole

Each example (options/cover_*.opts) runs on 2 ranks at three cell sizes, halving from its coarsest;
the membrane's peak strain is read over one fixed gauge length per example (-cover_strain_gauge,
the coarsest cell: a gauge shorter than a cell reads the grid's cell-period noise, not the sheet),
so the three meshes measure the same quantity. The table gives, per mesh: particles, steps over
all stages, wall time, whether every stage reached -tol, the final peak strain, tension and
differential settlement, and the change of the peak strain from the next coarser mesh. The answer
holds at a mesh when the change from it to the next finer one is within 5 %.
"""
import argparse
import csv
from pathlib import Path

from benchmarks_md import publish, run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "cover_refinement"
MARK_BEGIN, MARK_END = "<!-- cover_refinement.py begin -->", "<!-- cover_refinement.py end -->"

# example: (options file, cell sizes coarse to fine, gauge length m)
EXAMPLES = {
    "slope": ("options/cover_slope.opts", [0.5, 0.25, 0.125], 1.0),  # holds at 0.25 m
    "sinkhole": ("options/cover_sinkhole.opts", [0.5, 0.25, 0.125], 0.5),
    "degradation": ("options/cover_degradation.opts", [1.0, 0.5, 0.25], 1.0),
}


def run(np_, args, out, timeout=7200):
    """Run pmpm; return (summary, stage rows) or None with the error printed."""
    s = run_pmpm(ROOT / "build" / "pmpm", np_, args, out, timeout)
    if s is None:
        return None
    with open(out / "stages.csv") as f:
        rows = list(csv.DictReader(f))
    return s, rows


def study(name, quick):
    opts, hs, gauge = EXAMPLES[name]
    if quick:
        hs = hs[:2]
    lines = [f"#### {name} ({opts}, gauge {gauge} m)", "",
             "| h (m) | particles | steps | wall (s) | all stages converged | peak strain (%) | "
             "at x (m) | peak tension (kN/m) | differential settlement (m) | change from coarser |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    prev, data = None, []
    for h in hs:
        r = run(2, ["-options_file", opts, "-cell_size", h, "-cover_strain_gauge", gauge],
                OUT / f"{name}_h{h}")
        if r is None:
            lines.append(f"| {h} | failed | | | | | | | | |")
            continue
        s, rows = r
        m = s["results"]["membrane"]
        eps = m["peak_strain"]
        change = "" if prev is None else f"{100 * (eps / prev - 1):+.1f} %"
        conv = all(q["converged"] == "1" for q in rows)
        lines.append(f"| {h} | {s['particles']} | {s['steps']} | {s['wall_seconds']:.0f} | "
                     f"{'yes' if conv else 'no'} | {100 * eps:.3f} | {m['peak_strain_x']:.2f} | "
                     f"{m['peak_tension'] / 1e3:.2f} | {m['differential_settlement']:.3f} | "
                     f"{change} |")
        data.append((h, eps, s["wall_seconds"], conv))
        prev = eps
        print(lines[-1], flush=True)
    with open(OUT / f"{name}.csv", "w") as f:
        f.write("h,peak_strain,wall_seconds,converged\n")
        for h, eps, w, conv in data:
            f.write(f"{h},{eps:.8e},{w:.2f},{int(conv)}\n")
    return lines + [""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    names = ["slope"] if a.quick else (a.only.split(",") if a.only else list(EXAMPLES))
    md = [MARK_BEGIN, "## Field covers: refinement of the shipped examples (bench/cover_refinement.py)",
          "", "2 ranks, this 2-core machine; each example's stages as shipped, the cell size "
          "halved twice, the peak strain read over a fixed gauge.", ""]
    for n in names:
        md += study(n, a.quick)
    md.append(MARK_END)
    text = "\n".join(md) + "\n"
    publish(text, OUT / "COVER_REFINEMENT.md", MARK_BEGIN, MARK_END, not a.quick and not a.only)


if __name__ == "__main__":
    main()
