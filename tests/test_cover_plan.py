"""The cover's waste surface as a plan grid of heights (-dim 3, -cover_plan_x, -cover_plan_z,
-cover_plan_heights): a surface of any shape in plan, bilinear between the grid's nodes.

usage: test_cover_plan.py EXE OUTDIR

tests/cover_plan.opts: a 2 x 2 m box whose waste surface is a mound (4 m at the edges, 4.1 m at
the centre, slopes of 10 %), 0.5 m of soil on an HDPE sheet, uniform isotropic degradation in two
stages, rollers on every side and a fixed base.
1. Laid as asked (a capped one-step run): every sheet point lies on the bilinear surface computed
   here from the grid (1e-6 m), and the waste's particle volumes add up to the volume under it
   (exact for a bilinear surface sampled at symmetric columns: 1e-9 relative).
2. Uniform isotropic degradation settles every column of the waste by the closed form whatever
   the surface (u_y = -e y in the waste changes no stress; test_cover3d.py part 3c for a plane
   grade): the top row of waste settles by y (1 - exp(-(1 + nu) / (1 - nu) e_v / 6)) per stage,
   the mean over its columns within 0.5 %, every column within 1 %; every stage converges.
3. On 2 ranks (the box cut in y, where the waste is compressed to the mound) against 1, 600
   fixed steps of the load ramp: the same particles, positions to 1e-10 of the box's height
   (measured 7e-13) and stresses to 1e-7 of the largest (measured 5e-9: the sheet's contact and
   the kinetic-damping resets amplify round-off, as in test_cover3d.py part 5); a particle given
   to the wrong rank or lifted twice is of the order of the relief, 2e-2 of the height.
"""
import math
import sys

import h5py
import numpy as np
from pmpmtest import Checks, particles, run, stages, waste_column_tops

exe, out = sys.argv[1], sys.argv[2]
c = Checks("cover_plan")
base = ["-options_file", "tests/cover_plan.opts"]
gx, gz = np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 2.0])
gh = np.array([4, 4, 4, 4, 4.1, 4, 4, 4, 4], float).reshape(3, 3)  # [z][x]


def surface(x, z):
    """The bilinear surface through the grid, computed independently of pmpm's plan_height."""
    i = np.clip(np.searchsorted(gx, x, side="right") - 1, 0, len(gx) - 2)
    j = np.clip(np.searchsorted(gz, z, side="right") - 1, 0, len(gz) - 2)
    r = (x - gx[i]) / (gx[i + 1] - gx[i])
    t = (z - gz[j]) / (gz[j + 1] - gz[j])
    return ((1 - t) * ((1 - r) * gh[j, i] + r * gh[j, i + 1]) +
            t * ((1 - r) * gh[j + 1, i] + r * gh[j + 1, i + 1]))


# 1. the surface as laid
d = f"{out}/laid"
run(exe, 1, base + ["-max_steps", "1"], d, capped=True)
p = np.genfromtxt(f"{d}/sheet_hdpe.csv", delimiter=",", names=True)
c.le("the sheet's points on the plan grid's bilinear surface (largest |y - H(x, z)|, m)",
     np.abs(p["y0"] - surface(p["x0"], p["z0"])).max(), 1e-6)
with h5py.File(f"{d}/series/stage_000.h5") as f:
    vol = f["particles/volume0"][:].ravel()
    mat = f["particles/material"][:].ravel()
exact = sum(0.25 * (gh[j, i] + gh[j, i + 1] + gh[j + 1, i] + gh[j + 1, i + 1]) *
            (gx[i + 1] - gx[i]) * (gz[j + 1] - gz[j]) for i in range(2) for j in range(2))
c.le(f"the waste's volume under the mound ({vol[mat == 0].sum():.12g} m3 against "
     f"{exact:.12g}; relative)", abs(vol[mat == 0].sum() / exact - 1), 1e-9)

# 2. uniform isotropic degradation: the closed form under any surface
d1 = f"{out}/np1"
run(exe, 1, base, d1)
rows = stages(d1)
c.check("three stages, all converged", len(rows) == 3 and all(r["converged"] == "1" for r in rows))
nu, ev = 0.3, 0.05
factor = (1 + nu) / (1 - nu) / 3
y, x0, top = waste_column_tops(d1, 3)
c.check(f"the top row of waste follows the mound ({top.sum()} columns; highest "
        f"{y[0][top].max():.3f} m, lowest {y[0][top].min():.3f} m)",
        y[0][top].max() - y[0][top].min() > 0.07)
for k in (1, 2):
    closed = y[k - 1][top] * (1 - math.exp(-factor * ev))
    err = (y[k - 1][top] - y[k][top]) / closed - 1
    c.le(f"stage {k}: the top row of waste settles by the closed form (mean relative error)",
         abs(err.mean()), 0.005)
    c.le(f"stage {k}: every column of it (largest relative error)", np.abs(err).max(), 0.01)

# 3. two ranks, the box cut in y: 600 fixed steps of stage 0 (the load ramp, the sheet's faces
# in contact) on 1 and 2 ranks, every particle
fixed = base + ["-tol", "1e-12", "-max_steps", "600"]
run(exe, 1, fixed, f"{out}/fixed_np1", capped=True)
run(exe, 2, fixed + ["-da_processors_x", "1", "-da_processors_y", "2", "-da_processors_z", "1"],
    f"{out}/fixed_np2", capped=True)
(i1, a), (i2, b) = particles(f"{out}/fixed_np1"), particles(f"{out}/fixed_np2")
c.check("2 ranks against 1: the same particles", np.array_equal(i1, i2))
c.le("2 ranks against 1: positions (relative to the box's height)",
     np.abs(a["position"] - b["position"]).max() / 5.0, 1e-10)
c.le("2 ranks against 1: stresses (relative to the largest)",
     np.abs(a["stress"] - b["stress"]).max() / np.abs(a["stress"]).max(), 1e-7)
c.done()
