#!/usr/bin/python3
"""The 3D cover (issue 23): refinement of options/cover_sinkhole_3d.opts, and the same cover as a
body of revolution.

    /usr/bin/python3 bench/cover3d.py            # 3D at h = 0.5, 0.25, 0.125 m and axisymmetric
                                                 # at 0.5, 0.25, 0.125 m, 2 ranks: about an hour on
                                                 # 2 cores; rewrites docs/benchmarks/cover3d.md
    /usr/bin/python3 bench/cover3d.py --quick    # 3D at 0.5 and 0.25 m (about 4 minutes); writes
                                                 # bench/out/cover3d/ only
    /usr/bin/python3 bench/cover3d.py --reuse    # read runs already in bench/out/cover3d/ (their
                                                 # summary.json) instead of running them again
    --exe PATH: another pmpm binary (default build/pmpm)

The example: a quarter of a round void at the top of 3 m of waste, its centre on the symmetry
planes x = 0 and z = 0, under the layers and HDPE sheet of the 2D sinkhole, the void growing 0.5,
1, 1.5, 2, 2.5 m across. The axisymmetric runs are the same options with -dim 2 -geometry
axisymmetric (a cylinder of radius 6 m about the void's axis). Per run and stage: the void's
diameter as the particles see it, the membrane and surface settlement, the sheet's peak strain
(3D: the major principal strain of a point, with the minor strain there; axisymmetric: the
largest principal strain over one cell), the steps; per run: particles, wall time, and whether
every stage reached -tol.
"""
import argparse
import csv
import json
from pathlib import Path

from benchmarks_md import launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "cover3d"
MARK_BEGIN, MARK_END = "<!-- cover3d.py begin -->", "<!-- cover3d.py end -->"
OPTS = "options/cover_sinkhole_3d.opts"
AXI = ["-dim", "2", "-depth", "0", "-geometry", "axisymmetric"]


def run(exe, name, args, reuse):
    """(summary, stage rows) of one run, or None."""
    out = OUT / name
    if not (reuse and (out / "summary.json").exists()):
        s, log = launch(exe, 2, ["-options_file", OPTS, "-estimate_error", "0"] + args, out,
                        timeout=4 * 3600)
        if s is None:
            print(log)
            return None
    with open(out / "summary.json") as f:
        s = json.load(f)
    with open(out / "stages.csv") as f:
        return s, list(csv.DictReader(f))


def table(title, runs):
    """One table: a row per stage and mesh."""
    lines = [f"#### {title}", "",
             "| h (m) | stage | void (m) | membrane settlement (mm) | surface settlement (mm) | "
             "peak strain (%) | minor there (%) | steps |",
             "|---|---|---|---|---|---|---|---|"]
    for h, (s, rows) in runs:
        for r in rows[1:]:
            minor = f"{100 * float(r['peak_strain_minor']):.3f}" if "peak_strain_minor" in r else ""
            lines.append(f"| {h} | {r['stage']} | {float(r['void_width']):.3f} | "
                         f"{1e3 * float(r['membrane_settlement']):.2f} | "
                         f"{1e3 * float(r['surface_settlement']):.2f} | "
                         f"{100 * float(r['peak_strain']):.3f} | {minor} | {r['steps']} |")
    lines += ["", "| h (m) | particles | ranks | steps | wall (s) | all stages converged |",
              "|---|---|---|---|---|---|"]
    for h, (s, rows) in runs:
        conv = all(q["converged"] == "1" for q in rows)
        lines.append(f"| {h} | {s['particles']} | {s['ranks']} | {s['steps']} | "
                     f"{s['wall_seconds']:.0f} | {'yes' if conv else 'no'} |")
    return lines + [""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--exe", default=str(ROOT / "build" / "pmpm"))
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    hs = [0.5, 0.25] if a.quick else [0.5, 0.25, 0.125]
    md = [MARK_BEGIN, "## The 3D cover: a round void (bench/cover3d.py)", "",
          f"`{OPTS}` on 2 ranks of this 2-core machine, the cell size halved twice, beside the same "
          "cover as a body of revolution.", ""]
    for title, extra in (("3D (a quarter, -dim 3)", []), ("axisymmetric (-geometry axisymmetric)",
                                                          AXI)):
        if a.quick and extra:
            continue
        runs = []
        for h in hs:
            tag = ("axi" if extra else "3d") + f"_h{h}"
            r = run(a.exe, tag, extra + ["-cell_size", str(h)], a.reuse)
            if r is not None:
                runs.append((h, r))
                print(f"{tag}: {r[0]['wall_seconds']:.0f} s", flush=True)
        md += table(title, runs)
    md.append(MARK_END)
    publish("\n".join(md) + "\n", OUT / "COVER3D.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
