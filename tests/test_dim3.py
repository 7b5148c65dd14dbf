"""-dim 3 -depth D against the 2D run: the column extruded along z with rollers on both z faces is
in plane strain, so every particle of the 3D run must follow its 2D parent (docs/method.md,
"Three dimensions").

usage: test_dim3.py EXE OUTDIR

1. Fixed step count (-tol tiny, so every run takes the same steps): the column (linear elastic,
   h = 0.0625 m, 2 ppc) in 2D on 1 rank, and extruded over 0.5 m (8 cells, 16 particles along z)
   on 1 rank, 2 ranks (PETSc's process grid), 4 ranks as 2x2x1 and as 1x1x4. Each 3D particle's
   x, y and its stresses xx, yy, zz, xy equal its 2D parent's (id // 16) to 1e-10 of the column
   height and of the largest stress; its z stays put and its out-of-plane shears yz, xz stay zero
   to the same bounds. The 3D runs agree among themselves by the same token (rank invariance).
   The same on one rank for neo-Hookean at 26 % compression, von Mises and Drucker-Prager
   (both yielding at the base: the 3D return maps on a plane-strain path; the two plastic laws
   also on 4 ranks as 2x1x2 against the 1-rank 3D run, positions and eps_p), and cpGIMP on 2 ranks
   (its blocks' half-sizes from the 3D polar decomposition against 2D's closed form).
2. Converged (the column's own tolerance): the 3D settlement equals the 2D one to 1e-10 of the
   height and the closed-form errors equal the 2D run's. The two runs stop a few steps apart
   (the unbalanced-force ratio divides by the mean nodal load, which the z faces' half-loaded
   nodes lower in 3D), so the bound is the position bound, not round-off.
The bar between free z faces against the closed form of uniaxial stress (only 3D has it); the
   vibrating bar (explicit dynamics) against its 2D run, and between free z faces at nu = 0.3
   against the period of the modulus E / (1 - nu^2).
   Checkpoint and restart in 3D against the uninterrupted run: bit for bit on 1 rank, 1e-10 on 2
   and 4 (1x1x4) ranks; a restart that changes -depth is refused.
   -balance setup on 1x2x2 ranks: the y cut moves so each rank holds 1/4 of the particles (1.125
   to 1.0), counted from the plane before any 3D particle exists, and the particles do not change.
3. The summary and the particles file say 3D: cells [4, 18, 8], the partition's three
   directions, XYZ geometry in the .xmf.
The 1e-10 bounds: round-off after a few hundred steps of sums that differ in order between 2D and
3D (measured: a few 1e-13), with three orders of margin; a wrong z coupling, a lost shear or a
mis-weighted z-face node is of the order of the strain itself (1e-4 and up).
"""
import re
import subprocess
import sys
import numpy as np
from pmpmtest import ENV, Checks, compare_extruded, particles, run, summary, uniaxial_bar

exe, out = sys.argv[1], sys.argv[2]
c = Checks("dim3")
H = 1.0
BASE = ["-options_file", "options/column.opts", "-cell_size", "0.0625"]
FIXED = ["-tol", "1e-30", "-max_steps", "400", "-ramp_steps", "200"]
D3 = ["-dim", "3", "-depth", "0.5"]
NZ = 16  # particles along z: 8 cells x 2 ppc
FIELDS = ("position", "position0", "stress")

MATERIALS = {
    "elastic": [],
    "neo_hookean": ["-mat_column_model", "neo_hookean", "-mat_column_E", "1e6",
                    "-mat_column_nu", "0", "-mat_column_gamma", "3e5"],
    "von_mises": ["-mat_column_model", "von_mises", "-mat_column_yield_stress", "5e3",
                  "-mat_column_hardening", "1e5"],
    "drucker_prager": ["-mat_column_model", "drucker_prager", "-mat_column_cohesion", "1e3",
                       "-mat_column_friction_angle", "5", "-mat_column_dilation_angle", "0"],
}


def compare_to_2d(name, p2, p3, nz=NZ, axis=1, moved=1e-5):
    """Every 3D particle (nz along z per 2D particle) against its 2D parent, and the 2D run's
    largest displacement along `axis` at least `moved` x H (the body did deform)."""
    r = compare_extruded(c, name, p2, p3, nz, H, "H")
    if r is not None:
        x2, x02 = r
        c.ge(f"{name}: the body deformed (max |u_{'xy'[axis]}| / H)",
             np.abs(x2[:, axis] - x02[:, axis]).max() / H, moved)


