"""Block on an incline sliding on a membrane chain (options/incline_chain.opts): the chain contact.

usage: test_incline_chain.py EXE NP OUTDIR
A 1.5 mm HDPE-like sheet (chain "membrane") lies on the base slab's top surface, the block rests on
it; -interface_type contact on both faces, mu_top = the block-sheet friction, mu_bottom = 10 holds
the sheet on the base. Exact: the block slides on a fixed sheet, a = g (sin theta - mu cos theta)
(theta = 30 deg, g = 9.81: mu = 0 gives 4.905, mu = 0.3 gives 2.356 m/s^2), it sticks for
tan theta <= mu (0.577). Bounds (the issue's): 3 % on the sliding acceleration; sticking means an
acceleration after the start-up transient below 1 % of g sin theta; a large mu reproduces the
bonded displacement to 1 mm (as tests/test_incline.py); the sheet stays where it was laid (its
largest displacement along the slope below 1 mm).

The run is dynamic with physical densities (-inertia_scaling none), so the sheet has its own
inertia (1.43 kg/m; a sheet given the block's wave speed would be 186 times heavier and nearly
weightless, and floated off the base: -chain_inertia_scaling follows -inertia_scaling). Its axial
wave (1,000 m/s against the block's 82) sets the step: 55,000 steps for the 0.49 s of the run.
Measured (1 rank; 2 ranks agree to the digits shown), h = 0.02 m:
  mu = 0 within +0.035 %, mu = 0.3 within -0.095 %; the runs that stick, and the bonded one,
  last half as long (27,500 steps): mu = 0.7 sticks (0.47 % of g sin theta; 0.15 % over the
  whole 0.49 s), mu = 10 against bonded 0.11 mm; mu = 0.3 at h = 0.01 m -1.04 % (110,000 steps), mu = 0.5
  (a = 0.657, near the sticking limit: -6.1 %; printed, as the resolved interface's contact
  drifts there too, docs/limitations.md): these two run by hand with --refine.
Two ranks repeat mu = 0.3, the sliding contact (the rest is rank-invariant, tested).
Friction capacity: each sheet point's pressure times its length (contact_bodies' normal pass and
chain_friction_capacity); with each node's own normal impulse the same run gave -2.1 % at mu = 0.3.
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


STEPS = ["-max_steps", "55000"]  # 0.49 s, the duration of options/incline.opts
HALF = ["-max_steps", "27500"]  # the blocks that stay put: half the run tells them apart
if np == 2:
    slide("contact_0.3", "contact, mu = 0.3", "-interface_mu_top", "0.3", *STEPS)
    c.done()
bonded = case("bonded", "-interface_type", "bonded", *HALF)
c.check("bonded: the chain is in the scene and the block sits on it", "sheet_max_displacement_x" in bonded)
r = slide("contact_0", "contact, mu = 0", "-interface_mu_top", "0", *STEPS)
held("contact, mu = 0", r)
r03 = slide("contact_0.3", "contact, mu = 0.3", "-interface_mu_top", "0.3", *STEPS)
held("contact, mu = 0.3", r03)
stick("contact_stick", "contact, mu = 0.7 > tan 30", "-interface_mu_top", "0.7", *HALF)
r = stick("contact_high_mu", "contact, mu = 10", "-interface_mu_top", "10", *HALF)
c.le("contact, mu = 10 reproduces the bonded displacement (m)", abs(r["displacement"] - bonded["displacement"]), 1e-3)
runs = [("0.02", r03)]
if "--refine" in sys.argv:  # the refined run (110,000 steps; measured -1.04 %), by hand
    fine = slide("contact_0.3_fine", "contact, mu = 0.3, h = 0.01 m", "-interface_mu_top", "0.3",
                 "-cell_size", "0.01", "-max_steps", "110000")
    held("contact, mu = 0.3, h = 0.01 m", fine)
    runs.append(("0.01", fine))
for h, r in runs:
    print(f"info mu = 0.3, h = {h} m: a = {r['acceleration']:.5f} (exact {r['acceleration_exact']:.5f}, "
          f"{100 * (r['acceleration'] / r['acceleration_exact'] - 1):+.3f} %), sheet moved "
          f"{1e3 * r['sheet_max_displacement_x']:.3f} mm along, lifted {1e3 * r['sheet_max_displacement_y']:.3f} mm")
if "--refine" in sys.argv:  # near the sticking limit, printed only (measured -6.1 %), by hand
    r = case("contact_0.5", "-interface_mu_top", "0.5", *STEPS)
    print(f"info mu = 0.5 (near the sticking limit): a = {r['acceleration']:.5f} (exact "
          f"{r['acceleration_exact']:.5f}, {100 * (r['acceleration'] / r['acceleration_exact'] - 1):+.2f} %)")
c.done()
