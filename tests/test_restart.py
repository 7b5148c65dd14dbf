"""Checkpoint and restart (-checkpoint_every, -checkpoint_at_stage_end, -restart).

usage: test_restart.py EXE OUTDIR

1. The staged cover column (tests/cover_column.opts: geostatic stage, then two shrinkage stages)
   on 2 ranks, uninterrupted, and again writing checkpoints every 1200 steps and at every stage's
   end (the checkpoints must not change the run: bit for bit). Restarted on 2 ranks from step
   1200 (inside stage 1, within its shrinkage ramp), from the end of stage 0 and from the end of
   the last stage (nothing left to run: the output alone), it ends bit for bit as the
   uninterrupted run: every particle's position, stress, velocity and F (in the same
   order), chain_hdpe.csv, and the stage record (stages.csv without its wall times). Restarted on
   1 rank from the 2-rank checkpoint, positions and stresses agree to 1e-10 relative (round-off:
   the ghost sums add in another order), the chain's points to 1e-10 of its extent, and the stage
   record's steps are equal (its strains and tensions to what that position bound allows).
   Restarted from the end of stage 0 with a tighter -tol and a -relax_history file (the
   relaxation's controls are run control), the later stages meet the new tolerance.
2. The void cover (tests/cover_void.opts: particles removed at stage 1): restarted on 2 ranks
   from inside the void stage (a checkpoint with fewer particles than the scene generates), bit
   for bit again.
3. A truncated checkpoint, a file that is not HDF5, a missing file, a checkpoint missing a
   particle field or with one too short, and a checkpoint of another run each stop the restart with exit code != 0, one error line naming -restart and the file,
   and no output.
"""
import csv
import filecmp
import os
import shutil
import sys

import h5py
import numpy as np
from pmpmtest import Checks, run

exe, out = sys.argv[1], sys.argv[2]
c = Checks("restart")
COLUMN = ["-options_file", "tests/cover_column.opts"]
VOID = ["-options_file", "tests/cover_void.opts"]
FIELDS = ("position", "stress", "velocity", "F")


def raw(d):
    """particles.h5 in file order (rank blocks in rank order) and the ids."""
    with h5py.File(os.path.join(d, "particles.h5"), "r") as f:
        return {k: f["particles/" + k][:] for k in FIELDS + ("id",)}


def stage_rows(d):
    with open(os.path.join(d, "stages.csv")) as f:
        return [{k: v for k, v in r.items() if k != "wall_seconds"} for r in csv.DictReader(f)]


def bitwise(what, a, b):
    pa, pb = raw(a), raw(b)
    same = all(np.array_equal(pa[k], pb[k]) for k in FIELDS + ("id",))
    c.check(f"{what}: particles bit for bit (same order)", same,
            f"({len(pa['id'])} particles)")
    for f in sorted(x for x in os.listdir(a) if x.startswith("chain_") and x.endswith(".csv")):
        c.check(f"{what}: {f} bit for bit",
                filecmp.cmp(os.path.join(a, f), os.path.join(b, f), shallow=False))
    if os.path.exists(os.path.join(a, "stages.csv")):
        c.check(f"{what}: stages.csv rows equal", stage_rows(a) == stage_rows(b))


def sorted_fields(d):
    p = raw(d)
    o = np.argsort(p["id"].ravel())
    return p["id"].ravel()[o], {k: p[k][o] for k in FIELDS}


# 1. the staged cover column on 2 ranks
base, ck = f"{out}/column", f"{out}/column_checkpointed"
run(exe, 2, COLUMN, base)
run(exe, 2, COLUMN + ["-checkpoint_every", "1200", "-checkpoint_at_stage_end"], ck)
rows = stage_rows(base)
ends = np.cumsum([int(r["steps"]) for r in rows])  # the step each stage ended at
names = sorted(x for x in os.listdir(ck) if x.startswith("checkpoint_"))
want = sorted({f"checkpoint_{s}.h5" for s in list(ends) + list(range(1200, ends[-1] + 1, 1200))})
c.check("checkpoints every 1200 steps and at every stage end, no .tmp left", names == want,
        f"({names})")
c.check("stage 1 spans step 1200 (a checkpoint inside a stage)", ends[0] < 1200 < ends[1],
        f"(stage ends {list(ends)})")
bitwise("writing checkpoints", base, ck)
for name, what in ((f"checkpoint_{ends[0]}.h5", "restart at stage 0's end"),
                   ("checkpoint_1200.h5", "restart inside stage 1"),
                   (f"checkpoint_{ends[-1]}.h5", "restart at the last stage's end")):
    d = f"{out}/restart_{name[:-3]}"
    run(exe, 2, COLUMN + ["-restart", f"{ck}/{name}"], d)
    bitwise(f"{what} (2 ranks)", base, d)

