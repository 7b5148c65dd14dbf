"""The seed landfill (paper section 4) extruded along z (-dim 3 -depth D): the colour interface
(the geomembrane's Coulomb friction-slip, seed paper section 3.2) in its 3D form, against the 2D
run particle by particle.

usage: test_landfill3d.py EXE OUTDIR

options/landfill.opts at h = 1 mm (4,680 particles in 2D; 1 mm membrane of one particle row per
half cell), extruded between rollers: a plane-strain problem, so each 3D particle must follow its
2D parent (id // (2 x cells along z)) while the interface works on the 3D body grid (body 1's
mass, momentum, force and normals on a second 3D DMDA, the friction cone a 3D vector update).
1. 300 fixed steps (-tol tiny), -interface_type paper with the paper's cell normals: the 2D run on
   1 rank against 3D over 2 cells of depth on 1 rank and over 4 cells on 4 ranks (2x1x2): x, y
   and the stresses xx yy zz xy equal the 2D run's to 1e-10 of the width and of the largest
   stress; z and the shears yz, xz stay zero.
2. The same for -interface_type contact with the particles' colour gradient as normals
   (-interface_normals particles) on 2 ranks: on the z faces' rollers (symmetry planes) the
   gradient's z component is the mirror's, zero (interface.cpp); before that rule the one-sided
   gradient tilted the normals out of the plane and the 3D stresses were 72 % off the 2D ones.
   Checkpoint at step 150 and restart: bit for bit on 1 rank, 1e-10 on 2 ranks.
3. The bonded landfill (no interface) on 1 rank, the same bounds.
4. Converged (the options' -tol 1e-5), paper interface, 2D on 1 rank and 3D on 2 ranks: the
   settlement at the centre and the peak membrane strain within 1e-6 relative (the runs stop a
   few steps apart: the ratio divides by a mean nodal load the z faces' half-loaded nodes lower;
   measured 2e-8 and 1.3e-7), the normal impulse in 3D the 2D one (per metre) times the depth
   within 1 % (summed over 1528 against 1525 steps: 0.25 %), the same tension ratio within 1 %.
The 1e-10 bounds: round-off after 300 steps of sums in another order (measured 3e-12 of the
stress), while a wrong normal or a friction cone with a z leak is of the order of the slip.
"""
import sys
import numpy as np
from pmpmtest import Checks, compare_extruded, particles, run, summary

exe, out = sys.argv[1], sys.argv[2]
c = Checks("landfill3d")
W = 0.03  # the landfill's width (m)
BASE = ["-options_file", "options/landfill.opts", "-cell_size", "0.001"]
FIXED = ["-tol", "1e-30", "-max_steps", "300", "-ramp_steps", "150"]
PAPER = ["-interface_type", "paper"]
CONTACT = ["-interface_type", "contact", "-interface_normals", "particles"]
FIELDS = ("position", "position0", "stress")


def d3(depth):
    return ["-dim", "3", "-depth", str(depth)]


def compare(name, d2, d3_, nz):
    """Every 3D particle (nz along z per 2D particle) against its 2D parent; the cover moved."""
    r = compare_extruded(c, name, particles(d2, FIELDS), particles(d3_, FIELDS), nz, W,
                         "W")
    if r is not None:
        x2, x02 = r
        c.ge(f"{name}: the cover settled (max |u_y| / W)",
             np.abs(x2[:, 1] - x02[:, 1]).max() / W, 1e-2)


# 1. the paper's interface, fixed steps, 1 and 4 ranks
run(exe, 1, BASE + FIXED + PAPER, out + "/paper2d", capped=True)
run(exe, 1, BASE + FIXED + PAPER + d3(0.002), out + "/paper3d", capped=True)
compare("paper, 1 rank", out + "/paper2d", out + "/paper3d", 4)
grid = ["-da_processors_x", "2", "-da_processors_y", "1", "-da_processors_z", "2"]
run(exe, 4, BASE + FIXED + PAPER + d3(0.004) + grid, out + "/paper3d_np4", capped=True)
compare("paper, 4 ranks (2x1x2)", out + "/paper2d", out + "/paper3d_np4", 8)
c.check("4 ranks: the 2x1x2 process grid",
        summary(out + "/paper3d_np4")["partition"]["processes"] == [2, 1, 2])
