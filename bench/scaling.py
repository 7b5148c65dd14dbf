#!/usr/bin/python3
"""A scaling model from measurements (issue 10): what one step costs per particle, per node and per
chain point, how many bytes each rank exchanges, how many reductions and migrations a step does,
measured on 1, 2 and 4 ranks, then projected to 64-1024 ranks for a 100 m cover at 2 cm cells.

    /usr/bin/python3 bench/scaling.py          # ~6 min on 2 busy cores; writes
                                               # bench/out/scaling/SCALING.md, bench/scaling.png
                                               # and the "Scaling model" section of docs/benchmarks/scaling.md
    /usr/bin/python3 bench/scaling.py --quick  # fewer steps, no drift run, no docs/benchmarks/scaling.md

Measurements (all with -log_view; PETSc counts every MPI_Allreduce / MPI_Bcast of pmpm's own code
as a reduction and every message of the DMDA ghost exchanges and the DMSwarm migration):
1. options/cover_slope.opts at -cell_size 0.25 (34,858 particles, 240 x 53 cells, one membrane
   of 986 chain points), -max_steps S per stage with -tol 1e-300 (4 stages of S steps each):
   1 rank (compute per particle, per node and per chain point), 2 ranks (PETSc's 2x1), 4 ranks
   (PETSc's grid) and 2x2. The 4-rank runs are oversubscribed on this 2-core machine: counts
   only. The machine is shared: every time is also given per CPU second the run received
   (core share = CPU seconds / (ranks x wall seconds), from getrusage of the children).
2. perf record (cpu-clock samples of the 1-rank run: only while pmpm runs, so other jobs do not
   bias it) splits the Chain event into the owned-point work (p2g_chain, g2p_chain and their
   helpers: divided among the ranks) and the work every rank repeats on every point (pack,
   unpack, tension update, owner count).
3. options/cover_degradation.opts on a 1x2 grid (the waste settles across the rank boundary):
   migrations per step, and each migration's reductions, messages and time.
4. Output sizes: particles.h5 and checkpoint_<step>.h5 of the slope at -ppc 2 and 4 (same grid
   and chain): bytes per particle = difference of the sizes / difference of the particles.
"""
import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from benchmarks_md import MPI_ENV, publish  # noqa: E402

OUT = ROOT / "bench" / "out" / "scaling"
PNG = ROOT / "bench" / "scaling.png"
MARK_BEGIN, MARK_END = "<!-- scaling.py begin -->", "<!-- scaling.py end -->"
PMPM = str(ROOT / "build" / "pmpm")

SLOPE = ["-options_file", "options/cover_slope.opts", "-cell_size", "0.25"]
DEGRADATION = ["-options_file", "options/cover_degradation.opts"]
# the events of one step, by what their work grows with
PARTICLE_EVENTS = ["P2G", "G2P", "FBar", "StressUpdate"]
NODE_EVENTS = ["GridUpdate", "Contact", "GhostAdd", "GhostScatter"]
# Values per grid node (src/model/simulation.cpp): nbody = 2 nchain + 1 blocks of GridDof::NDOF =
# 1 + 3 DIM = 7 values, then ChainDof::NDOF = 9 per chain.
NDOF, CHAIN_NDOF = 7, 9
# The chains' allreduce: 2 DIM + 5 doubles per point (src/step/cycle.cpp, chain_pack).
CHAIN_DOUBLES = 2 * 2 + 5
GHOST = 2  # DMDA stencil width (src/core/grid.cpp)
EXCHANGES = 3  # ghost exchanges per step with a chain: GhostAdd, Contact's, GhostScatter
ENERGY_EVERY = 5  # src/solvers/relaxation.cpp kEnergyEvery: one allreduce every 5 steps
# perf symbols of the Chain event: the owned points' work, and the work every rank repeats
CHAIN_OWNED = ["p2g_chain", "g2p_chain", "point_halfsize", "point_frame"]
CHAIN_REPEATED = ["chain_pack", "chain_unpack", "chain_update_tension", "chain_owner_count"]

# The projection: a 100 m cover at 2 cm cells, ppc 2 (4 particles per cell).
WIDTH, COVER_DEPTH, WASTE_DEPTH, H, PPC = 100.0, 1.2, 10.0, 0.02, 2
CHAIN_SPACING = 0.25  # -chain_spacing default (cells)
RANKS = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024]
# Network figures: ASSUMPTIONS, not measurements (no cluster here).
NETWORKS = {"InfiniBand-class (alpha 2 us, beta 10 GB/s)": (2e-6, 10e9),
            "25 Gb/s Ethernet, TCP (alpha 20 us, beta 3.1 GB/s)": (20e-6, 25e9 / 8)}


def cmd_str(cmd):
    return " ".join(str(c) for c in cmd).replace(str(ROOT) + "/", "")


