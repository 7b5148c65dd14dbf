"""Membrane chains under -geometry axisymmetric: a membrane of revolution with hoop strain
(include/pmpm/contact/chain.hpp), alone against an independent solution, in a cover against the
overburden, and the round sinkhole example.

usage: test_membrane_axisymmetric.py EXE OUTDIR

1. A circular membrane clamped at its rim, sagging under its own weight (options/catenary.opts
   under -geometry axisymmetric: radius a = 10 m, q = gamma t = 100 Pa, E t = 1e5 N/m, nu = 0.3,
   plane-stress J = E t / (1 - nu^2)), against the membrane of revolution solved here as a
   boundary-value problem (scipy's solve_bvp, 1e-10): reference radius R, current (r, z),
   eps = |(r', z')| - 1 and th = r / R - 1, N = J (eps + nu th), N_th = J (th + nu eps), and
       (R N r' / (1 + eps))' = N_th,   R N z' / (1 + eps) = q R^2 / 2,
   r = a and z = 0 at the rim, isotropic at the centre. The chain's discrete energy is this
   functional's, so the two agree as h -> 0 (the Foppl-Hencky small-slope estimate, 0.653 a
   (q a / E t)^(1/3) = 1.41 m at nu = 0.3 (Fichter 1997), is printed beside: the slopes here reach
   0.3). Measured (1 rank; relative errors):
       h = 0.5 m  : sag -4.3e-3, centre strain -2.2e-3, rim tension -1.1e-3, rim strain -1.3e-2
       h = 0.25 m : sag -1.3e-3, centre strain -7.3e-4, rim tension -3.1e-4, rim strain -6.4e-3
       h = 0.125 m: sag -3.8e-4, centre strain -2.3e-4, rim tension -9.6e-5, rim strain -3.2e-3
   (the rim strain is the last two segments' extrapolated: first order). Asserted at h = 0.25 m:
   sag 3e-3, centre strain 2e-3, rim tension 1e-3, rim strain 1.5e-2, the rim's hoop tension
   (nu N there) 1e-2; the sag's and the centre strain's errors fall by more than 2x from 0.5 to
   0.25 m; at the centre the hoop strain equals the meridional one (isotropy, 2e-3 relative;
   measured 7e-5); the rim's reaction plus the pinned rim point's own weight is the weight per
   radian q a^2 / 2 (2e-3; measured 2e-5). The centre point stays on the axis (x = 0 exactly).
   The tension_only law (the tension field model) gives the linear law's answer here, where
   nothing compresses (1e-6; measured 0). 1 and 2 ranks agree to 1e-12 (the chain alone; 1e-13).
2. A level cover on the axis (tests/cover_zones.opts under -geometry axisymmetric: 0.5 m of soil,
   18 kN/m^3, on a 1.5 mm sheet with friction on both faces over 4 m of waste; gravity only, so
   uniaxial strain): the sheet's pressure on its upper face is the soil's weight, 9,000 Pa, and
   on its lower face that plus the sheet's own weight (14.1 Pa), at every point more than two
   cells from the axis and the outer wall (0.5 %; measured 3.3e-3 next to the wall, 4e-5 between;
   within 1.5 cells of the axis the pressure reads low, 7.7 % on the axis, 1 % at 1.2 h: the
   sheet's blocks are a cell long, the soil's half a cell, and the ring's area grows with r
   across them; docs/limitations.md); the sheet unstrained (meridional and hoop < 1e-5) and not
   slipping (< 1e-5 m); its settlement the waste top's.
3. The round sinkhole (options/cover_sinkhole_round.opts) at h = 0.5 m, one mesh (-estimate_error
   0; its two-mesh verdict costs 5 minutes, docs/cover.md): every stage converges,
   the verdict is PASS with exit 0, the comparison block says the void is round and gives
   Giroud's spherical cap and Terzaghi's round trapdoor, and the sheet starts on the axis and
   stays there (no hole at its centre).
"""
import sys

import numpy as np

from membrane_bvp import membrane_bvp
from pmpmtest import Checks, run, stages, summary

exe, out = sys.argv[1], sys.argv[2]
c = Checks("membrane_axisymmetric")
A, Q, NU, ET = 10.0, 100.0, 0.3, 1e7 * 0.01
J = ET / (1 - NU * NU)


ex = membrane_bvp(A, Q, J, NU)
print(f"     membrane of revolution: sag {ex['sag']:.5f} m (Foppl-Hencky, small slopes: "
      f"{0.653 * A * (Q * A / ET)**(1 / 3):.3f} m), centre strain {ex['strain_centre']:.6f}, "
      f"rim strain {ex['strain_rim']:.6f}, rim tension {ex['tension_rim']:.2f} N/m")
AXI = ["-options_file", "options/catenary.opts", "-geometry", "axisymmetric",
       "-mat_membrane_axial_stiffness", "plane_strain", "-mat_membrane_nu", str(NU)]

# 1. the circular membrane
err = {}
for h, np_ in ((0.5, 1), (0.25, 1), (0.5, 2)):
    d = f"{out}/circle_h{h}_np{np_}"
    run(exe, np_, AXI + ["-cell_size", str(h)], d)
    s = summary(d)
    r = s["results"]
    err[(h, np_)] = (r, {k: r[k] / ex[k] - 1 for k in ex})
    print(f"     h = {h}, {np_} rank(s): " + ", ".join(f"{k} {v:+.2e}" for k, v in
                                                     err[(h, np_)][1].items()))
