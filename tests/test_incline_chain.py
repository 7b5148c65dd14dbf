"""Block on an incline sliding on a membrane chain (options/incline_chain.opts): the chain contact.

usage: test_incline_chain.py EXE NP OUTDIR
A 1.5 mm HDPE-like sheet (chain "membrane") lies on the base slab's top surface, the block rests on
it; -interface_type contact on both faces, mu_top = the block-sheet friction, mu_bottom = 10 holds
the sheet on the base. Exact: the block slides on a fixed sheet, a = g (sin theta - mu cos theta)
(theta = 30 deg, g = 9.81: mu = 0 gives 4.905, mu = 0.3 gives 2.356 m/s^2), it sticks for
tan theta <= mu (0.577). Bounds (the issue's): 3 % on the sliding acceleration; sticking means an
acceleration after the start-up transient below 1 % of g sin theta; a large mu reproduces the
bonded displacement to 1 mm (as tests/test_incline.py); the sheet stays where it was laid (its
largest displacement along the slope below 1 mm, 0.4 % of the block's slide at mu = 0.3).

Measured at h = 0.02 m, 4000 steps (0.48 s), the same on 1 and 2 ranks to the digits shown:
  mu = 0:    a = 4.9014, -0.074 %                mu = 0.3:  a = 2.3428, -0.573 %
  mu = 0.7:  |a| = 0.035-0.042 % of g sin theta   mu = 10:   0.024 mm from the bonded displacement
  sheet: 0.09 mm along the slope at mu = 0.3 (the block slides 0.275 m), lifted up to 0.9 mm.
  h = 0.01 m (8000 steps, the same 0.48 s), mu = 0.3: a = 2.3274, -1.23 %.

The default chain inertia scaling (-chain_inertia_scaling: the sheet's mass set to J / c^2 so its
axial wave is the block's, 82 m/s) makes the sheet 186 times heavier (265 kg/m against 1.43) with
its weight unchanged: it responds to gravity as if g were 0.053 m/s^2. In this undamped run the
base, loaded at once, vibrates and throws the sheet off (98 of 114 contact nodes separated at step
100); it floats up to 1-9 mm above the base, where the lower face cannot hold it, and bows up ahead
of the block, whose normal force then has a component against the sliding (slope about 0.014).
mu = 0.3 is 0.57 % slow at h and 1.23 % at h/2 (a node's sheet mass goes as h, its continuum mass
as h^2, so the sheet weighs more at a node as h falls); near the critical mu the same force error is amplified: mu = 0.5 (a = 0.657) is 12.4 % slow at h = 0.02 and
32 % at h = 0.01. With the sheet's own inertia (-chain_inertia_scaling 0, a 13.7 times smaller
step) mu = 0.3 is within +0.07 % and mu = 0.5 within -0.17 %: that run is checked below; the scaled
mu = 0.5 run is printed for information. Not the cause: -interface_tail_share 0, -pic 0.05,
pinned ends, -chain_spacing 1 leave mu = 0.5 7-12 % slow; a lower face that cannot separate (paper,
not selectable per face by options; tried by hand) brings it to -0.49 %.
CPU time about 15 s per rank count, 8 s of it the own-inertia run (55000 steps).
"""
import sys
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"incline_chain_np{np}")


def case(name, *extra):
    d = f"{out}/{name}"
    run(exe, np, ["-options_file", "options/incline_chain.opts"] + list(extra), d)
    return summary(d)["results"]


def slide(name, what, *extra):
    r = case(name, *extra)
    c.check(f"{what}: the exact solution slides", r["sticks_exact"] is False)
    c.le(f"{what}: |a - g (sin - mu cos)| / a_exact", abs(r["acceleration"] / r["acceleration_exact"] - 1), 0.03)
    return r


def stick(name, what, *extra):
    r = case(name, *extra)
    c.check(f"{what}: the exact solution sticks", r["sticks_exact"] is True)
    c.le(f"{what}: |a| / (g sin theta) after the transient", abs(r["acceleration"]) / r["acceleration_free_slip"], 0.01)
    return r


def held(what, r):
    c.le(f"{what}: the sheet's largest displacement along the slope (m)", r["sheet_max_displacement_x"], 1e-3)


bonded = case("bonded", "-interface_type", "bonded")
c.check("bonded: the chain is in the scene and the block sits on it", "sheet_max_displacement_x" in bonded)
r = slide("contact_0", "contact, mu = 0", "-interface_mu_top", "0")
held("contact, mu = 0", r)
r03 = slide("contact_0.3", "contact, mu = 0.3", "-interface_mu_top", "0.3")
held("contact, mu = 0.3", r03)
stick("contact_stick", "contact, mu = 0.7 > tan 30", "-interface_mu_top", "0.7")
r = stick("contact_high_mu", "contact, mu = 10", "-interface_mu_top", "10")
c.le("contact, mu = 10 reproduces the bonded displacement (m)", abs(r["displacement"] - bonded["displacement"]), 1e-3)
fine = slide("contact_0.3_fine", "contact, mu = 0.3, h = 0.01 m", "-interface_mu_top", "0.3",
             "-cell_size", "0.01", "-max_steps", "8000")
held("contact, mu = 0.3, h = 0.01 m", fine)
for h, r in (("0.02", r03), ("0.01", fine)):
    print(f"info mu = 0.3, h = {h} m: a = {r['acceleration']:.5f} (exact {r['acceleration_exact']:.5f}, "
          f"{100 * (r['acceleration'] / r['acceleration_exact'] - 1):+.3f} %), sheet moved "
          f"{1e3 * r['sheet_max_displacement_x']:.3f} mm along, lifted {1e3 * r['sheet_max_displacement_y']:.3f} mm")

# The sheet with its own inertia (no chain inertia scaling): 13.7 times the steps for the same 0.48 s.
r = slide("contact_0.5_own_inertia", "contact, mu = 0.5, the sheet's own inertia", "-interface_mu_top", "0.5",
          "-chain_inertia_scaling", "0", "-max_steps", "55000")
r = case("contact_0.5_scaled", "-interface_mu_top", "0.5")
print(f"info mu = 0.5 with the default chain inertia scaling: a = {r['acceleration']:.5f} (exact "
      f"{r['acceleration_exact']:.5f}, {100 * (r['acceleration'] / r['acceleration_exact'] - 1):+.2f} %; the "
      f"floating sheet, see the docstring), sheet lifted {1e3 * r['sheet_max_displacement_y']:.2f} mm")
c.done()