def run(np_, args, tag, more_env=None, prefix=()):
    """One pmpm run with -log_view into OUT/tag.txt; returns (summary, log, core share, cmd)."""
    d = OUT / tag
    if d.is_dir():
        shutil.rmtree(d)
    log = OUT / f"{tag}.log.csv"
    cmd = list(prefix) + ["mpiexec", "-n", str(np_), PMPM] + args + \
        ["-output_dir", str(d), "-quiet", "-log_view", f":{log}:ascii_csv"]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        print(p.stdout[-3000:])
        sys.exit(f"pmpm failed: {cmd_str(cmd)}")
    s = json.loads((d / "summary.json").read_text())
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lg = parse_log(log)
    share = cpu / (np_ * lg["stage_total"]["wall"]) if lg["stage_total"]["wall"] > 0 else 1.0
    print(f"  {tag}: {s['particles']} particles, {s['steps']} steps, wall "
          f"{s['wall_seconds']:.2f} s, core share {share:.2f}, load {os.getloadavg()[0]:.1f}",
          flush=True)
    return s, lg, min(share, 1.0), cmd_str(cmd)


def parse_log(path):
    """The Relaxation stage of a -log_view CSV file (one row per event and rank, full
    precision): per event {count, time (max over ranks), messages and bytes sent (summed over
    ranks; PETSc's counts add sends and receives, so halved), reductions (rank 0)}, and the
    stage's totals in "summary"."""
    ev = {}
    for line in Path(path).read_text().splitlines()[1:]:
        f = line.split(",")
        if len(f) < 9 or f[0] != "Relaxation":
            continue
        e = ev.setdefault(f[1], {"count": 0, "time": 0.0, "messages": 0.0, "bytes": 0.0,
                                 "reductions": 0.0})
        e["time"] = max(e["time"], float(f[4]))
        e["messages"] += float(f[5]) / 2
        e["bytes"] += float(f[6]) / 2
        if f[2] == "0":
            e["count"] = int(float(f[3]))
            e["reductions"] = float(f[7])
    total = ev.pop("summary")
    total["wall"] = total["time"]
    return {"events": ev, "stage_total": total}


