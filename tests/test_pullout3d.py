"""The pull-out extruded (-dim 3): the chain becomes a strip of 3D sheet across the depth, a body of
its own between the two blocks, with Coulomb friction on both faces as cones (sheet_contact.hpp,
contact_stack3). It must give the 2D answer, and the closed form (closed_forms.pullout).

usage: test_pullout3d.py EXE NP OUTDIR
options/pullout.opts (L = 1 m, p = 20 kPa, mu_t = 0.3, mu_b = 0.4, J = 1e6 N/m, P = 5 kN/m,
h = 0.02 m) over -depth 0.06 m (three cells; the z faces rollers, the strip's edge rows held in z):
  - converged; below capacity;
  - anchored length and end displacement within 3 % of P / m and P^2 / (2 m J) (the 2D test's
    bound; measured 2.9 %, 2D 2.2 %), and within 1.5 % of the 2D run's (measured 0.8 % and 0.7 %:
    an edge effect, the strip's edge rows on the z faces carrying a slightly different share of
    the pressure than the blocks give their nodes there; over 6 cells of depth 0.26 %);
  - the sheet in equilibrium: the friction on it (from the contact's impulses) = P to 1e-3;
  - contact pressure on both faces = p within 2 %;
  - plane strain: the pulled end's column moves as one (spread of its u_x below 5e-3 u0;
    measured 1.9e-3, the edge rows' share again), no point moves across (|u_z| below 1e-3 u0;
    measured 3.3e-4), and the slip on each face at the pulled end is u0
    within 3 % (the blocks are at rest);
  - on NP > 1 ranks, on a process grid cut in x and in z (the sheet crosses rank boundaries in two
    directions), the same answers as on one rank to 1e-9 (measured 8e-12).
Above capacity (L = 2 m, P = 35 kN/m = 1.25 m L, 1,500 steps: 1,000 after the ramp), as the 2D
test: the friction the sheet carries while all of it slides = (mu_t + mu_b) p L within 3 %
(measured 2.80 %; 2.77 % over 2,500 steps).
"""
import sys

import numpy as np

from closed_forms import pullout
from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"pullout3d_np{np_}")
base = ["-options_file", "options/pullout.opts"]
dim3 = ["-dim", "3", "-depth", "0.06"]
# 2 ranks: cut in z (across the strip); 4: in x and z (2 x 1 x 2)
grid = {2: ["-da_processors_x", "1", "-da_processors_y", "1", "-da_processors_z", "2"],
        4: ["-da_processors_x", "2", "-da_processors_y", "1", "-da_processors_z", "2"]}.get(np_, [])

run(exe, 1, base, f"{out}/plane")
run(exe, np_, base + dim3 + grid, f"{out}/strip")
s2, s3 = summary(f"{out}/plane"), summary(f"{out}/strip")
r2, r3 = s2["results"], s3["results"]
P, p, J, L = r3["force"], r3["pressure"], r3["axial_stiffness"], r3["length"]
ex = pullout(P, p, r3["mu_top"], r3["mu_bottom"], J, L)
c.check("3D: converged", s3["converged"] is True, f"({s3['steps']} steps)")
c.check("3D: below capacity", r3["pulled_out"] is False)
for key, exact in (("anchored_length", ex["x_a"]), ("end_displacement", ex["u0"])):
    c.le(f"3D: |{key} / closed form - 1|", abs(r3[key] / exact - 1), 0.03)
    c.le(f"3D: |{key} / 2D - 1|", abs(r3[key] / r2[key] - 1), 0.015)
c.le("3D: |friction / P - 1| (the sheet in equilibrium)", abs(r3["friction_force"] / P - 1), 1e-3)
for face in ("top", "bottom"):
    c.le(f"3D: |contact pressure ({face}) / p - 1|", abs(r3[f"contact_pressure_{face}"] / p - 1),
         0.02)
prof = np.genfromtxt(f"{out}/strip/sheet_membrane.csv", delimiter=",", names=True)
end = prof["x0"] == prof["x0"].max()
c.le("3D: spread of the pulled column's u_x / u0", np.ptp(prof["ux"][end]) / ex["u0"], 5e-3)
c.le("3D: max |u_z| / u0", np.max(np.abs(prof["uz"])) / ex["u0"], 1e-3)
for face in ("top", "bottom"):
    sl = np.mean(prof[f"slip_{face}_x"][end])
    c.le(f"3D: |slip ({face}) at the pulled end / u0 - 1|", abs(sl / ex["u0"] - 1), 0.03)

if np_ > 1:  # the same scene on one rank
    run(exe, 1, base + dim3, f"{out}/strip_np1")
    r1 = summary(f"{out}/strip_np1")["results"]
    for key in ("anchored_length", "end_displacement", "friction_force", "contact_pressure_top",
                "contact_pressure_bottom"):
        c.le(f"{np_} ranks against 1: |{key}| relative difference", abs(r3[key] / r1[key] - 1), 1e-9)
else:
    run(exe, 1, base + dim3 + ["-pullout_length", "2", "-pullout_force", "35000",
                               "-pullout_margin", "0.4", "-ramp_steps", "500", "-max_steps",
                               "1500"], f"{out}/pulled_out", capped=True)
    s = summary(f"{out}/pulled_out")
    r = s["results"]
    what = "3D, P = 1.25 (mu_t + mu_b) p L"
    c.check(f"{what}: pulled out", r["pulled_out"] is True)
    c.ge(f"{what}: the sheet slid (end u_x / h)", r["end_displacement"] / s["h"], 2.0)
    c.ge(f"{what}: share of the steps after the ramp with the whole sheet sliding",
         r["sliding_steps"] / r["steps_after_ramp"], 0.25)
    c.le(f"{what}: |friction (whole sheet sliding) / (mu_t + mu_b) p L - 1|",
         abs(r["friction_force_sliding"] / r["capacity"] - 1), 0.03)
c.done()