r, e = err[(0.25, 1)]
for k, tol in (("sag", 3e-3), ("strain_centre", 2e-3), ("tension_rim", 1e-3),
               ("strain_rim", 1.5e-2), ("tension_hoop_rim", 1e-2)):
    c.le(f"h = 0.25 m: {k} against the membrane of revolution (relative)", abs(e[k]), tol)
for k in ("sag", "strain_centre"):
    c.check(f"{k}: the error falls by more than 2x from h = 0.5 to 0.25 m",
            abs(e[k]) < 0.5 * abs(err[(0.5, 1)][1][k]),
            f"({err[(0.5, 1)][1][k]:+.2e} -> {e[k]:+.2e})")
c.le("centre: hoop strain equals the meridional strain (relative)",
     abs(r["strain_hoop_centre"] / r["strain_centre"] - 1), 2e-3)
# the pinned rim point keeps its own weight, q (h / 2) a per radian (h = 0.25 m, one point per cell)
c.le("rim reaction + the rim point's weight = q a^2 / 2 per radian (relative)",
     abs((r["vertical_reaction"] + Q * 0.125 * A) / (0.5 * Q * A * A) - 1), 2e-3)
pts = np.genfromtxt(f"{out}/circle_h0.25_np1/chain_membrane.csv", delimiter=",", names=True)
c.check("the centre point stays on the axis", pts["x"][0] == 0.0, f"(x = {pts['x'][0]})")
r1, r2 = err[(0.5, 1)][0], err[(0.5, 2)][0]
worst = max(abs(r2[k] - r1[k]) / max(abs(r1[k]), 1e-300) for k in ex)
c.le("1 and 2 ranks agree (largest relative difference of the results)", worst, 1e-12)
d = f"{out}/circle_tension_only"
run(exe, 1, AXI + ["-cell_size", "0.5", "-mat_membrane_law", "tension_only"], d)
c.le("tension_only: the linear law's sag where nothing compresses (relative)",
     abs(summary(d)["results"]["sag"] / r1["sag"] - 1), 1e-6)

# 2. a level cover on the axis: pressures on both faces, no strain, no slip
d = f"{out}/column"
run(exe, 2, ["-options_file", "tests/cover_zones.opts", "-geometry", "axisymmetric"], d)
p = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
h = 0.25
inner = (p["x0"] > 2 * h) & (p["x0"] < 4.0 - 2 * h)
sheet_w = 9.4e3 * 0.0015
c.le("column: upper-face pressure = the soil's weight 9,000 Pa, 2 cells from axis and wall "
     "(largest relative difference)", float(np.abs(p["pressure_top"][inner] / 9000 - 1).max()),
     5e-3)
c.le("column: lower-face pressure = that + the sheet's weight (largest relative difference)",
     float(np.abs(p["pressure_bottom"][inner] / (9000 + sheet_w) - 1).max()), 5e-3)
c.le("column: the sheet unstrained (largest meridional or hoop strain)",
     float(max(np.abs(p["strain"]).max(), np.abs(p["strain_hoop"]).max())), 1e-5)
c.le("column: no slip on either face (m)",
     float(max(np.abs(p["slip_top"]).max(), np.abs(p["slip_bottom"]).max())), 1e-5)
rows = stages(d)
c.le("column: the sheet settles with the waste top (spread of its settlement, m)",
     float(np.ptp(p["uy"])), 1e-5)
print(f"     column: pressure at the first point (r = {p['x0'][0]:.3f} m) "
      f"{p['pressure_top'][0]:.0f} Pa, membrane settlement {rows[-1]['membrane_settlement']} m")

# 3. the round sinkhole
d = f"{out}/round"
code, _ = run(exe, 2, ["-options_file", "options/cover_sinkhole_round.opts", "-cell_size", "0.5",
                      "-estimate_error", "0"], d)
s = summary(d)
rows = stages(d)
c.check("round sinkhole: every stage converged",
        all(r_["converged"] == "1" for r_ in rows), f"({[r_['converged'] for r_ in rows]})")
c.check("round sinkhole: verdict PASS, exit 0", s["verdict"] == "PASS" and code == 0,
        f"({s['verdict']}, {code})")
v = s["results"]["void"]
c.check("round sinkhole: the comparison is for a round void (Giroud's cap, Terzaghi's round "
        "trapdoor)", v.get("round") is True and v["B"] == 8 and "giroud_strain" in v,
        f"({v.get('round')}, B {v['B']})")
p = np.genfromtxt(f"{d}/chain_hdpe.csv", delimiter=",", names=True)
c.check("round sinkhole: the sheet has no hole (its first point on the axis, and it stays there)",
        p["x0"][0] == 0.0 and p["x"][0] == 0.0, f"(x0 {p['x0'][0]}, x {p['x'][0]})")
print(f"     round sinkhole: peak {100 * s['design']['answers']['peak_strain']:.3f} % "
      f"(Giroud's cap {100 * v['giroud_strain']:.3f} %), sag {v['pmpm_sag']:.3f} m "
      f"(Giroud {v['giroud_sag']:.3f} m), pressure {v['pmpm_pressure']:.0f} Pa (Terzaghi "
      f"{v.get('terzaghi_K1', 0):.0f}-{v.get('terzaghi_Ka', 0):.0f} Pa)")
c.done()
