#!/usr/bin/python3
"""The linear solver under -solver newton against the number of unknowns (issue 12): MUMPS LU
(AMD ordering, and METIS by -mat_mumps_icntl_7 5), GMRES + GAMG and GMRES + hypre BoomerAMG on
the bonded landfill (options/landfill.opts) at three or four cell sizes: Newton and linear
iterations, wall time and peak memory.

    /usr/bin/python3 bench/linear_solvers.py           # ~15 min on 2 cores; rewrites the "Linear
                                                       # solvers" section of docs/benchmarks/linear_solvers.md
    /usr/bin/python3 bench/linear_solvers.py --quick   # h = 1 and 0.5 mm; bench/out only

One rank each, run without mpiexec (an MPI singleton) so that /usr/bin/time's peak resident set
is pmpm's own. The unknowns are 2 per grid node (held and unsupported nodes included: they are
identity rows). Time is summary.json's wall_seconds (the solve, not the setup). The iterative
solvers run to -ksp_rtol 1e-10 so that Newton's iterations match the direct solve's; a looser
tolerance would cost Newton iterations instead.
"""
import argparse
import json
import shutil
import subprocess
import time
from pathlib import Path

from benchmarks_md import MPI_ENV, ROOT, publish

OUT = ROOT / "bench" / "out" / "linear_solvers"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- linear_solvers.py begin -->", "<!-- linear_solvers.py end -->"

SOLVERS = [
    ("MUMPS LU (AMD)", []),
    ("MUMPS LU (METIS)", ["-mat_mumps_icntl_7", "5"]),
    ("GMRES + GAMG", ["-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-10"]),
    ("GMRES + hypre", ["-ksp_type", "gmres", "-pc_type", "hypre", "-ksp_rtol", "1e-10"]),
]


def run(h, extra, out, timeout=3600):
    """pmpm on one rank with its peak RSS; the summary with "rss_mb", or {"error": ...}."""
    out = Path(out)
    if out.is_dir():
        shutil.rmtree(out)
    cmd = ["/usr/bin/time", "-f", "RSS_KB %M", str(EXE), "-options_file", "options/landfill.opts",
           "-solver", "newton", "-cell_size", repr(h)] + extra + ["-output_dir", str(out),
                                                                   "-quiet"]
    t0 = time.time()
    p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=timeout)
    if p.returncode != 0:
        return {"error": p.stdout.strip().splitlines()[-2:]}
    with open(out / "summary.json") as f:
        s = json.load(f)
    s["elapsed"] = time.time() - t0
    s["rss_mb"] = next(int(ln.split()[1]) for ln in p.stdout.splitlines()
                       if ln.startswith("RSS_KB")) / 1024.0
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="h = 1 and 0.5 mm; no docs/benchmarks/linear_solvers.md")
    a = ap.parse_args()
    hs = (0.001, 0.0005) if a.quick else (0.001, 0.0005, 0.00025, 0.000125)
    rows = []
    for h in hs:
        for label, extra in SOLVERS:
            # GAMG's setup grows past the others' whole runs at the finest size: left out there
            if h < 0.0002 and "GAMG" in label:
                continue
            s = run(h, extra, OUT / f"h{h * 1e3:g}mm_{label.split()[0]}_{len(extra)}")
            rows.append((h, label, s))
            if "error" in s:
                print(f"h = {h * 1e3:g} mm, {label}: failed: {s['error']}", flush=True)
                continue
            nw = s["newton"]
            print(f"h = {h * 1e3:g} mm, {label}: {s['wall_seconds']:.2f} s, "
                  f"{nw['nonlinear_iterations']} Newton / {nw['linear_iterations']} linear, "
                  f"{s['rss_mb']:.0f} MB", flush=True)
    lines = [MARK_BEGIN, "## Linear solvers under Newton (bench/linear_solvers.py)", "",
             "Bonded landfill (options/landfill.opts) under `-solver newton`, 1 rank; unknowns = 2 "
             "per grid node; time = the solve's wall seconds; memory = peak resident set of the "
             "process (setup and output included). Iterative solvers to -ksp_rtol 1e-10.", "",
             "| h (mm) | unknowns | particles | solver | Newton its | linear its | wall (s) | "
             "peak RSS (MB) | centre settlement (mm) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for h, label, s in rows:
        if "error" in s:
            lines.append(f"| {h * 1e3:g} | | | {label} | failed: {' '.join(s['error'])} | | | | |")
            continue
        nx, ny = s["cells"]
        nw = s["newton"]
        settle = f"{1e3 * s['results']['settlement_centre']:.4f}"
        lines.append(f"| {h * 1e3:g} | {2 * (nx + 1) * (ny + 1)} | {s['particles']} | {label} | "
                     f"{nw['nonlinear_iterations']} | {nw['linear_iterations']} | "
                     f"{s['wall_seconds']:.2f} | {s['rss_mb']:.0f} | {settle} |")
    lines += ["", "Command: `/usr/bin/python3 bench/linear_solvers.py`. The machine is shared "
              "(2 cores): times vary up to 2x between runs; compare within a row group.", MARK_END]
    OUT.mkdir(parents=True, exist_ok=True)
    publish("\n".join(lines) + "\n", OUT / "linear_solvers.md", MARK_BEGIN, MARK_END,
            not a.quick)


if __name__ == "__main__":
    main()
