"""Veneer on the finite slope of the cover scene (issue 9): where the cover starts to slide on the
sheet, beside Koerner and Soong's two-wedge factor of safety (docs/method.md, section 6.3).

usage: test_cover_veneer.py EXE NP OUTDIR
options/cover_slope.opts, stage 0 only (the veneer under its own weight), h = 0.5 m: a 0.57 m
(normal) cover on 30 m of 3H:1V slope with its toe on level ground; the sheet's lower face held
(delta 40 deg on the waste), its upper face at delta. The cover is made cohesionless
(-mat_soil_cohesion 0) because Koerner and Soong's closed form has no cohesion: with the shipped
2 kPa the cover holds down to 14.3 deg (docs/benchmarks/cover_veneer.md) and the comparison would measure c.
The test runs without F-bar (-fbar 0; the example turns it on): cohesionless Drucker-Prager has no
strength at zero confinement, and with F-bar the cover's surface row flows (apex returns, plastic
strain 0.34) so no stage reaches equilibrium even at 18.2 deg, where the sheet slips 8 mm and the
ratio stays at 0.16. The locked cells hold that row, and they also stiffen the toe wedge: part of
the 1.1 deg by which pmpm's threshold lies below Koerner-Soong's may be locking.

Closed forms: the infinite slope slides for delta < beta = 18.43 deg; Koerner and Soong's finite
slope, with its passive toe wedge, has FS = 1 at delta_KS = 16.9 deg. pmpm's threshold measured
by hand with bench/cover_veneer.py's rule (2 ranks, cohesionless): holds at 16.5 deg (slip 9 mm)
and 16.0 deg (17 mm); at 15.5 deg it slides 7.6 cm before it finds equilibrium; at 14.5 deg it
slides on (0.53 m at 8,000 steps). pmpm's threshold is 15.75 +- 0.25 deg, 1.1 deg below
Koerner-Soong's (a limit-equilibrium estimate with an assumed wedge shape; the continuum finds its
own toe mechanism) and 2.7 deg below the infinite slope's. Asserted, bracketing that threshold:
  - delta = delta_KS: the cover holds (stage 0 converges, slip on the sheet below 5 cm): a
    cover Koerner-Soong calls stable at FS = 1 is stable in pmpm;
  - delta = delta_KS - 2.5 deg (14.4): the cover slides (no equilibrium within 4,000 steps, or a
    slip past 5 cm): the toe wedge does not hold more than the closed form allows by 2.5 deg.
  - the scene's own Koerner-Soong FS (summary.json, include/pmpm/scenes/veneer.hpp) equals this file's
    independent implementation at both angles (1e-9), and is 1 at delta_KS.
"""
import csv
import math
import sys
from closed_forms import koerner_soong_fs
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"cover_veneer_np{np}")
beta, L, phi, gamma = 18.435, 30.0, 32.0, 18e3
h_normal = 0.6 * math.cos(math.radians(beta))
ks = lambda d: koerner_soong_fs(gamma, h_normal, L, beta, phi, d)  # noqa: E731
lo, hi = 1.0, beta
for _ in range(60):
    mid = 0.5 * (lo + hi)
    lo, hi = (lo, mid) if ks(mid) >= 1 else (mid, hi)
delta_ks = hi
print(f"Koerner-Soong FS = 1 at delta = {delta_ks:.3f} deg; infinite slope at {beta} deg")
SLIP_LIMIT = 0.05


def stage0(name, delta, max_steps):
    d = f"{out}/{name}"
    run(exe, np, ["-options_file", "options/cover_slope.opts", "-fbar", "0",
                  "-cover_shrink_total", "0",
                  "-cover_shrink_stages", "0", "-mat_soil_cohesion", "0",
                  "-chain_hdpe_delta_top", repr(delta), "-chain_hdpe_delta_bottom", "40",
                  "-max_steps", str(max_steps)], d, capped=True)
    with open(f"{d}/stages.csv") as f:
        row = list(csv.DictReader(f))[0]
    return row, summary(d)["results"]["slope"]


for name, delta, steps, expect_hold in (("holds_at_ks", delta_ks, 8000, True),
                                        ("slides_below", delta_ks - 2.5, 4000, False)):
    row, slope = stage0(name, delta, steps)
    slip, conv = float(row["max_slip"]), row["converged"] == "1"
    holds = conv and slip < SLIP_LIMIT
    c.check(f"delta = {delta:.2f} deg: the cover {'holds' if expect_hold else 'slides'}",
            holds == expect_hold,
            f"(converged {conv}, slip {slip:.4f} m, {row['steps']} steps, ratio {row['ratio']})")
    c.le(f"delta = {delta:.2f}: scene's Koerner-Soong FS against the closed form",
         abs(slope["fs_koerner_soong"] - ks(delta)), 1e-9)
    c.le(f"delta = {delta:.2f}: scene's infinite-slope FS against tan(delta)/tan(beta)",
         abs(slope["fs_infinite"] - math.tan(math.radians(delta)) / math.tan(math.radians(beta))),
         1e-12)
    if expect_hold:
        c.le("Koerner-Soong FS at delta_KS is 1", abs(slope["fs_koerner_soong"] - 1), 1e-9)
c.done()
