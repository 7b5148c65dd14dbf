"""A sheet's slip is the relative tangential motion of the sheet and the body on that face, at
the same nodes: bonded on both faces it is zero.

usage: test_chain_slip.py EXE NP OUTDIR
tests/cover_column.opts (an elastic cover over shrinking waste, two stages of 5 %) with
-chain_hdpe_interface bonded at h = 0.5 and 0.25 m: every point's slip on both faces is zero to
round-off (bound 1e-12 of the sheet's settlement; a bonded node's bodies share one velocity, so
the measured value is exactly 0). Before slip compared the sheet's velocity with each body's
mass-weighted one, which leans to the body's own row of nodes: 3.9 and 2.4 um at h = 0.5 and
0.25 m here (5.7, 3.0, 1.4 mm at h = 0.5, 0.25, 0.125 m on a degrading cover), the shear of the
body over half a cell. The pull-out (test_pullout.py) checks a slipping sheet's slip against its
closed form.
"""
import sys

import numpy as np

from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"chain_slip_np{np_}")
for h in ("0.5", "0.25"):
    d = f"{out}/h{h}"
    run(exe, np_, ["-options_file", "tests/cover_column.opts", "-chain_hdpe_interface", "bonded",
                   "-cell_size", h], d)
    s = summary(d)
    prof = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
    settle = np.abs(prof["uy"]).max()
    c.ge(f"h = {h}: the sheet settled (m)", settle, 1e-3)
    for face in ("top", "bottom"):
        c.le(f"h = {h}: max |slip ({face})| / settlement",
             np.abs(prof[f"slip_{face}"]).max() / settle, 1e-12)
        c.le(f"h = {h}: summary max_slip_{face} / settlement",
             s["chains"]["hdpe"][f"max_slip_{face}"] / settle, 1e-12)
c.done()
