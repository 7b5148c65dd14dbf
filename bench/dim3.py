#!/usr/bin/python3
"""The explicit step in 3D (-dim 3, issue 22): time per step by phase and peak memory per
particle of the extruded column at about 1 M and 4 M particles, beside the 2D column at 262 k and
a 2D baseline binary (the 2D path must keep its speed: within 3 %).

    /usr/bin/python3 bench/dim3.py                 # ~4 min on 1 core (plus a baseline build);
                                                   # writes bench/out/dim3/DIM3.md and
                                                   # docs/benchmarks/dim3.md
    /usr/bin/python3 bench/dim3.py --quick         # 2D and 1 M only, no baseline, no docs
    /usr/bin/python3 bench/dim3.py --baseline REV  # the 2D baseline's git revision (default
                                                   # 20c9024, main before the 3D step)

Every run takes a fixed number of steps (-tol 1e-30) on one rank, with -log_view; the table gives
the Relaxation stage's seconds per step, the step's phases (P2G, G2P, StressUpdate, GridUpdate) in
ms per step, particle-updates per second, and the peak resident size (/usr/bin/time) less the 48 MB
a rank's libraries take, per particle. The 2D rows alternate the baseline and this build, three
times each (the machine may be shared): medians.
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from benchmarks_md import build_revision, launch, publish  # noqa: E402
from run import parse_log  # noqa: E402

OUT = ROOT / "bench" / "out" / "dim3"
MARK_BEGIN, MARK_END = "<!-- dim3.py begin -->", "<!-- dim3.py end -->"
COLUMN = ["-options_file", "options/column.opts", "-column_width", "1", "-tol", "1e-30",
          "-ramp_steps", "10"]
# label -> (extra options, steps)
CASES = {
    "2D, h = 1/256": (["-cell_size", "0.00390625"], 50),
    "3D, h = 1/64, depth 0.5": (["-cell_size", "0.015625", "-dim", "3", "-depth", "0.5"], 20),
    "3D, h = 1/64, depth 2": (["-cell_size", "0.015625", "-dim", "3", "-depth", "2"], 10),
}
PHASES = ("P2G", "G2P", "StressUpdate", "GridUpdate")
BASE_RSS_KB = 48 * 1024
# Particle state one 3D update must move at least (bytes): read x, v, lp (3 each), F (9), stress
# (6), mass, vol0, weight, eps_p, mat (29 values); write x, v (3 each), F (9), stress (6), vol,
# eps_p (23); the velocity gradient written by G2P and read by the stress update (9 + 9):
# 70 x 8 = 560 B. 2D: 404 B (docs/benchmarks/run.md, section 2).
STATE_BYTES = {2: 404, 3: 560}


def triad():
    """This machine's STREAM triad bandwidth (bench/stream.c, 1 thread, 2^25 doubles, best of 10),
    bytes per second."""
    exe = OUT / "stream"
    OUT.mkdir(parents=True, exist_ok=True)
    subprocess.run(["gcc", "-O3", "-o", str(exe), str(ROOT / "bench" / "stream.c")], check=True)
    out = subprocess.run([str(exe), "25", "10"], stdout=subprocess.PIPE, text=True,
                         check=True).stdout
    return float(re.search(r"triad_GBps (\S+)", out).group(1)) * 1e9


def run(exe, label, tag):
    """One fixed-step run on one rank under GNU time (its peak resident size)."""
    extra, steps = CASES[label]
    s, log = launch("/usr/bin/time", 1, ["-f", "RSS_KB %M", exe] + COLUMN + extra +
                    ["-max_steps", steps, "-log_view"], OUT / tag)
    if s is None:
        print(log[-3000:])
        sys.exit(f"pmpm failed: {label}")
    stages, events = parse_log(log)
    phases = {ph: events[ph]["max_s"] / steps * 1e3 if ph in events else 0.0 for ph in PHASES}
    rss = int(re.search(r"RSS_KB (\d+)", log).group(1))
    return {"n": s["particles"], "step_s": stages["Relaxation"] / steps, "phases": phases,
            "rss_kb": rss, "steps": steps}


def row(label, r, bw):
    ph = " | ".join(f"{r['phases'][p]:.1f}" for p in PHASES)
    dim = 3 if label.startswith("3D") else 2
    per = r["step_s"] / r["n"]  # seconds per particle update
    return (f"| {label} | {r['n']:,} | {r['steps']} | {r['step_s'] * 1e3:.1f} | {ph} | "
            f"{r['n'] / r['step_s'] / 1e6:.2f} | {per * bw:.0f} | "
            f"{per * bw / STATE_BYTES[dim]:.1f} | {r['rss_kb'] / 1024:.0f} | "
            f"{(r['rss_kb'] - BASE_RSS_KB) * 1024 / r['n']:.0f} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--baseline", default="20c9024")
    a = ap.parse_args()
    exe = ROOT / "build" / "pmpm"
    bw = triad()
    rows = []
    two = list(CASES)[0]
    if not a.quick:
        base = build_revision(a.baseline, "dim3")
        b, c = [], []
        for k in range(3):
            b.append(run(base, two, f"2d_base_{k}"))
            c.append(run(exe, two, f"2d_{k}"))
        med = lambda rs: sorted(rs, key=lambda r: r["step_s"])[1]  # noqa: E731
        rows.append(row(f"{two}, baseline {a.baseline}", med(b), bw))
        rows.append(row(f"{two}, this build", med(c), bw))
        ratio = med(c)["step_s"] / med(b)["step_s"]
    else:
        rows.append(row(f"{two}, this build", run(exe, two, "2d_0"), bw))
        ratio = None
    for label in list(CASES)[1:(2 if a.quick else 3)]:
        rows.append(row(label, run(exe, label, label.replace(" ", "").replace(",", "_")
                                   .replace("/", "").replace("=", "")), bw))
    text = "\n".join([
        MARK_BEGIN, "## The explicit step in 3D: time and memory", "",
        "`/usr/bin/python3 bench/dim3.py`: the column (`options/column.opts`, width 1 m, linear "
        "elastic, 2 ppc) on one rank, a fixed number of steps; 3D is the same column extruded "
        "(`-dim 3 -depth D`, 8 particles a cell). Phases in ms per step from `-log_view`; "
        "memory is the peak resident size and, per particle, that less the 48 MB of a rank's "
        "libraries (it includes the grid and the particles file's output buffers).", "",
        f"Bandwidth: STREAM triad {bw / 1e9:.1f} GB/s (bench/stream.c, 1 thread). "
        "`triad bytes` is what a purely bandwidth-bound kernel would move in the time of one "
        "particle update; `x state` divides it by the particle state an update must move at "
        f"least ({STATE_BYTES[2]} B in 2D, {STATE_BYTES[3]} B in 3D: positions, velocities, "
        "half-sizes, F, stress, scalars, and the velocity gradient between G2P and the stress "
        "update). The bandwidth bound is that state over the triad bandwidth; the step runs "
        "that many times slower than it.", "",
        "| run | particles | steps | ms / step | P2G | G2P | StressUpdate | GridUpdate | "
        "M particle-updates / s | triad bytes / update | x state | peak RSS (MB) | B / particle |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        *rows, "",
        "In 3D a uGIMP block straddling cell faces touches 3 x 3 x 3 = 27 nodes with 3 components "
        "(P2G scatters mass, momentum and force into 10 values a node; G2P gathers 6), against 9 "
        "in 2D: three times the stencil work for 1.4 times the particle state, so the 3D step is "
        "further from the bandwidth bound than the 2D one, and the time goes where 2D's does "
        "(docs/benchmarks/run.md, section 2): the scatter-add into the grid and the gather from "
        "it. No lean plain-array 3D loop was written yet: the 2D comparison of pmpm against its "
        "own leaner cycle is docs/benchmarks/lean_cycle.md.",
        (f"2D this build / baseline, ms per step (medians of 3, alternated): {ratio:.3f}."
         if ratio else "(--quick: no baseline.)"),
        MARK_END, ""])
    OUT.mkdir(parents=True, exist_ok=True)
    publish(text, OUT / "DIM3.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