# 1. fixed steps, linear elastic on 1, 2 and 4 ranks
run(exe, 1, BASE + FIXED, out + "/2d", capped=True)
ref = particles(out + "/2d", FIELDS)
runs3 = {}
for label, np_, grid in [("np1", 1, []), ("np2", 2, []),
                         ("np4_2x2x1", 4, ["-da_processors_x", "2", "-da_processors_y", "2",
                                           "-da_processors_z", "1"]),
                         ("np4_1x1x4", 4, ["-da_processors_x", "1", "-da_processors_y", "1",
                                           "-da_processors_z", "4"])]:
    run(exe, np_, BASE + FIXED + D3 + grid, out + "/3d_" + label, capped=True)
    runs3[label] = particles(out + "/3d_" + label, FIELDS)
    compare_to_2d("elastic 3D " + label, ref, runs3[label])
s = summary(out + "/3d_np4_1x1x4")
c.check("1x1x4: the partition has 4 ranks along z", s["partition"]["processes"] == [1, 1, 4],
        str(s["partition"]["processes"]))
s = summary(out + "/3d_np4_2x2x1")
c.check("2x2x1: the partition", s["partition"]["processes"] == [2, 2, 1],
        str(s["partition"]["processes"]))
x1 = runs3["np1"][1]["position"]
for label in ("np2", "np4_2x2x1", "np4_1x1x4"):
    c.le(f"3D {label} positions equal 1 rank's (/H)",
         np.abs(runs3[label][1]["position"] - x1).max() / H, 1e-10)

# -balance setup in 3D (balance.hpp, BalanceSetupExtruded): the column fills 16 of the grid's 18
# cell rows, so PETSc's even split of 1x2x2 ranks gives 9 and 9 rows, 1152 and 896 particles a
# rank (max / mean 1.125); the plane's counts cut the rows at 8 (1024 each, 1.0). The imbalances
# the summary reports are counted from the plane before the particles exist: they must equal the
# ranks' particle counts after; the balanced run's particles equal the unbalanced run's.
BAL = BASE + FIXED + D3 + ["-da_processors_x", "1", "-da_processors_y", "2", "-da_processors_z",
                           "2"]
bal = {}
for mode in ("setup", "none"):
    run(exe, 4, BAL + ["-balance", mode], out + "/3d_balance_" + mode, capped=True)
    bal[mode] = summary(out + "/3d_balance_" + mode)
    counts = np.array(bal[mode]["partition"]["particles_per_rank"], dtype=float)
    c.le(f"balance {mode}: reported imbalance equals the ranks' counts' max / mean",
         abs(bal[mode]["balance"]["imbalance_after"] - counts.max() / counts.mean()), 1e-12)
    c.le(f"balance {mode}: positions equal 1 rank's (/H)",
         np.abs(particles(out + "/3d_balance_" + mode, FIELDS)[1]["position"] - x1).max() / H,
         1e-10)
bs, bn = bal["setup"]["balance"], bal["none"]["balance"]
c.check("balance setup: rebuilt the grid", bs["rebuilt"] is True and bn["rebuilt"] is False)
c.le("balance setup: the imbalance before equals the unbalanced run's",
     abs(bs["imbalance_before"] - bn["imbalance_after"]), 1e-12)
c.le("balance setup: PETSc's split 1.125 lowered to 1.0 (after)", bs["imbalance_after"], 1.0 + 1e-12)
c.ge("balance setup: PETSc's split was imbalanced (before)", bs["imbalance_before"], 1.1)

