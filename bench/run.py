#!/usr/bin/python3
"""pmpm benchmarks: work-precision, throughput, parallel speed-up, and the cost of skipped stages.

    /usr/bin/python3 bench/run.py            # full run (~20 min): docs/benchmarks/run.md + bench/*.png
    /usr/bin/python3 bench/run.py --quick    # CI smoke run (< 1 min): bench/out/BENCHMARKS.md, bench/out/*.png
    /usr/bin/python3 bench/run.py --full     # also the landfill at -cell_size 0.000125 (~+25 min)

Every run goes to bench/out/runs*/NAME/ (summary.json, log.txt with -log_view, stderr.txt, meta.json).
The binary is a snapshot of build/pmpm copied at start (bench/out/runs*/bin/pmpm), so a rebuild by
someone else during the benchmark does not mix two versions. Call it from anywhere; it runs from the
repository root so that options/*.opts resolve.

Developer options: --reuse (take a run's meta.json when its command is unchanged, skip the run),
--only 1,2,3,4 (sections to run), --no-build-check.
"""
import argparse
import datetime
import hashlib
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BENCH = ROOT / "bench"
OUT = BENCH / "out"
EVENTS = ["P2G", "Interface", "GhostAdd", "GridUpdate", "GhostScatter", "G2P", "MUSLRemap",
          "StressUpdate", "Migrate"]
ENV = dict(os.environ)
if os.geteuid() == 0:
    ENV.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
CLK = os.sysconf("SC_CLK_TCK")
NCPU = os.cpu_count() or 1


# ------------------------------------------------------------------------------------------------
# Parameters: full and quick
# ------------------------------------------------------------------------------------------------
def params(quick, full):
    if quick:
        return dict(
            col_levels=[8, 16], col_ppc=[1, 2], col_relax=[("local", 0.05), ("kinetic", 0.05)],
            bar_cells=[0.05], lf_levels=[0.001, 0.0005], lf_mpm_levels=[0.001],
            lf_relax_h=0.001, lf_relax=[("kinetic", 0.0), ("kinetic", 0.05)],
            lf_extra=["-ramp_steps", 200, "-tol", "1e-3"], bar_ppc=[1], lf_ppc=[], lf_ppc_h=0.001,
            wait_budget=0, col_wait=0, tp_min=1, skip_min=1,
            bar_relax=[("kinetic", 0.0)],
            tp_sizes=[64, 128], tp_steps=10, par_n=128, par_lf_h=0.001,
            skip_h=0.001, skip_steps=100, stream=(22, 3), quiet_wait=0, retries=0)
    lf = [0.001, 0.0005, 0.00025] + ([0.000125] if full else [])
    return dict(
        col_levels=[8, 16, 32, 64], col_ppc=[1, 2, 3],
        col_relax=[("local", 0.0), ("local", 0.05), ("kinetic", 0.0), ("kinetic", 0.05)],
        bar_cells=[0.125, 0.05, 0.025], lf_levels=lf, lf_mpm_levels=[0.001, 0.0005],
        lf_relax_h=0.0005, tp_min=2, skip_min=3,
        bar_relax=[("local", 0.0), ("local", 0.05), ("kinetic", 0.0), ("kinetic", 0.05)],
        lf_relax=[("local", 0.0), ("local", 0.05), ("kinetic", 0.0), ("kinetic", 0.05)],
        lf_extra=[], bar_ppc=[1, 3], lf_ppc=[1, 3], lf_ppc_h=0.0005,
        tp_sizes=[160, 512, 1024], tp_steps=50, par_n=512, par_lf_h=0.0005,
        skip_h=0.0005, skip_steps=1000, stream=(25, 10), quiet_wait=45, retries=2,
        wait_budget=420, col_wait=0)


# ------------------------------------------------------------------------------------------------
# Running pmpm
# ------------------------------------------------------------------------------------------------
def cpu_jiffies():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:9]]
    return sum(v), v[3] + v[4]  # total, idle + iowait


def busy_cores(interval=0.5):
    t0, i0 = cpu_jiffies()
    time.sleep(interval)
    t1, i1 = cpu_jiffies()
    return NCPU * (1 - (i1 - i0) / max(1, t1 - t0))


def wait_quiet(max_wait, threshold=0.3):
    """Wait (at most max_wait s) until other processes use < threshold cores. Returns that load."""
    t0 = time.time()
    b = busy_cores(0.3)
    while b > threshold and time.time() - t0 < max_wait:
        time.sleep(1.0)
        b = busy_cores(0.5)
    return b


def parse_log(text):
    stages = {m.group(1): float(m.group(2))
              for m in re.finditer(r"^\s*\d+:\s+(\w+):\s+([0-9.eE+-]+)", text, re.M)}
    events = {}
    i = text.find("--- Event Stage 2: Relaxation")
    if i >= 0:
        j = text.find("--- Event Stage 3", i)
        block = text[i:j if j > 0 else None]
        for m in re.finditer(r"^(\w+)\s+(\d+)\s+[0-9.]+\s+([0-9.eE+-]+)\s", block, re.M):
            events[m.group(1)] = {"count": int(m.group(2)), "max_s": float(m.group(3))}
    return stages, events


class Runner:
    def __init__(self, runs_dir, binary, reuse, quiet_wait, retries, wait_budget=0):
        self.runs = runs_dir
        self.bin = binary
        self.reuse = reuse
        self.quiet_wait = quiet_wait
        self.retries = retries
        self.records = {}
        self.wait_left = wait_budget  # total seconds we may spend waiting for a quiet machine
        self.waited = 0.0
        self.commands = {}  # section -> list of command strings

    def rel(self, p):
        return os.path.relpath(p, ROOT)

    def run(self, section, name, opts, extra, ranks=1, timed=False, wait=None, min_attempts=1):
        """Run one pmpm job. timed: wait for a quiet machine first and repeat (self.retries) if
        other processes took CPU during the run; keep the attempt with the shortest cycle."""
        d = self.runs / name
        args = [self.rel(self.bin), "-options_file", f"options/{opts}", *[str(e) for e in extra],
                "-output_dir", self.rel(d), "-quiet", "-log_view"]
        cmd = (["mpirun", "-n", str(ranks)] if ranks > 1 else []) + args
        cmd_s = " ".join(cmd)
        self.commands.setdefault(section, []).append(cmd_s)
        meta = d / "meta.json"
        if self.reuse and meta.exists():
            rec = json.loads(meta.read_text())
            if rec.get("cmd") == cmd_s:
                self.records[name] = rec
                return rec
        tries = []
        wait = self.quiet_wait if wait is None else wait
        for attempt in range(max(min_attempts, 1 + (self.retries if timed else 0))):
            rec = self._once(d, cmd, cmd_s, name, section, ranks, wait if timed else 0)
            tries.append(rec)
            if not rec["ok"]:
                break
            if len(tries) < min_attempts:
                continue
            # short runs: CPU accounting (10 ms ticks) cannot tell; always take the best of two
            if rec["elapsed"] < 0.3 and len(tries) < 2:
                continue
            if rec["others_cores"] < 0.25:
                break
        good = [t for t in tries if t["ok"]]
        best = min(good, key=lambda t: t["cycle_s"]) if good else tries[-1]
        best["attempts"] = len(tries)
        best["cycles"] = [t["cycle_s"] for t in good]
        meta.write_text(json.dumps(best, indent=1))
        self.records[name] = best
        return best

    def _once(self, d, cmd, cmd_s, name, section, ranks, wait):
        if d.exists():
            shutil.rmtree(d)
        d.mkdir(parents=True)
        w = min(wait, self.wait_left)
        if w > 0:
            t0 = time.time()
            bg = wait_quiet(w)
            dt = max(0.0, time.time() - t0 - 0.3)
            self.wait_left -= dt
            self.waited += dt
        else:
            bg = busy_cores(0.05)
        tot0, idle0 = cpu_jiffies()
        t0 = time.perf_counter()
        with open(d / "log.txt", "w") as fo, open(d / "stderr.txt", "w") as fe:
            p = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=fo, stderr=fe)
            _, status, ru = os.wait4(p.pid, 0)
            p.returncode = os.waitstatus_to_exitcode(status)
        elapsed = time.perf_counter() - t0
        tot1, idle1 = cpu_jiffies()
        busy_s = ((tot1 - tot0) - (idle1 - idle0)) / CLK
        own_s = ru.ru_utime + ru.ru_stime
        others = max(0.0, busy_s - own_s) / max(elapsed, 1e-9)
        text = (d / "log.txt").read_text(errors="replace")
        err_text = (d / "stderr.txt").read_text(errors="replace")
        stages, events = parse_log(text)
        summary = None
        if (d / "summary.json").exists():
            summary = json.loads((d / "summary.json").read_text())
        error = None
        for line in (err_text + "\n" + text).splitlines():
            if "pmpm: error" in line:
                error = line.split("error", 1)[1].lstrip(" :")
                error = re.sub(r"^on rank \d+: ", "", error)
                break
        ok = p.returncode == 0 and summary is not None
        if not ok and error is None:
            error = f"exit code {p.returncode}"
        cycle = stages.get("Relaxation", summary["wall_seconds"] if summary else float("nan"))
        # keep disk use small: the big particle files are not needed
        h5 = d / "particles.h5"
        if h5.exists() and h5.stat().st_size > 20e6:
            h5.unlink()
        return dict(name=name, section=section, cmd=cmd_s, ranks=ranks, rc=p.returncode, ok=ok,
                    error=error, summary=summary, stages=stages, events=events, elapsed=elapsed,
                    cycle_s=cycle, maxrss_kb=ru.ru_maxrss, bg_before=bg, others_cores=others)


