"""What a sheet reports on each face, slip and pressure, against what a level cover must give.

usage: test_chain_slip.py EXE NP OUTDIR
tests/cover_column.opts: an elastic cover (0.5 m of soil, 18 kN/m^3) over 4 m of shrinking waste
between rollers, two stages of 5 %, at h = 0.5 and 0.25 m. The column is uniaxial, so the soil
presses on the sheet with its overburden, 9 kPa, everywhere, and the waste carries that plus the
sheet's weight (9.4 kN/m^3 x 1.5 mm = 14.1 Pa).

- Bonded on both faces: every point's slip is zero to round-off (bound 1e-12 of the sheet's
  settlement; a bonded node's bodies share one velocity, so the measured value is exactly 0).
  Before, slip compared the sheet's velocity with each body's mass-weighted one, which leans to
  the body's own row of nodes: 3.9 and 2.4 um at h = 0.5 and 0.25 m here, the shear of the body
  over half a cell.
- Bonded and with friction (delta 20 deg): the pressure on the top face is the overburden, and the
  bottom face's exceeds it by the sheet's weight, at the points more than 3 cells from the walls.
  The pressure is a point's shares of its nodes' normal impulses, so the pressures add up to the
  sheet's share of the impulses; the ratio of the stencil's sums used before overstated it by 13-17 % once the shrinking
  waste had carried the sheet between two rows of nodes (10.2-10.5 kPa here), and a bonded sheet's
  by a factor of 3.9 (only the compressive impulses were kept). Tolerances: 0.5 % on the
  overburden (measured within 0.02 %), 2 % on the 14.1 Pa difference (measured within 0.05 %);
  within 3 cells of a roller wall, where the sheet stops half a point spacing short of the wall
  and a point's block is clipped at it, the pressure is 0.94 to 1.025 times the overburden (every
  point: 10 %). A node at a sheet's end gives the sheet only its share LEN / AREA of its impulse.
The pull-out (test_pullout.py) checks a slipping sheet's slip against its closed form.
"""
import sys

import numpy as np

from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"chain_slip_np{np_}")
overburden = 18e3 * 0.5
sheet_weight = 9.4e3 * 0.0015
width = 4.0
for interface in ("bonded", "friction"):
    for h in ("0.5", "0.25"):
        d = f"{out}/{interface}_h{h}"
        extra = ["-chain_hdpe_interface", "bonded"] if interface == "bonded" else []
        run(exe, np_, ["-options_file", "tests/cover_column.opts", "-cell_size", h] + extra, d)
        s = summary(d)
        prof = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
        tag = f"{interface}, h = {h}"
        if interface == "bonded":
            settle = np.abs(prof["uy"]).max()
            c.ge(f"{tag}: the sheet settled (m)", settle, 1e-3)
            for face in ("top", "bottom"):
                c.le(f"{tag}: max |slip ({face})| / settlement",
                     np.abs(prof[f"slip_{face}"]).max() / settle, 1e-12)
                c.le(f"{tag}: summary max_slip_{face} / settlement",
                     s["chains"]["hdpe"][f"max_slip_{face}"] / settle, 1e-12)
        inner = np.abs(prof["x0"] - 0.5 * width) <= 0.5 * width - 3 * float(h)
        c.ge(f"{tag}: points checked away from the walls", inner.sum(), 4)
        top = prof["pressure_top"][inner]
        c.le(f"{tag}: max |pressure_top / overburden - 1|",
             np.abs(top / overburden - 1).max(), 5e-3)
        c.le(f"{tag}: max |pressure_top / overburden - 1|, every point",
             np.abs(prof["pressure_top"] / overburden - 1).max(), 0.1)
        diff = prof["pressure_bottom"][inner] - top
        c.le(f"{tag}: max |(pressure_bottom - pressure_top) / sheet weight - 1|",
             np.abs(diff / sheet_weight - 1).max(), 2e-2)
c.done()
