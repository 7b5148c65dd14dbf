#!/usr/bin/python3
"""The scaling model of bench/scaling.py redone for 3D halos (issue 22): what one 3D step costs per
particle and per node, what each rank exchanges, measured on 1, 2 and 4 ranks, then projected to
a 60 x 60 x 20 m cover at 0.25 m cells on 64 and 1024 ranks.

    /usr/bin/python3 bench/scaling3d.py          # ~2 min on 2 cores; writes
                                                 # bench/out/scaling3d/SCALING3D.md and
                                                 # docs/benchmarks/scaling3d.md
    /usr/bin/python3 bench/scaling3d.py --quick  # fewer steps, no docs

Measured: the column extruded (-dim 3: width 1 m, h = 1/32 m, depth 1 m, 2 ppc: 262,144
particles, 32 x 34 x 32 cells), S steps with -tol 1e-300 and -log_view, on 1 rank (the compute
per particle: P2G + G2P + StressUpdate; per node: GridUpdate), and on 2 ranks (2x1x1) and 4 ranks
(2x2x1, 1x1x4; oversubscribed on 2 cores: counts only) for the messages, bytes and reductions a
step makes. The model of a rank's halo: the ghost add and the scatter move, per face a rank
shares, 2 node layers (the stencil width) x the face's nodes x the values per node (10: mass,
3 momentum, 3 internal and 3 external force; both exchanges carry every value) x 8 B, each way;
26 neighbours at most (faces, edges, corners of the box stencil). The measured bytes check it.

Projection (the cluster is assumed, not measured: 100 Gb/s links, 12.5 GB/s, 2 us per message,
an allreduce of a few doubles 2 us x log2(ranks)): per step, time = particles / rank x t_p +
nodes / rank x t_n + halo bytes / bandwidth + 26 x 2 exchanges x latency + reductions x
allreduce. The cover: 240 x 240 x 80 cells, 8 particles a cell where there is soil or waste (the
whole box in this estimate: 36.9 M particles), ranks as near-cubes of cells.
"""
import argparse
import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from benchmarks_md import launch, publish  # noqa: E402
from run import parse_log  # noqa: E402

OUT = ROOT / "bench" / "out" / "scaling3d"
MARK_BEGIN, MARK_END = "<!-- scaling3d.py begin -->", "<!-- scaling3d.py end -->"
COLUMN = ["-options_file", "options/column.opts", "-cell_size", "0.03125", "-column_width", "1",
          "-dim", "3", "-depth", "1", "-tol", "1e-300", "-ramp_steps", "5"]
NCELL = (32, 34, 32)
NDOF = 10  # GridDofT<3>::NDOF
BW, LAT = 12.5e9, 2e-6  # the assumed cluster: bytes/s, seconds per message


def run(np_, grid, steps, tag):
    """One fixed-step run: the Relaxation stage's time, messages, their average length and
    reductions (its -log_view summary line), and its events."""
    s, log = launch(ROOT / "build" / "pmpm", np_, COLUMN + grid + ["-max_steps", steps,
                                                                  "-log_view"], OUT / tag)
    if s is None:
        print(log[-3000:])
        sys.exit(f"pmpm failed on {np_} ranks {' '.join(grid)}")
    m = re.search(r"^\s*\d+:\s+Relaxation:\s+(\S+)\s+\S+\s+\S+\s+\S+\s+(\S+)\s+\S+\s+(\S+)\s+\S+"
                  r"\s+(\S+)", log, re.M)
    _, events = parse_log(log)
    ev = {name: e["max_s"] for name, e in events.items()}
    return {"time": float(m.group(1)), "messages": float(m.group(2)), "avg_len": float(m.group(3)),
            "reductions": float(m.group(4)), "events": ev, "n": s["particles"], "steps": steps}


def halo_bytes(cells, parts):
    """Bytes one interior-most rank sends per exchange: 2 node layers over each shared face (and
    the edges and corners the box stencil adds), for ranks of cells[d] / parts[d] cells."""
    sub = [cells[d] / parts[d] + 1 for d in range(3)]  # nodes per rank (shared planes once)
    faces = [2 * sub[1] * sub[2], 2 * sub[0] * sub[2], 2 * sub[0] * sub[1]]
    total = 0.0
    for d in range(3):
        if parts[d] > 1:
            total += 2 * 2 * faces[d]  # both sides, 2 layers
    edges = sum(4 * 4 * sub[d] for d in range(3) if all(parts[e] > 1 for e in range(3) if e != d))
    corners = 8 * 8 if all(p > 1 for p in parts) else 0
    return (total + edges + corners) * NDOF * 8


