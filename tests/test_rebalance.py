"""Rebalancing during a run (-balance run): the partition follows the particles at a stage's end.

usage: test_rebalance.py EXE OUTDIR

The void cover (tests/cover_void.opts) with its void moved off centre (x = 2 m, widths 1.5 then
2 m): the first void stage removes particles from rank 0's half only, so at that stage's end the
2 ranks hold 1.026 x the mean. With -balance run (threshold 1, gain 0: rebalance whenever the
particle-balanced partition is better) the grid is rebuilt and the particles move.

1. The run rebalances once, at stage 1's end, to an imbalance below the one it had (the plan's
   granularity is a cell column: 1.017 here), and summary.json says so.
2. Its answer is the unbalanced run's (-balance setup) to round-off carried through the
   relaxation: the two partitions sum the ghost nodes in another order, the relaxations stop at
   steps a few apart (tol 1e-3), so particle positions agree to 1e-6 of the domain and stresses
   to 1e-3 of the largest (the bounds of the cover scenes' rank-invariance test; measured 7e-8
   and 1.9e-4).
3. A restart from the checkpoint written after the rebalance (stage 1's end) on 2 ranks ends bit
   for bit as the uninterrupted run: the checkpoint carries the partition, and the restart
   rebuilds the grid with it before it hands each rank its block of particles back.
"""
import csv
import filecmp
import json
import sys

import h5py
import numpy as np
from pmpmtest import Checks, run

exe, out = sys.argv[1], sys.argv[2]
c = Checks("rebalance")
# Stage 1 needs about 20,000 steps (19,778 before the contact's tail-share fix, 20,242 after):
# twice the file's cap, so that the check is of the rebalancing, not of a capped stage.
VOID = ["-options_file", "tests/cover_void.opts", "-cover_void_x", "2", "-cover_void_widths",
        "1.5,2", "-max_steps", "40000"]
RUN = ["-balance", "run", "-balance_threshold", "1", "-balance_gain", "0"]


def particles(d):
    with h5py.File(f"{d}/particles.h5", "r") as f:
        return {k: f["particles/" + k][:] for k in ("position", "stress", "velocity", "F", "id")}


def summary(d):
    with open(f"{d}/summary.json") as f:
        return json.load(f)


reb, ref = f"{out}/rebalanced", f"{out}/setup_only"
run(exe, 2, VOID + RUN + ["-checkpoint_at_stage_end"], reb)
run(exe, 2, VOID + ["-balance", "setup"], ref)

# 1. it rebalanced, once, and lowered the imbalance
b = summary(reb)["balance"]
c.check("one rebalance during the run", b["rebalances"] == 1, f"({b['rebalances']})")
c.check("the rebalance lowered max/mean particles per rank",
        b["last_imbalance_after"] < b["last_imbalance_before"],
        f"({b['last_imbalance_before']:.4f} -> {b['last_imbalance_after']:.4f})")
c.check("the unbalanced run did not rebalance", summary(ref)["balance"]["rebalances"] == 0)
c.check("both runs converged", summary(reb)["converged"] and summary(ref)["converged"])

# 2. the same answer to round-off
pa, pb = particles(reb), particles(ref)
oa, ob = np.argsort(pa["id"].ravel()), np.argsort(pb["id"].ravel())
same = np.array_equal(pa["id"].ravel()[oa], pb["id"].ravel()[ob])
c.check("the same particles", same)
if same:
    xa, xb = pa["position"][oa], pb["position"][ob]
    sa, sb = pa["stress"][oa], pb["stress"][ob]
    c.le("max position difference / domain size", np.abs(xa - xb).max() / np.ptp(xb), 1e-6)
    c.le("max stress difference / max |stress|", np.abs(sa - sb).max() / np.abs(sb).max(), 1e-3)

# 3. restart from the checkpoint written after the rebalance: bit for bit
with open(f"{reb}/stages.csv") as f:
    ends = np.cumsum([int(r["steps"]) for r in csv.DictReader(f)])
rst = f"{out}/restarted"
run(exe, 2, VOID + RUN + ["-restart", f"{reb}/checkpoint_{ends[1]}.h5"], rst)
pr = particles(rst)
c.check("restart after the rebalance: particles bit for bit (same order)",
        all(np.array_equal(pa[k], pr[k]) for k in pa), f"({len(pa['id'])} particles)")
c.check("restart after the rebalance: chain_hdpe.csv bit for bit",
        filecmp.cmp(f"{reb}/chain_hdpe.csv", f"{rst}/chain_hdpe.csv", shallow=False))
c.check("restart after the rebalance: the rebuilt partition",
        summary(rst)["partition"] == summary(reb)["partition"])
c.done()
