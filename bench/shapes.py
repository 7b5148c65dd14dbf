#!/usr/bin/python3
"""Shapes (issue 11): error against time for -shape mpm, pmpm (uGIMP) and cpgimp, so the shipped
default stays chosen by evidence.

    /usr/bin/python3 bench/shapes.py                       # ~10 min on 2 cores; rewrites the
                                                           # "Shapes" section of docs/benchmarks/shapes.md
    /usr/bin/python3 bench/shapes.py --quick               # seconds; bench/out/shapes/ only
    /usr/bin/python3 bench/shapes.py --baseline EXE        # also time uGIMP with EXE, a pmpm
                                                           # built from the parent revision

1. The bar past 60 % stretch (options/bar_large.opts, neo-Hookean, t = 4.63e6 Pa, -ppc 4) at four
   cell sizes: L2 errors of sigma_xx and of the displacement against the exact homogeneous
   stretch (tests/closed_forms.py neo_hookean_bar), computed here from particles.h5.
2. The column past 40 % compression (options/column_large.opts, -mat_column_gamma 6e5: J = 0.566
   at the base) at four cell sizes: the scene's L2 stress and displacement errors.
3. A stiff layer on a soft one (options/layers.opts, E_top / E_bottom = 1e2 and 1e5): the
   scene's L2 stress error and interface settlement error.
4. Cost per step: the column at h = 1/64 for a fixed 3000 steps, best of 5 alternating runs (CPU
   seconds of the process): pmpm and cpgimp with this build, pmpm with --baseline's.
Time is the relaxation wall time (summary.json wall_seconds), 1 rank; runs that fail or do not
converge are listed with their error and left out of the plot.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from benchmarks_md import MPI_ENV, error_line, launch, publish

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from closed_forms import neo_hookean_bar  # noqa: E402

OUT = ROOT / "bench" / "out" / "shapes"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- shapes.py begin -->", "<!-- shapes.py end -->"
SHAPES = ("mpm", "pmpm", "cpgimp")
T_BAR, E_BAR, NU_BAR = 4.63e6, 1e7, 0.3
BAR = ["-options_file", "options/bar_large.opts", "-mat_bar_model", "neo_hookean",
       "-bar_traction", repr(T_BAR), "-bar_box_length", "2.0", "-ppc", "4"]
COLUMN = ["-options_file", "options/column_large.opts", "-mat_column_gamma", "6e5"]
LAYERS = ["-options_file", "options/layers.opts", "-mat_bottom_gamma", "2e4", "-mat_top_gamma",
          "2e4"]


def run(args, out, exe=EXE, timeout=3600):
    """Run pmpm on 1 rank; its summary (with elapsed) or {"error": message}."""
    s, output = launch(exe, 1, args, out, timeout)
    if s is None:
        return {"error": error_line(output, 200).split(": ", 2)[-1].split(". ")[0]}
    return s


def bar_errors(out):
    """L2 errors of sigma_xx and of u against the exact homogeneous stretch (as test_cpgimp.py)."""
    import h5py
    ex = neo_hookean_bar(T_BAR, E_BAR, NU_BAR)
    with h5py.File(Path(out) / "particles.h5", "r") as f:
        X, x, s = (f["particles/" + k][:] for k in ("position0", "position", "stress"))
    ue = np.column_stack(((ex["l1"] - 1) * X[:, 0], (ex["l2"] - 1) * X[:, 1]))
    es = float(np.sqrt(np.mean((s[:, 0] - ex["sigma_xx"]) ** 2)) / ex["sigma_xx"])
    eu = float(np.sqrt(np.sum((x - X - ue) ** 2) / np.sum(ue ** 2)))
    return es, eu


def sweep(name, base, hs, h0, errors, quick):
    """Every shape at every h; rows (h, shape, particles, steps, converged, time, es, eu, note).
    The options file's ramp (2000 steps at its cell size h0) is scaled by h0 / h, so every mesh
    ramps the load over the same physical time, a few wave transits (docs/limitations.md:
    a fixed step count is a faster, more dynamic ramp on a finer mesh)."""
    rows = []
    for h in hs[:2] if quick else hs:
        ramp = round(2000 * h0 / h)
        for shape in SHAPES:
            out = OUT / f"{name}_{shape}_h{h:g}"
            s = run(base + ["-cell_size", repr(h), "-shape", shape, "-ramp_steps", ramp,
                            "-max_steps", 10 * ramp + 20000], out)
            if "error" in s:
                rows.append((h, shape, None, None, False, None, None, None, s["error"]))
            else:
                es, eu = errors(s, out)
                rows.append((h, shape, s["particles"], s["steps"], s["converged"],
                             s["wall_seconds"], es, eu, ""))
            print(name, rows[-1], flush=True)
    return rows


def table(rows, hname="h (m)"):
    md = [f"| {hname} | shape | particles | steps | converged | time (s) | stress err | "
          "displ. err | note |", "|---|---|---|---|---|---|---|---|---|"]
    for h, shape, n, steps, conv, t, es, eu, note in rows:
        if n is None:
            md.append(f"| {h:g} | {shape} | | | failed | | | | {note} |")
        else:
            md.append(f"| {h:g} | {shape} | {n} | {steps} | {'yes' if conv else 'no'} | "
                      f"{t:.3g} | {es:.3g} | {eu:.3g} | |")
    return md


def cpu_seconds(exe, args, out):
    """CPU seconds of one run and its particle count."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    subprocess.run([str(exe)] + args + ["-output_dir", str(out), "-quiet"], cwd=ROOT, env=MPI_ENV,
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(Path(out) / "summary.json") as f:
        n = json.load(f)["particles"]
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - r0, n


