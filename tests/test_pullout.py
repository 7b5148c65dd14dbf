"""Pull-out of an anchored sheet between two stiff blocks (docs/method.md, section 6.2): the chain's Coulomb
friction on both faces against the rigid-plastic closed form (closed_forms.pullout).

usage: test_pullout.py EXE NP OUTDIR [pmpm options for every run]
options/pullout.opts: L = 1 m anchored, p = 20 kPa, J = E t = 1e6 N/m (uniaxial), blocks
E = 1e10 Pa (near-rigid, weightless), h = 0.02 m, P and p ramped together over 1000 steps,
kinetic damping. x is measured from the pulled point's initial position (the sheet's right end,
inside the blocks; src/scenes/pullout.cpp says why).
The segments' strain is projected on the grid (-chain_strain_projection, the default): tension
RMS 0.6-0.7 %, anchored length 1.5 % and 2.2 % (bounds below); pullout_chord_np1 runs the same with
the chord strain (-chain_strain_projection 0: the numbers measured below).

Below capacity, P = 5 kN/m, two cases: mu_t = mu_b = 0.25 (m = 10 kN/m^2, x_a = 0.5 m,
u0 = 1.25 mm) and the mu_t of docs/method.md, section 6.2, = 0.3, mu_b = 0.4 (m = 14 kN/m^2, x_a = 0.357 m, u0 = 0.893 mm):
  - the tension profile of chain_membrane.csv against T(x) = max(P - m x, 0): RMS error / P
    <= 2 % (it carries the smear of the force's entry over about a cell);
  - the anchored length (base of the tension triangle, 2 sum T l0 / P) and the pulled point's
    u_x within 3 % (the issue's bound) of P / m and P^2 / (2 m J). With a linear law and the far
    end at rest they are the same number (u0 = sum eps l0 = area / J);
  - the sheet in equilibrium (its friction = P to 1e-3), the contact pressure on both faces = p
    (2 %), the sheet beyond x_a + 2 cells at rest (|u_x| < 2 % of u0; exact: 0).
Above capacity (mu 0.3 + 0.4, L = 2 m, capacity 28 kN/m, P = 35 kN/m, 2500 steps): the sheet
slides out; the friction it carries while the whole sheet slides (every point a cell or more from
its ends slips on both faces that step) equals (mu_t + mu_b) p L within 3 %, averaged over those
steps after the ramp (at least a quarter of them). Why not every step: a kinetic-damping reset
stops the sheet and parts of it stick again for some 20 steps (friction down to 0.6 m L), which
is the damping, not the interface; the mean over all of the last quarter of the steps was -3.4 %
to +2 % depending on where the resets fell (-4.8 % to +2 % without the change below). The tension
at the pulled end is no measure: it stays about P, the excess P - m L accelerating the sheet.

Measured, 1 rank (2 ranks agree to 1e-12), x_a and u0 error / RMS / sliding friction error:
  engine of this commit: mu 0.25 + 0.25: +14.1 % / 5.5 % (15848 steps); mu 0.3 + 0.4: +4.2 % /
    3.1 % (8206 steps); pulled out: +3.6 % (last quarter +1.4 %). FAILS: the friction of a sheet
    between two bodies is capped by the less-pressed of the two node rows it straddles
    (contact_bodies, src/contact/chain.cpp; see the pullout report), so the slip zone carries 0.5-0.99
    of m; at h = 0.01 m the errors grow to +51 % and +40 % (87835, 42167 steps; pulled out
    +2.5 %).
  with the chain face capacity taken from the sheet's pressure times its length at the node (a
    contact_bodies prototype with last step's pressure, not in this commit; same-step pressure:
    within 0.3 % of these): mu 0.25 + 0.25: -1.3 % / 0.50 % (1235 steps); mu 0.3 + 0.4: -2.1 % /
    0.70 % (1172 steps); the sheet shifted by 1/4, 1/2, 3/4 cell: -1.1 to -2.6 %; pressure
    +0.6 %, far sheet at rest to 1.2e-4 u0; pulled out: +2.0 % (P = 1.1 m L: +1.3 %). At
    h = 0.01 m (blocks 0.025 m, ramp 2000): +1.1 % / 0.38 % and +0.76 % / 0.26 % (3079, 2385
    steps); pulled out +0.3 % (1.1 m L: +1.1 %).
"""
import sys

