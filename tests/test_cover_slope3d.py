"""A 3D cover on a side slope (-dim 3): the slope example extruded, its membrane a strip of 3D sheet
laid along the waste surface's toe, slope and crest (sheet_strip), against the plane-strain run.

usage: test_cover_slope3d.py EXE NP OUTDIR

options/cover_slope.opts (a 3H:1V side slope 30 m long and a 2 % deck, 0.6 m of Drucker-Prager
soil on a tension-only HDPE sheet with friction on both faces, the deck's waste degrading in three
stages) at its shipped h = 0.5 m, in 2D and under -dim 3 -depth 0.5 (one cell, rollers on the two
z faces: a plane-strain slice). The two discretise the membrane differently (a chain of segments
against a lattice of triangles whose strain is read per point, and a one-cell face against a
friction cone), so the 3D run is held to the 2D one within bounds set from what was measured:

- the sheet's lattice lies on the waste surface at every z (to a step's motion, 1e-6 m: it is
  the 2D chain's line, taken from wall to wall);
- each stage's surface and membrane settlement within 0.2 % (measured 0.06 %);
- each stage's peak membrane strain within 5 % (measured 0.1 to 3 %: 0.034 against 0.035 % at
  the geostatic stage, 0.707 against 0.699 % at stage 1, 1.980 against 1.982 % at stage 3), where
  it peaks within a cell of the 2D peak;
- each stage's largest slip within 3 % (measured 0.2 to 1.3 %); the geostatic stage's is the
  veneer's creep, 7.3 mm against 7.4 mm (before the slip rule skipped a body's tail share of a
  node, a round-off mass at the toe put 0.11 m there in one step);
- the final slip on each face within 3 % (bottom, measured 0.8 %) and 10 % (top, 5 %);
- the sheet's two rows (z = 0 and z = depth) move alike, to 1e-4 of the settlement (measured
  4e-5: the lattice's alternating diagonals are not symmetric about the slice's mid-plane), and
  nothing moves along z;
- the same verdict, and the same closed forms beside it (infinite slope and Koerner-Soong).
"""
import sys

import numpy as np
from pmpmtest import Checks, run, stages, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"cover_slope3d_np{np_}")
base = ["-options_file", "options/cover_slope.opts", "-estimate_error", "0"]
d2, d3 = f"{out}/plane", f"{out}/extruded"
run(exe, np_, base, d2)
run(exe, np_, base + ["-dim", "3", "-depth", "0.5"], d3)

# the lattice on the waste surface: level ground to the toe at x = 6 m, the slope at 18.435 deg
# for 30 m, the deck at 2 % to x = 60 m (options/cover_slope.opts), every row from wall to wall
# (one step: the geostatic stage, capped, lays the sheet where that step left it)
run(exe, np_, base + ["-dim", "3", "-depth", "0.5", "-max_steps", "1"], f"{out}/laid", capped=True)
sh = np.genfromtxt(f"{out}/laid/sheet_hdpe.csv", delimiter=",", names=True)
zs = np.unique(sh["z0"])
beta = np.radians(18.435)
xc, yc = 6 + 30 * np.cos(beta), 2 + 30 * np.sin(beta)
surface = np.interp(sh["x0"], [0, 6, xc, 60], [2, 2, yc, yc + 0.02 * (60 - xc)])
c.le(f"the sheet's points on the waste surface (toe, slope, crest, deck) at each z (rows at z = "
     f"{zs}; m; the capped stage lays the sheet where its one step left it)",
     np.abs(sh["y0"] - surface).max(), 1e-6)
c.check("its rows run from wall to wall", len(zs) == 2 and sh["x0"].min() == 0 and
        abs(sh["x0"].max() - 60) < 1e-9)
c.check("the sheet is sloped (rises from the toe to the crest)",
        sh["y0"].max() - sh["y0"].min() > 9.0, f"({sh['y0'].min():.3g} to {sh['y0'].max():.3g} m)")

r2, r3 = stages(d2), stages(d3)
c.check("3D: every stage converged", len(r3) == len(r2) == 4 and
        all(r["converged"] == "1" for r in r3), f"({[r['steps'] for r in r3]} steps)")
h = summary(d2)["h"]
for a, b in zip(r2, r3):
    k = a["stage"]
    for key, tol in (("surface_settlement", 2e-3), ("membrane_settlement", 2e-3),
                     ("peak_strain", 0.05), ("max_slip", 0.03)):
        x2, x3 = float(a[key]), float(b[key])
        if key.endswith("settlement") and x2 == 0:
            c.check(f"stage {k}: {key} zero in both", x3 == 0)
            continue
        c.le(f"stage {k}: {key} 3D against 2D ({x3:.5g}, {x2:.5g})", abs(x3 / x2 - 1), tol)
    c.le(f"stage {k}: the peak strain's x within a cell of the 2D peak's ({b['peak_strain_x']}, "
         f"{a['peak_strain_x']} m)", abs(float(b["peak_strain_x"]) - float(a["peak_strain_x"])),
         h * (1 + 1e-9))

m2, m3 = summary(d2)["results"]["membrane"], summary(d3)["results"]["membrane"]
c.le(f"final slip on the bottom face 3D against 2D ({m3['max_slip_bottom']:.4g}, "
     f"{m2['max_slip_bottom']:.4g} m)", abs(m3["max_slip_bottom"] / m2["max_slip_bottom"] - 1), 0.03)
c.le(f"final slip on the top face 3D against 2D ({m3['max_slip_top']:.4g}, "
     f"{m2['max_slip_top']:.4g} m)", abs(m3["max_slip_top"] / m2["max_slip_top"] - 1), 0.10)
sh = np.genfromtxt(f"{d3}/sheet_hdpe.csv", delimiter=",", names=True)
lo, hi = sh["z0"] == zs[0], sh["z0"] == zs[-1]
spread = max(np.abs(sh[k][lo] - sh[k][hi]).max() for k in ("ux", "uy"))
c.le("the sheet's two rows move alike (/ the largest settlement)",
     spread / np.abs(sh["uy"]).max(), 1e-4)
c.le("the sheet stays in its plane slice (|uz| / the largest settlement)",
     np.abs(sh["uz"]).max() / np.abs(sh["uy"]).max(), 1e-9)
s2, s3 = summary(d2), summary(d3)
c.check("the same verdict", s2["verdict"] == s3["verdict"], f"({s3['verdict']})")
sl2, sl3 = s2["results"].get("slope"), s3["results"].get("slope")
c.check("the slope's closed forms beside the 3D answer (infinite slope, Koerner-Soong)",
        sl3 is not None and sl2 is not None and
        abs(sl3["fs_infinite"] - sl2["fs_infinite"]) < 1e-12 and
        abs(sl3["fs_koerner_soong"] - sl2["fs_koerner_soong"]) < 1e-12,
        f"({sl3 and sl3.get('fs_koerner_soong')})")
c.done()
