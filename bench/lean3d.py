#!/usr/bin/python3
"""pmpm's 3D explicit step (-dim 3, issue 22) against a lean plain-array 3D loop (bench/lean3d.cpp):
time per step by phase, particle-updates per second on one core at about 1 M particles, the ratio
pmpm / lean per phase, and both against the bandwidth bound (the bytes an update must move over
this machine's STREAM triad bandwidth).

    /usr/bin/python3 bench/lean3d.py           # ~2 min on 1 core, after waiting (up to 10 min)
                                               # for a load average below 1.3; writes
                                               # bench/out/lean3d/LEAN3D.md and
                                               # docs/benchmarks/lean3d.md
    /usr/bin/python3 bench/lean3d.py --quick   # 65 k particles, 1 run each, no docs (< 20 s)
    /usr/bin/python3 bench/lean3d.py --reps 5  # runs of each binary (default 3; medians)

The case is bench/dim3.py's 1 M one: the column extruded (options/column.opts, -column_width 1,
-cell_size 1/64, -dim 3 -depth 0.5, -ramp_steps 10), 20 steps (-tol 1e-30), one rank, -log_view.
bench/lean3d.cpp is built with pmpm's release flags (g++ -O3 -march=native -DNDEBUG) into
bench/out/lean3d/ and generates the same particles, takes the same steps (the same dt, load ramp,
FLIP / PIC blend, kinetic damping, boundary conditions, Jaumann-rate linear elastic stress) and
times its phases with std::chrono; build/pmpm is copied to bench/out/lean3d/pmpm first (a rebuild
by someone else during the runs cannot mix two versions). The binaries alternate (pmpm, then each
lean variant, --reps times; the machine may be shared), each run started when other processes use
under 0.3 cores (waiting at most 20 min in all; the study itself first waits up to 10 min for a
1-minute load average below 1.3): per binary the run of median time, with the cores other
processes used while each run ran.

Before timing, the same computation is checked: a small case (-cell_size 0.0625 -depth 0.25, 8192
particles) after 20 and 300 steps (the latter through kinetic damping's velocity resets), every
particle of every lean variant against pmpm's particles.h5 (matched by id), and at 1 M the sum of
the time steps and the mean vertical stress and displacement of both.
"""
import argparse
import re
import shutil
import subprocess
import sys
import os
import time
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from benchmarks_md import launch, publish  # noqa: E402
from run import parse_log  # noqa: E402

OUT = ROOT / "bench" / "out" / "lean3d"
MARK_BEGIN, MARK_END = "<!-- lean3d.py begin -->", "<!-- lean3d.py end -->"
CXX = ["g++", "-O3", "-march=native", "-DNDEBUG", "-std=c++17"]
COLUMN = ["-options_file", "options/column.opts", "-column_width", "1", "-tol", "1e-30",
          "-ramp_steps", "10"]
FULL = ["-cell_size", "0.015625", "-depth", "0.5"]   # 64 x 66 x 32 cells, 1,048,576 particles
QUICK = ["-cell_size", "0.03125", "-depth", "0.25"]  # 32 x 34 x 8 cells, 65,536 particles
SMALL = ["-cell_size", "0.0625", "-depth", "0.25"]   # the agreement check: 8,192 particles
STEPS = 20
PHASES = ("P2G", "GridUpdate", "G2P", "StressUpdate")
# label -> lean3d options
VARIANTS = {
    "lean, pmpm's node (10 values, scalar)": [],
    "lean, 8-value vector node": ["-node", "8"],
    "lean, 8-value node, stress in G2P": ["-node", "8", "-fuse"],
    "lean, 8-value node, stress in G2P, 27 nodes": ["-node", "8", "-fuse", "-stencil27"],
}
TAGS = {k: f"lean{i}" for i, k in enumerate(VARIANTS)}
# Bytes of particle state one update must move (each array read once by each pass that reads it,
# written once by each pass that writes it), by pass, in doubles (mat: 4 bytes):
#   P2G reads x, v, lp (3 each), mass, vol, stress (6), weight: 18
#   G2P reads x, v, lp, F (9), vol0, mass, weight (21) and mat; writes x, v, F, vol (16) and
#       dudx (9), or with the stress in G2P also reads and writes the stress (6 + 6)
#   stress update reads dudx, stress (15) and mat, writes the stress (6)
# pmpm also reads and writes eps_p in its linear elastic update and reads the material's index
# list (4 bytes), and every 5 steps its energy check reads vol, stress and mat (60 / 5 bytes).
STATE_BYTES = {"separate": (18 + 21 + 25 + 15 + 6) * 8 + 8,
               "fused": (18 + 27 + 22) * 8 + 4}