# ------------------------------------------------------------------------------------------------
# Helpers
# ------------------------------------------------------------------------------------------------
def pareto(points):
    """points: list of (time, error, key). Returns the keys of the non-dominated points."""
    pts = sorted([p for p in points if np.isfinite(p[0]) and np.isfinite(p[1]) and p[1] > 0],
                 key=lambda p: (p[0], p[1]))
    front, best = [], float("inf")
    for t, e, k in pts:
        if e < best * (1 - 1e-3):  # errors equal to 0.1 % count as equal
            front.append(k)
            best = e
    return front


def fmt(x, nd=3):
    if x is None or (isinstance(x, float) and not np.isfinite(x)):
        return "–"
    if isinstance(x, (int, np.integer)):
        return str(x)
    if x == 0:
        return "0"
    a = abs(x)
    if a >= 1e5 or a < 1e-3:
        return f"{x:.{nd - 1}e}"
    return f"{x:.{nd}g}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out)


def spread(rec):
    c = [x for x in rec.get("cycles", []) if x and np.isfinite(x)]
    if len(c) < 2:
        return "–"
    return f"{100 * (max(c) / min(c) - 1):.0f} % ({len(c)} runs)"


def relax_label(damp, pic):
    return f"{damp}/pic {pic:g}"


def stage_ms_per_step(rec, steps):
    ev = rec["events"]
    out = {}
    for e in EVENTS:
        if e in ev:
            out[e] = 1e3 * ev[e]["max_s"] / steps
    out["other"] = max(0.0, 1e3 * rec["cycle_s"] / steps - sum(out.values()))
    return out


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True, cwd=ROOT).stdout.strip()
    except Exception:
        return ""


def machine_info():
    lscpu = sh("lscpu")
    model = re.search(r"Model name:\s*(.+)", lscpu)
    cpus = re.search(r"^CPU\(s\):\s*(\d+)", lscpu, re.M)
    tpc = re.search(r"Thread\(s\) per core:\s*(\d+)", lscpu)
    l2 = re.search(r"L2 cache:\s*(.+)", lscpu)
    l3 = re.search(r"L3 cache:\s*(.+)", lscpu)
    mem = re.search(r"MemTotal:\s*(\d+)", Path("/proc/meminfo").read_text())
    return dict(
        model=model.group(1).strip() if model else "?",
        cpus=int(cpus.group(1)) if cpus else NCPU,
        threads_per_core=tpc.group(1) if tpc else "?",
        l2=l2.group(1).strip() if l2 else "?", l3=l3.group(1).strip() if l3 else "?",
        mem_gib=int(mem.group(1)) / 2**20 if mem else float("nan"),
        kernel=platform_release(),
        gcc=sh("g++ --version | head -1"),
        mpi=sh("mpirun --version 2>&1 | head -1"),
        petsc=sh("dpkg-query -W -f='${Version}' petsc-dev 2>/dev/null"),
    )


def platform_release():
    import platform
    return f"{platform.system()} {platform.release()}"


def git_info():
    head = sh("git rev-parse --short HEAD")
    o = subprocess.run("git status --porcelain -- src include CMakeLists.txt", shell=True,
                       capture_output=True, text=True, cwd=ROOT).stdout
    dirty = [line[3:] for line in o.splitlines() if len(line) > 3]
    return head, dirty


# ------------------------------------------------------------------------------------------------
# Section 1: work-precision
# ------------------------------------------------------------------------------------------------
def section1(R, P, md, fig_dir, quick):
    res = {}
    # --- column sweep
    col = []
    for n in P["col_levels"]:
        for ppc in P["col_ppc"]:
            for shape in ["mpm", "pmpm"]:
                for damp, pic in P["col_relax"]:
                    name = f"col_h{n}_ppc{ppc}_{shape}_{damp}_pic{pic:g}"
                    r = R.run("1", name, "column.opts",
                              ["-cell_size", repr(1.0 / n), "-ppc", ppc, "-shape", shape,
                               "-damping", damp, "-pic", pic], timed=True, wait=P["col_wait"])
                    col.append(dict(n=n, ppc=ppc, shape=shape, damp=damp, pic=pic, rec=r))
    for c in col:
        s = c["rec"]["summary"]
        c["ok"] = c["rec"]["ok"] and s["converged"]
        c["t"] = s["wall_seconds"] if s else float("nan")
        c["steps"] = s["steps"] if s else None
        c["es"] = s["results"]["stress_l2_error_rel"] if s else float("nan")
        c["eu"] = s["results"]["displacement_l2_error_rel"] if s else float("nan")
        c["key"] = (c["n"], c["ppc"], c["shape"], c["damp"], c["pic"])
    good = [c for c in col if c["ok"]]
    fronts = {}
    for m in ["es", "eu"]:
        fronts[m] = set(pareto([(c["t"], c[m], c["key"]) for c in good]))
    res["col"] = col
    res["fronts"] = fronts

    # --- bar under large load
    bar = []
    for h in P["bar_cells"]:
        for shape in ["mpm", "pmpm"]:
            r = R.run("1", f"bar_large_h{h:g}_{shape}", "bar_large.opts",
                      ["-cell_size", h, "-shape", shape])
            bar.append(dict(h=h, shape=shape, ppc=2, rec=r))
    hb = 0.05 if 0.05 in P["bar_cells"] else P["bar_cells"][0]
    for ppc in P["bar_ppc"]:
        r = R.run("1", f"bar_large_h{hb:g}_pmpm_ppc{ppc}", "bar_large.opts",
                  ["-cell_size", hb, "-shape", "pmpm", "-ppc", ppc])
        bar.append(dict(h=hb, shape="pmpm", ppc=ppc, rec=r))
    for damp, pic in P["bar_relax"]:
        r = R.run("1", f"bar_large_h{hb:g}_pmpm_{damp}_pic{pic:g}", "bar_large.opts",
                  ["-cell_size", hb, "-shape", "pmpm", "-damping", damp, "-pic", pic])
        bar.append(dict(h=hb, shape="pmpm", ppc=2, damp=damp, pic=pic, rec=r))
    res["bar"] = bar

    # --- landfill against its finest mesh
    lf = []
    for h in P["lf_levels"]:
        r = R.run("1", f"landfill_h{h:g}_pmpm_np2", "landfill.opts",
                  ["-cell_size", h] + P["lf_extra"], ranks=2, timed=True)
        lf.append(dict(h=h, shape="pmpm", damp="kinetic", pic=0.05, ppc=2, ranks=2, rec=r))
    for h in P["lf_mpm_levels"]:
        r = R.run("1", f"landfill_h{h:g}_mpm_np2", "landfill.opts",
                  ["-cell_size", h, "-shape", "mpm"] + P["lf_extra"], ranks=2)
        lf.append(dict(h=h, shape="mpm", damp="kinetic", pic=0.05, ppc=2, ranks=2, rec=r))
    lfr = []
    for damp, pic in P["lf_relax"]:
        r = R.run("1", f"landfill_h{P['lf_relax_h']:g}_{damp}_pic{pic:g}_np1", "landfill.opts",
                  ["-cell_size", P["lf_relax_h"], "-damping", damp, "-pic", pic] + P["lf_extra"],
                  timed=True, wait=P["col_wait"])
        lfr.append(dict(h=P["lf_relax_h"], shape="pmpm", damp=damp, pic=pic, ppc=2, ranks=1,
                        rec=r))
    # particle density on the landfill (step cap 20000: a run that does not converge by then
    # would not in 100000 either at the rate it goes)
    lfp = []
    for ppc in P["lf_ppc"]:
        r = R.run("1", f"landfill_h{P['lf_ppc_h']:g}_ppc{ppc}_np1", "landfill.opts",
                  ["-cell_size", P["lf_ppc_h"], "-ppc", ppc, "-max_steps", 20000] + P["lf_extra"],
                  timed=True, wait=P["col_wait"])
        lfp.append(dict(h=P["lf_ppc_h"], shape="pmpm", damp="kinetic", pic=0.05, ppc=ppc,
                        ranks=1, rec=r))
    fine = [x for x in lf if x["shape"] == "pmpm" and x["rec"]["ok"]]
    ref = min(fine, key=lambda x: x["h"]) if fine else None
    for x in lf + lfr + lfp:
        s = x["rec"]["summary"]
        x["ok"] = x["rec"]["ok"] and s["converged"]
        x["t"] = s["wall_seconds"] if s else float("nan")
        if s and ref:
            rs = ref["rec"]["summary"]["results"]
            x["e_settle"] = abs(s["results"]["settlement_centre"] / rs["settlement_centre"] - 1)
            x["e_strain"] = abs(s["results"]["peak_axial_strain"] / rs["peak_axial_strain"] - 1)
        else:
            x["e_settle"] = x["e_strain"] = float("nan")
    res["lf"], res["lfr"], res["lf_ref"], res["lfp"] = lf, lfr, ref, lfp

    plot_column(col, fronts, fig_dir / "work_precision_column.png")
    plot_landfill(lf, lfr, lfp, ref, fig_dir / "work_precision_landfill.png")
    return res


SHAPE_COLORS = {("mpm", 1): "#9ecae1", ("mpm", 2): "#4292c6", ("mpm", 3): "#08306b",
                ("pmpm", 1): "#fdae6b", ("pmpm", 2): "#e6550d", ("pmpm", 3): "#7f2704"}
RELAX_MARKERS = {("local", 0.0): "s", ("local", 0.05): "D", ("kinetic", 0.0): "^",
                 ("kinetic", 0.05): "o"}


