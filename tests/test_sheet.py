"""The 3D sheet on the grid (options/sheet.opts, -scene sheet -dim 3; docs/method.md, section 10):
a circular membrane of radius a = 10 m clamped at its rim, under its own weight q = 100 Pa,
E t = 1e5 N/m, nu = 0.3, against the membrane of revolution with the same law (membrane_bvp.py)
and Foppl-Hencky's small-slope centre deflection 0.653 a (q a / E t)^(1/3).

usage: test_sheet.py EXE NP OUTDIR

Asserted at h = 1 m (331 points) and, on one rank, 0.5 m (1,261 points): the run converges
(-tol 1e-3; 14,730 and 56,651 steps); the sag within 2e-3 of the BVP (measured -1.2e-4 and
-1.7e-6) and within 2 % of Foppl-Hencky (+0.7 %: the slopes reach 0.3); the centre strain (the
mean over the centre's triangles, first order in the lattice gap) and the rim's radial strain
within 2 % (measured -0.93 % and -0.12 % at 1 m, -0.25 % and -0.03 % at 0.5 m), the centre
strain's error falling from 1 to 0.5 m; nothing wrinkles (every triangle taut: both principal
tensions are tensile over a clamped disc). On 2 ranks the h = 1 m answers equal the one-rank
run's to 1e-8 (measured 5e-14; the points are shared by an allreduce, the nodal sums' order
changes).
"""
import sys
from pathlib import Path

from membrane_bvp import membrane_bvp
from pmpmtest import Checks, run, summary

def rel(c, what, got, want, tol):
    """got within tol (absolute) of want; prints the relative difference."""
    c.check(what, abs(got - want) <= tol, f"({got:.7g} vs {want:.7g}, {got / want - 1:+.2e})")


exe, np_, out = sys.argv[1], int(sys.argv[2]), Path(sys.argv[3])
c = Checks(f"sheet_np{np_}")
A, Q, NU, ET = 10.0, 100.0, 0.3, 1e5
J = ET / (1 - NU * NU)
ex = membrane_bvp(A, Q, J, NU)
fh = 0.653 * A * (Q * A / ET)**(1 / 3)
print(f"     membrane of revolution: sag {ex['sag']:.5f} m, centre strain {ex['strain_centre']:.6f},"
      f" rim strain {ex['strain_rim']:.6f}; Foppl-Hencky {fh:.5f} m")

meshes = [1.0, 0.5] if np_ == 1 else [1.0]
res = {}
for h in meshes:
    o = out / f"h{h}"
    run(exe, np_, ["-options_file", "options/sheet.opts", "-cell_size", str(h)], o)
    s = summary(o)
    r = s["results"]
    res[h] = r
    c.check(f"h = {h}: converged", s["converged"], f"({s['steps']} steps)")
    rel(c, f"h = {h}: sag against the BVP", r["sag"], ex["sag"], 2e-3 * ex["sag"])
    rel(c, f"h = {h}: sag against Foppl-Hencky", r["sag"], fh, 0.02 * fh)
    rel(c, f"h = {h}: centre strain", r["strain_centre"], ex["strain_centre"], 0.02 * ex["strain_centre"])
    rel(c, f"h = {h}: rim strain", r["strain_rim"], ex["strain_rim"], 0.02 * ex["strain_rim"])
    c.check(f"h = {h}: every triangle taut", r["triangles_not_taut"] == 0)
if len(res) > 1:
    e = [abs(res[h]["strain_centre"] / ex["strain_centre"] - 1) for h in meshes]
    c.check("centre strain's error falls from 1 to 0.5 m", e[1] < e[0], f"({e[0]:.2e} -> {e[1]:.2e})")
if np_ > 1:
    o = out / "np1"
    run(exe, 1, ["-options_file", "options/sheet.opts"], o)
    r1 = summary(o)["results"]
    for k in ("sag", "strain_centre", "strain_rim"):
        rel(c, f"{k}: {np_} ranks against 1", res[1.0][k], r1[k], 1e-8 * abs(r1[k]))
c.done()