PMPM_EXTRA_BYTES = 16 + 4 + 12
NCPU = os.cpu_count() or 1
GRID_PASSES = 6  # zeroed, P2G's read and write, the grid update's read and write, G2P's read


def sh(cmd, **kw):
    return subprocess.run(cmd, cwd=ROOT, check=True, stdout=subprocess.PIPE, text=True, **kw).stdout


def load_avg():
    return float(Path("/proc/loadavg").read_text().split()[0])


def wait_quiet(limit, budget):
    """Wait (at most budget seconds) for the 1-minute load average to fall below limit."""
    t0 = time.time()
    while load_avg() >= limit and time.time() - t0 < budget:
        time.sleep(10)
    return load_avg()


def cpu_jiffies():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:9]]
    return sum(v), v[3] + v[4]  # total, idle + iowait


def busy_cores(a, b):
    """Cores busy between two cpu_jiffies() samples."""
    return NCPU * (1 - (b[1] - a[1]) / max(1, b[0] - a[0]))


class Others:
    """The cores other processes used while a run ran: the machine's busy cores less the run's
    own (its processes' CPU time over the wall time)."""

    def __enter__(self):
        self.j, self.t, self.c = cpu_jiffies(), time.time(), os.times()
        return self

    def __exit__(self, *exc):
        c = os.times()
        own = (c.children_user + c.children_system - self.c.children_user -
               self.c.children_system) / max(1e-9, time.time() - self.t)
        self.cores = max(0.0, busy_cores(self.j, cpu_jiffies()) - own)


class Quiet:
    """Before each timed run, wait until other processes use under 0.3 cores (sampled over 1 s;
    at most `budget` seconds over the whole study); each run records the cores others used while
    it ran (the busy cores less its own one)."""

    def __init__(self, budget):
        self.left = budget

    def wait(self):
        while self.left > 0:
            a = cpu_jiffies()
            time.sleep(1)
            if busy_cores(a, cpu_jiffies()) < 0.3:
                return
            time.sleep(4)
            self.left -= 5


def triad(quick):
    """This machine's STREAM triad bandwidth (bench/stream.c, 1 thread, 2^25 doubles an array, best
    of 10; --quick 2^23, best of 5), bytes per second."""
    exe = OUT / "stream"
    subprocess.run(["gcc", "-O3", "-o", str(exe), str(ROOT / "bench" / "stream.c")], check=True)
    out = sh([str(exe)] + (["23", "5"] if quick else ["25", "10"]))
    return float(re.search(r"triad_GBps (\S+)", out).group(1)) * 1e9


def lean_args(case, steps):
    """lean3d's options for a pmpm case: the column's own (options/column.opts) and the case's."""
    known = {"-ppc", "-column_height", "-mat_column_E", "-mat_column_nu", "-mat_column_gamma"}
    args = []
    for line in (ROOT / "options" / "column.opts").read_text().splitlines():
        f = line.split("#")[0].split()
        if len(f) == 2 and f[0] in known:
            args += f
    return args + ["-column_width", "1", "-ramp_steps", "10", "-max_steps", str(steps)] + case


def run_lean(exe, label, case, steps, dump=None):
    load = load_avg()
    with Others() as o:
        out = sh([str(exe)] + lean_args(case, steps) + VARIANTS[label] +
                 (["-dump", str(dump)] if dump else []))
    kv = {}
    for line in out.splitlines():
        f = line.split()
        if f[0] == "phase_ms":
            kv[f[1]] = float(f[2])
        elif len(f) == 2:
            kv[f[0]] = f[1]
    return {"n": int(kv["particles"]), "step_ms": float(kv["step_ms"]),
            "phases": {p: kv[p] for p in PHASES}, "rest": kv["rest"],
            "nodes": float(kv["nodes_per_particle"]), "time": float(kv["time"]),
            "syy": float(kv["mean_stress_yy"]), "uy": float(kv["mean_uy"]),
            "rss_kb": int(kv["peak_rss_kb"]), "load": load, "other": o.cores}