# a stage at its step cap names the node of the largest unbalanced force; in 3D with its z. After
# 20 steps the column's largest force sits on the top row of nodes (y = 0.9375 m; its x is a tie
# between mirror nodes); the 3D force at an interior z node is the 2D force per unit depth times
# the node's depth share h (2D 3.12 N/m, 3D 0.195 N: printed to 3 digits, so 1 % bound).
NODE = re.compile(r"largest unbalanced force \((\S+) (N/m|N)\) is at the node \(([^)]*)\) m")
caps = {}
for tag, np_, extra in (("2d", 1, []), ("3d", 2, D3)):
    p = subprocess.run(["mpiexec", "-n", str(np_), exe] + BASE + extra +
                       ["-max_steps", "20", "-output_dir", out + "/cap_" + tag], env=ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    m = NODE.search(p.stdout)
    ok = p.returncode == 3 and m is not None
    c.check(f"capped {tag}: exit 3 and the node of the largest force in the log", ok,
            "" if ok else p.stdout[-300:])
    if m:
        caps[tag] = (float(m.group(1)), m.group(2), [float(v) for v in m.group(3).split(",")])
if len(caps) == 2:
    (f2, u2, x2), (f3, u3, x3) = caps["2d"], caps["3d"]
    c.check("capped 3D: the node has x, y, z and the force is in N (2D: x, y and N/m)",
            len(x3) == 3 and u3 == "N" and len(x2) == 2 and u2 == "N/m", f"{x3} {u3}")
    c.le("capped 3D: the node's y equals 2D's", abs(x3[1] - x2[1]), 1e-12)
    c.check("capped 3D: the node's z inside the depth", len(x3) == 3 and 0 < x3[2] < 0.5, str(x3))
    c.le("capped 3D: force = 2D force x h (relative)", abs(f3 / (f2 * 0.0625) - 1), 1e-2)

# the other three laws on one rank
for name, opts in MATERIALS.items():
    if name == "elastic":
        continue
    run(exe, 1, BASE + opts + FIXED, out + "/2d_" + name, capped=True)
    run(exe, 1, BASE + opts + FIXED + D3, out + "/3d_" + name, capped=True)
    compare_to_2d(name + " 3D", particles(out + "/2d_" + name, FIELDS + ("eps_p",)),
                  particles(out + "/3d_" + name, FIELDS))
    if name in ("von_mises", "drucker_prager"):
        ep = particles(out + "/3d_" + name, ("eps_p",))[1]["eps_p"]
        c.ge(f"{name} 3D: the base yielded (max eps_p)", float(np.max(ep)), 1e-6)
        # the plastic state across ranks: 4 ranks as 2x1x2 against the 1-rank 3D run
        run(exe, 4, BASE + opts + FIXED + D3 + ["-da_processors_x", "2", "-da_processors_y", "1",
                                                "-da_processors_z", "2"],
            out + "/3d_" + name + "_np4", capped=True)
        ids4, f4 = particles(out + "/3d_" + name + "_np4", ("position", "eps_p"))
        ids1, f1 = particles(out + "/3d_" + name, ("position", "eps_p"))
        c.check(f"{name} 3D np4 (2x1x2): the same particles", np.array_equal(ids4, ids1))
        c.le(f"{name} 3D np4 (2x1x2): positions equal 1 rank's (/H)",
             np.abs(f4["position"] - f1["position"]).max() / H, 1e-10)
        c.le(f"{name} 3D np4 (2x1x2): eps_p equal 1 rank's (/max eps_p)",
             np.abs(f4["eps_p"] - f1["eps_p"]).max() / np.max(ep), 1e-10)

# the method's variants on one rank: MUSL, standard MPM (-shape mpm), APIC (its B_p in 3x3),
# local damping, FIRE (30 steps: its restarts are discrete events that turn round-off into 1e-8
# differences later on, as 2D shows between 1 and 2 ranks: 9e-10 after 300 steps), and a
# surcharge (-bc_ymax_traction: the extruded load table)
for name, opts in [("musl", ["-musl"]), ("mpm", ["-shape", "mpm"]),
                   ("apic", ["-transfer", "apic"]),
                   ("local damping", ["-damping", "local"]),
                   ("fire", ["-damping", "fire", "-max_steps", "30"]),
                   ("surcharge", ["-bc_ymax_traction", "0,-2e4"])]:
    tag = name.replace(" ", "_")
    run(exe, 1, BASE + FIXED + opts, out + "/2d_" + tag, capped=True)
    run(exe, 1, BASE + FIXED + opts + D3, out + "/3d_" + tag, capped=True)
    compare_to_2d(name + " 3D", particles(out + "/2d_" + tag, FIELDS),
                  particles(out + "/3d_" + tag, FIELDS))

# cpGIMP on 2 ranks (its blocks follow F: the neo-Hookean column, 26 % compression, so the blocks
# shrink along y by V_yy; in 3D V comes from the polar decomposition, in 2D from its closed form;
# measured 7.8e-16 of H and 1.5e-14 of the stress; the eigen decomposition it replaced was 1e-12
# off per step and reached 9.7e-11 of the stress). The written half-sizes equal the 2D ones.
CPG = BASE + MATERIALS["neo_hookean"] + FIXED + ["-shape", "cpgimp"]
run(exe, 2, CPG, out + "/2d_cpgimp", capped=True)
run(exe, 2, CPG + D3, out + "/3d_cpgimp", capped=True)
p2c = particles(out + "/2d_cpgimp", FIELDS + ("halfsize",))
p3c = particles(out + "/3d_cpgimp", FIELDS + ("halfsize",))
compare_to_2d("cpgimp 3D (2 ranks)", p2c, p3c)
par = np.searchsorted(p2c[0], p3c[0] // NZ)
l2, l3 = p2c[1]["halfsize"][par], p3c[1]["halfsize"]
c.le("cpgimp 3D: half-sizes x, y equal the 2D run's (/h)", np.abs(l3[:, :2] - l2).max() / 0.0625,
     1e-10)
c.le("cpgimp 3D: half-size z stays h/4 (/h)", np.abs(l3[:, 2] - 0.015625).max() / 0.0625, 1e-10)
c.le("cpgimp 3D: the blocks shrank along y (min l_y / (h/4))", l2[:, 1].min() / 0.015625, 0.9)

# two layers of a stiffness and weight contrast (the layers scene, E 1e7 over 1e6, gamma 2e4
# over 1e4: two materials, -inertia_scaling wave_speed), 2 ranks
LAY = ["-options_file", "options/layers.opts", "-cell_size", "0.0625", "-mat_top_E", "1e6",
       "-mat_top_gamma", "1e4"] + FIXED
run(exe, 1, LAY, out + "/layers_2d", capped=True)
run(exe, 2, LAY + D3, out + "/layers_3d", capped=True)
compare_to_2d("layers 3D (2 ranks)", particles(out + "/layers_2d", FIELDS),
              particles(out + "/layers_3d", FIELDS))

# the bar under end traction (a face load, the xmax face), 2 ranks; its length L = 1 m = H, so
# the bounds read the same; 2 cells x 2 ppc along z; it stretches along x
BAR = ["-options_file", "options/bar.opts", "-tol", "1e-30", "-max_steps", "400"]
run(exe, 1, BAR, out + "/bar_2d", capped=True)
run(exe, 2, BAR + ["-dim", "3", "-depth", "0.1"], out + "/bar_3d", capped=True)
compare_to_2d("bar 3D (2 ranks)", particles(out + "/bar_2d", FIELDS),
              particles(out + "/bar_3d", FIELDS), nz=4, axis=0, moved=1e-6)
run(exe, 2, ["-options_file", "options/bar.opts", "-dim", "3", "-depth", "0.1"], out + "/bar_conv")
rb = summary(out + "/bar_conv")["results"]
c.le("bar 3D converged: tip displacement against the closed form (2D: 8.6e-6)",
     rb["tip_displacement_error_rel"], 1e-4)

# the vibrating bar (explicit dynamics: -dynamic, undamped FLIP, nu = 0), 700 steps (4.4
# periods: the displacement is 0.7 of its amplitude), 2 ranks: particle by particle against 2D,
# the same period, the energy 2D's times the depth. Between free z faces at nu = 0.3 (y on
# rollers) the bar has sigma_zz = 0 and eps_yy = 0, modulus E / (1 - nu^2): the period is
# sqrt(1 - nu^2) of nu = 0's (0.0382 s), which plane strain (0.04 s x sqrt((1 + nu)(1 - 2 nu) /
# (1 - nu)) = 0.0345 s) cannot give; measured 0.12 % off (2D's own period error: 0.08 %), bound
# 1 % (the 2D vibration test's).
VIB = ["-options_file", "options/bar_vibration.opts", "-max_steps", "700"]
run(exe, 1, VIB, out + "/vib_2d")
run(exe, 2, VIB + ["-dim", "3", "-depth", "0.1"], out + "/vib_3d")
compare_to_2d("vibrating bar 3D (2 ranks)", particles(out + "/vib_2d", FIELDS),
              particles(out + "/vib_3d", FIELDS), nz=4, axis=0, moved=1e-6)
v2, v3 = summary(out + "/vib_2d")["results"], summary(out + "/vib_3d")["results"]
c.le("vibrating bar 3D: period equals 2D's (relative)", abs(v3["period"] / v2["period"] - 1),
     1e-10)
c.le("vibrating bar 3D: energy equals 2D's times the depth (relative)",
     abs(v3["energy_final"] / (0.1 * v2["energy_final"]) - 1), 1e-10)
run(exe, 2, VIB + ["-dim", "3", "-depth", "0.1", "-mat_bar_nu", "0.3", "-bc_zmin", "free",
                   "-bc_zmax", "free"], out + "/vib_free_z")
vf = summary(out + "/vib_free_z")["results"]
T_mixed = vf["period_exact"] * np.sqrt(1 - 0.3 ** 2)
c.le("vibrating bar between free z faces: period against sqrt(1 - nu^2) T0 (relative)",
     abs(vf["period"] / T_mixed - 1), 1e-2)

# a closed form only 3D has: the bar between free z faces is in uniaxial stress, u_x = t x / E,
# u_y = -nu t y / E, u_z = -nu t (z - z_mid) / E (plane strain: t (1 - nu^2) x / E and
# -nu (1 + nu) t y / E, 9.9 % and 30 % away). The lateral slopes are least-squares fits over every
# particle; the state is uniform, so they are exact up to the relaxation's tolerance: bound 1e-4
# (measured 4.4e-6, as the tip's 1.1e-5), far below those gaps.
run(exe, 1, ["-options_file", "options/bar.opts", "-dim", "3", "-depth", "0.1", "-bc_zmin",
             "free", "-bc_zmax", "free"], out + "/bar_uniaxial")
uniaxial_bar(c, out + "/bar_uniaxial")

# checkpoint and restart in 3D: resumed from step 100 on 1 rank (bit for bit), on 2 ranks and from
# step 200 on 4 ranks as 1x1x4 (the particles sent to their cells' owners), against the
# uninterrupted 300-step run; a restart that changes -depth is refused, naming it
R = BASE + ["-tol", "1e-30", "-max_steps", "300", "-ramp_steps", "100"] + D3
run(exe, 1, R, out + "/restart_full", capped=True)
run(exe, 1, R + ["-checkpoint_every", "100"], out + "/restart_ck", capped=True)
ids0, f0 = particles(out + "/restart_full", FIELDS)
for label, np_, ck, grid in [("1 rank", 1, 100, []), ("2 ranks", 2, 100, []),
                             ("4 ranks 1x1x4", 4, 200, ["-da_processors_x", "1",
                                                        "-da_processors_y", "1",
                                                        "-da_processors_z", "4"])]:
    tag = label.replace(" ", "_")
    run(exe, np_, R + grid + ["-restart", f"{out}/restart_ck/checkpoint_{ck}.h5"],
        out + "/restart_" + tag, capped=True)
    ids, f = particles(out + "/restart_" + tag, FIELDS)
    same = len(ids) == len(ids0) and np.all(ids == ids0)
    c.check(f"restart on {label} from step {ck}: the same particles", same)
    if not same:
        continue
    dx = np.abs(f["position"] - f0["position"]).max() / H
    ds = np.abs(f["stress"] - f0["stress"]).max() / np.abs(f0["stress"]).max()
    if np_ == 1:
        c.check(f"restart on {label}: bit for bit", dx == 0 and ds == 0, f"{dx:g} {ds:g}")
    else:
        c.le(f"restart on {label}: positions (/H)", dx, 1e-10)
        c.le(f"restart on {label}: stresses (/max |stress|)", ds, 1e-10)
rc, log = run(exe, 1, BASE + ["-dim", "3", "-depth", "0.25", "-restart",
                              f"{out}/restart_ck/checkpoint_100.h5"],
              out + "/restart_depth", expect_ok=False)
c.check("restart with another -depth refused, naming it", rc == 1 and "-depth" in log,
        log.strip().splitlines()[0] if log.strip() else "")

# 2. converged, against the closed form and the 2D run
run(exe, 1, BASE, out + "/2d_conv")
run(exe, 2, BASE + D3, out + "/3d_conv")
s2, s3 = summary(out + "/2d_conv"), summary(out + "/3d_conv")
c.check("3D converged", s3["converged"] is True)
r2, r3 = s2["results"], s3["results"]
c.le("converged settlement: 3D - 2D (/H)", abs(r3["top_settlement"] - r2["top_settlement"]) / H,
     1e-10)
c.le("converged stress L2 error: 3D - 2D", abs(r3["stress_l2_error_rel"] - r2["stress_l2_error_rel"]),
     1e-8)
c.le("converged stress L2 error against the closed form (2D's at h = H/16: 2.7 %)",
     r3["stress_l2_error_rel"], 0.03)

# 3. what the files say
c.check("summary cells [4, 18, 8]", s3["cells"] == [4, 18, 8], str(s3["cells"]))
c.check("partition has z ranges", "nodes_z" in s3["partition"] and
        "cell_bounds_z" in s3["partition"])
with open(out + "/3d_conv/particles.xmf") as f:
    xmf = f.read()
c.check("particles.xmf: XYZ geometry, 3-vectors, 6 stress components",
        'GeometryType="XYZ"' in xmf and "Dimensions=\"%d 3\"" % s3["particles"] in xmf and
        "Dimensions=\"%d 6\"" % s3["particles"] in xmf)
c.done()