def cost(baseline, repeats):
    """Best-of-N CPU seconds of the column at h = 1/64 over a fixed 3000 steps."""
    args = COLUMN + ["-cell_size", "0.015625", "-tol", "1e-300", "-max_steps", "3000"]
    runs = [("pmpm (this build)", EXE, "pmpm"), ("cpgimp (this build)", EXE, "cpgimp")]
    if baseline:
        runs.insert(0, ("pmpm (parent revision)", Path(baseline), "pmpm"))
    best, n = {k: float("inf") for k, _, _ in runs}, 0
    for _ in range(repeats):  # alternate, so a busy spell of the shared machine hits all alike
        for k, exe, shape in runs:
            sec, n = cpu_seconds(exe, args + ["-shape", shape], OUT / "cost")
            best[k] = min(best[k], sec)
    return [f"- {k}: {1e3 * v / 3000:.4f} ms per step ({1e6 * v / 3000 / n:.3f} us per particle "
            f"per step)" for k, v in best.items()], best


def plot(bar, col, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, rows, title in ((axes[0], bar, "bar, 60 % stretch (ppc 4)"),
                            (axes[1], col, "column, 43 % compression (ppc 2)")):
        for shape, mk, col in zip(SHAPES, "sod", ("C2", "C0", "C1")):
            pts = [(t, es) for h, s, n, st, conv, t, es, eu, note in rows
                   if s == shape and n is not None and conv]
            if pts:
                ax.loglog(*zip(*pts), mk + "-", color=col, label=shape)
        ax.axhline(0.01, color="grey", lw=0.8, ls=":")
        ax.set_xlabel("relaxation wall time (s), 1 rank")
        ax.set_ylabel("L2 stress error (relative)")
        ax.set_title(title + "\nruns that failed are left out", fontsize=10)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--baseline", default="", help="pmpm built from the parent revision")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    load0 = os.getloadavg()[0]

    bar = sweep("bar", BAR, [0.125, 0.0625, 0.03125, 0.015625], 0.05,
                lambda s, out: bar_errors(out), a.quick)
    col = sweep("column", COLUMN, [0.0625, 0.03125, 0.015625, 0.0078125], 0.03125,
                lambda s, out: (s["results"]["stress_l2_error_rel"],
                                s["results"]["displacement_l2_error_rel"]), a.quick)
    lay = []
    for r in ([1e2] if a.quick else [1e2, 1e5]):
        for shape in SHAPES:
            s = run(LAYERS + ["-mat_top_E", repr(r * 1e7), "-shape", shape],
                    OUT / f"layers_{shape}_r{r:g}")
            if "error" in s:
                lay.append(f"| {r:g} | {shape} | | failed | | | | {s['error']} |")
                continue
            res = s["results"]
            lay.append(f"| {r:g} | {shape} | {s['steps']} | {'yes' if s['converged'] else 'no'} | "
                       f"{s['wall_seconds']:.3g} | {res['stress_l2_error_rel']:.3g} | "
                       f"{res['interface_settlement_error_rel']:.3g} | |")
            print(lay[-1], flush=True)
    cost_lines, _ = cost(a.baseline, 2 if a.quick else 5)
    for ln in cost_lines:
        print(ln)
    png = ROOT / "bench" / "work_precision_shapes.png"
    plot(bar, col, OUT / "work_precision_shapes.png" if a.quick else png)

    md = [MARK_BEGIN, "## Shapes: mpm, pmpm (uGIMP), cpgimp (bench/shapes.py)", "",
          f"Generated by `/usr/bin/python3 bench/shapes.py{' --baseline EXE' if a.baseline else ''}`"
          f" on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} ({(time.time() - t0) / 60:.1f}"
          f" min; load average {load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end, on "
          "this shared 2-core machine: times are indicative). 1 rank; time is the relaxation wall "
          "time; errors are L2 relative to the exact solution's norm.", "",
          "![shapes work-precision](bench/work_precision_shapes.png)", "",
          "### Bar past 60 % stretch", "",
          "`options/bar_large.opts -mat_bar_model neo_hookean -bar_traction 4.63e6 "
          "-bar_box_length 2 -ppc 4 -ramp_steps 2000 x 0.05 / h`: exact stretch 1.6006, sigma_xx = "
          "t / l2 (plane strain, dead load); errors of sigma_xx and of u over the particles.", ""]
    md += table(bar)
    md += ["", "### Column past 40 % compression", "",
           "`options/column_large.opts -mat_column_gamma 6e5 -ramp_steps 2000 x 0.03125 / h` "
           "(neo-Hookean, nu = 0): exact J = 0.566 "
           "at the base; the scene's `stress_l2_error_rel`, `displacement_l2_error_rel`.", ""]
    md += table(col)
    md += ["", "### Stiff layer on a soft one", "",
           "`options/layers.opts` with `-mat_top_E` = r x 1e7 Pa (h = 1/32 m, ppc 2): the scene's "
           "L2 stress error and interface settlement error.", "",
           "| E_top / E_bottom | shape | steps | converged | time (s) | stress err | "
           "interface settlement err | note |", "|---|---|---|---|---|---|---|---|"] + lay
    md += ["", "### Cost per step", "",
           "`options/column_large.opts -mat_column_gamma 6e5 -cell_size 0.015625 -tol 1e-300 "
           "-max_steps 3000`, CPU seconds of the process, best of "
           f"{2 if a.quick else 5} alternating runs (setup and output included):", ""]
    md += cost_lines
    md.append(MARK_END)
    text = "\n".join(md) + "\n"
    publish(text, OUT / "SHAPES.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
