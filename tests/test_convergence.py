"""Column mesh convergence: PMPM's L2 stress error must fall >= 1.7x per halving of h over three
refinements (8, 16, 32, 64 cells over the height); standard MPM is reported beside it.
Expected first order for GIMP-type shapes (docs/method.md, section 2.2); measured 2.02, 2.03, 2.07.

usage: test_convergence.py EXE NP OUTDIR
"""
import sys
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks("column_convergence")
levels = [8, 16, 32, 64]
errs = {}
for shape in ("pmpm", "mpm"):
    errs[shape] = []
    for n in levels:
        d = f"{out}/{shape}_{n}"
        run(exe, np, ["-options_file", "options/column.opts", "-shape", shape,
                      "-cell_size", repr(1.0 / n)], d)
        s = summary(d)
        errs[shape].append((s["results"]["stress_l2_error_rel"],
                            s["results"]["displacement_l2_error_rel"]))
print("cells  pmpm_stress  pmpm_disp    mpm_stress   mpm_disp")
for i, n in enumerate(levels):
    print(f"{n:5d}  {errs['pmpm'][i][0]:.4e}   {errs['pmpm'][i][1]:.4e}   "
          f"{errs['mpm'][i][0]:.4e}   {errs['mpm'][i][1]:.4e}")
for i in range(1, len(levels)):
    c.ge(f"PMPM stress error ratio {levels[i-1]}->{levels[i]}",
         errs["pmpm"][i - 1][0] / errs["pmpm"][i][0], 1.7)
c.done()