def run_pmpm(exe, case, steps, tag):
    load = load_avg()
    with Others() as o:
        s, log = launch("/usr/bin/time", 1, ["-f", "RSS_KB %M", exe] + COLUMN + case +
                        ["-dim", "3", "-max_steps", steps, "-log_view"], OUT / tag)
    if s is None:
        print(log[-3000:])
        sys.exit("pmpm failed")
    stages, events = parse_log(log)
    step_ms = stages["Relaxation"] / steps * 1e3
    phases = {p: events[p]["max_s"] / steps * 1e3 if p in events else 0.0 for p in PHASES}
    with h5py.File(OUT / tag / "particles.h5") as f:
        g = f["particles"]
        syy = float(np.mean(g["stress"][:, 1]))
        uy = float(np.mean(g["position"][:, 1] - g["position0"][:, 1]))
    (OUT / tag / "particles.h5").unlink()  # 300 MB at 1 M particles: read, not kept
    return {"n": s["particles"], "step_ms": step_ms, "phases": phases,
            "rest": step_ms - sum(phases.values()), "time": s["time"], "syy": syy, "uy": uy,
            "rss_kb": int(re.search(r"RSS_KB (\d+)", log).group(1)), "load": load,
            "other": o.cores}


def agreement(pmpm, lean):
    """Each lean variant's particles against pmpm's after 20 and 300 steps of the small case: the
    largest difference over the particles relative to the field's largest value."""
    rows = []
    for steps in (STEPS, 300):
        s, log = launch(pmpm, 1, COLUMN + SMALL + ["-dim", "3", "-max_steps", steps],
                        OUT / f"agree_{steps}")
        if s is None:
            print(log[-3000:])
            sys.exit("pmpm failed (agreement case)")
        with h5py.File(OUT / f"agree_{steps}" / "particles.h5") as f:
            P = {k: f["particles"][k][()] for k in ("id", "position", "position0", "velocity",
                                                      "stress", "F")}
        op = np.argsort(P["id"])
        u = P["position"][op] - P["position0"][op]
        for label in VARIANTS:
            dump = OUT / f"agree_{TAGS[label]}.bin"
            r = run_lean(lean, label, SMALL, steps, dump)
            raw = np.fromfile(dump, dtype=np.float64)
            n = int(raw[:1].view(np.int64)[0])
            a = raw[1:].reshape(n, 23)
            ol = np.argsort(a[:, 0])
            assert np.array_equal(a[ol, 0], P["id"][op]), "particle ids differ"
            rel = lambda x, y: float(np.abs(x - y).max() / np.abs(y).max())  # noqa: E731
            rows.append({"label": label, "steps": steps, "n": n,
                         "stress": rel(a[ol, 7:13], P["stress"][op]),
                         "u": rel(a[ol, 1:4] - P["position0"][op], u),
                         "v": rel(a[ol, 4:7], P["velocity"][op]),
                         "F": float(np.abs(a[ol, 13:22] - P["F"][op]).max()),
                         "dt_sum": (r["time"], s["time"])})
    return rows


def state_bytes(label):
    fused = label is not None and "-fuse" in VARIANTS[label]
    b = STATE_BYTES["fused" if fused else "separate"]
    return b + (PMPM_EXTRA_BYTES if label is None else 0)