def perf_split(args, steps_tag):
    """cpu-clock samples of a 1-rank run by symbol; None when perf is unavailable."""
    if shutil.which("perf") is None:
        return None, None
    data = OUT / f"{steps_tag}.perf.data"
    d = OUT / steps_tag
    if d.is_dir():
        shutil.rmtree(d)
    cmd = ["perf", "record", "-e", "cpu-clock", "-F", "2000", "-o", str(data), PMPM] + args + \
        ["-output_dir", str(d), "-quiet"]
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print("perf record failed; the Chain event is taken as repeated on every rank")
        return None, None
    rep = subprocess.run(["perf", "report", "-i", str(data), "--no-children", "--sort", "symbol",
                          "--stdio", "-g", "none", "-n"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True).stdout
    samples = {}
    for line in rep.splitlines():
        m = re.match(r"^\s*([\d.]+)%\s+(\d+)\s+\[.\]\s+(.*?)\s*$", line)
        if m:
            samples[m.group(3)] = samples.get(m.group(3), 0) + int(m.group(2))
    return samples, cmd_str(cmd)


def group(samples, names):
    return sum(n for sym, n in samples.items() if any(re.search(rf"\b{k}\b", sym) for k in names))


def halo(nodes_x, nodes_y, nd):
    """Per rank of a DMDA partition (nodes per rank column / row): the ghost nodes it receives
    in one exchange (box stencil of width GHOST; none outside the box: DM_BOUNDARY_GHOSTED),
    its neighbours, and the bytes (8 per value)."""
    nx, ny = sum(nodes_x), sum(nodes_y)
    xs = [sum(nodes_x[:i]) for i in range(len(nodes_x))]
    ys = [sum(nodes_y[:j]) for j in range(len(nodes_y))]
    out = []
    for j, (y0, my) in enumerate(zip(ys, nodes_y)):
        for i, (x0, mx) in enumerate(zip(xs, nodes_x)):
            gx = min(nx, x0 + mx + GHOST) - max(0, x0 - GHOST)
            gy = min(ny, y0 + my + GHOST) - max(0, y0 - GHOST)
            ghosts = gx * gy - mx * my
            nb = sum(1 for dj in (-1, 0, 1) for di in (-1, 0, 1) if (di or dj) and
                     0 <= i + di < len(nodes_x) and 0 <= j + dj < len(nodes_y))
            out.append({"ghosts": ghosts, "neighbours": nb, "bytes": ghosts * nd * 8})
    return out


def even_split(n, parts):
    return [n // parts + (1 if k < n % parts else 0) for k in range(parts)]


def best_grid(P, nx, ny, nd):
    """The process grid px x py = P with the fewest ghost bytes on the busiest rank."""
    best = None
    for px in range(1, P + 1):
        if P % px:
            continue
        py = P // px
        if nx // px < 2 or ny // py < 2:
            continue
        h = halo(even_split(nx, px), even_split(ny, py), nd)
        worst = max(h, key=lambda r: (r["bytes"], r["neighbours"]))
        if best is None or worst["bytes"] < best[2]["bytes"]:
            best = (px, py, worst)
    return best


def step_time(P, m, scene, alpha, beta):
    """The model's seconds per step on P ranks, by term."""
    Np, Nn, Nc = scene["particles"], scene["nodes"], scene["chain_points"]
    px, py, worst = best_grid(P, scene["nx"], scene["ny"], scene["nd"])
    logP = math.log2(P) if P > 1 else 0.0
    t = {}
    t["particles"] = Np / P * m["t_p"]
    t["nodes"] = Nn / P * m["t_n"]
    t["chain (owned points)"] = Nc / P * m["t_c_owned"]
    t["chain (repeated)"] = Nc * m["t_c_repeated"]
    t["halo"] = 0.0 if P == 1 else \
        EXCHANGES * (worst["neighbours"] * alpha + worst["bytes"] / beta)
    t["reductions"] = m["small_reductions"] * alpha * logP
    # the chains' allreduce of every point: reduce-scatter + allgather (Rabenseifner)
    cb = Nc * CHAIN_DOUBLES * 8
    t["chain allreduce"] = 0.0 if P == 1 else 2 * logP * alpha + 2 * (P - 1) / P * cb / beta
    t["migration"] = 0.0 if P == 1 else m["mig_per_step"] * (
        Np / P * m["t_mig"] + m["mig_reductions"] * alpha * logP +
        m["mig_messages"] * alpha)
    return t, (px, py, worst)


def cover_scene(width):
    nx = round(width / H)
    ny = round((COVER_DEPTH + WASTE_DEPTH) / H) + 2  # the box: highest top + two cells
    filled = round((COVER_DEPTH + WASTE_DEPTH) / H)
    return {"nx": nx + 1, "ny": ny + 1, "nodes": (nx + 1) * (ny + 1),
            "particles": nx * filled * PPC * PPC,
            "chain_points": round(width / (CHAIN_SPACING * H)),
            "nd": 3 * NDOF + CHAIN_NDOF}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--steps", type=int, default=100, help="steps per stage of the slope runs")
    ap.add_argument("--repeat", type=int, default=2, help="1- and 2-rank runs (minimum kept)")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    steps = 20 if a.quick else a.steps
    repeat = 1 if a.quick else a.repeat
    fixed = SLOPE + ["-max_steps", str(steps), "-tol", "1e-300"]
    commands = []

    # 1. the slope on 1, 2, 4 ranks
    print("slope runs:", flush=True)
    runs = {}
    layouts = [("np1", 1, [], repeat), ("np2", 2, [], repeat), ("np4", 4, [], 1),
               ("np4_2x2", 4, ["-da_processors_x", "2", "-da_processors_y", "2"], 1)]
    for tag, np_, more, reps in layouts:
        best = None
        for r in range(reps):
            s, lg, share, cmd = run(np_, fixed + more, f"slope_{tag}")
            commands.append(cmd)
            # the minimum over repeats of the CPU-share-corrected stage time
            key = lg["stage_total"]["wall"] * share
            if best is None or key < best[3]:
                best = (s, lg, share, key)
        runs[tag] = best

    s1, lg1, share1, _ = runs["np1"]
    nsteps = s1["steps"]
    Np1 = s1["particles"]
    nodes1 = sum(s1["partition"]["nodes_x"]) * sum(s1["partition"]["nodes_y"])
    chain_pts = sum(1 for _ in open(OUT / "slope_np1" / "chain_hdpe.csv")) - 1
    nd = 3 * NDOF + CHAIN_NDOF

    def ev_time(lg, name):
        return lg["events"].get(name, {"time": 0.0})["time"]

    # per-event seconds per unit per step on 1 rank, corrected by the core share
    events_known = PARTICLE_EVENTS + NODE_EVENTS + ["Chain", "Migrate", "Output"]
    stage1 = lg1["stage_total"]["wall"]
    other1 = stage1 - sum(ev_time(lg1, e) for e in events_known) - \
        ev_time(lg1, "CheckpointWrite")
    per = {}
    for e in PARTICLE_EVENTS:
        per[e] = ev_time(lg1, e) * share1 / (nsteps * Np1)
    for e in NODE_EVENTS:
        per[e] = ev_time(lg1, e) * share1 / (nsteps * nodes1)
    per["Chain"] = ev_time(lg1, "Chain") * share1 / (nsteps * chain_pts)
    per["other"] = other1 * share1 / (nsteps * Np1)

    # 2. perf: the Chain event's owned and repeated parts
    print("perf split of the 1-rank run:", flush=True)
    samples, perf_cmd = perf_split(fixed, "slope_np1_perf")
    if samples:
        commands.append(perf_cmd)
        owned, repeated = group(samples, CHAIN_OWNED), group(samples, CHAIN_REPEATED)
        total = sum(samples.values())
        f_rep = repeated / (owned + repeated) if owned + repeated else 1.0
    else:
        owned = repeated = total = 0
        f_rep = 1.0

    # 3. migrations: the degradation example on a 1x2 grid
    mig = {"per_step": 0.0, "reductions": 0.0, "messages": 0.0, "seconds": 0.0,
           "per_particle": 0.0, "steps": 0, "count": 0, "share": 1.0}
    if not a.quick:
        print("migration run:", flush=True)
        deg_steps = max(steps * 3, 300)
        s, lg, share, cmd = run(2, DEGRADATION + ["-max_steps", str(deg_steps), "-tol", "1e-300",
                                                  "-da_processors_x", "1", "-da_processors_y",
                                                  "2"], "degradation_1x2")
        commands.append(cmd)
        m = lg["events"].get("Migrate")
        if m and m["count"]:
            npr = max(s["partition"]["particles_per_rank"])
            mig.update(per_step=m["count"] / s["steps"], reductions=m["reductions"] / m["count"],
                       messages=m["messages"] / m["count"] / 2, seconds=m["time"] / m["count"],
                       per_particle=m["time"] * share / m["count"] / npr, steps=s["steps"],
                       count=m["count"], share=share, particles=s["particles"], npr=npr)

    # 4. output sizes: ppc 2 and 4 on the same grid, one checkpoint per stage
    print("output sizes:", flush=True)
    sizes = {}
    for ppc in (2, 4):
        s, lg, share, cmd = run(1, SLOPE[:2] + ["-cell_size", "0.5", "-ppc", str(ppc), "-max_steps",
                                            "2", "-tol", "1e-300", "-checkpoint_at_stage_end"],
                                f"size_ppc{ppc}")
        commands.append(cmd)
        d = OUT / f"size_ppc{ppc}"
        ck = sorted(d.glob("checkpoint_*.h5"), key=lambda p: int(p.stem.split("_")[1]))[-1]
        sizes[ppc] = (s["particles"], (d / "particles.h5").stat().st_size, ck.stat().st_size)
    dn = sizes[4][0] - sizes[2][0]
    bpp_particles = (sizes[4][1] - sizes[2][1]) / dn
    bpp_checkpoint = (sizes[4][2] - sizes[2][2]) / dn

    # counts: halo bytes (derived from the partition, checked against PETSc's), reductions
    counts = []
    for tag in ("np2", "np4", "np4_2x2"):
        s, lg, share, _ = runs[tag]
        part = s["partition"]
        h = halo(part["nodes_x"], part["nodes_y"], nd)
        derived = sum(r["bytes"] for r in h)  # bytes of one exchange, all ranks
        derived_msgs = sum(r["neighbours"] for r in h)
        per_call = {e: (lg["events"][e]["bytes"] / lg["events"][e]["count"],
                        lg["events"][e]["messages"] / lg["events"][e]["count"])
                    for e in ("GhostScatter", "Contact", "GhostAdd")}
        red = lg["stage_total"]["reductions"] - sum(
            lg["events"].get(e, {"reductions": 0})["reductions"] for e in ("Output", "Migrate"))
        chain_red = lg["events"]["Chain"]["reductions"]
        counts.append({
            "tag": tag, "grid": "x".join(map(str, part["processes"])), "steps": s["steps"],
            "ppr": part["particles_per_rank"], "imbalance": part["imbalance"],
            "ghost_per_rank": [r["ghosts"] for r in h],
            "bytes_per_rank_step": [EXCHANGES * r["bytes"] for r in h],
            "derived_bytes": derived, "derived_msgs": derived_msgs, "per_call": per_call,
            "red_per_step": red / s["steps"], "chain_red_per_step": chain_red / s["steps"],
            "migrations": s["migrations"]})
    code_red = 4 + 1 / ENERGY_EVERY  # 2 in Step, chain buffer, ChainReductions; energy check

    # the model's measured coefficients
    t_p = sum(per[e] for e in PARTICLE_EVENTS) + per["other"]
    t_n = sum(per[e] for e in NODE_EVENTS)
    model = {"t_p": t_p, "t_n": t_n, "t_c_owned": per["Chain"] * (1 - f_rep),
             "t_c_repeated": per["Chain"] * f_rep,
             "small_reductions": code_red - 1,  # the chain buffer's is its own term
             "mig_per_step": mig["per_step"], "t_mig": mig["per_particle"],
             "mig_reductions": mig["reductions"], "mig_messages": mig["messages"]}

    scene = cover_scene(WIDTH)
    # strong scaling: the 100 m cover on P ranks; weak: its 64-rank share per rank, the width
    # growing with P (the chain with it)
    per_rank_64 = scene["particles"] / 64
    strong, weak = {}, {}
    for net, (alpha, beta) in NETWORKS.items():
        t1 = sum(step_time(1, model, scene, alpha, beta)[0].values())
        strong[net] = []
        for P in RANKS:
            t, (px, py, worst) = step_time(P, model, scene, alpha, beta)
            T = sum(t.values())
            strong[net].append({"P": P, "grid": f"{px}x{py}", "T": T, "terms": t,
                                "eff": t1 / (P * T), "ppr": scene["particles"] / P,
                                "eff_rest": t1 / (P * (T - t["migration"])),
                                "halo": EXCHANGES * worst["bytes"]})
        weak[net] = []
        for P in RANKS:
            w = WIDTH * P / 64
            sc = cover_scene(w)
            t, (px, py, worst) = step_time(P, model, sc, alpha, beta)
            T = sum(t.values())
            ideal = per_rank_64 * model["t_p"] + sc["nodes"] / P * model["t_n"]
            weak[net].append({"P": P, "grid": f"{px}x{py}", "T": T, "terms": t,
                              "eff": ideal / T, "eff_rest": ideal / (T - t["migration"]),
                              "width": w, "chain": sc["chain_points"]})

    # ---------------------------------------------------------------------------------------
    L = [MARK_BEGIN, "## Scaling model (bench/scaling.py)", ""]
    L += ["A model of one step's time on P ranks, its coefficients measured here on 1, 2 and 4 "
          "ranks, projected to 64-1024 ranks for a 100 m cover at 2 cm cells. The counts "
          "(bytes, messages, reductions, migrations) are exact; the times come from a shared "
          "2-core machine (load average "
          f"{os.getloadavg()[0]:.1f} at the end of the run) and are corrected by the share of a "
          "core the run received (CPU seconds / (ranks x wall seconds), getrusage); the network "
          "figures are **assumptions** (no cluster was available).", ""]
    L += ["### Measured", "",
          f"Scene: `options/cover_slope.opts -cell_size 0.25` ({Np1:,} particles, "
          f"{s1['cells'][0]} x {s1['cells'][1]} cells = {nodes1:,} nodes, one membrane of "
          f"{chain_pts} chain points, {nd} values per node: 3 bodies x {NDOF} + {CHAIN_NDOF} "
          f"chain slots), {steps} steps per stage x 4 stages = {nsteps} steps, -tol 1e-300. "
          f"The 4-rank runs are oversubscribed (2 cores): their counts only.", "",
          f"**Compute per step on 1 rank** (core share {share1:.2f}; seconds x share / (steps x "
          f"units)):", "",
          "| event | per | ns per unit per step | wall on 1 rank (s) |", "|---|---|---|---|"]
    for e in PARTICLE_EVENTS:
        L.append(f"| {e} | particle | {1e9 * per[e]:.1f} | {ev_time(lg1, e):.3f} |")
    L.append(f"| other (stage - events: reductions, damping, energy check, monitor) | particle | "
             f"{1e9 * per['other']:.1f} | {other1:.3f} |")
    for e in NODE_EVENTS:
        L.append(f"| {e} | node | {1e9 * per[e]:.1f} | {ev_time(lg1, e):.3f} |")
    L.append(f"| Chain | chain point | {1e9 * per['Chain']:.1f} | {ev_time(lg1, 'Chain'):.3f} |")
    L += ["", f"t_p = {1e9 * t_p:.0f} ns per particle-step, t_n = {1e9 * t_n:.0f} ns per "
          f"node-step, t_c = {1e9 * per['Chain']:.0f} ns per chain point-step. "
          f"(docs/benchmarks/run.md section 2 measured the column's P2G + G2P + stress at about 80 ns "
          f"per particle-step on an idle core; the cover adds Drucker-Prager's return map, "
          f"F-bar and the eigenstrain.)", ""]
    if samples:
        L += [f"**The Chain event split** (perf cpu-clock samples of the 1-rank run, "
              f"{total:,} samples): owned points ({', '.join(CHAIN_OWNED)}) {owned:,} samples, "
              f"repeated on every rank ({', '.join(CHAIN_REPEATED)}) {repeated:,}: "
              f"{100 * f_rep:.1f} % of the chain work is repeated by every rank, the rest "
              f"is divided among the ranks (each moves the points in its cells).", ""]
    L += ["**Counts on 2 and 4 ranks** (halo derived from the partition in summary.json: each "
          f"rank receives the nodes of its ghost box, width {GHOST}, box stencil, none outside "
          f"the box, x {nd} values x 8 bytes, {EXCHANGES} exchanges per step: GhostAdd, the "
          "contact's GlobalToLocal, GhostScatter; PETSc's from the -log_view CSV):", "",
          "| ranks (grid) | particles per rank | halo bytes per rank per step | one "
          "exchange, all ranks: derived bytes (messages) | PETSc GhostScatter | PETSc Contact "
          "| PETSc GhostAdd | reductions per step (PETSc) | of them in Chain | migrations |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for c in counts:
        pc = {e: f"{b:,.0f} ({m:.2f})" for e, (b, m) in c["per_call"].items()}
        L.append(f"| {c['tag'].replace('np', '').split('_')[0]} ({c['grid']}) | {c['ppr']} | "
                 f"{c['bytes_per_rank_step']} | {c['derived_bytes']:,} ({c['derived_msgs']}) | "
                 f"{pc['GhostScatter']} | {pc['Contact']} | {pc['GhostAdd']} | "
                 f"{c['red_per_step']:.3f} | {c['chain_red_per_step']:.2f} | "
                 f"{c['migrations']} |")
    L += ["", "PETSc's figures are bytes and messages sent per call (the CSV log, summed over "
          "ranks); GhostAdd's include the vector scatter's one-time set-up in its first call."]
    L += ["", "Reductions counted in the code per step with a chain: "
          f"{code_red:.1f} (src/step/cycle.cpp Step: the MAX and the SUM allreduce; the chain "
          "buffer's allreduce; ChainReductions; "
          f"src/solvers/relaxation.cpp: the energy check's allreduce every {ENERGY_EVERY} steps). PETSc "
          "counts the stage's MPI_Allreduce and MPI_Bcast calls (here less the Output and "
          "Migrate events'); the rest, "
          f"{(counts[0]['red_per_step'] - code_red) * nsteps / 4:.1f} per stage, are the "
          "stage's start and end (wave speed, energy budget, the cover's stage record).", ""]
    if mig["count"]:
        L += [f"**Migrations**: options/cover_degradation.opts on a 1x2 grid, {mig['steps']} "
              f"steps ({mig['particles']:,} particles, the waste settling across the rank "
              f"boundary): {mig['count']} migrations = {mig['per_step']:.3f} per step; each "
              f"DMSwarmMigrate does {mig['reductions']:.0f} reductions (DMSwarm's data exchange "
              f"builds its communication map each time) and {mig['messages']:.1f} messages per "
              f"rank, and took {1e3 * mig['seconds']:.1f} ms wall (core share "
              f"{mig['share']:.2f}: {1e9 * mig['per_particle']:.0f} ns per particle on the "
              f"larger rank, {mig['npr']:,} particles). The slope above, a relaxation at rest, "
              f"migrates {counts[0]['migrations']} times.", ""]
    L += ["**Output sizes** (slope at -cell_size 0.5, -ppc 2 and 4, -checkpoint_at_stage_end; "
          "difference of file sizes / difference of particles): "
          f"particles.h5 {bpp_particles:.1f} bytes per particle (25 doubles = 200 written by "
          f"src/io/output.cpp), checkpoint {bpp_checkpoint:.1f} bytes per particle (the 26 "
          f"doubles of the swarm fields, src/core/particles.cpp, = 208).", ""]

    L += ["Five runs of this script on 2 December 2026 (load average 4-9 on the 2 cores) "
          "gave t_p = 169-205 ns, t_n = 130-177 ns, a repeated chain share of 2-4 % (tens of "
          "perf samples) and t_mig = 101-340 ns (timed across two ranks: the least certain): "
          "read the projections below to about +-20 % at rest, and the settling ones as "
          "rougher.", ""]
    L += ["### The model", "", "```",
          "T_step(P) = N_p/P t_p + N_n/P t_n + N_c (t_c,own/P + t_c,rep)",
          f"          + {EXCHANGES} (n_nb alpha + B_halo/beta)            ghost exchanges, "
          "busiest rank",
          f"          + {code_red - 1:.1f} alpha log2 P                         small allreduces",
          "          + 2 alpha log2 P + 2 (P-1)/P B_chain/beta      chain allreduce "
          "(reduce-scatter + allgather)",
          "          + f_mig (N_p/P t_mig + r_mig alpha log2 P + m_mig alpha)   migration",
          "```", "",
          f"Measured: t_p = {1e9 * t_p:.0f} ns, t_n = {1e9 * t_n:.0f} ns, t_c,own = "
          f"{1e9 * model['t_c_owned']:.0f} ns, t_c,rep = {1e9 * model['t_c_repeated']:.1f} ns, "
          f"f_mig = {mig['per_step']:.3f}, t_mig = {1e9 * mig['per_particle']:.0f} ns, "
          f"r_mig = {mig['reductions']:.0f}, m_mig = {mig['messages']:.1f}.", "",
          "Assumptions (named, not measured): "]
    for net, (alpha, beta) in NETWORKS.items():
        L.append(f"- {net}: latency alpha = {1e6 * alpha:g} us per message, bandwidth "
                 f"beta = {beta / 1e9:.3g} GB/s per rank;")
    L += ["- every rank has the bandwidth to itself (ranks sharing a node share its link: with "
          "32 ranks a node, divide beta by up to 32 for the inter-node part of the halo);",
          "- the compute coefficients are this machine's (one core of a shared 2-core box, "
          "core-share corrected) and do not change with P (no cache effects);",
          "- perfect balance of particles (-balance setup gives 1.001-1.01 on x-splits; on "
          "2-D grids less even, docs/cluster.md, \"Running on more ranks\"), and the process grid with "
          "the fewest halo bytes on its busiest rank;",
          f"- migration in {100 * mig['per_step']:.0f} % of the steps (the settling "
          "degradation example on 2 ranks; more rank boundaries would raise it; a relaxation "
          "at rest has none);",
          "- a migration's time proportional to the rank's particles (measured at one size "
          "only, on 2 ranks of a busy machine: the least certain coefficient);",
          "- no overlap of communication and computation (pmpm does none).", ""]
    L += ["### Projection: a 100 m cover at 2 cm cells", "",
          f"{WIDTH:g} m wide, {COVER_DEPTH} m of cover layers over {WASTE_DEPTH:g} m of waste "
          f"(the sinkhole example's section), h = {H} m, ppc {PPC}: {scene['nx'] - 1} x "
          f"{scene['ny'] - 1} cells, N_p = {scene['particles']:,} particles, N_n = "
          f"{scene['nodes']:,} nodes, one membrane at the default -chain_spacing "
          f"{CHAIN_SPACING} cells: N_c = {scene['chain_points']:,} points, whose allreduce "
          f"moves B_chain = {scene['chain_points']} x {CHAIN_DOUBLES} doubles = "
          f"{scene['chain_points'] * CHAIN_DOUBLES * 8 / 1e6:.2f} MB every step "
          f"({scene['chain_points'] // 4:,} points and "
          f"{scene['chain_points'] // 4 * CHAIN_DOUBLES * 8 / 1e6:.2f} MB at -chain_spacing 1).",
          ""]
    for net in NETWORKS:
        L += [f"**Strong scaling**, {net} (efficiency = T(1) / (P T(P)), T(1) = the model's "
              "compute on one rank):", "",
              "| ranks | grid | particles per rank | halo bytes per rank per step | ms per step "
              "| particles | nodes + chain | halo | reductions + chain allreduce | migration "
              "| efficiency | at rest (no migration) |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in strong[net]:
            if r["P"] < 16:
                continue
            t = r["terms"]
            L.append(
                f"| {r['P']} | {r['grid']} | {r['ppr']:,.0f} | {r['halo'] / 1e3:.0f} kB | "
                f"{1e3 * r['T']:.2f} | {1e3 * t['particles']:.2f} | "
                f"{1e3 * (t['nodes'] + t['chain (owned points)'] + t['chain (repeated)']):.2f} | "
                f"{1e3 * t['halo']:.3f} | "
                f"{1e3 * (t['reductions'] + t['chain allreduce']):.3f} | "
                f"{1e3 * t['migration']:.3f} | **{100 * r['eff']:.0f} %** | "
                f"{100 * r['eff_rest']:.0f} % |")
        L += ["", f"**Weak scaling**, {net}: {per_rank_64:,.0f} particles per rank (the 100 m "
              "cover's share on 64 ranks), the cover widening with P (its membrane too); "
              "efficiency = the rank's own particle and node work / T(P):", "",
              "| ranks | width (m) | chain points | ms per step | chain allreduce (ms) "
              "| migration (ms) | efficiency | at rest (no migration) |",
              "|---|---|---|---|---|---|---|---|"]
        for r in weak[net]:
            if r["P"] < 16:
                continue
            L.append(f"| {r['P']} | {r['width']:,.0f} | {r['chain']:,} | {1e3 * r['T']:.2f} | "
                     f"{1e3 * r['terms']['chain allreduce']:.3f} | "
                     f"{1e3 * r['terms']['migration']:.3f} | **{100 * r['eff']:.0f} %** | "
                     f"{100 * r['eff_rest']:.0f} % |")
        L.append("")

    # where it breaks down: the terms of the last strong-scaling row, largest first
    nets = list(NETWORKS)
    ib, eth = nets[0], nets[1]
    last = strong[ib][-1]
    comp = ["particles", "nodes", "chain (owned points)"]
    rest = sorted(((k, v) for k, v in last["terms"].items() if k not in comp),
                  key=lambda kv: -kv[1])

    def first_below(rows, key, level=0.5):
        return next((r["P"] for r in rows if r[key] < level), None)

    def below(rows, key):
        p = first_below(rows, key)
        return f"below 50 % from {p} ranks" if p else "above 50 % to 1024 ranks"

    L += ["**Where it breaks down.** Strong scaling of the 100 m cover, InfiniBand-class: "
          f"{below(strong[ib], 'eff')} while the waste settles (migration in "
          f"{100 * mig['per_step']:.0f} % of the steps), {below(strong[ib], 'eff_rest')} at "
          f"rest; 25 GbE: {below(strong[eth], 'eff')} settling, "
          f"{below(strong[eth], 'eff_rest')} at rest. At {last['P']} ranks "
          f"({last['ppr']:,.0f} particles per rank) the step's "
          f"{1e3 * last['T']:.2f} ms are {1e3 * sum(last['terms'][k] for k in comp):.2f} ms of "
          "divided work and, beyond it: " +
          ", ".join(f"{k} {1e3 * v:.3f} ms" for k, v in rest) + ". "
          "The migration: each DMSwarmMigrate does "
          f"{mig['reductions']:.0f} reductions and, taken as proportional to the rank's "
          f"particles, costs {100 * mig['per_step'] * model['t_mig'] / model['t_p']:.0f} % of "
          "the particle work at any P while particles move (more rank boundaries would make "
          "it more frequent); at rest it is zero. "
          "The chain's terms do not shrink with P: every rank repeats "
          f"{100 * f_rep:.0f} % of the chain work on all points, and the chain allreduce moves "
          f"{scene['chain_points'] * CHAIN_DOUBLES * 8 / 1e6:.2f} MB every step whatever P. "
          "The halo is small (a 2 cm cover is shallow: the busiest rank sends "
          f"{last['halo'] / 1e3:.0f} kB a step at {last['P']} ranks). In weak scaling the "
          "chain grows with the width, so its allreduce grows with P: "
          f"{1e3 * weak[ib][-1]['terms']['chain allreduce']:.1f} ms (InfiniBand-class) and "
          f"{1e3 * weak[eth][-1]['terms']['chain allreduce']:.1f} ms (25 GbE) a step at 1024 "
          f"ranks ({weak[ib][-1]['width']:,.0f} m of sheet), weak efficiency "
          f"{100 * weak[ib][-1]['eff_rest']:.0f} % and {100 * weak[eth][-1]['eff_rest']:.0f} % "
          "at rest. Remedies, in order: a cheaper migration (profile DMSwarmMigrate first; pmpm's "
          "G2P already counts the particles that left, so a migration could send just those), "
          "or migrate every k steps with a wider ghost band; send the chain points to the ranks "
          "whose cells they are near "
          "(a neighbour exchange like the grid's) instead of allreducing the whole sheet; "
          "overlap the halo exchange with the interior P2G.", "",
        "![scaling](bench/scaling.png)", ""]
    L += ["<details><summary>Commands</summary>", "", "```"] + commands + \
        ["```", "</details>", MARK_END]

    # the figure: strong and weak efficiency, and the strong-scaling terms (InfiniBand-class)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for net in NETWORKS:
        lab = net.split(" (")[0]
        ax[0].semilogx([r["P"] for r in strong[net]], [100 * r["eff"] for r in strong[net]],
                       "o-", base=2, label=f"strong, {lab}")
        ax[0].semilogx([r["P"] for r in weak[net] if r["P"] >= 64],
                       [100 * r["eff"] for r in weak[net] if r["P"] >= 64], "s--", base=2,
                       label=f"weak, {lab}")
    ax[0].set_xlabel("ranks")
    ax[0].set_ylabel("parallel efficiency (%)")
    ax[0].set_ylim(0, 105)
    ax[0].grid(True, alpha=0.3)
    ax[0].legend(fontsize=8)
    ax[0].set_title("100 m cover, 2 cm cells (model)")
    names = list(strong[ib][0]["terms"])
    rows = [r for r in strong[ib] if r["P"] > 1]  # P = 1 has no communication terms
    for k in names:
        ax[1].plot([r["P"] for r in rows], [1e3 * r["terms"][k] for r in rows], "o-", label=k,
                   ms=3)
    ax[1].set_xscale("log", base=2)
    ax[1].set_yscale("log")
    ax[1].set_xlabel("ranks")
    ax[1].set_ylabel("ms per step")
    ax[1].set_title("strong scaling terms, " + ib.split(" (")[0])
    ax[1].grid(True, alpha=0.3)
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "scaling.png" if a.quick else PNG, dpi=110)

    text = "\n".join(L) + "\n"
    (OUT / "model.json").write_text(json.dumps({"model": model, "per_event": per,
                                                "counts": counts, "migration": mig,
                                                "bytes_per_particle": [bpp_particles,
                                                                       bpp_checkpoint],
                                                "scene": scene}, indent=1))
    publish(text, OUT / "SCALING.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
