"""The same scene on 1 and 2 ranks agrees to 1e-10 relative in every particle position and stress,
and in every membrane-chain point's position (chain_<name>.csv); chain strains and tensions to
what that position bound allows (1e-10 of the extent over the shortest segment; J times that).

usage: test_rank_invariance.py EXE OUTDIR OPTIONS_FILE [--stress-tol T] [extra options]
--stress-tol replaces the stress bound for a scene whose stiffness turns the position bound into
a looser stress one (the CMake entry says why).
Both runs take the same fixed number of steps (-tol tiny, so neither stops early at a different
step): what remains is the summation order of ghost contributions, i.e. round-off. Positions are
compared relative to the domain size, stresses relative to the largest stress magnitude.
"""
import glob
import os
import sys
import numpy as np
from pmpmtest import Checks, particles, run

exe, out, opts = sys.argv[1], sys.argv[2], sys.argv[3]
extra = sys.argv[4:]
stress_tol = 1e-10
if extra[:1] == ["--stress-tol"]:
    stress_tol, extra = float(extra[1]), extra[2:]
extra = extra + ["-tol", "1e-300"]
name = opts.split("/")[-1].replace(".opts", "")
c = Checks(f"rank_invariance_{name}")
res = {}
for np_ in (1, 2):
    run(exe, np_, ["-options_file", opts] + extra, f"{out}/np{np_}")
    res[np_] = particles(f"{out}/np{np_}", ("position", "stress"))
ids1, f1 = res[1]
ids2, f2 = res[2]
c.check("same particle ids on 1 and 2 ranks", np.array_equal(ids1, ids2), f"({len(ids1)} particles)")
if np.array_equal(ids1, ids2) and len(ids1):
    scale_x = np.abs(f1["position"]).max()
    dx = np.abs(f1["position"] - f2["position"]).max() / scale_x
    scale_s = np.abs(f1["stress"]).max()
    ds = np.abs(f1["stress"] - f2["stress"]).max() / scale_s
    c.le("max position difference / domain size", dx, 1e-10)
    c.le("max stress difference / max |stress|", ds, stress_tol)
for f in sorted(glob.glob(f"{out}/np1/chain_*.csv")):
    chain = os.path.basename(f)
    a = np.genfromtxt(f, delimiter=",", names=True)
    b = np.genfromtxt(f"{out}/np2/{chain}", delimiter=",", names=True)
    c.check(f"{chain}: same points on 1 and 2 ranks", a.shape == b.shape, f"({a.shape[0]} points)")
    if a.shape == b.shape:
        scale = max(np.abs(a["x"]).max(), np.abs(a["y"]).max())
        dx = max(np.abs(a["x"] - b["x"]).max(), np.abs(a["y"] - b["y"]).max()) / scale
        c.le(f"{chain}: max position difference / extent", dx, 1e-10)
        # a strain is a difference of positions over a segment: the position bound allows
        # 1e-10 x extent / (shortest segment) of it; tension is J times that
        import json
        with open(f"{out}/np1/summary.json") as fs:
            J = json.load(fs)["chains"][chain[6:-4]]["axial_stiffness"]
        l0 = np.diff(a["s0"]).min()
        scale = max(np.abs(a["x"]).max(), np.abs(a["y"]).max())
        tol_eps = max(1e-10 * np.abs(a["strain"]).max(), 1e-10 * scale / l0)
        c.le(f"{chain}: max strain difference", np.abs(a["strain"] - b["strain"]).max(), tol_eps)
        c.le(f"{chain}: max tension difference (N/m)", np.abs(a["tension"] - b["tension"]).max(),
             max(1e-10 * np.abs(a["tension"]).max(), J * tol_eps))
c.done()
