"""The active trapdoor under -solver newton (docs/newton.md, "Moving supports"): the door's
displacement imposed in load steps, the door's pressure from the residual's prescribed rows.

usage: test_trapdoor_newton.py EXE NP OUTDIR
test_trapdoor.py's coarse case under Newton: H/B = 1 (B = H = 1 m), half model 2 m wide,
h = B/8, phi 30 deg, psi 0, c = 0, no F-bar, the door lowered to 0.2, 0.5 and 1 % of B in
-newton_load_steps 10 load steps a stage (then equilibrium steps to -tol 1e-4). Terzaghi
(docs/method.md, section 6.4, c = q = 0) over gamma H: K = 1 gives 0.5931, K = Ka = 1/3 0.8300.

Measured (1 rank): p / gamma H = 1.00000, 0.5749, 0.5304, 0.5242 (the minimum, at 1 % B; on to
2 and 3 % B: 0.5288, 0.5381, the arch holding); with 20 load steps a stage (every step halved)
0.99999, 0.5739, 0.5298, 0.5241 (largest difference 1.05e-3 gamma H, at 0.2 % B; 5 steps against
10: 2.0e-3, so the difference halves with the step: first order in it); 2 ranks equal to 1 to
the 9 digits trapdoor.csv prints. Relaxation at this mesh and 1e-5 cells per step
(test_trapdoor.py): 1, 0.579, 0.544, 0.534 (and 0.538, 0.546 at 2 and 3 % B): the same shape,
0.01 gamma H above, as a slower door lowers it (docs/benchmarks/trapdoor.md).

Asserted:
  - every stage reaches equilibrium;
  - stage 0 (door held): p / gamma H = 1 within 1e-4. A laterally uniform column's base
    reactions equal its weight at equilibrium, and Newton's reaction is the residual's rows on
    the base's dofs, which the equilibrium of the free rows (-tol 1e-4 of the mean load) leaves
    exact to that share (measured 1 - 4e-6 with 20 load steps, 1 to 9 digits with 10);
  - the minimum inside [0.85 Terzaghi(K = 1), Terzaghi(K = 1)]: at h = B/8 the grid arches more
    than at B/16 (relaxation: +0.027 gamma H from B/8 to B/16), the measured minimum 0.884 of the
    K = 1 value; the lower end allows that with 0.02 gamma H to spare (and fails for a lost or
    misweighted reaction), the upper end fails for a curve lifted above the K = 1 prism's load,
    as relaxation's fast doors are (0.665 and 0.591 gamma H at 1e-4 and 3e-5 cells per step,
    h = B/16): a quasi-static answer has no inertia to lift it;
  - falls: p < 0.75 gamma H at 0.2 % B and within 0.02 gamma H of the minimum by 0.5 % B, as
    test_trapdoor.py asserts of relaxation;
  - 1 rank: halving every load step (20 a stage) moves no stage's p by more than 3e-3 gamma H
    (measured 1.05e-3; relaxation's minimum moves by 0.03 gamma H from 3e-5 to 1e-5 cells per
    step): the curve is quasi-static, its step error 10x under relaxation's rate effect;
  - 2 ranks: every stage's p equal to 1 rank's within 1e-8 gamma H (round-off: trapdoor.csv's 9
    digits resolve 1e-9; measured equal to all of them).
"""
import csv
import math
import sys

import closed_forms as cf
from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"trapdoor_newton_np{np_}")
B, H, phi = 1.0, 1.0, 30.0
ARGS = ["-options_file", "options/trapdoor.opts", "-cell_size", "0.125", "-trapdoor_height",
        str(H), "-trapdoor_soil_width", "2", "-trapdoor_displacements", "0.002,0.005,0.01",
        "-solver", "newton", "-newton_load_steps", "10"]


def curve(d):
    with open(f"{d}/trapdoor.csv") as f:
        return [float(r["pressure_over_gammaH"]) for r in csv.DictReader(f)]


run(exe, np_, ARGS, out)
r = summary(out)["results"]
st = r["stages"]
for s in st:
    print(f"  door {100 * s['displacement_over_B']:.2f} % B: p / gamma H = {s['ratio']:.5f} "
          f"({'equilibrium' if s['converged'] else 'NOT converged'}, {s['steps']} load steps)")
ka = (1 - math.sin(math.radians(phi))) / (1 + math.sin(math.radians(phi)))
k1 = cf.terzaghi_arching(1.0, B, H, 1.0, phi) / H
print(f"  Terzaghi over gamma H: K = 1 {k1:.4f}, K = Ka {cf.terzaghi_arching(1.0, B, H, ka, phi):.4f}")
c.check("every stage reaches equilibrium", len(st) == 4 and all(s["converged"] for s in st))
c.le("stage 0: p / gamma H - 1 (door held)", abs(st[0]["ratio"] - 1), 1e-4)
c.ge("minimum above 0.85 Terzaghi(K = 1)", r["min_ratio"], 0.85 * k1)
c.le("minimum below Terzaghi(K = 1)", r["min_ratio"], k1)
c.le("falls: p / gamma H at 0.2 % B", st[1]["ratio"], 0.75)
c.le("falls within 0.5 % B: p at 0.5 % B - minimum", st[2]["ratio"] - r["min_ratio"], 0.02)
p = curve(out)
if np_ == 1:
    run(exe, 1, ARGS[:-1] + ["20"], out + "_n20")
    p20 = curve(out + "_n20")
    c.le("20 load steps a stage against 10: largest |p difference| / gamma H",
         max(abs(a - b) for a, b in zip(p, p20)), 3e-3)
else:
    run(exe, 1, ARGS, out + "_np1")
    p1 = curve(out + "_np1")
    c.le("2 ranks against 1: largest |p difference| / gamma H",
         max(abs(a - b) for a, b in zip(p, p1)), 1e-8)
c.done()