def near_cube(ranks, cells):
    best = None
    for px in range(1, ranks + 1):
        if ranks % px:
            continue
        for py in range(1, ranks // px + 1):
            if (ranks // px) % py:
                continue
            pz = ranks // px // py
            parts = (px, py, pz)
            surf = halo_bytes(cells, parts)
            if best is None or surf < best[0]:
                best = (surf, parts)
    return best[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    steps = 5 if a.quick else 20
    one = run(1, [], steps, "np1")
    ev = one["events"]
    nodes = (NCELL[0] + 1) * (NCELL[1] + 1) * (NCELL[2] + 1)
    t_p = sum(ev.get(e, 0.0) for e in ("P2G", "G2P", "StressUpdate")) / steps / one["n"]
    t_n = ev.get("GridUpdate", 0.0) / steps / nodes
    rows, reductions = [], []
    for label, np_, grid in [("2 (2x1x1)", 2, ["-da_processors_x", "2", "-da_processors_y", "1",
                                                "-da_processors_z", "1"]),
                             ("4 (2x2x1)", 4, ["-da_processors_x", "2", "-da_processors_y", "2",
                                                "-da_processors_z", "1"]),
                             ("4 (1x1x4)", 4, ["-da_processors_x", "1", "-da_processors_y", "1",
                                                "-da_processors_z", "4"])]:
        r = run(np_, grid, steps, "np" + label.replace(" ", "").replace("(", "_").replace(")", ""))
        parts = tuple(int(g) for g in grid[1::2])
        # the ghost exchanges' bytes per step over all ranks, from -log_view (messages x average
        # length), against the model summed over the ranks (each rank's own shared faces)
        measured = r["messages"] * r["avg_len"] / steps
        model = 0.0
        for d in range(3):
            if parts[d] > 1:
                face = 1.0
                for e in range(3):
                    if e != d:
                        face *= NCELL[e] + 1
                model += (parts[d] - 1) * face * 2 * 2 * 2  # cuts x face x 2 layers x 2 sides x 2 exchanges
        model *= NDOF * 8
        rows.append(f"| {label} | {r['messages'] / steps:.1f} | {measured / 1e6:.2f} | "
                    f"{model / 1e6:.2f} | {r['reductions'] / steps:.2f} |")
        reductions.append(r["reductions"] / steps)
    red = max(reductions)
    # projection
    cells = (240, 240, 80)
    npart = cells[0] * cells[1] * cells[2] * 8
    nnode = (cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1)
    prow = []
    for ranks in (64, 1024):
        parts = near_cube(ranks, cells)
        comp = npart / ranks * t_p + nnode / ranks * t_n
        halo = halo_bytes(cells, parts)
        comm = 2 * halo / BW + 2 * 26 * LAT
        allred = red * LAT * math.log2(ranks)
        step = comp + comm + allred
        prow.append(f"| {ranks} | {parts[0]}x{parts[1]}x{parts[2]} | {npart / ranks:,.0f} | "
                    f"{comp * 1e3:.1f} | {halo / 1e6:.2f} | {comm * 1e3:.2f} | "
                    f"{allred * 1e3:.3f} | {step * 1e3:.1f} | {comp / step * 100:.0f} % |")
    text = "\n".join([
        MARK_BEGIN, "## Scaling model in 3D (bench/scaling3d.py)", "",
        f"Measured on one rank ({one['n']:,} particles, {nodes:,} nodes, {steps} steps): "
        f"t_p = {t_p * 1e9:.0f} ns per particle (P2G + G2P + StressUpdate), "
        f"t_n = {t_n * 1e9:.1f} ns per node (GridUpdate).", "",
        "Ghost exchanges per step (all ranks), measured by -log_view against the model (2 node "
        "layers x the shared face x 10 values x 8 B, each way, for the ghost add and the "
        "scatter):", "",
        "| ranks | messages / step | MB / step measured | MB / step model | reductions / step |",
        "|---|---|---|---|---|", *rows, "",
        f"Projection for a 60 x 60 x 20 m cover at 0.25 m cells ({npart:,} particles, "
        f"{nnode:,} nodes), with an assumed cluster of 12.5 GB/s links, 2 us a message and "
        f"{red:.1f} allreduces a step at 2 us x log2(ranks):", "",
        "| ranks | process grid | particles / rank | compute ms | halo MB / exchange | "
        "exchange ms | allreduce ms | step ms | compute share |",
        "|---|---|---|---|---|---|---|---|---|", *prow, "",
        "The halo grows as the surface of a rank's block, (N / P)^(2/3), against its volume "
        "N / P: at 1024 ranks each rank still computes about 36 k particles a step, and the "
        "exchanges stay a few per cent of the step. Relaxation needs thousands of steps per "
        "stage (docs/benchmarks/relaxation_steps.md): the step time times those steps is the "
        "stage's time.",
        MARK_END, ""])
    OUT.mkdir(parents=True, exist_ok=True)
    publish(text, OUT / "SCALING3D.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
