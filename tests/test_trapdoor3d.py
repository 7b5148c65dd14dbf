"""The trapdoor (arching over a yielding strip, docs/trapdoor.md) extruded along z (-dim 3): the
prescribed nodal velocities of the door and the base (the support table on every node plane of
the 3D grid) and the door's reaction, against the 2D run.

usage: test_trapdoor3d.py EXE OUTDIR

options/trapdoor.opts at h = 0.125 m (B = 1 m door, H = 2 m of Drucker-Prager sand, phi = 30 deg),
two lowering stages (0.001 B, 0.005 B), extruded between rollers: a plane-strain problem.
1. Fixed steps (-tol tiny, 400 steps a stage, the door lowered in each): the 2D run on 1 rank
   against 3D over 2 cells of depth on 1 and 2 ranks and over 4 cells on 4 ranks (2x1x2): each
   3D particle's x, y and stresses xx yy zz xy equal its 2D parent's to 1e-10 of the height and
   of the largest stress; z and yz, xz zero.
2. Converged (the options' -tol 1e-4), 2D on 1 rank and 3D on 2: the pressure on the door over
   gamma H at each stage within 1e-3 relative of 2D's (the 3D reaction divided by the depth; the
   runs stop some steps apart, at the relaxation's tolerance: measured 4e-6, 6e-6 and 6e-5), and
   the same arching: the door's pressure drops below 0.35 gamma H at 0.005 B.
3. -balance run (1x2x1 ranks, h = B/16, the door lowered 0.25 B then 0.3 B, converged): one
   rebalance at the first lowering stage's end (the y cut moves; max/mean 1.039 -> 1.023), and
   the answer of the run that kept its setup partition to what the relaxation's tolerance leaves
   (the two partitions sum ghost nodes in another order and the stages stop some steps apart, as
   in 2D's tests/test_rebalance.py): positions 1e-6 of H, stresses 1e-3 of the largest, the
   door's pressures 1e-3 relative (measured 3e-16, 1.3e-14 and 0: here both stopped at the same
   steps).
The 1e-10 bounds: round-off in sums taken in another order (measured below 1e-13), while a door
node missed on one z plane or a reaction counted twice is of the order of the load.
"""
import sys
import numpy as np
from pmpmtest import Checks, compare_extruded, particles, run, summary

exe, out = sys.argv[1], sys.argv[2]
c = Checks("trapdoor3d")
H = 2.0
BASE = ["-options_file", "options/trapdoor.opts", "-cell_size", "0.125",
        "-trapdoor_displacements", "0.001,0.005"]
FIXED = ["-tol", "1e-30", "-max_steps", "400"]
FIELDS = ("position", "position0", "stress")


def d3(depth):
    return ["-dim", "3", "-depth", str(depth)]


def compare(name, d2, d3_, nz):
    """Every 3D particle (nz along z per 2D particle) against its 2D parent; the soil moved."""
    r = compare_extruded(c, name, particles(d2, FIELDS), particles(d3_, FIELDS), nz, H,
                         "H")
    if r is not None:
        x2, x02 = r
        c.ge(f"{name}: the soil followed the door (max settlement, m)",
             -(x2[:, 1] - x02[:, 1]).min(), 1e-3)


run(exe, 1, BASE + FIXED, out + "/fixed2d", capped=True)
run(exe, 1, BASE + FIXED + d3(0.25), out + "/fixed3d_np1", capped=True)
compare("1 rank", out + "/fixed2d", out + "/fixed3d_np1", 4)
run(exe, 2, BASE + FIXED + d3(0.25), out + "/fixed3d_np2", capped=True)
compare("2 ranks", out + "/fixed2d", out + "/fixed3d_np2", 4)
grid = ["-da_processors_x", "2", "-da_processors_y", "1", "-da_processors_z", "2"]
run(exe, 4, BASE + FIXED + d3(0.5) + grid, out + "/fixed3d_np4", capped=True)
compare("4 ranks (2x1x2)", out + "/fixed2d", out + "/fixed3d_np4", 8)

run(exe, 1, BASE, out + "/conv2d")
run(exe, 2, BASE + d3(0.25), out + "/conv3d")
s2 = summary(out + "/conv2d")["results"]["stages"]
s3 = summary(out + "/conv3d")["results"]["stages"]
c.check("converged: every stage in 2D and 3D", len(s2) == len(s3) == 3
        and all(s["converged"] for s in s2 + s3))
for a, b in zip(s2, s3):
    c.le(f"door at {a['displacement_over_B']} B: 3D pressure ({b['ratio']:.6f} gamma H) against "
         f"2D ({a['ratio']:.6f}), relative", abs(b["ratio"] / a["ratio"] - 1), 1e-3)
c.le("arching: the door's pressure at 0.005 B (gamma H)", s3[-1]["ratio"], 0.35)

# 3. -balance run in 3D: the door lowered 0.25 B (4 cells at h = B/16) moves the soil above it
# across the y cut of a 1x2x1 process grid; at the stage's end the cuts follow the particles, the
# grid is rebuilt and the particles move. Against the run that kept its setup partition.
MOVE = ["-options_file", "options/trapdoor.opts", "-cell_size", "0.0625",
        "-trapdoor_displacements", "0.25,0.3", "-trapdoor_rate", "1e-3"] + d3(0.125) + \
    ["-da_processors_x", "1", "-da_processors_y", "2", "-da_processors_z", "1"]
run(exe, 2, MOVE + ["-balance", "run", "-balance_threshold", "1", "-balance_gain", "0"],
    out + "/rebalanced")
run(exe, 2, MOVE + ["-balance", "setup"], out + "/setup_only")
sa, sb = summary(out + "/rebalanced"), summary(out + "/setup_only")
b = sa["balance"]
c.check("-balance run: one rebalance, at the first lowering stage's end", b["rebalances"] == 1,
        f"({b['rebalances']})")
c.check("-balance run: the rebalance lowered max/mean particles per rank",
        b["last_imbalance_after"] < b["last_imbalance_before"],
        f"({b['last_imbalance_before']:.4f} -> {b['last_imbalance_after']:.4f})")
c.check("-balance setup: no rebalance", sb["balance"]["rebalances"] == 0)
ya, yb = sa["partition"]["cell_bounds_y"], sb["partition"]["cell_bounds_y"]
c.check("-balance run: the y cut moved", ya != yb, f"({ya} against {yb})")
ids_a, fa = particles(out + "/rebalanced", FIELDS)
ids_b, fb = particles(out + "/setup_only", FIELDS)
same = np.array_equal(ids_a, ids_b)
c.check("-balance run: the same particles", same)
if same:
    c.le("-balance run: positions against the setup partition's run (/H)",
         np.abs(fa["position"] - fb["position"]).max() / H, 1e-6)
    c.le("-balance run: stresses against the setup partition's run (/max |stress|)",
         np.abs(fa["stress"] - fb["stress"]).max() / np.abs(fb["stress"]).max(), 1e-3)
for a, bb in zip(sa["results"]["stages"], sb["results"]["stages"]):
    c.le(f"-balance run: the door's pressure at {a['displacement_over_B']} B, relative",
         abs(a["ratio"] / bb["ratio"] - 1), 1e-3)
c.done()