s3 = summary(out + "/paper3d")
c.check("3D summary: the paper's interface and three cell counts",
        s3["interface"]["type"] == "paper" and len(s3["cells"]) == 3)

# 1b. checkpoint and restart with the interface in 3D: resumed from step 150 on 1 rank (bit for
# bit: the body grid is rebuilt, the interface's impulse sums come from the checkpoint) and on 2
# ranks (the particles sent to their cells' owners), against the uninterrupted run
run(exe, 1, BASE + FIXED + PAPER + d3(0.002) + ["-checkpoint_every", "150"], out + "/ck",
    capped=True)
_, full = particles(out + "/paper3d", FIELDS)
ia_full = summary(out + "/paper3d")["interface"]["normal_impulse_compression"]
for np_ in (1, 2):
    d = f"{out}/restart_np{np_}"
    run(exe, np_, BASE + FIXED + PAPER + d3(0.002) + ["-restart", f"{out}/ck/checkpoint_150.h5"],
        d, capped=True)
    _, f = particles(d, FIELDS)
    dx = np.abs(f["position"] - full["position"]).max() / W
    ds = np.abs(f["stress"] - full["stress"]).max() / np.abs(full["stress"]).max()
    di = abs(summary(d)["interface"]["normal_impulse_compression"] / ia_full - 1)
    if np_ == 1:
        c.check("restart on 1 rank from step 150: bit for bit (positions, stresses, impulse)",
                dx == 0 and ds == 0 and di == 0, f"({dx:g} {ds:g} {di:g})")
    else:
        c.le("restart on 2 ranks: positions (/W)", dx, 1e-10)
        c.le("restart on 2 ranks: stresses (/max |stress|)", ds, 1e-10)
        c.le("restart on 2 ranks: the normal impulse, relative", di, 1e-10)

# 2. Bardenhagen's contact with the particles' normals, 2 ranks
run(exe, 1, BASE + FIXED + CONTACT, out + "/contact2d", capped=True)
run(exe, 2, BASE + FIXED + CONTACT + d3(0.002), out + "/contact3d", capped=True)
compare("contact, particle normals, 2 ranks", out + "/contact2d", out + "/contact3d", 4)

# 3. bonded (no interface)
run(exe, 1, BASE + FIXED, out + "/bonded2d", capped=True)
run(exe, 1, BASE + FIXED + d3(0.002), out + "/bonded3d", capped=True)
compare("bonded, 1 rank", out + "/bonded2d", out + "/bonded3d", 4)

# 4. converged: the design numbers and the interface's impulses
run(exe, 1, BASE + PAPER, out + "/conv2d")
run(exe, 2, BASE + PAPER + d3(0.002), out + "/conv3d")
a, b = summary(out + "/conv2d"), summary(out + "/conv3d")
for key in ("settlement_centre", "peak_axial_strain"):
    c.le(f"converged: {key} 3D ({b['results'][key]:.9g}) against 2D ({a['results'][key]:.9g}), "
         "relative", abs(b["results"][key] / a["results"][key] - 1), 1e-6)
ia, ib = a["interface"], b["interface"]
c.le("converged: 3D normal impulse against 2D's times the depth, relative",
     abs(ib["normal_impulse_compression"] / (0.002 * ia["normal_impulse_compression"]) - 1), 0.01)
c.le("converged: the same tension ratio, relative",
     abs(ib["tension_ratio"] / ia["tension_ratio"] - 1), 0.01)
c.done()
