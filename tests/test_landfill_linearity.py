"""Load I is exactly half of load II under small strain: with every unit weight scaled by 1e-3
(strains of 1e-4, geometric nonlinearity 1e-4), the settlement ratio must be 0.5 to 1e-3.

usage: test_landfill_linearity.py EXE NP OUTDIR
"""
import sys
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"landfill_linearity_np{np}")
scaled = {"options/landfill.opts": ["1.5e6", "9.55e3", "2.0e3", "2.0"],
          "options/landfill_load1.opts": ["7.5e5", "5.0e3", "1.0e3", "1.0"]}
res = {}
for opts, gam in scaled.items():
    d = f"{out}/{opts.split('/')[-1]}"
    args = ["-options_file", opts, "-cell_size", "0.001", "-tol", "1e-7"]
    for mat, g in zip(("soil", "membrane", "waste", "soft"), gam):
        args += [f"-mat_{mat}_gamma", g]
    run(exe, np, args, d)
    res[opts] = summary(d)["results"]
ratio = res["options/landfill_load1.opts"]["settlement_centre"] / res["options/landfill.opts"]["settlement_centre"]
c.le("small-strain settlement ratio load I / load II - 0.5", abs(ratio - 0.5), 1e-3)
c.done()
