"""The landfill with the paper's Coulomb friction-slip interface (mu = 0.3 on both faces) against
the bonded case at h = 0.5 mm (the membrane must span two cells so that its two faces do not
share nodes): the membrane slips where it bends and its peak strain differs.
Measured: slip at the top face 3.2e-5 m against 6.7e-6 m bonded (4.7x), peak strain 1.839 %
against 1.756 % (+4.7 %). Bounds: slip at least 3x bonded, peak strain differs by at least 2 %.

usage: test_landfill_friction.py EXE NP OUTDIR
"""
import sys
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"landfill_friction_np{np}")
run(exe, np, ["-options_file", "options/landfill.opts"], out + "/bonded")
run(exe, np, ["-options_file", "options/landfill_friction.opts"], out + "/friction")
b = summary(out + "/bonded")
f = summary(out + "/friction")
c.check("friction run converged", f["converged"] is True)
c.ge("top-face slip, friction / bonded", f["results"]["max_slip_top"] / b["results"]["max_slip_top"], 3.0)
c.ge("peak strain differs from bonded (relative)",
     abs(f["results"]["peak_axial_strain"] / b["results"]["peak_axial_strain"] - 1), 0.02)
c.done()