def plot_column(col, fronts, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6))
    for ax, m, title in [(axes[0], "es", "stress (σyy) L2 error, relative"),
                         (axes[1], "eu", "displacement L2 error, relative")]:
        groups = {}
        for c in col:
            if c["ok"]:
                groups.setdefault((c["shape"], c["ppc"], c["damp"], c["pic"]), []).append(c)
        for (shape, ppc, damp, pic), cs in groups.items():
            cs = sorted(cs, key=lambda c: c["n"])
            ax.plot([c["t"] for c in cs], [c[m] for c in cs], "-", lw=0.6, alpha=0.5,
                    color=SHAPE_COLORS.get((shape, ppc), "gray"))
            ax.scatter([c["t"] for c in cs], [c[m] for c in cs], s=26,
                       marker=RELAX_MARKERS.get((damp, pic), "x"),
                       color=SHAPE_COLORS.get((shape, ppc), "gray"), zorder=3)
        fr = sorted([c for c in col if c["ok"] and c["key"] in fronts[m]], key=lambda c: c["t"])
        if fr:
            ax.step([c["t"] for c in fr], [c[m] for c in fr], where="post", color="k", lw=1.2,
                    zorder=2)
            ax.scatter([c["t"] for c in fr], [c[m] for c in fr], s=110, facecolors="none",
                       edgecolors="k", lw=1.3, zorder=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("relaxation wall time (s), 1 rank")
        ax.set_ylabel(title)
        ax.grid(True, which="both", alpha=0.25)
        ax.set_title(f"column: {title.split(',')[0]} vs time")
    from matplotlib.lines import Line2D
    h1 = [Line2D([], [], color=v, marker="o", ls="-", label=f"{k[0]} ppc {k[1]}")
          for k, v in SHAPE_COLORS.items() if any(c["shape"] == k[0] and c["ppc"] == k[1] for c in col)]
    h2 = [Line2D([], [], color="gray", marker=v, ls="", label=relax_label(*k))
          for k, v in RELAX_MARKERS.items() if any((c["damp"], c["pic"]) == k for c in col)]
    h3 = [Line2D([], [], color="k", marker="o", mfc="none", ms=10, ls="-", label="Pareto front")]
    fig.legend(handles=h1 + h2 + h3, loc="lower center", ncol=6, fontsize=8, frameon=False)
    fig.suptitle("Column under self-weight (options/column.opts): h = 1/8 … 1/64 m "
                 "(lines join refinements of one setting; colour: shape and ppc, marker: relaxation)",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def widen_log(ax, axis, vals, factor=10.0):
    """At least `factor` between the log-axis limits, so that a few close points stay readable."""
    v = [x for x in vals if x and np.isfinite(x) and x > 0]
    if not v:
        return
    lo, hi = min(v), max(v)
    if hi / lo < factor:
        g = np.sqrt(factor / (hi / lo))
        (ax.set_ylim if axis == "y" else ax.set_xlim)(lo / g, hi * g)


def plot_landfill(lf, lfr, lfp, ref, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    pts_all = [x for x in lf + lfr + lfp if x["ok"] and x is not ref]
    for ax, m, title in [(axes[0], "e_settle", "settlement at the centre"),
                         (axes[1], "e_strain", "peak axial strain of the membrane")]:
        cs = sorted([x for x in lf if x["ok"] and x["shape"] == "pmpm" and x is not ref],
                    key=lambda x: x["t"])
        ax.plot([x["t"] for x in cs], [x[m] for x in cs], "o-", color="#e6550d",
                label="h sweep: pmpm ppc 2, kinetic/pic 0.05, 2 ranks")
        for x in cs:
            ax.annotate(f"h={x['h'] * 1e3:g} mm", (x["t"], x[m]), textcoords="offset points",
                        xytext=(6, 4), fontsize=8)
        first = True
        for i, x in enumerate(lfr):
            if x["rec"]["summary"]:
                ax.scatter([x["t"]], [x[m]], marker=RELAX_MARKERS.get((x["damp"], x["pic"]), "x"),
                           color="#31a354", s=40, zorder=3,
                           label=f"relaxation variants, h={x['h'] * 1e3:g} mm, 1 rank"
                           if first else None)
                first = False
                ax.annotate(relax_label(x["damp"], x["pic"]), (x["t"], x[m]),
                            textcoords="offset points", xytext=(6, -10 - 9 * (i % 2)),
                            fontsize=7, color="#31a354")
        first = True
        for x in lfp:
            if x["rec"]["summary"]:
                ax.scatter([x["t"]], [x[m]], marker="P", color="#3182bd", s=50, zorder=3,
                           label=f"ppc variants, h={x['h'] * 1e3:g} mm, 1 rank" if first else None)
                first = False
                ax.annotate(f"ppc {x['ppc']}" + ("" if x["ok"] else " (not converged)"),
                            (x["t"], x[m]), textcoords="offset points", xytext=(6, 4), fontsize=7,
                            color="#3182bd")
        fr = pareto([(x["t"], x[m], id(x)) for x in pts_all])
        fx = sorted([x for x in pts_all if id(x) in fr], key=lambda x: x["t"])
        if fx:
            ax.step([x["t"] for x in fx], [x[m] for x in fx], where="post", color="k", lw=1.0,
                    zorder=2)
            ax.scatter([x["t"] for x in fx], [x[m] for x in fx], s=130, facecolors="none",
                       edgecolors="k", lw=1.3, zorder=4, label="Pareto front (converged runs)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        shown = [x for x in lf + lfr + lfp if x["rec"]["summary"] and x is not ref]
        widen_log(ax, "y", [x[m] for x in shown])
        widen_log(ax, "x", [x["t"] for x in shown], factor=4)
        ax.set_xlabel("relaxation wall time (s)")
        ax.set_ylabel(f"relative error in {title}")
        ax.grid(True, which="both", alpha=0.25)
        ax.set_title(title, fontsize=10)
    h, l = axes[0].get_legend_handles_labels()
    fig.legend(h, l, loc="lower center", ncol=2, fontsize=8, frameon=False)
    fig.suptitle(f"Landfill (options/landfill.opts): error against the h = {ref['h'] * 1e3:g} mm "
                 f"run (pmpm, 2 ranks)" if ref else "Landfill", fontsize=10)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def md_section1(res, md, R, P, defaults):
    col, fronts = res["col"], res["fronts"]
    md.append("## 1. Work-precision\n")
    md.append("Time is the relaxation wall time (`wall_seconds` in summary.json: the explicit "
              "cycle from the first step to convergence, without setup and output). Every run "
              "must converge to the tolerance of its options file; runs that did not (or "
              "failed) are listed and left out of the fronts.\n")
    md.append("### 1.1 Column under self-weight\n")
    md.append(f"`options/column.opts` (linear elastic, tolerance 1e-7), swept over -cell_size "
              f"1/{', 1/'.join(str(n) for n in P['col_levels'])} m, -ppc "
              f"{', '.join(str(p) for p in P['col_ppc'])}, -shape mpm|pmpm and relaxation "
              f"{', '.join(relax_label(*r) for r in P['col_relax'])} (-damping, -pic): "
              f"{len(col)} runs on 1 rank.\n")
    md.append("![column work-precision](bench/work_precision_column.png)\n")
    bad = [c for c in col if not c["ok"]]
    if bad:
        md.append("Runs that failed or did not converge: " + "; ".join(
            f"h=1/{c['n']} ppc {c['ppc']} {c['shape']} {relax_label(c['damp'], c['pic'])}: "
            f"{c['rec']['error'] or 'not converged'}" for c in bad) + "\n")
    for m, label in [("es", "stress error"), ("eu", "displacement error")]:
        fr = sorted([c for c in col if c["key"] in fronts[m]], key=lambda c: c["t"])
        md.append(f"**Pareto front, {label} vs time** ({len(fr)} of "
                  f"{sum(c['ok'] for c in col)} converged runs):\n")
        md.append(table(["h (m)", "ppc", "shape", "relaxation", "steps", "time (s)",
                         "stress err", "displ. err"],
                        [[f"1/{c['n']}", c["ppc"], c["shape"], relax_label(c["damp"], c["pic"]),
                          c["steps"], fmt(c["t"]), fmt(c["es"]), fmt(c["eu"])] for c in fr]))
        md.append("")
    # Matched comparisons
    by = {c["key"]: c for c in col if c["ok"]}
    base_relax = ("local", 0.05) if ("local", 0.05) in P["col_relax"] else P["col_relax"][0]
    relax_stats = {}
    for rl in P["col_relax"]:
        tr, sr, des, deu = [], [], [], []
        for c in col:
            if not c["ok"] or (c["damp"], c["pic"]) != base_relax:
                continue
            o = by.get((c["n"], c["ppc"], c["shape"], *rl))
            if o:
                tr.append(o["t"] / c["t"])
                sr.append(o["steps"] / c["steps"])
                des.append(abs(o["es"] / c["es"] - 1))
                deu.append(abs(o["eu"] / c["eu"] - 1))
        if tr:
            relax_stats[rl] = dict(t=statistics.median(tr), steps=statistics.median(sr),
                                   tmin=min(tr), tmax=max(tr), des=max(des), deu=max(deu), n=len(tr))
    md.append(f"**Relaxation settings**, each against {relax_label(*base_relax)} (the code "
              "default) at the same h, ppc and shape (median and range over the matched runs; "
              "the error columns give the largest relative change of the error):\n")
    md.append(table(["relaxation", "matched runs", "steps ratio (median)", "time ratio (median)",
                     "time ratio (min–max)", "max Δ stress err", "max Δ displ. err"],
                    [[relax_label(*k), v["n"], fmt(v["steps"]), fmt(v["t"]),
                      f"{fmt(v['tmin'])}–{fmt(v['tmax'])}", f"{100 * v['des']:.2g} %",
                      f"{100 * v['deu']:.2g} %"] for k, v in relax_stats.items()]))
    md.append("")
    # shape comparison
    shape_rows = []
    nf = max(P["col_levels"])
    for ppc in P["col_ppc"]:
        es, eu, tt, euf, esf = [], [], [], [], []
        for c in col:
            if c["ok"] and c["shape"] == "mpm" and c["ppc"] == ppc:
                o = by.get((c["n"], ppc, "pmpm", c["damp"], c["pic"]))
                if o:
                    es.append(o["es"] / c["es"])
                    eu.append(o["eu"] / c["eu"])
                    tt.append(o["t"] / c["t"])
                    if c["n"] == nf:
                        esf.append(o["es"] / c["es"])
                        euf.append(o["eu"] / c["eu"])
        if es:
            shape_rows.append([ppc, len(es), fmt(statistics.median(es)),
                               fmt(statistics.median(eu)), fmt(statistics.median(tt)),
                               fmt(statistics.median(esf)) if esf else "–",
                               fmt(statistics.median(euf)) if euf else "–"])
    md.append("**Shapes**, pmpm against mpm at the same h, ppc and relaxation (medians of the "
              "ratios pmpm / mpm):\n")
    md.append(table(["ppc", "matched runs", "stress err ratio", "displ. err ratio", "time ratio",
                     f"stress err ratio at h = 1/{nf}", f"displ. err ratio at h = 1/{nf}"],
                    shape_rows))
    md.append("")
    # particle density against ppc 2
    if 2 in P["col_ppc"]:
        rows = []
        for ppc in P["col_ppc"]:
            for shape in ["mpm", "pmpm"]:
                es, eu, tt = [], [], []
                for c in col:
                    if c["ok"] and c["ppc"] == 2 and c["shape"] == shape:
                        o = by.get((c["n"], ppc, shape, c["damp"], c["pic"]))
                        if o:
                            es.append(o["es"] / c["es"])
                            eu.append(o["eu"] / c["eu"])
                            tt.append(o["t"] / c["t"])
                if es and ppc != 2:
                    rows.append([ppc, shape, len(es), fmt(statistics.median(es)),
                                 fmt(statistics.median(eu)), fmt(statistics.median(tt))])
        md.append("**Particle density**, ppc k against ppc 2 at the same h, shape and relaxation "
                  "(medians of the ratios):\n")
        md.append(table(["ppc", "shape", "matched runs", "stress err ratio", "displ. err ratio",
                         "time ratio"], rows))
        md.append("")
        md.append("At ppc 1 every particle sits at a cell centre, where a cell-wise constant "
                  "stress equals the linearly varying exact stress of the column; the low ppc-1 "
                  "stress error is that sampling point, and ppc 1 fails on the large-deformation "
                  "runs below.\n")
    # convergence rates (pmpm vs mpm, kinetic/pic 0.05 if present) between the two finest levels
    if len(P["col_levels"]) >= 2:
        n1, n2 = sorted(P["col_levels"])[-2:]
        rows = []
        for shape in ["mpm", "pmpm"]:
            for ppc in P["col_ppc"]:
                rl = ("kinetic", 0.05) if ("kinetic", 0.05) in P["col_relax"] else P["col_relax"][0]
                a, b = by.get((n1, ppc, shape, *rl)), by.get((n2, ppc, shape, *rl))
                if a and b:
                    k = np.log(n2 / n1)
                    rows.append([shape, ppc, fmt(a["es"]), fmt(b["es"]),
                                 f"{np.log(a['es'] / b['es']) / k:.2f}", fmt(a["eu"]),
                                 fmt(b["eu"]), f"{np.log(a['eu'] / b['eu']) / k:.2f}"])
        md.append(f"Observed order of convergence between h = 1/{n1} and 1/{n2} m "
                  f"({relax_label(*rl)}):\n")
        md.append(table(["shape", "ppc", f"stress err 1/{n1}", f"stress err 1/{n2}", "order",
                         f"displ. err 1/{n1}", f"displ. err 1/{n2}", "order"], rows))
        md.append("")
    # finest level table per setting
    nf = max(P["col_levels"])
    rows = []
    for c in sorted([c for c in col if c["n"] == nf],
                    key=lambda c: (c["shape"], c["ppc"], c["damp"], c["pic"])):
        rows.append([c["shape"], c["ppc"], relax_label(c["damp"], c["pic"]), c["steps"] or "–",
                     fmt(c["t"]), fmt(c["es"]), fmt(c["eu"]),
                     "yes" if c["ok"] else (c["rec"]["error"] or "not converged")])
    md.append(f"At the finest level, h = 1/{nf} m:\n")
    md.append(table(["shape", "ppc", "relaxation", "steps", "time (s)", "stress err", "displ. err",
                     "converged"], rows))
    md.append("")
    allrows = [[f"1/{c['n']}", c["ppc"], c["shape"], relax_label(c["damp"], c["pic"]),
                c["steps"] or "–", fmt(c["t"]), fmt(c["es"]), fmt(c["eu"]),
                ("F" if c["key"] in fronts["es"] else "") + ("f" if c["key"] in fronts["eu"] else "")]
               for c in sorted(col, key=lambda c: (c["n"], c["shape"], c["ppc"], c["damp"], c["pic"]))]
    md.append("<details><summary>All column runs (F: on the stress front, f: on the displacement "
              "front)</summary>\n")
    md.append(table(["h (m)", "ppc", "shape", "relaxation", "steps", "time (s)", "stress err",
                     "displ. err", "front"], allrows))
    md.append("\n</details>\n")

    # --- bar
    md.append("### 1.2 Bar under large load\n")
    dflt = f"{defaults.get('damping')}/pic {defaults.get('pic')} (code default)"
    md.append("`options/bar_large.opts` (20 % strain, particles cross cell faces). "
              "`force_residual_mpm` / `force_residual_pmpm` are the static unbalanced-force ratios "
              "of the final state evaluated with linear (eq. 13) and uGIMP (eq. 19) shapes.\n")
    rows = []
    for b in res["bar"]:
        r = b["rec"]
        s = r["summary"]
        if s:
            rl = relax_label(b["damp"], b["pic"]) if "damp" in b else dflt
            rows.append([fmt(b["h"]), b["shape"], b["ppc"], rl, s["particles"], s["steps"],
                         "yes" if s["converged"] else "no", fmt(s["wall_seconds"]),
                         fmt(s["results"].get("force_residual_mpm")),
                         fmt(s["results"].get("force_residual_pmpm")),
                         fmt(s["results"].get("tip_displacement"))])
        else:
            rl = relax_label(b["damp"], b["pic"]) if "damp" in b else dflt
            rows.append([fmt(b["h"]), b["shape"], b["ppc"], rl, "", "", "failed", "", "", "",
                         r["error"]])
    md.append(table(["h (m)", "shape", "ppc", "relaxation", "particles", "steps", "converged", "time (s)",
                     "force_residual_mpm", "force_residual_pmpm", "tip displacement (m) / error"],
                    rows))
    md.append("")

    # --- landfill
    lf, lfr, ref = res["lf"], res["lfr"], res["lf_ref"]
    md.append("### 1.3 Landfill against its finest mesh\n")
    md.append(f"`options/landfill.opts` (load II, bonded, kinetic damping with PIC 0.05) on 2 "
              f"ranks at -cell_size {', '.join(fmt(h) for h in P['lf_levels'])} m; the reference "
              f"is the finest run (h = {fmt(ref['h']) if ref else '?'} m). Errors are relative to "
              "it, in `results.settlement_centre` and `results.peak_axial_strain`. The relaxation "
              f"variants are 1-rank runs at h = {fmt(P['lf_relax_h'])} m; the particle-density "
              f"variants 1-rank runs at h = {fmt(P['lf_ppc_h'])} m capped at 20000 steps."
              + (f" Extra options in this mode: `{' '.join(map(str, P['lf_extra']))}`."
                 if P["lf_extra"] else "") + "\n")
    md.append("![landfill work-precision](bench/work_precision_landfill.png)\n")
    rows = []
    for x in lf + lfr + res["lfp"]:
        r, s = x["rec"], x["rec"]["summary"]
        if s:
            rows.append([fmt(x["h"]), x["shape"], x["ppc"], relax_label(x["damp"], x["pic"]), x["ranks"],
                         s["particles"], s["steps"], "yes" if s["converged"] else "no",
                         fmt(s["wall_seconds"]), fmt(s["results"]["settlement_centre"] * 1e3, 5),
                         fmt(s["results"]["peak_axial_strain"] * 100, 5),
                         "ref" if x is ref else f"{100 * x['e_settle']:.2g} %",
                         "ref" if x is ref else f"{100 * x['e_strain']:.2g} %", s["migrations"]])
        else:
            rows.append([fmt(x["h"]), x["shape"], x["ppc"], relax_label(x["damp"], x["pic"]),
                         x["ranks"], "", "", "failed", "", "", "", "", "", r["error"]])
    md.append(table(["h (m)", "shape", "ppc", "relaxation", "ranks", "particles", "steps", "converged",
                     "time (s)", "settlement (mm)", "peak strain (%)", "err settlement",
                     "err strain", "migrations"], rows))
    md.append("")
    return relax_stats, shape_rows


def failure(rec):
    """None if the run converged; else a short reason. Input errors (an invalid combination of
    options, e.g. a cell size that does not divide the body) return 'input'."""
    s = rec["summary"]
    if rec["ok"] and s and s["converged"]:
        return None
    if rec["ok"] and s:
        return f"not converged in {s['steps']} steps"
    e = rec["error"] or "failed"
    if "Instability" not in e and "converge" not in e:
        return "input"
    return e.split("(")[0].strip().rstrip(".")


def recommend(res, relax_stats, P, defaults):
    """Facts-only recommendation from the measurements."""
    col, fronts = res["col"], res["fronts"]
    ok = [c for c in col if c["ok"]]
    out = []
    cnt = {}
    for m in ["es", "eu"]:
        for c in ok:
            if c["key"] in fronts[m]:
                for dim, v in [("shape", c["shape"]), ("ppc", c["ppc"]),
                               ("relax", (c["damp"], c["pic"]))]:
                    cnt.setdefault(dim, {}).setdefault(v, [0, 0])
                    cnt[dim][v][0 if m == "es" else 1] += 1
    out.append("**Settings on the column fronts** (number of front points, stress front + "
               "displacement front):\n")
    for dim in ["shape", "ppc", "relax"]:
        items = sorted(cnt.get(dim, {}).items(), key=lambda kv: -sum(kv[1]))
        out.append(f"- {dim}: " + ", ".join(
            f"{relax_label(*k) if dim == 'relax' else k}: {v[0]} + {v[1]}" for k, v in items))
    out.append("")
    # Large-deformation trials: (setting, where, failure reason or None); input errors dropped.
    trials = []
    for b in res["bar"]:
        trials.append(dict(shape=b["shape"], ppc=b["ppc"],
                           relax=(b.get("damp"), b.get("pic")) if "damp" in b else None,
                           where=f"bar h={fmt(b['h'])}", why=failure(b["rec"])))
    for x in res["lf"] + res["lfp"] + res["lfr"]:
        trials.append(dict(shape=x["shape"], ppc=x["ppc"], relax=(x["damp"], x["pic"]),
                           where=f"landfill h={fmt(x['h'])}", why=failure(x["rec"])))
    trials = [t for t in trials if t["why"] != "input"]

    def fails(pred):
        return [t for t in trials if pred(t) and t["why"]]

    def count(pred):
        return sum(1 for t in trials if pred(t))

    lines = ["**Recommendation** (shipped defaults), from the measurements above:\n"]
    # shape
    sh = cnt.get("shape", {})
    sp, sm = sum(sh.get("pmpm", [0, 0])), sum(sh.get("mpm", [0, 0]))
    fm = fails(lambda t: t["shape"] == "mpm")
    fp = fails(lambda t: t["shape"] == "pmpm" and t["ppc"] == 2 and t["relax"] in
               (None, ("kinetic", 0.05)))
    nf = max(P["col_levels"])
    fine = {(c["shape"], c["ppc"], c["damp"], c["pic"]): c for c in ok if c["n"] == nf}
    ratios = [fine[("pmpm", *k[1:])]["eu"] / v["eu"] for k, v in fine.items()
              if k[0] == "mpm" and ("pmpm", *k[1:]) in fine]
    lines.append(
        f"- `-shape pmpm`: {sp} of {sp + sm} column front points are pmpm; at h = 1/{nf} m its "
        f"displacement error is {fmt(statistics.median(ratios)) if ratios else '?'}× that of mpm "
        f"(median over ppc and relaxation). Standard MPM failed in {len(fm)} of "
        f"{count(lambda t: t['shape'] == 'mpm')} large-deformation runs"
        + (f" ({'; '.join(sorted(set(t['where'] + ': ' + t['why'] for t in fm)))})" if fm else "")
        + f"; pmpm at ppc 2 failed in {len(fp)} of "
        f"{count(lambda t: t['shape'] == 'pmpm' and t['ppc'] == 2)}.")
    # ppc: converged on every large-deformation run, then most front points, then cheaper
    robust = [p for p in P["col_ppc"] if not fails(lambda t: t["shape"] == "pmpm" and
                                                   t["ppc"] == p and t["relax"] in
                                                   (None, ("kinetic", 0.05)))]
    if robust:
        rec_ppc = max(robust, key=lambda p: (sum(cnt.get("ppc", {}).get(p, [0, 0])), -p))
        v = cnt.get("ppc", {}).get(rec_ppc, [0, 0])
        why = []
        for p in P["col_ppc"]:
            f = fails(lambda t: t["shape"] == "pmpm" and t["ppc"] == p)
            if f:
                why.append(f"ppc {p} failed on " + "; ".join(f"{t['where']} ({t['why']})"
                                                               for t in f))
        lines.append(f"- `-ppc {rec_ppc}`: of the particle densities that converged on every "
                     f"large-deformation run, it has the most column front points ({v[0]} "
                     f"stress + {v[1]} displacement; ties go to the cheaper one)."
                     + (" " + "; ".join(why) + "." if why else ""))
    # relaxation: column steps within 5 % of the best, errors unchanged, no failure on the bar
    # or the landfill; then fewest landfill steps
    if relax_stats:
        best = min(v["steps"] for v in relax_stats.values())
        lf_r = {(x["damp"], x["pic"]): x for x in res["lfr"] if x["ok"]}
        cands = [k for k, v in relax_stats.items()
                 if v["steps"] <= 1.05 * best and v["des"] < 0.05 and v["deu"] < 0.05
                 and not fails(lambda t: t["relax"] == k and t["shape"] == "pmpm"
                               and t["ppc"] == 2)]
        if cands:
            def lf_steps(k):
                return lf_r[k]["rec"]["summary"]["steps"] if k in lf_r else 1e18
            rec = min(cands, key=lambda k: (lf_steps(k), relax_stats[k]["steps"]))
            # a tie (landfill steps within 10 %) keeps the current default PIC fraction
            try:
                pic0 = float(defaults.get("pic"))
            except (TypeError, ValueError):
                pic0 = None
            tie = [k for k in cands if k[0] == rec[0] and pic0 is not None
                   and abs(k[1] - pic0) < 1e-12 and lf_steps(k) <= 1.10 * lf_steps(rec)]
            tie_note = ""
            if tie and tie[0] != rec:
                tie_note = (f" ({relax_label(*rec)} took {lf_steps(rec)} landfill steps against "
                            f"{lf_steps(tie[0])}: within 10 %, a tie, so the current PIC fraction "
                            f"stays)")
                rec = tie[0]
            v = relax_stats[rec]
            txt = (f"- `-damping {rec[0]} -pic {rec[1]:g}`{tie_note}: on the column it needs "
                   f"{fmt(v['steps'])}× the steps and {fmt(v['t'])}× the time of "
                   f"{relax_label('local', 0.05)} (medians over {v['n']} matched runs), with the "
                   f"errors changed by at most {100 * max(v['des'], v['deu']):.2g} %.")
            others = [k for k in cands if k != rec]
            if others:
                txt += (" Within 5 % of it in column steps: "
                        + ", ".join(f"{relax_label(*k)} ({fmt(relax_stats[k]['steps'])}×)"
                                    for k in others) + ".")
            if lf_r:
                txt += (f" Landfill at h = {fmt(next(iter(lf_r.values()))['h'])} m (1 rank): "
                        + ", ".join(f"{relax_label(*k)} {x['rec']['summary']['steps']} steps / "
                                    f"{fmt(x['t'])} s" for k, x in sorted(
                                        lf_r.items(), key=lambda kv: kv[1]["t"])) + ".")
            fr = fails(lambda t: t["relax"] is not None and t["relax"] not in cands
                       and t["shape"] == "pmpm" and t["ppc"] == 2)
            if fr:
                txt += " Failures of other settings: " + "; ".join(
                    f"{relax_label(*t['relax'])} on {t['where']} ({t['why']})" for t in fr) + "."
            lines.append(txt)
    lines.append(f"- Current code defaults (from -help): -shape {defaults.get('shape')}, -ppc "
                 f"{defaults.get('ppc')}, -damping {defaults.get('damping')}, -pic "
                 f"{defaults.get('pic')}.")
    return out + lines


# ------------------------------------------------------------------------------------------------
# Section 2: throughput, Section 3: parallel
# ------------------------------------------------------------------------------------------------
def stream_bw(P, out_dir):
    exe = out_dir / "stream"
    src = BENCH / "stream.c"
    cc = f"gcc -O3 -o {os.path.relpath(exe, ROOT)} bench/stream.c"
    subprocess.run(cc, shell=True, cwd=ROOT, check=True)
    lg, reps = P["stream"]
    wait_quiet(P["quiet_wait"])
    cmd = f"{os.path.relpath(exe, ROOT)} {lg} {reps}"
    o = subprocess.run(cmd, shell=True, cwd=ROOT, capture_output=True, text=True).stdout
    bw = float(re.search(r"triad_GBps\s+([0-9.]+)", o).group(1))
    return bw, [cc, cmd], src


def section2(R, P, bw):
    tp = []
    for n in P["tp_sizes"]:
        for shape in ["mpm", "pmpm"]:
            r = R.run("2", f"tp_n{n}_{shape}_np1", "column.opts",
                      ["-column_width", "1.0", "-cell_size", repr(1.0 / n), "-ppc", 2,
                       "-shape", shape, "-max_steps", P["tp_steps"], "-tol", "1e-300"],
                      timed=True, min_attempts=P["tp_min"])
            tp.append(dict(n=n, shape=shape, ranks=1, rec=r))
    for x in tp:
        s = x["rec"]["summary"]
        if x["rec"]["ok"]:
            x["particles"], x["steps"] = s["particles"], s["steps"]
            x["ups"] = x["particles"] * x["steps"] / (x["rec"]["cycle_s"] * x["ranks"])
            x["ns"] = 1e9 / x["ups"]
            x["split"] = stage_ms_per_step(x["rec"], x["steps"])
    return tp


def section3(R, P, tp):
    par = []
    one = {(x["n"], x["shape"]): x for x in tp}
    for shape in ["mpm", "pmpm"]:
        n = P["par_n"]
        r = R.run("3", f"tp_n{n}_{shape}_np2", "column.opts",
                  ["-column_width", "1.0", "-cell_size", repr(1.0 / n), "-ppc", 2,
                   "-shape", shape, "-max_steps", P["tp_steps"], "-tol", "1e-300"],
                  ranks=2, timed=True, min_attempts=P["tp_min"])
        x = dict(n=n, shape=shape, ranks=2, rec=r)
        if r["ok"]:
            s = r["summary"]
            x["particles"], x["steps"] = s["particles"], s["steps"]
            x["ups"] = x["particles"] * x["steps"] / (r["cycle_s"] * 2)
            x["split"] = stage_ms_per_step(r, x["steps"])
        x["one"] = one.get((n, shape))
        par.append(x)
    lfp = []
    for ranks in [1, 2]:
        r = R.run("3", f"landfill_h{P['par_lf_h']:g}_par_np{ranks}", "landfill.opts",
                  ["-cell_size", P["par_lf_h"]], ranks=ranks, timed=True,
                  min_attempts=P["tp_min"])
        x = dict(ranks=ranks, rec=r)
        if r["ok"]:
            x["steps"] = r["summary"]["steps"]
            x["split"] = stage_ms_per_step(r, x["steps"])
        lfp.append(x)
    return par, lfp


def nice_count(n):
    return f"{n / 1e6:.2g}M" if n >= 1e6 else f"{n / 1e3:.3g}k"


STAGE_COLORS = dict(P2G="#1f77b4", Interface="#17becf", GhostAdd="#9467bd", GridUpdate="#8c564b",
                    GhostScatter="#e377c2", G2P="#ff7f0e", MUSLRemap="#bcbd22",
                    StressUpdate="#2ca02c", Migrate="#d62728", other="#7f7f7f")


def plot_throughput(tp, par, lfp, bw, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.0), gridspec_kw=dict(width_ratios=[1.1, 1]))
    stages = EVENTS + ["other"]
    ax = axes[0]
    ok = [x for x in tp if x["rec"]["ok"]]
    labels = [f"{nice_count(x['particles'])}\n{x['shape']}" for x in ok]
    bottom = np.zeros(len(ok))
    used = []
    for st in stages:
        vals = np.array([1e6 * x["split"].get(st, 0.0) / x["particles"] for x in ok])  # ns/update
        if vals.sum() <= 0:
            continue
        ax.bar(range(len(ok)), vals, bottom=bottom, color=STAGE_COLORS[st])
        used.append(st)
        bottom += vals
    for i, x in enumerate(ok):
        ax.text(i, bottom[i] * 1.01, f"{x['ups'] / 1e6:.1f}M/s", ha="center", va="bottom",
                fontsize=8)
    ax.set_xticks(range(len(ok)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("ns per particle update, 1 rank")
    ax.set_title("Column, ppc 2: time per particle update by stage\n(label: particle updates/s "
                 "per core)", fontsize=9)
    ax.set_ylim(0, bottom.max() * 1.15 if len(bottom) else 1)
    # parallel: horizontal bars, ms per step
    ax = axes[1]
    cases = []
    for x in par:
        if x["rec"]["ok"] and x.get("one") and x["one"]["rec"]["ok"]:
            cases.append((f"column {nice_count(x['particles'])} {x['shape']}", x["one"]["split"],
                          x["split"], x["one"]["rec"]["cycle_s"] / x["rec"]["cycle_s"]))
    if len(lfp) == 2 and all(x["rec"]["ok"] for x in lfp):
        cases.append((f"landfill h={lfp[0]['rec']['summary']['h'] * 1e3:g} mm", lfp[0]["split"],
                      lfp[1]["split"], lfp[0]["rec"]["cycle_s"] / lfp[1]["rec"]["cycle_s"]))
    yt, yl = [], []
    for i, (lab, s1, s2, speedup) in enumerate(cases):
        t1 = sum(s1.values())
        for j, sp in enumerate([s1, s2]):
            pos = -(i * 2.6 + j)
            left = 0.0
            for st in stages:
                v = sp.get(st, 0.0) / t1
                if v > 0:
                    ax.barh(pos, v, left=left, color=STAGE_COLORS[st], height=0.85)
                    if st not in used:
                        used.append(st)
                    left += v
            tot = sum(sp.values())
            ax.text(left, pos, f" {tot:.3g} ms" + (f", speed-up {speedup:.2f}" if j else ""),
                    va="center", fontsize=7)
            yt.append(pos)
            yl.append(f"{lab}, {j + 1} rank{'s' if j else ''}")
    ax.set_yticks(yt)
    ax.set_yticklabels(yl, fontsize=8)
    ax.set_xlabel("time per step relative to 1 rank (slowest rank's stage times)")
    ax.set_title("1 vs 2 ranks: time per step by stage", fontsize=9)
    xmax = ax.get_xlim()[1]
    ax.set_xlim(0, max(1.0, xmax) * 1.35)
    from matplotlib.patches import Patch
    fig.legend(handles=[Patch(color=STAGE_COLORS[s], label=s) for s in stages if s in used],
               loc="lower center", ncol=len(used), fontsize=8, frameon=False)
    fig.suptitle(f"pmpm explicit-cycle throughput (STREAM triad on this machine: {bw:.1f} GB/s, "
                 f"1 thread)", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=90)
    plt.close(fig)


# Bytes of particle state one explicit step reads and writes per particle (2D, doubles): P2G reads
# x, lp, v, stress, mass, volume, weight; G2P reads x, v, lp, F, mass, volume0, material and writes
# x, v, F, volume, dudx; the elastic stress update reads dudx and reads/writes the stress.
STATE_BYTES = 8 * ((2 + 2 + 2 + 4 + 3) + (2 + 2 + 2 + 4 + 2 + 0.5) + (2 + 2 + 4 + 1 + 4) + (4 + 8))


def throughput_analysis(ok, bw):
    """What stands between the measured PMPM rate and the 15 M updates/s/core target."""
    big = [x for x in ok if x["particles"] >= 1_000_000]
    rows = {x["shape"]: x for x in sorted(big, key=lambda x: x["particles"])}
    if "pmpm" not in rows:
        return ""
    pm, mp = rows["pmpm"], rows.get("mpm")
    total = 1e3 * pm["rec"]["cycle_s"] / pm["steps"]
    p2g, g2p = pm["split"].get("P2G", 0.0), pm["split"].get("G2P", 0.0)
    lines = [f"**Against the target** (PMPM >= 15 M particle-updates/s/core at >= 1 M particles): "
             f"measured {pm['ups'] / 1e6:.1f} M at {pm['particles']:,} particles "
             f"({pm['ns']:.0f} ns per update). What stands in the way, from the split above:\n"]
    lines.append(f"- P2G and G2P take {100 * (p2g + g2p) / total:.0f} % of the cycle "
                 f"({p2g:.1f} + {g2p:.1f} of {total:.1f} ms per step); the grid update, the ghost "
                 "exchanges and the stress update together take the rest.")
    if mp:
        mp2g = mp["split"].get("P2G", 0.0)
        lines.append(f"- PMPM's P2G costs {p2g / mp2g:.2f}x standard MPM's ({mp2g:.1f} ms): a "
                     "uGIMP block that straddles a cell face touches 3 x 3 nodes instead of 2 x 2, "
                     "and its 1D weights are integrals of the hats. Standard MPM reaches "
                     f"{mp['ups'] / 1e6:.1f} M on the same case.")
    lines.append(f"- It is not memory bandwidth: one update moves about {STATE_BYTES:.0f} bytes of "
                 f"particle state, but its time would move {bw * pm['ns']:.0f} bytes at this "
                 f"machine's triad bandwidth ({bw:.1f} GB/s), "
                 f"{bw * pm['ns'] / STATE_BYTES:.1f}x more. The time goes to the scalar "
                 "scatter-add into the grid and the gather from it (dependent loads and "
                 "read-modify-writes of 7 nodal values per stencil node) and to evaluating the "
                 "stencil twice per step.")
    lines.append("- Next steps, in order of expected gain: keep P2G's weights for G2P (one stencil "
                 "evaluation per step instead of two), fuse the elastic stress update into G2P "
                 "(drops the dudx round trip), sort particles by cell with a counting sort and "
                 "vectorise across the particles of a cell.\n")
    return "\n".join(lines)


def md_section2(md, tp, bw, P, stream_cmds):
    md.append("## 2. Throughput\n")
    md.append(f"Column (`options/column.opts`) with -column_width 1.0 and -ppc 2, -max_steps "
              f"{P['tp_steps']} -tol 1e-300 (never converges early), 1 rank. Cycle time = the "
              "`Relaxation` stage of -log_view (no setup, no output). Updates/s/core = particles × "
              "steps / (cycle seconds × ranks). Stage split in ms per step, from the per-event "
              "maxima of -log_view (`other` = the rest of the stage: reductions, damping, "
              "convergence test). A run that other processes disturbed was repeated (at most "
              f"{P['retries'] + 1} runs), keeping the fastest.\n")
    md.append(f"STREAM triad (bench/stream.c, 1 thread, 2^{P['stream'][0]} doubles per array, best "
              f"of {P['stream'][1]}): **{bw:.1f} GB/s**. The column `triad-equivalent bytes` is "
              "that bandwidth × the time per particle update: the memory traffic a purely "
              "bandwidth-bound kernel would move in the same time.\n")
    md.append("![throughput](bench/throughput.png)\n")
    rows = []
    for x in tp:
        r = x["rec"]
        if not r["ok"]:
            rows.append([f"1/{x['n']}", x["shape"], "", "", "", "", "", "", r["error"]])
            continue
        rows.append([f"1/{x['n']}", x["shape"], f"{x['particles']:,}", x["steps"],
                     fmt(r["cycle_s"]), fmt(1e3 * r["cycle_s"] / x["steps"]), fmt(x["ns"]),
                     f"**{x['ups'] / 1e6:.2f}**", f"{r['maxrss_kb'] / 1024:.0f}",
                     f"{r['maxrss_kb'] * 1024 / x['particles']:.0f}",
                     f"{bw * x['ns']:.0f}", fmt(r["others_cores"], 2), spread(r)])
    md.append(table(["h (m)", "shape", "particles", "steps", "cycle (s)", "ms/step",
                     "ns/update", "M updates/s/core", "peak RSS (MiB)", "RSS bytes/particle",
                     "triad-equivalent bytes/update", "other load (cores)",
                     "spread of the cycle time"], rows))
    md.append("")
    ok = [x for x in tp if x["rec"]["ok"]]
    stages = [e for e in EVENTS + ["other"] if any(x["split"].get(e, 0) > 0 for x in ok)]
    md.append("Stage split (ms per step; G2P is the velocity and the kinematics passes together):\n")
    md.append(table(["particles", "shape"] + stages + ["total"],
                    [[f"{x['particles']:,}", x["shape"]] +
                     [fmt(x["split"].get(s, 0.0)) for s in stages] +
                     [fmt(1e3 * x["rec"]["cycle_s"] / x["steps"])] for x in ok]))
    md.append("")
    md.append(throughput_analysis(ok, bw))
    md.append("<details><summary>STREAM commands</summary>\n\n```\n" + "\n".join(stream_cmds) +
              "\n```\n</details>\n")


def speedup_analysis(allx, stages):
    """Where the 2-rank PMPM column loses against half the 1-rank time, stage by stage."""
    pm = [x for x in allx if x["shape"] == "pmpm"]
    if not pm:
        return ""
    x = pm[-1]
    one, two = x["one"]["split"], x["split"]
    t1 = sum(one.get(e, 0.0) for e in stages)
    t2 = sum(two.get(e, 0.0) for e in stages)
    gaps = sorted(((two.get(e, 0.0) - 0.5 * one.get(e, 0.0), e) for e in stages), reverse=True)
    parts = [f"{e} +{g:.2f} ms" for g, e in gaps if g > 0.05 * (t2 - 0.5 * t1)]
    return (f"**Against the target** (>= 1.8x from 1 to 2 ranks): the PMPM column gives "
            f"{t1 / t2:.2f}x by the stage sums ({t1:.1f} -> {t2:.1f} ms per step; ideal "
            f"{0.5 * t1:.1f}). The stages that miss half their 1-rank time, largest first: "
            + ", ".join(parts) + ". P2G and G2P run at one rank per core but share the memory "
            "system and the L3 cache, so each rank's share takes longer than half; the ghost "
            "exchanges include waiting for the slower rank; `other` holds the reductions and the "
            "energy-balance check, which do not shrink with the particle count per rank. On this "
            "2-core machine the measurement also varies by about 0.15 between runs (1.67 to 1.94 "
            "seen for the same case). Next steps: keep the weights between P2G and G2P (less "
            "memory traffic per rank), fold the load-power sum of the energy check into G2P, and "
            "measure on a machine with more than two cores.\n")


def md_section3(md, par, lfp):
    md.append("## 3. Parallel: 1 vs 2 ranks\n")
    md.append("Speed-up = 1-rank cycle time / 2-rank cycle time (Relaxation stage); efficiency = "
              "speed-up / 2. The machine has 2 cores, so 2 ranks use all of it: any other process "
              "running at the same time slows the 2-rank runs most (`other load` is the CPU taken "
              "by other processes during the run, in cores).\n")
    rows = []
    for x in par:
        o = x.get("one")
        if x["rec"]["ok"] and o and o["rec"]["ok"]:
            sp = o["rec"]["cycle_s"] / x["rec"]["cycle_s"]
            rows.append([f"column {x['particles']:,} particles, {x['shape']}", x["steps"],
                         fmt(o["rec"]["cycle_s"]), fmt(x["rec"]["cycle_s"]), f"**{sp:.2f}**",
                         f"{100 * sp / 2:.0f} %", f"{x['ups'] / 1e6:.2f}",
                         f"{fmt(o['rec']['others_cores'], 2)} / {fmt(x['rec']['others_cores'], 2)}",
                         x["rec"]["summary"]["migrations"]])
        else:
            rows.append([f"column 1/{x['n']} {x['shape']}", "", "", "", "", "", "", "",
                         x["rec"]["error"]])
    if len(lfp) == 2 and all(x["rec"]["ok"] for x in lfp):
        a, b = lfp
        sp = a["rec"]["cycle_s"] / b["rec"]["cycle_s"]
        sa, sb = a["rec"]["summary"], b["rec"]["summary"]
        rows.append([f"landfill h = {fmt(sa['h'])} m, {sa['particles']:,} particles (to convergence)",
                     f"{sa['steps']} / {sb['steps']}", fmt(a["rec"]["cycle_s"]),
                     fmt(b["rec"]["cycle_s"]), f"**{sp:.2f}**", f"{100 * sp / 2:.0f} %",
                     f"{sa['particles'] * sb['steps'] / (b['rec']['cycle_s'] * 2) / 1e6:.2f}",
                     f"{fmt(a['rec']['others_cores'], 2)} / {fmt(b['rec']['others_cores'], 2)}",
                     sb["migrations"]])
    md.append(table(["case", "steps", "1 rank (s)", "2 ranks (s)", "speed-up", "efficiency",
                     "M updates/s/core (2 ranks)", "other load 1 / 2 ranks", "migrations (2 ranks)"],
                    rows))
    md.append("")
    allx = [x for x in par if x["rec"]["ok"] and x.get("one") and x["one"]["rec"]["ok"]]
    stages = [e for e in EVENTS + ["other"]
              if any(x["split"].get(e, 0) > 0 or x["one"]["split"].get(e, 0) > 0 for x in allx)
              or any(x["rec"]["ok"] and x["split"].get(e, 0) > 0 for x in lfp)]
    rows = []
    for x in allx:
        for ranks, y in [(1, x["one"]), (2, x)]:
            rows.append([f"column {x['particles'] / 1e6:.2g}M {x['shape']}", ranks] +
                        [fmt(y["split"].get(s, 0.0)) for s in stages])
    for y in lfp:
        if y["rec"]["ok"]:
            rows.append([f"landfill h={fmt(y['rec']['summary']['h'])}", y["ranks"]] +
                        [fmt(y["split"].get(s, 0.0)) for s in stages])
    md.append("Stage split (ms per step, slowest rank; on 2 ranks GhostAdd and GhostScatter "
              "include the wait for the other rank):\n")
    md.append(table(["case", "ranks"] + stages, rows))
    md.append("")
    md.append(speedup_analysis(allx, stages))


# ------------------------------------------------------------------------------------------------
# Section 4: skips
# ------------------------------------------------------------------------------------------------
def section4(R, P):
    h, n = P["skip_h"], P["skip_steps"]
    fixed = ["-cell_size", h, "-max_steps", n, "-tol", "1e-300"]
    mats = ["soil", "membrane", "waste", "soft"]
    dp = []
    for m in mats:
        dp += [f"-mat_{m}_model", "drucker_prager", f"-mat_{m}_cohesion", "1e9",
               f"-mat_{m}_friction_angle", "30"]
    variants = [
        ("base", "bonded interface, elastic, kinetic/pic 0.05 (landfill.opts)", [], None),
        ("paper", "-interface_type paper", ["-interface_type", "paper"], "Interface"),
        ("contact", "-interface_type contact", ["-interface_type", "contact"], "Interface"),
        ("dp", "Drucker-Prager, c = 1e9 Pa, φ = 30° (elastic, runs the return map)", dp,
         "StressUpdate"),
        ("local", "-damping local", ["-damping", "local"], "GridUpdate"),
        ("none", "-damping none", ["-damping", "none"], "GridUpdate"),
        ("dynamic", "-dynamic (no damping, no kinetic test)", ["-dynamic"], "GridUpdate"),
        ("pic0", "-pic 0 (pure FLIP)", ["-pic", "0"], "G2P"),
        ("musl", "-musl (extra momentum remap)", ["-musl"], "MUSLRemap"),
    ]
    out = []
    for key, label, extra, ev in variants:
        r = R.run("4", f"skip_{key}_h{h:g}", "landfill.opts", fixed + extra, timed=True,
                  min_attempts=P["skip_min"])
        out.append(dict(key=key, label=label, ev=ev, rec=r, steps=n))
    return out


def md_section4(md, sk, res1, par_lf, P):
    md.append("## 4. Skipped stages: what each saves\n")
    md.append(f"Landfill (`options/landfill.opts`) at -cell_size {fmt(P['skip_h'])} m on 1 rank "
              f"for a fixed {P['skip_steps']} steps (-max_steps {P['skip_steps']} -tol 1e-300), "
              "so every variant does the same number of cycles; each variant ran "
              f"{P['skip_min']} time(s), keeping the fastest (`spread`: slowest / fastest − 1). "
              "`saved` is what the default (first row) saves per step against the variant: the "
              "stage it skips or simplifies. Differences of the order of the spread are noise; "
              "the stage column isolates the stage itself.\n")
    base = next((x for x in sk if x["key"] == "base" and x["rec"]["ok"]), None)
    rows = []
    for x in sk:
        r = x["rec"]
        if not r["ok"]:
            rows.append([x["label"], "", "", "", "", "", r["error"]])
            continue
        ms = 1e3 * r["cycle_s"] / x["steps"]
        ev_ms = 1e3 * r["events"].get(x["ev"], {}).get("max_s", 0.0) / x["steps"] if x["ev"] else None
        bms = 1e3 * base["rec"]["cycle_s"] / base["steps"] if base else float("nan")
        bev = (1e3 * base["rec"]["events"].get(x["ev"], {}).get("max_s", 0.0) / base["steps"]
               if (base and x["ev"]) else None)
        s = r["summary"]["results"]
        rows.append([x["label"], fmt(ms), f"{ms - bms:+.3f} ms ({100 * (ms / bms - 1):+.0f} %)"
                     if x is not base else "–",
                     f"{x['ev']}: {fmt(bev)} → {fmt(ev_ms)}" if x["ev"] else "–",
                     fmt(r["others_cores"], 2), spread(r),
                     f"{fmt(s['settlement_centre'] * 1e3, 5)} / {fmt(s['peak_axial_strain'] * 100, 4)}"])
    md.append(table(["variant", "ms/step", "saved by the default (per step)",
                     "stage ms/step: default → variant", "other load (cores)",
                     "spread of the cycle time",
                     f"settlement (mm) / peak strain (%) after {P['skip_steps']} steps"], rows))
    md.append("")
    dp = next((x for x in sk if x["key"] == "dp" and x["rec"]["ok"]), None)
    if dp and base:
        a = base["rec"]["summary"]["results"]
        b = dp["rec"]["summary"]["results"]
        d = max(abs(b[k] / a[k] - 1) for k in ["settlement_centre", "peak_axial_strain"])
        md.append(f"The Drucker-Prager run stays elastic: its settlement and peak strain differ "
                  f"from the elastic run by at most {d:.1e} (relative).\n")
    # migrations
    md.append("**Migration** happens only on steps where a particle left its rank's cells "
              "(summary `migrations`); the table gives what migrating on every step would add, "
              "at the measured cost per migration.\n")
    rows = []
    cases = [x for x in res1.get("lf", []) if x["ranks"] == 2 and x["rec"]["ok"]]
    cases += [x for x in par_lf if x["ranks"] == 2 and x["rec"]["ok"]]
    seen = set()
    for x in cases:
        r = x["rec"]
        if r["name"] in seen:
            continue
        seen.add(r["name"])
        s = r["summary"]
        mig = s["migrations"]
        mt = r["events"].get("Migrate", {}).get("max_s", 0.0)
        per = mt / mig if mig else float("nan")
        rows.append([r["name"], s["particles"], s["steps"], mig,
                     f"{100 * mig / s['steps']:.1f} %", fmt(1e3 * per),
                     f"{100 * mt / r['cycle_s']:.1f} %",
                     fmt(per * (s["steps"] - mig)) if mig else "–",
                     f"{100 * per * (s['steps'] - mig) / r['cycle_s']:.0f} %" if mig else "–"])
    md.append(table(["run (2 ranks)", "particles", "steps", "migrations", "of steps",
                     "ms per migration", "share of cycle", "saved (s)", "saved (% of cycle)"],
                    rows))
    md.append("")


# ------------------------------------------------------------------------------------------------
def code_defaults(binary):
    o = subprocess.run([os.path.relpath(binary, ROOT), "-options_file", "options/column.opts",
                        "-help"], cwd=ROOT, capture_output=True, text=True, env=ENV).stdout
    d = {}
    for k in ["shape", "ppc", "damping", "pic"]:
        m = re.search(rf"^\s+-{k} <(?:now \S+ : formerly (\S+?)|\S+ : (\S+?))>", o, re.M)
        if m:
            d[k] = m.group(1) or m.group(2)
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI smoke run: tiny sizes, bench/out/")
    ap.add_argument("--full", action="store_true", help="also the finest landfill, h = 0.000125")
    ap.add_argument("--reuse", action="store_true", help="reuse runs whose command is unchanged")
    ap.add_argument("--only", default="1,2,3,4", help="sections to run, e.g. 1,4")
    args = ap.parse_args()
    os.chdir(ROOT)
    P = params(args.quick, args.full)
    only = set(args.only.split(","))
    runs_dir = OUT / ("runs-quick" if args.quick else "runs")
    fig_dir = OUT if args.quick else BENCH
    md_path = OUT / "BENCHMARKS.md" if args.quick else ROOT / "docs" / "benchmarks" / "run.md"
    runs_dir.mkdir(parents=True, exist_ok=True)
    fig_dir.mkdir(parents=True, exist_ok=True)
    src_bin = ROOT / "build" / "pmpm"
    binary = runs_dir / "bin" / "pmpm"
    binary.parent.mkdir(exist_ok=True)
    if not (args.reuse and binary.exists()):
        if not src_bin.exists():
            sys.exit("bench: build/pmpm not found: run `bash scripts/setup.sh` first")
        shutil.copy2(src_bin, binary)
    sha = hashlib.sha256(binary.read_bytes()).hexdigest()[:12]
    bin_mtime = datetime.datetime.fromtimestamp(binary.stat().st_mtime).strftime("%Y-%m-%d %H:%M")
    R = Runner(runs_dir, binary, args.reuse, P["quiet_wait"], P["retries"], P["wait_budget"])
    t_start = time.time()
    started = datetime.datetime.now().astimezone()
    mi = machine_info()
    head, dirty = git_info()
    defaults = code_defaults(binary)

    def log(msg):
        print(f"[{time.time() - t_start:6.0f} s] {msg}", flush=True)

    md = []
    res1, tp, par, lfp, sk = {}, [], [], [], []
    bw, stream_cmds = float("nan"), []
    timings = {}
    if "1" in only:
        log("section 1: work-precision")
        t0 = time.time()
        res1 = section1(R, P, md, fig_dir, args.quick)
        timings["1"] = time.time() - t0
    if "2" in only or "3" in only:
        log("STREAM triad")
        bw, stream_cmds, _ = stream_bw(P, runs_dir)
        log(f"  {bw:.1f} GB/s")
    if "2" in only or "3" in only:
        log("section 2: throughput")
        t0 = time.time()
        tp = section2(R, P, bw)
        timings["2"] = time.time() - t0
    if "3" in only:
        log("section 3: parallel")
        t0 = time.time()
        par, lfp = section3(R, P, tp)
        timings["3"] = time.time() - t0
    if "4" in only:
        log("section 4: skips")
        t0 = time.time()
        sk = section4(R, P)
        timings["4"] = time.time() - t0
    if tp:
        plot_throughput(tp, par, lfp, bw, fig_dir / "throughput.png")

    # ---------------------------------------------------------------- markdown
    total = time.time() - t_start
    head_md = ["# pmpm benchmarks\n",
               f"Generated by `/usr/bin/python3 bench/run.py{' --quick' if args.quick else ''}"
               f"{' --full' if args.full else ''}` on {started:%Y-%m-%d %H:%M %Z} "
               f"({total / 60:.1f} min). Do not edit by hand: rerun the script.\n",
               "**Machine.** " + f"{mi['model']}, {mi['cpus']} CPUs ({mi['threads_per_core']} "
               f"thread per core), {mi['mem_gib']:.1f} GiB memory, L2 {mi['l2']}, L3 {mi['l3']}; "
               f"{mi['kernel']}; {mi['gcc']}; {mi['mpi']}; PETSc (Debian) {mi['petsc']}.\n",
               f"**Code.** git {head}" + (f" plus uncommitted changes in {', '.join(dirty)}"
                                          if dirty else "") +
               f"; binary build/pmpm of {bin_mtime} (sha256 {sha}…), copied to "
               f"`{os.path.relpath(binary, ROOT)}` at start so that every run uses the same build.\n",
               "**Commands.** Each run is `[mpirun -n 2] "
               f"{os.path.relpath(binary, ROOT)} -options_file options/X.opts [options] "
               f"-output_dir {os.path.relpath(runs_dir, ROOT)}/NAME -quiet -log_view`, from the repository root; "
               "every section lists its exact commands in a collapsed block. The run directories "
               "(summary.json, log.txt with the -log_view output, meta.json) stay in "
               f"`{os.path.relpath(runs_dir, ROOT)}/` (ignored by git).\n",
               "**Noise.** Other engineers share this 2-core machine. The script waits for a "
               "quiet machine before each timed run (sections 2–4; it waited "
               f"{R.waited:.0f} s in all), measures the CPU that other processes took during "
               "each run (`other load`, in cores; at most "
               f"{max([r['others_cores'] for r in R.records.values() if r['section'] != '1'] or [0]):.2f}"
               " in sections 2–4) and repeats disturbed runs, keeping the fastest.\n"]
    if res1:
        relax_stats, _ = md_section1(res1, md, R, P, defaults)
        md.extend(recommend(res1, relax_stats, P, defaults))
        md.append("")
        md.append("<details><summary>Section 1 commands</summary>\n\n```\n" +
                  "\n".join(R.commands.get("1", [])) + "\n```\n</details>\n")
    if tp:
        md_section2(md, tp, bw, P, stream_cmds)
        md.append("<details><summary>Section 2 commands</summary>\n\n```\n" +
                  "\n".join(R.commands.get("2", [])) + "\n```\n</details>\n")
    if par or lfp:
        md_section3(md, par, lfp)
        md.append("<details><summary>Section 3 commands</summary>\n\n```\n" +
                  "\n".join(R.commands.get("3", [])) + "\n```\n</details>\n")
    if sk:
        md_section4(md, sk, res1, lfp, P)
        md.append("<details><summary>Section 4 commands</summary>\n\n```\n" +
                  "\n".join(R.commands.get("4", [])) + "\n```\n</details>\n")
    # anomalies
    an = []
    for r in R.records.values():
        if not r["ok"]:
            an.append(f"- `{r['name']}` failed: {r['error']}")
        elif r["others_cores"] > 0.3 and r["section"] != "1":
            an.append(f"- `{r['name']}`: other processes took {r['others_cores']:.2f} cores "
                      f"during the run (timing disturbed; {r.get('attempts', 1)} attempt(s)).")
        s = r.get("summary")
        if r["ok"] and s and not s["converged"] and "-tol 1e-300" not in r["cmd"]:
            an.append(f"- `{r['name']}` did not converge ({s['steps']} steps, ratio "
                      f"{s['unbalanced_force_ratio']:.2e}).")
        out_s = r["stages"].get("Output", 0.0)
        if r["ok"] and out_s > max(1.0, r["cycle_s"]):
            an.append(f"- `{r['name']}`: the Output stage took {out_s:.1f} s, more than the "
                      f"cycle ({r['cycle_s']:.1f} s).")
    n_dist = sum(1 for r in R.records.values() if r["section"] == "1" and r["others_cores"] > 0.3)
    if n_dist:
        an.append(f"- {n_dist} of {sum(1 for r in R.records.values() if r['section'] == '1')} "
                  "section-1 runs shared the CPU with other processes (> 0.3 cores); their times "
                  "carry that noise.")
    md.append("## Anomalies (automatic)\n")
    md.append("\n".join(an) if an else "None detected.")
    md.append("")
    md.append("Section times: " + ", ".join(f"{k}: {v / 60:.1f} min" for k, v in timings.items()))
    text = "\n".join(head_md + md) + "\n"
    # image links relative to the report: the quick one sits in bench/out/ beside its plots, the
    # full one in docs/benchmarks/ (its plots in bench/)
    md_path.write_text(text.replace("](bench/", "](" if args.quick else "](../../bench/"))
    print(text)
    log(f"wrote {os.path.relpath(md_path, ROOT)} and the plots in {os.path.relpath(fig_dir, ROOT)}/")


if __name__ == "__main__":
    main()