# ... on 1 rank from the 2-rank checkpoint
d = f"{out}/restart_np1"
run(exe, 1, COLUMN + ["-restart", f"{ck}/checkpoint_1200.h5"], d)
ids1, f1 = sorted_fields(base)
ids2, f2 = sorted_fields(d)
c.check("restart on 1 rank: same particles", np.array_equal(ids1, ids2))
if np.array_equal(ids1, ids2):
    dx = np.abs(f1["position"] - f2["position"]).max() / np.abs(f1["position"]).max()
    ds = np.abs(f1["stress"] - f2["stress"]).max() / np.abs(f1["stress"]).max()
    c.le("restart on 1 rank: max position difference / domain size", dx, 1e-10)
    c.le("restart on 1 rank: max stress difference / max |stress|", ds, 1e-10)
a = np.genfromtxt(f"{base}/chain_hdpe.csv", delimiter=",", names=True)
b = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
scale = max(np.abs(a["x"]).max(), np.abs(a["y"]).max())
dxc = max(np.abs(a["x"] - b["x"]).max(), np.abs(a["y"] - b["y"]).max()) / scale
c.le("restart on 1 rank: chain points' max position difference / extent", dxc, 1e-10)
ra, rb = stage_rows(base), stage_rows(d)
c.check("restart on 1 rank: the same stages, steps and convergence",
        [(r["stage"], r["steps"], r["converged"]) for r in ra] ==
        [(r["stage"], r["steps"], r["converged"]) for r in rb])
# settlements are positions: 1e-10 of the domain; strains are differences of positions over a
# segment (1e-10 x extent / shortest segment), tensions J times that (J < 1e6 N/m here)
tol_eps = 1e-10 * scale / np.diff(a["s0"]).min()
for key, tol in (("surface_settlement", 1e-10 * scale), ("membrane_settlement", 1e-10 * scale),
                 ("peak_strain", tol_eps), ("peak_tension", 1e6 * tol_eps)):
    diff = max(abs(float(p[key]) - float(q[key])) for p, q in zip(ra, rb))
    c.le(f"restart on 1 rank: stages.csv {key} max difference", diff, tol)

# ... with the relaxation's own controls changed (run control): a tighter -tol and a history
# file; the later stages then meet the new tolerance, and the history has their rows
d = f"{out}/restart_tol"
hist = f"{out}/restart_tol_history.csv"
run(exe, 2, COLUMN + ["-restart", f"{ck}/checkpoint_{ends[0]}.h5", "-tol", "5e-6",
                      "-relax_history", hist], d)
rt = stage_rows(d)
c.check("restart with -tol 5e-6: the later stages converged to it",
        all(r["converged"] == "1" and float(r["ratio"]) <= 5e-6 for r in rt[1:]),
        f"({[(r['stage'], r['ratio']) for r in rt]})")
with open(hist) as f:
    hs = {int(r["stage"]) for r in csv.DictReader(f)}
c.check("restart with -relax_history: rows for the later stages only", hs == set(range(1, len(rt))),
        f"(stages {sorted(hs)})")

# 2. the void cover: a checkpoint inside the stage that removed particles
vck = f"{out}/void"
run(exe, 2, VOID + ["-checkpoint_every", "1000"], vck)
d = f"{out}/void_restart"
run(exe, 2, VOID + ["-restart", f"{vck}/checkpoint_1000.h5"], d)
bitwise("void cover, restart inside the void stage (2 ranks)", vck, d)

# 3. bad checkpoints
bad = f"{out}/bad"
os.makedirs(bad, exist_ok=True)
src = f"{ck}/checkpoint_1200.h5"
with open(src, "rb") as f:
    blob = f.read()
with open(f"{bad}/truncated.h5", "wb") as f:
    f.write(blob[: len(blob) // 2])
with open(f"{bad}/text.h5", "w") as f:
    f.write("not a checkpoint\n")
shutil.copy(src, f"{bad}/missing_field.h5")
with h5py.File(f"{bad}/missing_field.h5", "a") as f:
    del f["particles/stress"]
shutil.copy(src, f"{bad}/short_field.h5")
with h5py.File(f"{bad}/short_field.h5", "a") as f:
    s = f["particles/stress"][:]
    del f["particles/stress"]
    f["particles/stress"] = s[:-4]
cases = [("truncated checkpoint", COLUMN, f"{bad}/truncated.h5"),
         ("non-HDF5 file", COLUMN, f"{bad}/text.h5"),
         ("missing file", COLUMN, f"{bad}/no_such_checkpoint.h5"),
         ("checkpoint without a particle field", COLUMN, f"{bad}/missing_field.h5"),
         ("checkpoint with a short particle field", COLUMN, f"{bad}/short_field.h5"),
         ("checkpoint of another run", VOID, src)]
for what, opts, path in cases:
    d = f"{out}/bad_{what.replace(' ', '_')}"
    code, text = run(exe, 2, opts + ["-restart", path], d, expect_ok=False)
    lines = [l for l in text.splitlines() if l.startswith("pmpm: error")]
    c.check(f"{what}: non-zero exit", code != 0, f"(exit {code})")
    c.check(f"{what}: one error line naming -restart and the file",
            len(lines) == 1 and "-restart" in lines[0] and path in lines[0],
            f"[{' | '.join(lines)[:160]}]")
    c.check(f"{what}: no HDF5 error stack", "HDF5-DIAG" not in text)
    c.check(f"{what}: no output written", not os.path.exists(d))
c.done()
