"""-solver newton in 3D (-dim 3): extruded scenes against their 2D Newton runs, the rank count,
a closed form only 3D has, moving supports, and the refusal of a rigid translation.

usage: test_newton3d.py EXE OUTDIR

1. The column (options/column.opts, h = 0.125 m, 3 load steps) extruded over 1 m (8 cells, 16
   particles along z) between rollers is in plane strain: under Newton every 3D particle must
   follow its 2D parent (compare_extruded: x, y and stresses to 1e-10, z put, yz and xz zero),
   for the four laws (linear elastic, neo-Hookean, von Mises and Drucker-Prager yielding at the
   base). The 3D runs take the 2D default linear solver (MUMPS LU), so both solve the same
   equations exactly: measured 0 to 1e-15. The 3D default (GMRES with BoomerAMG to 1e-8, the
   Newton iterations stopping at the same residual) on von Mises: positions within 1e-9 of the
   height (measured 4e-16), in the same Newton iterations (9).
2. Rank invariance: von Mises extruded on 2 ranks, 4 ranks as 2x2x1 and as 1x1x4, LU, against 1
   rank: positions and stresses to 1e-10 (round-off of MUMPS's parallel factorisation).
3. The bar (options/bar.opts) with z faces roller and free is in uniaxial stress (a closed form
   only 3D has): tip displacement t L / E and the lateral slopes -nu t / E within 1e-4 (measured
   1.1e-5), as test_dim3 asserts of relaxation.
4. Moving supports in 3D: the trapdoor (test_trapdoor_newton's case, one door stage of 0.2 % B in
   5 load steps) extruded over 0.25 m on 2 ranks, the default GMRES: the door's pressure equals
   the 2D run's to 1e-7 gamma H (measured equal to the 9 digits trapdoor.csv writes).
5. The bar between two free z faces under Newton is refused before the run (exit 1, the message
   names -bc_zmin and -bc_zmax, no output): its rigid z translation makes the matrix singular.
The 1e-10 bounds are those of test_dim3 (round-off with three orders of margin); a wrong z
coupling, a lost shear or a misweighted z-face node is of the order of the strain (1e-4 and up).
"""
import csv
import os
import sys

import numpy as np
from pmpmtest import Checks, compare_extruded, particles, run, summary, uniaxial_bar

exe, out = sys.argv[1], sys.argv[2]
c = Checks("newton3d")
H = 1.0
NEWTON = ["-solver", "newton"]
COLUMN = ["-options_file", "options/column.opts", "-cell_size", "0.125", "-newton_load_steps",
          "3"] + NEWTON
D3 = ["-dim", "3", "-depth", "1"]
NZ = 16  # particles along z per 2D particle: 8 cells x 2 ppc
LU = ["-ksp_type", "preonly", "-pc_type", "lu", "-pc_factor_mat_solver_type", "mumps"]
FIELDS = ("position", "position0", "stress")
MATERIALS = {
    "linear_elastic": [],
    "neo_hookean": ["-mat_column_model", "neo_hookean"],
    "von_mises": ["-mat_column_model", "von_mises", "-mat_column_yield_stress", "6e3",
                  "-mat_column_hardening", "1e5"],
    "drucker_prager": ["-mat_column_model", "drucker_prager", "-mat_column_cohesion", "1e3",
                       "-mat_column_friction_angle", "5", "-mat_column_dilation_angle", "0"],
}


def yielded(d):
    _, f = particles(d, ("eps_p",))
    return int(np.count_nonzero(f["eps_p"] > 0))


# 1. extruded against 2D, each law
for name, args in MATERIALS.items():
    run(exe, 1, COLUMN + args, f"{out}/{name}_2d")
    run(exe, 1, COLUMN + args + D3 + LU, f"{out}/{name}_3d")
    compare_extruded(c, f"{name} 3D (LU)", particles(f"{out}/{name}_2d", FIELDS),
                     particles(f"{out}/{name}_3d", FIELDS), NZ, H, "H")
    s3 = summary(f"{out}/{name}_3d")
    c.check(f"{name} 3D: converged", s3["converged"] is True)
    if name in ("von_mises", "drucker_prager"):
        n2, n3 = yielded(f"{out}/{name}_2d"), yielded(f"{out}/{name}_3d")
        c.check(f"{name}: particles yield, {NZ} 3D ones per 2D one ({n2}, {n3})",
                n2 > 0 and n3 == NZ * n2)

