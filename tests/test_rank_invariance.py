"""The same scene on several rank counts and process grids agrees with the first run to 1e-10
relative in every particle position and stress, and in every membrane-chain point's position
(chain_<name>.csv); chain strains and tensions to what that position bound allows (1e-10 of the
extent over the shortest segment; J times that).

usage: test_rank_invariance.py EXE OUTDIR OPTIONS_FILE [--ranks 1,2,...] [--grids MxN,...]
                               [--chain-crosses] [--stress-tol T] [extra options]
--ranks      rank counts with PETSc's process grid (default 1,2); the first is the reference.
--grids      further runs on M x N ranks with -da_processors_x M -da_processors_y N.
--chain-crosses  every chain must cross a rank boundary in each direction the process grid cuts
             (x when M > 1, y when N > 1), checked from the partition in summary.json: a scene
             whose sheet is meant to test the chain's ghost exchange across ranks really does.
--stress-tol replaces the stress bound for a scene whose stiffness turns the position bound into
             a looser stress one (the CMake entry says why).
--pos-tol    replaces the position bound (1e-10) for a scene whose discrete events (kinetic-damping
             resets, stick / slip, yield) amplify the round-off (the CMake entry says why), or
             tightens it.
--ratio-below R  the reference run's final unbalanced-force ratio must be at most R: the fixed
             step count reaches the scene's own convergence tolerance, so the comparison covers
             the whole relaxation, not its start.
Every run takes the same fixed number of steps (-tol tiny, so none stops early at a different
step): what remains is the summation order of ghost contributions, i.e. round-off. Positions are
compared relative to the domain size, stresses relative to the largest stress magnitude.
"""
import glob
import json
import os
import sys
import numpy as np
from pmpmtest import Checks, particles, run, summary

exe, out, opts = sys.argv[1], sys.argv[2], sys.argv[3]
extra = sys.argv[4:]
stress_tol = pos_tol = 1e-10
ranks, grids, chain_crosses, ratio_below = [1, 2], [], False, None
while extra[:1] and extra[0] in ("--stress-tol", "--pos-tol", "--ranks", "--grids", "--chain-crosses",
                                 "--ratio-below"):
    flag = extra.pop(0)
    if flag == "--chain-crosses":
        chain_crosses = True
        continue
    value = extra.pop(0)
    if flag == "--stress-tol":
        stress_tol = float(value)
    elif flag == "--pos-tol":
        pos_tol = float(value)
    elif flag == "--ratio-below":
        ratio_below = float(value)
    elif flag == "--ranks":
        ranks = [int(r) for r in value.split(",")]
    else:
        grids = [tuple(int(k) for k in g.split("x")) for g in value.split(",")]
extra = extra + ["-tol", "1e-300"]
name = opts.split("/")[-1].replace(".opts", "")
c = Checks(f"rank_invariance_{name}")

# (label, ranks, extra options) of every run; the first is the reference
runs = [(f"np{r}", r, []) for r in ranks]
runs += [(f"{m}x{n}", m * n, ["-da_processors_x", str(m), "-da_processors_y", str(n)])
         for m, n in grids]
res = {}
for label, np_, more in runs:
    run(exe, np_, ["-options_file", opts] + extra + more, f"{out}/{label}", capped=True)
    res[label] = particles(f"{out}/{label}", ("position", "stress"))
ref = runs[0][0]
ids1, f1 = res[ref]
if ratio_below is not None:
    c.le(f"{ref}: unbalanced-force ratio at the last step", summary(f"{out}/{ref}")["unbalanced_force_ratio"],
         ratio_below)
with open(f"{out}/{ref}/summary.json") as fs:
    axial = {k: v["axial_stiffness"] for k, v in json.load(fs).get("chains", {}).items()}


def chain_crossings(label, chain):
    """Rank boundaries (x, y) the chain's polyline crosses, and those the process grid has."""
    s = summary(f"{out}/{label}")
    part, h = s["partition"], s["h"]
    a = np.genfromtxt(chain, delimiter=",", names=True)
    got = []
    for d, key in ((0, "x"), (1, "y")):
        bounds = [part["origin"][d] + b * h for b in part[f"cell_bounds_{key}"][1:-1]]
        got.append((sum(1 for b in bounds if a[key].min() < b < a[key].max()), len(bounds)))
    return got, part["processes"]


for label, np_, _ in runs[1:]:
    ids2, f2 = res[label]
    c.check(f"{label}: same particle ids as {ref}", np.array_equal(ids1, ids2),
            f"({len(ids1)} particles)")
    if np.array_equal(ids1, ids2) and len(ids1):
        scale_x = np.abs(f1["position"]).max()
        dx = np.abs(f1["position"] - f2["position"]).max() / scale_x
        scale_s = np.abs(f1["stress"]).max()
        ds = np.abs(f1["stress"] - f2["stress"]).max() / scale_s
        c.le(f"{label}: max position difference / domain size", dx, pos_tol)
        c.le(f"{label}: max stress difference / max |stress|", ds, stress_tol)
    for f in sorted(glob.glob(f"{out}/{ref}/chain_*.csv")):
        chain = os.path.basename(f)
        a = np.genfromtxt(f, delimiter=",", names=True)
        b = np.genfromtxt(f"{out}/{label}/{chain}", delimiter=",", names=True)
        c.check(f"{label} {chain}: same points as {ref}", a.shape == b.shape,
                f"({a.shape[0]} points)")
        if a.shape == b.shape:
            scale = max(np.abs(a["x"]).max(), np.abs(a["y"]).max())
            dx = max(np.abs(a["x"] - b["x"]).max(), np.abs(a["y"] - b["y"]).max()) / scale
            c.le(f"{label} {chain}: max position difference / extent", dx, pos_tol)
            # a strain is a difference of positions over a segment: the position bound allows
            # pos_tol x extent / (shortest segment) of it; tension is J times that
            J = axial[chain[6:-4]]
            l0 = np.diff(a["s0"]).min()
            tol_eps = max(pos_tol * np.abs(a["strain"]).max(), pos_tol * scale / l0)
            c.le(f"{label} {chain}: max strain difference",
                 np.abs(a["strain"] - b["strain"]).max(), tol_eps)
            c.le(f"{label} {chain}: max tension difference (N/m)",
                 np.abs(a["tension"] - b["tension"]).max(),
                 max(pos_tol * np.abs(a["tension"]).max(), J * tol_eps))
        if chain_crosses:
            ((nx, bx), (ny, by)), procs = chain_crossings(label, f"{out}/{label}/{chain}")
            ok = (bx == 0 or nx > 0) and (by == 0 or ny > 0) and nx + ny > 0
            c.check(f"{label} {chain}: crosses rank boundaries in every cut direction", ok,
                    f"(process grid {procs[0]}x{procs[1]}: {nx} of {bx} x boundaries, "
                    f"{ny} of {by} y boundaries)")
c.done()