import numpy as np

from closed_forms import pullout
from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
extra_all = sys.argv[4:]
c = Checks(f"pullout_np{np_}" + (" " + " ".join(extra_all) if extra_all else ""))


def case(name, *extra, capped=False):
    d = f"{out}/{name}"
    run(exe, np_, ["-options_file", "options/pullout.opts"] + list(extra) + extra_all, d,
        capped=capped)
    prof = np.genfromtxt(f"{d}/chain_membrane.csv", delimiter=",", names=True)
    return summary(d), prof


def below(name, mu_t, mu_b):
    s, prof = case(name, "-interface_mu_top", str(mu_t), "-interface_mu_bottom", str(mu_b))
    r = s["results"]
    what = f"mu_t = {mu_t}, mu_b = {mu_b}"
    h = s["h"]
    P, p, J, L = r["force"], r["pressure"], r["axial_stiffness"], r["length"]
    ex = pullout(P, p, mu_t, mu_b, J, L)
    c.check(f"{what}: converged", s["converged"] is True, f"({s['steps']} steps)")
    c.check(f"{what}: below capacity", r["pulled_out"] is False)
    x = r["pulled_end_x0"] - prof["x0"]  # distance from the pulled point
    rms = np.sqrt(np.mean((prof["tension"] - ex["tension"](x)) ** 2)) / P
    c.le(f"{what}: RMS |T - (P - m x)| / P", rms, 0.02)
    c.le(f"{what}: |x_a / (P / m) - 1|", abs(r["anchored_length"] / ex["x_a"] - 1), 0.03)
    c.le(f"{what}: |u0 / (P^2 / (2 m J)) - 1|", abs(r["end_displacement"] / ex["u0"] - 1), 0.03)
    c.le(f"{what}: |friction / P - 1| (the sheet in equilibrium)",
         abs(r["friction_force"] / P - 1), 1e-3)
    for face in ("top", "bottom"):
        c.le(f"{what}: |contact pressure ({face}) / p - 1|",
             abs(r[f"contact_pressure_{face}"] / p - 1), 0.02)
    # slip: the blocks are at rest, so each face's slip is the sheet's displacement, the closed
    # form's u(x) = (P - m x)^2 / (2 m J); the sheet's own u_x meets it within 3 % at its end,
    # and the profile carries the force's entry smear as the tension does (bound as for T)
    u = ex["displacement"](x)
    end = int(np.argmin(x))
    for face in ("top", "bottom"):
        sl = prof[f"slip_{face}"] * np.sign(prof["ux"][end])
        c.le(f"{what}: |slip ({face}) at the pulled end / u0 - 1|", abs(sl[end] / ex["u0"] - 1), 0.03)
        c.le(f"{what}: RMS |slip ({face}) - u(x)| / u0", np.sqrt(np.mean((sl - u) ** 2)) / ex["u0"],
             0.02)
    beyond = x > ex["x_a"] + 2 * h
    c.le(f"{what}: max |u_x| beyond x_a + 2 cells / u0",
         np.max(np.abs(prof["ux"][beyond])) / ex["u0"], 0.02)


below("equal", 0.25, 0.25)
below("unequal", 0.3, 0.4)

s, _ = case("pulled_out", "-pullout_length", "2", "-pullout_force", "35000", "-pullout_margin",
            "0.4", "-ramp_steps", "500", "-max_steps", "2500", capped=True)
r = s["results"]
what = "P = 1.25 (mu_t + mu_b) p L"
c.check(f"{what}: pulled out", r["pulled_out"] is True)
c.ge(f"{what}: the sheet slid (end u_x / h)", r["end_displacement"] / s["h"], 2.0)
c.ge(f"{what}: the pulled end stayed clear of the side face (cells)", r["end_clearance_cells"], 2.0)
c.ge(f"{what}: share of the steps after the ramp with the whole sheet sliding",
     r["sliding_steps"] / r["steps_after_ramp"], 0.25)
c.le(f"{what}: |friction (whole sheet sliding) / (mu_t + mu_b) p L - 1|",
     abs(r["friction_force_sliding"] / r["capacity"] - 1), 0.03)
c.done()