# the 3D default linear solver
VM = COLUMN + MATERIALS["von_mises"] + D3
run(exe, 1, VM, f"{out}/von_mises_3d_gmres")
(i1, f1), (ig, fg) = (particles(f"{out}/von_mises_3d", FIELDS),
                      particles(f"{out}/von_mises_3d_gmres", FIELDS))
c.le("von Mises 3D, GMRES + BoomerAMG against LU: positions (/H)",
     np.abs(fg["position"] - f1["position"]).max() / H, 1e-9)
n_lu = summary(f"{out}/von_mises_3d")["newton"]["nonlinear_iterations"]
n_it = summary(f"{out}/von_mises_3d_gmres")["newton"]["nonlinear_iterations"]
c.check(f"von Mises 3D, GMRES + BoomerAMG: the LU's Newton iterations ({n_it}, {n_lu})",
        n_it == n_lu)

# 2. rank invariance
GRIDS = {"2 ranks": (2, []),
         "4 ranks 2x2x1": (4, ["-da_processors_x", "2", "-da_processors_y", "2",
                               "-da_processors_z", "1"]),
         "4 ranks 1x1x4": (4, ["-da_processors_x", "1", "-da_processors_y", "1",
                               "-da_processors_z", "4"])}
smax = np.abs(f1["stress"]).max()
for label, (n, grid) in GRIDS.items():
    d = f"{out}/von_mises_3d_np{n}_{'x'.join(grid[1::2]) or 'petsc'}"
    run(exe, n, VM + LU + grid, d)
    ids, f = particles(d, FIELDS)
    same = len(ids) == len(i1) and np.array_equal(ids, i1)
    c.check(f"{label}: the same particles as 1 rank", same)
    if same:
        c.le(f"{label}: positions against 1 rank (/H)",
             np.abs(f["position"] - f1["position"]).max() / H, 1e-10)
        c.le(f"{label}: stresses against 1 rank (/max |stress|)",
             np.abs(f["stress"] - f1["stress"]).max() / smax, 1e-10)

# 3. the uniaxial bar
BAR = ["-options_file", "options/bar.opts", "-dim", "3", "-depth", "0.1"] + NEWTON
run(exe, 1, BAR + ["-bc_zmin", "roller", "-bc_zmax", "free"], f"{out}/bar_uniaxial")
c.check("bar, z faces roller and free: converged", summary(f"{out}/bar_uniaxial")["converged"])
uniaxial_bar(c, f"{out}/bar_uniaxial")

# 4. the trapdoor's moving supports in 3D
DOOR = ["-options_file", "options/trapdoor.opts", "-cell_size", "0.125", "-trapdoor_height", "1",
        "-trapdoor_soil_width", "2", "-trapdoor_displacements", "0.002",
        "-newton_load_steps", "5"] + NEWTON


def door(d):
    with open(f"{d}/trapdoor.csv") as f:
        return [float(r["pressure_over_gammaH"]) for r in csv.DictReader(f)]


run(exe, 1, DOOR, f"{out}/door_2d")
run(exe, 2, DOOR + ["-dim", "3", "-depth", "0.25"], f"{out}/door_3d")
p2, p3 = door(f"{out}/door_2d"), door(f"{out}/door_3d")
c.check(f"trapdoor 3D: both stages converged ({p3})",
        len(p3) == 2 and summary(f"{out}/door_3d")["converged"] is True)
c.le("trapdoor 3D (2 ranks) against 2D: door pressure (/gamma H)",
     max(abs(a - b) for a, b in zip(p2, p3)), 1e-7)
c.check("trapdoor: the door's pressure falls (arching)", p3[1] < 0.75)

# 5. a rigid translation is refused before the run
rc, log = run(exe, 1, BAR + ["-bc_zmin", "free", "-bc_zmax", "free"], f"{out}/bar_free",
              expect_ok=False)
c.check("bar between free z faces: refused (exit 1), naming -bc_zmin and -bc_zmax, no output",
        rc == 1 and "-bc_zmin" in log and "-bc_zmax" in log
        and not os.path.exists(f"{out}/bar_free/summary.json"), log.strip()[-300:])
c.done()
