"""The block on an incline in 3D (-dim 3): the colour interface's Coulomb cone as a 3D vector law,
against the closed form of a block sliding down a fall line that is not in the x-y plane.

usage: test_incline3d.py EXE OUTDIR

options/incline.opts (theta = 30 deg, g = 9.81, Bardenhagen contact, undamped FLIP, h = 0.02 m):
a rigid block on a plane slides with a = g (sin theta - mu cos theta) along the fall line when
tan theta > mu and sticks otherwise (docs/method.md, section 2.5). Isotropic Coulomb friction
opposes the slip whatever its direction, so the answer does not depend on the fall line's
azimuth.
1. The 2D run and the same scene extruded over two cells between rollers (-depth 0.04), 2,000
   steps: each 3D particle follows its 2D parent (x, y to 1e-10 of the base length, measured
   2.8e-15; the stresses xx yy zz xy to 1e-8 of the largest, measured 9.6e-11 after 1,500 and
   after 2,000 steps alike: the undamped block's stick-slip switches at a few nodes turn
   round-off in the normals into 1e-10 of the stress, while a wrong z coupling is of the order of
   the strain, 1e-4 and up), and the same acceleration to 1e-10.
2. -incline_azimuth 45: gravity (sin t cos a, -cos t, sin t sin a), the block 0.1 m wide along z
   on a base 0.2 m deep with free z faces, 2 ranks, 2,000 steps (0.24 s): mu = 0.3 slides with
   the closed-form acceleration within 3 % (measured 0.05 %) along the azimuth within 1 degree
   (measured 44.92 deg). A friction law applied per component (a square cone) would give
   g sin t cos a - mu g cos t = 0.92 m/s^2 per direction, |a| = 1.30 m/s^2 (45 % low), still at
   45 deg; one applied in x only would turn the slide towards z. mu = 0.7 > tan 30 sticks:
   |a| after the start-up transient below 1 % of g sin theta (measured 0.48 %).
"""
import math
import sys
import numpy as np
from pmpmtest import Checks, particles, run, summary

exe, out = sys.argv[1], sys.argv[2]
c = Checks("incline3d")
BASE = ["-options_file", "options/incline.opts", "-max_steps", "2000"]
L = 1.0  # base length (m)
FIELDS = ("position", "position0", "stress")

# 1. plane strain: the extruded incline against 2D
PLANE = ["-options_file", "options/incline.opts", "-max_steps", "2000"]
run(exe, 1, PLANE, out + "/2d")
run(exe, 1, PLANE + ["-dim", "3", "-depth", "0.04"], out + "/3d_plane")
ids2, f2 = particles(out + "/2d", FIELDS)
ids3, f3 = particles(out + "/3d_plane", FIELDS)
nz = 4
parent = np.searchsorted(ids2, ids3 // nz)
same = len(ids3) == nz * len(ids2) and np.all(ids2[np.minimum(parent, len(ids2) - 1)] == ids3 // nz)
c.check("plane strain: 4 particles along z per 2D particle", same, f"({len(ids3)}, {len(ids2)})")
if same:
    smax = np.abs(f2["stress"]).max()
    c.le("plane strain: x, y equal the 2D run's (/L)",
         np.abs(f3["position"][:, :2] - f2["position"][parent]).max() / L, 1e-10)
    c.le("plane strain: xx yy zz xy equal the 2D run's (/max |stress|)",
         np.abs(f3["stress"][:, :4] - f2["stress"][parent]).max() / smax, 1e-8)
r2, r3 = summary(out + "/2d")["results"], summary(out + "/3d_plane")["results"]
c.le("plane strain: the 3D acceleration equals the 2D one, relative",
     abs(r3["acceleration"] / r2["acceleration"] - 1), 1e-10)

# 2. the fall line turned 45 deg towards z
TURNED = BASE + ["-dim", "3", "-depth", "0.2", "-incline_azimuth", "45", "-incline_block_z",
                 "0.04", "-incline_block_width", "0.1", "-bc_zmin", "free", "-bc_zmax", "free"]
run(exe, 2, TURNED, out + "/turned")
r = summary(out + "/turned")["results"]
c.check("turned: the exact solution slides (tan 30 > 0.3)", r["sticks_exact"] is False)
c.le(f"turned, mu = 0.3: |a - g (sin - mu cos)| / a_exact (a = {r['acceleration']:.5f} m/s^2)",
     abs(r["acceleration"] / r["acceleration_exact"] - 1), 0.03)
direction = math.degrees(math.atan2(r["displacement_z"],
                                    math.sqrt(max(r["displacement"] ** 2
                                                  - r["displacement_z"] ** 2, 0.0))))
c.le(f"turned, mu = 0.3: the slide follows the azimuth ({direction:.3f} deg), |error| in deg",
     abs(direction - 45.0), 1.0)
c.ge("turned, mu = 0.3: the block slid along z (m)", r["displacement_z"], 0.03)
run(exe, 2, TURNED + ["-interface_mu_top", "0.7"], out + "/turned_stick")
r = summary(out + "/turned_stick")["results"]
c.check("turned, mu = 0.7: the exact solution sticks", r["sticks_exact"] is True)
c.le("turned, mu = 0.7: |a| / (g sin theta) after the transient",
     abs(r["acceleration"]) / r["acceleration_free_slip"], 0.01)
c.done()