def grid_bytes(label, cells, n):
    nodes = 1
    for c in cells:
        nodes *= c + 1 + 4  # two ghost layers a side
    node = 64 if label is not None and "8" in VARIANTS[label] else 80
    return GRID_PASSES * nodes * node / n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reps", type=int, default=3)
    a = ap.parse_args()
    reps = 1 if a.quick else a.reps
    OUT.mkdir(parents=True, exist_ok=True)
    pmpm = OUT / "pmpm"
    shutil.copy2(ROOT / "build" / "pmpm", pmpm)
    lean = OUT / "lean3d"
    subprocess.run(CXX + ["-o", str(lean), str(ROOT / "bench" / "lean3d.cpp")], check=True)
    agree = agreement(pmpm, lean)
    load0 = load_avg() if a.quick else wait_quiet(1.3, 600)
    bw = triad(a.quick)
    case = QUICK if a.quick else FULL
    runs = {"pmpm": []} | {k: [] for k in VARIANTS}
    quiet = Quiet(0 if a.quick else 1200)
    for k in range(reps):
        quiet.wait()
        runs["pmpm"].append(run_pmpm(pmpm, case, STEPS, f"pmpm_{k}"))
        for label in VARIANTS:
            quiet.wait()
            runs[label].append(run_lean(lean, label, case, STEPS))
    med = {k: sorted(v, key=lambda r: r["step_ms"])[len(v) // 2] for k, v in runs.items()}
    P = med["pmpm"]
    n = P["n"]
    cells = [int(round(1 / float(case[1]))), int(round(1 / float(case[1]))) + 2,
             int(round(float(case[3]) / float(case[1])))]

    def row(label, r):
        key = None if label == "pmpm" else label
        per = r["step_ms"] * 1e-3 / r["n"]                       # seconds per update
        b = state_bytes(key) + grid_bytes(key, cells, r["n"])    # bytes an update must move
        loads = ", ".join(f"{x['other']:.2f}" for x in runs[label])
        nodes = f"{r['nodes']:.1f}" if "nodes" in r else f"{med[list(VARIANTS)[0]]['nodes']:.1f}"
        return (f"| {'pmpm -dim 3' if label == 'pmpm' else label} | {r['step_ms']:.1f} | " +
                " | ".join(f"{r['phases'][p]:.1f}" for p in PHASES) + f" | {r['rest']:.1f} | "
                f"{r['n'] / r['step_ms'] * 1e-3:.2f} | {nodes} | {b:.0f} | {b / bw * 1e9:.1f} | "
                f"{per * 1e9:.1f} | {per * bw / b:.1f} | {r['rss_kb'] / 1024:.0f} | {loads} |")

    def ratio_row(label):
        L = med[label]
        cell = lambda x, y: f"{x / y:.2f}" if y > 0.05 else "fused"  # noqa: E731
        return (f"| {label} | {P['step_ms'] / L['step_ms']:.2f} | " +
                " | ".join(cell(P["phases"][p], L["phases"][p]) for p in PHASES) + " |")

    dts = lambda d: "equal" if d[0] == d[1] else f"{abs(d[0] / d[1] - 1):.1e}"  # noqa: E731
    agree_rows = [f"| {r['label']} | {r['steps']} | {r['stress']:.1e} | {r['u']:.1e} | "
                  f"{r['v']:.1e} | {r['F']:.1e} | {dts(r['dt_sum'])} |" for r in agree]
    big = [f"| {'pmpm -dim 3' if k == 'pmpm' else k} | {med[k]['time']:.17g} | "
           f"{med[k]['syy']:.12g} | {med[k]['uy']:.12g} |" for k in med]
    L10, L8, LF, L27 = (med[k] for k in VARIANTS)
    fastest = min(list(VARIANTS)[:3], key=lambda k: med[k]["step_ms"])
    LB = med[fastest]
    same = max(P["phases"]["P2G"] / L10["phases"]["P2G"], P["phases"]["G2P"] / L10["phases"]["G2P"])
    stress_ratio = P["phases"]["StressUpdate"] / L10["phases"]["StressUpdate"]
    growth = LF["phases"]["G2P"] - L8["phases"]["G2P"]  # G2P's time with the stress in it
    fused_gain = P["phases"]["StressUpdate"] - max(growth, 0.0)
    nf = lambda k: state_bytes(k) + grid_bytes(k, cells, n)  # noqa: E731
    lean_args_s = " ".join(lean_args(case, STEPS))
    text = "\n".join([
        MARK_BEGIN, "## pmpm's 3D step against a lean plain-array 3D loop", "",
        f"`/usr/bin/python3 bench/lean3d.py{' --quick' if a.quick else ''}`: the column extruded "
        f"(`options/column.opts`, width 1 m, h = {case[1]} m, depth {case[3]} m, linear elastic, "
        f"8 particles a cell: {n:,} particles, {cells[0]} x {cells[1]} x {cells[2]} cells), "
        f"{STEPS} steps on one core. pmpm's phases are its -log_view events (ms per step; `rest` "
        "is the Relaxation stage less them: the ghost layers, reductions, kinetic damping, the "
        "energy check every 5 steps); the lean loop's are std::chrono around the same phases "
        "(`rest`: the ghost layers, kinetic damping, the next dt). bench/lean3d.cpp does pmpm's "
        "step in pmpm's order with plain std::vector arrays, one per particle field (pmpm's "
        "layout: each pass streams only its fields); its variants: pmpm's 10-value node with "
        "its scalar arithmetic (the same work as plain loops), an 8-value node that is one "
        "vector (external force as one scalar, gravity added in the grid update: a node takes "
        "two vector FMAs in P2G and two in G2P), the stress update inside G2P (pmpm does that "
        "in 2D only), and every particle on 27 nodes (zero weights added).", "",
        f"Medians of {reps} alternated runs (pmpm, then each variant) per binary, each started "
        "when other processes used under 0.3 cores; the last column gives the cores they used "
        "while it ran (the machine's 2 are shared). Bandwidth: STREAM triad "
        f"{bw / 1e9:.1f} GB/s (bench/stream.c, 1 thread). `must move` is the particle state an "
        "update reads and writes, each array once per pass that touches it "
        f"({STATE_BYTES['separate']} B with the stress update as its own pass, "
        f"{STATE_BYTES['fused']} B inside G2P; pmpm {PMPM_EXTRA_BYTES} B more: eps_p read and "
        "written, the material's index list, the energy check), plus the grid moved "
        f"{GRID_PASSES} times a step (80 B a node, 64 B with 8 values) over the particles; "
        "`bound` is that over the triad bandwidth, `x bound` the measured time over it. Peak "
        "RSS: GNU time's for pmpm (with its libraries, about 48 MB), getrusage's for the lean "
        "loop (which keeps x0 and the ids for its checks).", "",
        "| run | ms / step | P2G | GridUpdate | G2P | StressUpdate | rest | "
        "M particle-updates / s | nodes / particle | must move (B / update) | bound (ns / update) "
        "| measured (ns / update) | x bound | peak RSS (MB) | others' cores during each run |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        row("pmpm", P), *[row(k, med[k]) for k in VARIANTS], "",
        "pmpm / lean, time per step and per phase:", "",
        "| lean variant | step | P2G | GridUpdate | G2P | StressUpdate |",
        "|---|---|---|---|---|---|",
        *[ratio_row(k) for k in VARIANTS], "",
        "**The same computation.** Each lean variant's particles against pmpm's (matched by id) "
        "on the small case (`-cell_size 0.0625 -depth 0.25`, 8,192 particles): the largest "
        "difference over the particles over the field's largest value (F: absolute); the sum of "
        "the time steps (the next dt comes from the particles' wave speeds and velocities) "
        "against pmpm's summary `time`. 300 steps pass through kinetic damping's velocity "
        "resets (the velocities are then ~1e-9 m/s: their relative difference is round-off "
        "over a tiny scale).", "",
        "| lean variant | steps | stress | displacement | velocity | F | sum of dt |",
        "|---|---|---|---|---|---|---|", *agree_rows, "",
        f"And at {n:,} particles ({STEPS} steps; the sum of dt, the particles' mean sigma_yy (Pa) "
        "and mean y displacement (m), summed in each code's particle order):", "",
        "| run | sum of dt (s) | mean sigma_yy | mean u_y |", "|---|---|---|---|", *big, "",
        "What the comparison says:", "",
        "- **StressUpdate**: "
        f"{P['phases']['StressUpdate']:.1f} ms a step against the lean loop's "
        f"{L10['phases']['StressUpdate']:.1f} ({stress_ratio:.1f}x). Both write the "
        "Jaumann-rate update out on the six components (W s - s W = Q + Q^T, Q = W s; pmpm's "
        "elastic_rate_update3); the lean loop takes "
        f"{L10['phases']['StressUpdate'] * 1e6 / n:.1f} ns a particle for its 172 bytes "
        f"({172 / bw * 1e9:.1f} ns at the triad bandwidth); pmpm visits the particles through "
        "the material's index list. (The first run of this study, 2026-12-04, found pmpm's "
        "3D linear elastic going through the plastic models' predictor-corrector on Eigen 3x3 "
        "tensors: 38.9 ms against 6.0, 6.5x; written out since.) Fusing it into G2P as pmpm "
        f"does in 2D (FusedStress is 2D only) would save about {fused_gain:.0f} ms a step here "
        "(" +
        (f"the lean G2P takes {growth:.1f} ms more with the stress in it)." if growth > 0.05
         else "the lean G2P took no measurable time more with the stress in it)."),
        f"- **P2G and G2P** on pmpm's 10-value node with its scalar arithmetic: pmpm / lean "
        f"P2G {P['phases']['P2G'] / L10['phases']['P2G']:.2f}x, G2P "
        f"{P['phases']['G2P'] / L10['phases']['G2P']:.2f}x: " +
        ("pmpm's kernels are as fast as plain loops on the same node. " if same < 1.15 else
         f"pmpm's kernels cost up to {same:.2f}x plain loops on the same node. ") +
        "The gain is in the node: 8 values in one 64-byte vector "
        f"make P2G {L10['phases']['P2G'] / L8['phases']['P2G']:.1f}x and G2P "
        f"{L10['phases']['G2P'] / L8['phases']['G2P']:.1f}x faster than with pmpm's node "
        f"(pmpm / lean {P['phases']['P2G'] / L8['phases']['P2G']:.1f}x and "
        f"{P['phases']['G2P'] / L8['phases']['G2P']:.1f}x). pmpm scatters the external force as "
        "3 components and adds gravity to 3 force and 3 external-force slots; one scalar (the "
        "sum of w x weight) carries the same, and the node's 8 values then take two vector "
        "FMAs (the tensor-product factors taken a plane and a row at a time).",
        f"- **27 nodes.** The column's blocks touch {L8['nodes']:.1f} nodes on average, not 27: "
        "at -ppc 2 a block ends on cell faces, and only y moves (2 x 2.5 x 2). With every "
        "particle on 27 nodes the fused lean loop's P2G takes "
        f"{L27['phases']['P2G']:.1f} ms and G2P {L27['phases']['G2P']:.1f} (against "
        f"{LF['phases']['P2G']:.1f} and {LF['phases']['G2P']:.1f} at {LF['nodes']:.1f} "
        f"nodes): {27 / LF['nodes']:.1f}x the nodes for {L27['step_ms'] / LF['step_ms']:.2f}x "
        "the step, as a node costs two vector FMAs and the particle's own work (its weights, "
        "F, J, the checks and its state's bytes) does not grow.",
        f"- **Bandwidth.** An update must move about {nf(None):.0f} B in pmpm "
        f"({nf(list(VARIANTS)[2]):.0f} B in the fused lean loop): "
        f"{nf(None) / bw * 1e9:.0f} ns at {bw / 1e9:.1f} GB/s; pmpm takes "
        f"{P['step_ms'] * 1e6 / n:.0f} ns ({P['step_ms'] * 1e-3 / n * bw / nf(None):.1f}x the "
        f"bound), the fastest lean variant ({fastest}) {LB['step_ms'] * 1e6 / n:.0f} ns "
        f"({LB['step_ms'] * 1e-3 / n * bw / nf(fastest):.1f}x its {nf(fastest):.0f} B). "
        "The grid (the 27 "
        "node touches of a straddling block, 10 here) stays in cache: it adds the "
        f"{grid_bytes(None, cells, n):.0f} B of six passes over it (pmpm's node), not "
        "27 x 80 B a particle.",
        "", "<details><summary>Commands</summary>", "", "```",
        " ".join(CXX + ["-o", "bench/out/lean3d/lean3d", "bench/lean3d.cpp"]),
        "bench/out/lean3d/pmpm " + " ".join(COLUMN + case + ["-dim", "3", "-max_steps",
                                                            str(STEPS), "-log_view",
                                                            "-output_dir", "DIR", "-quiet"]),
        *[f"bench/out/lean3d/lean3d {lean_args_s} {' '.join(VARIANTS[k])}".rstrip()
          for k in VARIANTS],
        "# agreement: the same with " + " ".join(SMALL) + " and -max_steps 20, 300; "
        "lean3d -dump FILE against DIR/particles.h5", "```", "", "</details>",
        f"(load average before the timed runs: {load0:.2f})",
        MARK_END, ""])
    publish(text, OUT / "LEAN3D.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
