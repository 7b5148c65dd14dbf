"""A sheet's slip with the mesh: a degradation trough under a level elastic cover.

usage: test_slip_mesh.py EXE NP OUTDIR
tests/cover_trough.opts: 16 m wide, 4 m of elastic waste shrinking 10 % over x = 6..10 m (3 m
taper), 0.5 m of elastic soil over a sheet with 20-degree friction on both faces; run at h = 0.5
and 0.25 m to -tol 1e-4. The sheet is pulled toward the trough: it slips on both faces, about
8.6 cm on its lower face and 2.3-2.5 cm on its upper face at 3.5-4.5 m from the trough's centre.

Slip is path dependent and has no closed form here; what must hold:
- the geometry is symmetric about x = 8 m, so the slip profile is antisymmetric: slip(x) =
  -slip(16 - x) to 2 % of the largest slip (measured 1e-12 at h = 0.5 m, 0.8 % (upper face) and
  0.5 % (lower) at h = 0.25 m: which node rows stick or slip first amplifies round-off);
- slip converges with the mesh. Measured (1 rank, by hand, with h = 0.125 m too, whose stage 2
  stopped at 4.9e-4 after 20,000 steps): lower face 85.5 / 86.2 / 87.1 mm (0.8 %, 1.0 % per
  halving), upper face 25.0 / 22.8 / 21.3 mm (9 %, 7 %: the smaller slip converges more slowly,
  order about 0.5). Bounds at h = 0.5 against 0.25 m: the largest slip per face within 2 % (lower)
  and 12 % (upper); the profiles' relative L2 difference within 4 % (lower, measured 1.8 %) and
  15 % (upper, measured 10.2 %). Since a body counts in the slip rate only above its tail share
  of a node (2026-12-06; docs/cover.md, "Slopes and grades in 3D"): lower face 85.5 / 86.8 mm
  (1.5 %), L2 2.0 %; upper 25.0 / 22.8 mm (9.6 %), L2 10.4 %.
A bonded face's slip is exactly zero (test_chain_slip.py); the pull-out's slip meets its closed
form (test_pullout.py).
"""
import sys

import numpy as np

from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"slip_mesh_np{np_}")
prof, peak = {}, {}
for h in ("0.5", "0.25"):
    d = f"{out}/h{h}"
    run(exe, np_, ["-options_file", "tests/cover_trough.opts", "-cell_size", h], d)
    s = summary(d)
    c.check(f"h = {h}: every stage converged", bool(s["converged"]), s.get("verdict"))
    p = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
    prof[h] = p
    for face in ("top", "bottom"):
        sl = p[f"slip_{face}"]
        peak[(h, face)] = np.abs(sl).max()
        c.ge(f"h = {h}: largest slip ({face}) (m)", peak[(h, face)], 0.01)
        mirrored = np.interp(16.0 - p["x0"], p["x0"], sl)
        c.le(f"h = {h}: max |slip + slip(16 - x)| / max |slip| ({face})",
             np.abs(sl + mirrored).max() / peak[(h, face)], 0.02)
for face, bound_peak, bound_l2 in (("bottom", 0.02, 0.04), ("top", 0.12, 0.15)):
    c.le(f"|max slip (h 0.5) / max slip (h 0.25) - 1| ({face})",
         abs(peak[("0.5", face)] / peak[("0.25", face)] - 1), bound_peak)
    a, b = prof["0.5"], prof["0.25"]
    bi = np.interp(a["x0"], b["x0"], b[f"slip_{face}"])
    c.le(f"slip profile: L2 |h 0.5 - h 0.25| / L2 (h 0.25) ({face})",
         np.sqrt(np.mean((a[f"slip_{face}"] - bi) ** 2)) / np.sqrt(np.mean(bi ** 2)), bound_l2)
c.done()
