"""The cover scene in 3D (-dim 3): its membrane a 3D sheet between the waste and the cover soil,
friction cones on both faces (sheet_contact.hpp), against a closed form, against the same scene
as a body of revolution, and on several ranks.

usage: test_cover3d.py EXE NP OUTDIR

1. Uniform degradation (tests/cover_column.opts, extruded over 0.5 m: 4 m of linear elastic waste
   on rollers under 0.5 m of soil on the sheet, e_v = 0.05 per stage, vertical and isotropic
   eigenstrain). As in tests/test_cover.py: in uniaxial strain every waste height scales by the
   eigenstrain alone (isotropic: times (1 + nu) / (1 - nu) / 3, the z rollers restraining as
   plane strain does); the top row of waste settles by the closed form within 0.5 % per stage;
   the sheet follows the waste within 2 %; its strain stays zero (peak < 1e-5); every stage
   converges to -tol 1e-5.
2. A round void (options/cover_sinkhole_3d.opts at h = 0.5 m, the void growing 0.5, 1, 1.5,
   2 m across: the stages before the clay fails) against the same cover as a body of revolution
   (-dim 2 -geometry axisymmetric, the same layers, sheet and frictions, a cylinder of the box's
   width) at h = 0.25 and 0.125 m. The axisymmetric runs converge slowly (the 0.45 m clay plate is
   two to four particle rows thick): their membrane settlement at the 2 m void is 17.1, 15.3,
   11.6 mm at h = 0.5, 0.25, 0.125 m, where the 3D one is 11.9 and 11.8 mm at 0.5 and 0.25 m
   (docs/cover.md, "A round void in 3D"). So at the 1.5 and 2 m voids the 3D membrane settlement
   must lie within the axisymmetric discretisation error, |axi(0.25) - axi(0.125)|, of
   axi(0.125) (measured: 0.4 of it at 1.5 m, 0.1 at 2 m), and at 2 m within 5 % of it (measured
   2.8 %). Every stage converges; the design answer is a PASS with the peak principal strain at the
   void's rim (within a cell of its radius, as in the axisymmetric runs: the sheet is strained
   most where it leaves its support) and the minor strain there smaller in size (measured -4 % of
   the major: the hoop hardly strains at the rim); summary.json has the void's Giroud comparison
   (round) and the sheet's files carry slip and pressure per face.
3. Waste zones in 3D (1 rank; tests/cover_zones.opts over 1 m of depth): the stiff zone across
   the whole box (its _x only), a round soft pocket (_centre 2,0.5, _radius 0.6, 2 to 3 m deep)
   and a band bounded in z (_x 0,1, _z 0,0.5, 3.2 to 3.9 m deep): every waste particle's material
   is the one its centre gives, computed here independently (exact: a classification).
   A degrading zone round in plan (-cover_shrink_centre, -cover_shrink_radius): one that covers
   the box gives the uniform run's stage record exactly; one of 1 m radius about the corner
   settles the sheet 77 mm at its centre and 9 mm 3.5 m away (bound: a fifth).
   A deck graded along z (-cover_deck_grade_z 5 over 4 m of depth, a 0.5 m wide box) against the
   same deck graded along x (-cover_deck_grade 5, 4 m wide, 0.5 m deep): the cover turned a
   quarter. Uniform isotropic degradation settles the top row of waste by the closed form of
   part 1 whatever the surface (rollers on every side and a fixed base: u_y = -e y in the waste
   changes no stress): the mean over the 128 columns within 0.5 % (measured 0.07 and 0.2 % at the
   two stages in both), every column within 1 % (measured 0.50 %); the two settlement profiles
   along their grades agree within 1 % of the largest (measured 0.09 %), the sheet's settlement
   and differential settlement within 1 % (measured 0.007 and 0.1 %).
4. Restart (1 rank): the short void cover (0.5, 1, 1.5 m) restarted from stage 0's end (after
   the sheet is laid) and from inside stage 2 gives the uninterrupted run's sheet and stage record
   bit for bit (the wall seconds aside).
5. On NP > 1 ranks (4: a 2 x 1 x 2 process grid, the sheet crossing rank boundaries in x and z),
   the stage record and the sheet's points agree with one rank to 1e-8 relative (measured: the
   stage record's 8 digits equal, the sheet's displacements to 2e-12; the 2D cover allows 1e-4,
   where kinetic-damping resets and stick / slip switches amplified the round-off). The deck
   graded along z, cut in y (2 ranks) and in y and z (4), against one rank: settlements equal
   to the record's 8 digits, the peak strain and the slip within 1e-5 (measured 8e-7 and 3e-7:
   the same deck graded along x and cut in x differs by 2e-7, the stick and slip of the sheet's
   faces amplifying round-off as in 2D).
"""
import math
import sys

import numpy as np
from pmpmtest import (Checks, particles, run, stages, summary, uniform_degradation,
                      waste_column_tops)

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"cover3d_np{np_}")
grid = {4: ["-da_processors_x", "2", "-da_processors_y", "1", "-da_processors_z", "2"]}.get(np_, [])

# 1. uniform degradation, extruded
uniform_degradation(c, exe, np_, out, ["-dim", "3", "-depth", "0.5"], "3D ")

# 2. a round void: 3D against the body of revolution
base = ["-options_file", "options/cover_sinkhole_3d.opts", "-cover_void_widths", "0.5,1,1.5,2",
        "-estimate_error", "0"]
axi = ["-dim", "2", "-depth", "0", "-geometry", "axisymmetric"]
d3 = f"{out}/round3d"
run(exe, np_, base + grid, d3)
rows3 = stages(d3)
c.check("round void 3D: five stages recorded, all converged",
        len(rows3) == 5 and all(r["converged"] == "1" for r in rows3),
        f"({[r['steps'] for r in rows3]} steps)")
if np_ == 1:
    for hc in (0.25, 0.125):
        run(exe, 1, base + axi + ["-cell_size", str(hc)], f"{out}/axi_{hc}")
    ra, rb = stages(f"{out}/axi_0.25"), stages(f"{out}/axi_0.125")
    key = "membrane_settlement"
    for k in (3, 4):
        a, b, s3 = (float(r[k][key]) for r in (ra, rb, rows3))
        c.le(f"round void stage {k} ({rows3[k]['void_width']} m): |{key} 3D - axi(0.125)| within "
             f"|axi(0.25) - axi(0.125)| ({s3:.4g}, {a:.4g}, {b:.4g} m)", abs(s3 - b), abs(a - b))
    b, s3 = float(rb[4][key]), float(rows3[4][key])
    c.le(f"round void stage 4 (2 m): |{key} 3D / axi(0.125) - 1|", abs(s3 / b - 1), 0.05)
    s = summary(d3)
    r = s["results"]
    m = r["membrane"]
    c.check("round void 3D: verdict PASS", s["verdict"] == "PASS", s["verdict"])
    radius = math.hypot(m["peak_at"][0], m["peak_at"][2])
    c.le("round void 3D: the peak at the void's rim (|its radius - the void's| / h)",
         abs(radius - r["void"]["B"] / 2) / s["h"], 1.0)
    c.le("round void 3D: the minor strain there below the major (|minor| / major)",
         abs(m["peak_strain_minor"]) / m["peak_strain"], 1.0)
    c.check("round void 3D: Giroud's round void beside it",
            r["void"].get("round") is True and r["void"]["giroud_strain"] > 0)
    prof = np.genfromtxt(f"{d3}/sheet_hdpe.csv", delimiter=",", names=True)
    c.check("round void 3D: sheet_hdpe.csv has slip and pressure per face",
            all(k in prof.dtype.names for k in ("slip_top_x", "slip_bottom_z", "pressure_top",
                                                  "pressure_bottom")))
    c.check("round void 3D: stages.csv has the minor strain at the peak",
            "peak_strain_minor" in rows3[0])
    c.check("round void 3D: summary.json gives the void's centre in plan",
            r["void"].get("centre") == [0, 0])
    # the plots a user gets (scripts/run.sh): the stage history (3D and axisymmetric) and the
    # sheet's plan map and sections through the void's centre
    import os
    import subprocess
    for script, d, png in (("plot_cover.py", d3, "stages.png"),
                           ("plot_cover.py", f"{out}/axi_0.25", "cover_deformed.png"),
                           ("plot_sheet.py", d3, "sheet_hdpe_section.png")):
        p = subprocess.run(["/usr/bin/python3", f"scripts/{script}", d], capture_output=True,
                           text=True)
        c.check(f"scripts/{script} on {os.path.basename(d)} draws {png}",
                p.returncode == 0 and os.path.isfile(f"{d}/{png}"), p.stderr.strip()[-200:])
    # 3. zones in 3D
    dz = f"{out}/zones3d"
    run(exe, 1, ["-options_file", "tests/cover_zones.opts", "-dim", "3", "-depth", "1",
                 "-cover_zones", "stiff,pocket,band", "-cover_zone_pocket_centre", "2,0.5",
                 "-cover_zone_pocket_radius", "0.6", "-cover_zone_pocket_depth", "2,3",
                 "-cover_zone_band_x", "0,1", "-cover_zone_band_z", "0,0.5",
                 "-cover_zone_band_depth", "3.2,3.9", "-mat_pocket_model", "linear_elastic",
                 "-mat_pocket_E", "1e6", "-mat_pocket_nu", "0.3", "-mat_pocket_gamma", "9e3",
                 "-mat_band_model", "linear_elastic", "-mat_band_E", "3e6", "-mat_band_nu", "0.3",
                 "-mat_band_gamma", "11e3", "-max_steps", "200"], dz, capped=True)
    _, f = particles(dz, ("position0", "material"))
    x0, mat = f["position0"], f["material"].ravel().astype(int)
    waste = x0[:, 1] < 4.0  # the waste surface at y = 4 m (materials: waste 0, soil 1, then the
    depth = 4.0 - x0[:, 1]  # zones' in order)
    expect = np.zeros(len(x0), dtype=int)
    expect[waste & (depth <= 1.5)] = 2
    pocket = np.hypot(x0[:, 0] - 2, x0[:, 2] - 0.5) <= 0.6
    expect[waste & pocket & (depth >= 2) & (depth <= 3)] = 3
    band = (x0[:, 0] <= 1) & (x0[:, 2] <= 0.5)
    expect[waste & band & (depth >= 3.2) & (depth <= 3.9)] = 4
    c.check("zones in 3D: every waste particle's material from its centre",
            np.array_equal(mat[waste], expect[waste]),
            f"({np.sum(mat[waste] != expect[waste])} of {waste.sum()} differ; pocket "
            f"{np.sum(mat == 3)}, band {np.sum(mat == 4)} particles)")
    c.check("zones in 3D: the pocket and the band hold particles",
            np.sum(mat == 3) > 0 and np.sum(mat == 4) > 0)
    # 3b. a degrading zone round in plan: one that covers the box is the uniform run exactly;
    # one of 1 m radius about the corner settles the sheet there and hardly at the far corner
    dr = f"{out}/round_zone_all"
    col = ["-options_file", "tests/cover_column.opts", "-dim", "3", "-depth", "0.5",
           "-cover_shrink_centre", "0,0"]
    run(exe, 1, col + ["-cover_shrink_radius", "10"], dr)
    c.check("round degrading zone over the whole box: the uniform run's stage record exactly",
            [list(r.values())[:17] for r in stages(dr)] ==
            [list(r.values())[:17] for r in stages(f"{out}/degradation_vertical")])
    dr = f"{out}/round_zone_1m"
    run(exe, 1, col + ["-cover_shrink_radius", "1", "-cover_shrink_stages", "1",
                       "-cover_shrink_total", "0.05"], dr)
    p = np.genfromtxt(f"{dr}/sheet_hdpe.csv", delimiter=",", names=True)
    r = np.hypot(p["x0"], p["z0"])
    near, far = -p["uy"][r < 0.3].mean(), -p["uy"][r > 3.5].mean()
    c.le(f"round degrading zone of 1 m: the sheet's settlement 3.5 m away over that at its centre "
         f"({far:.4g}, {near:.4g} m)", far / near, 0.2)
    # 3c. a deck graded along z (-cover_deck_grade_z 5: the waste stretched to a surface rising
    # 0.2 m over 4 m of depth, the soil and the sheet lifted with it) against the same deck graded
    # along x (the plane's own grade, a 4 m wide box 0.5 m deep: the same cover turned a quarter),
    # and both against the closed form of uniform isotropic degradation, which holds for any
    # surface (rollers on every side and a fixed base: u_y = -e y in the waste, no stress change)
    nu, ev = 0.3, 0.05
    factor = (1 + nu) / (1 - nu) / 3
    gr = ["-options_file", "tests/cover_column.opts", "-dim", "3", "-cover_shrink_mode",
          "isotropic"]
    turned = {"z": gr + ["-cover_width", "0.5", "-depth", "4", "-cover_deck_grade_z", "5"],
              "x": gr + ["-cover_width", "4", "-depth", "0.5", "-cover_deck_grade", "5"]}
    run(exe, 1, turned["z"] + ["-max_steps", "1"], f"{out}/graded_z_laid", capped=True)
    p = np.genfromtxt(f"{out}/graded_z_laid/sheet_hdpe.csv", delimiter=",", names=True)
    c.le("deck graded along z: the sheet's points on the surface y = 4 + 0.05 z (m; the capped "
         "stage lays the sheet where its one step left it)",
         np.abs(p["y0"] - (4 + 0.05 * p["z0"])).max(), 1e-6)
    profile = {}
    for ax, args in turned.items():
        d = f"{out}/graded_{ax}"
        run(exe, 1, args, d)
        rows = stages(d)
        c.check(f"deck graded along {ax}: three stages, all converged",
                len(rows) == 3 and all(r["converged"] == "1" for r in rows))
        y, x0, top = waste_column_tops(d, 3)
        for k in (1, 2):
            exact = y[k - 1][top] * (1 - math.exp(-factor * ev))
            err = (y[k - 1][top] - y[k][top]) / exact - 1
            c.le(f"deck graded along {ax}, stage {k}: the top row of waste settles by the closed "
                 f"form (mean relative error; {top.sum()} columns)", abs(err.mean()), 0.005)
            c.le(f"deck graded along {ax}, stage {k}: every column of it (largest relative error)",
                 np.abs(err).max(), 0.01)
        i = 2 if ax == "z" else 0
        o = np.argsort(x0[top, i], kind="stable")
        profile[ax] = (x0[top, i][o], (y[0] - y[2])[top][o], rows)
    (cz, sz, rz), (cx, sx, rx) = profile["z"], profile["x"]
    c.le("the deck turned a quarter: the top row's settlement along the grade, z against x "
         "(relative to the largest)", np.abs(np.interp(cx, cz, sz) - sx).max() / sx.max(), 0.01)
    for key in ("membrane_settlement", "differential_settlement"):
        a, b = float(rz[2][key]), float(rx[2][key])
        c.le(f"the deck turned a quarter: the sheet's {key}, z against x ({a:.5g}, {b:.5g} m)",
             abs(a / b - 1), 0.01)
    # 4. checkpoint and restart of a 3D cover (its sheet laid after stage 0: the reference it
    # strains from is checkpointed): from stage 0's end and from inside stage 2, bit for bit
    short = ["-options_file", "options/cover_sinkhole_3d.opts", "-estimate_error", "0",
             "-cover_void_widths", "0.5,1,1.5"]
    run(exe, 1, short, f"{out}/restart_base")
    run(exe, 1, short + ["-checkpoint_every", "400", "-checkpoint_at_stage_end"],
        f"{out}/restart_ck")
    ends = [sum(int(r["steps"]) for r in stages(f"{out}/restart_ck")[:k + 1]) for k in range(4)]
    for step, what in ((ends[0], "stage 0's end"), (800, "inside stage 2")):
        d = f"{out}/restart_{step}"
        run(exe, 1, short + ["-restart", f"{out}/restart_ck/checkpoint_{step}.h5"], d)
        same = all(open(f"{out}/restart_base/{f}").read() == open(f"{d}/{f}").read()
                   for f in ("sheet_hdpe.csv",))
        rows_a = [list(r.values())[:18] for r in stages(f"{out}/restart_base")]
        rows_b = [list(r.values())[:18] for r in stages(d)]
        c.check(f"3D cover restarted from {what} (step {step}): the sheet and the stage record "
                f"bit for bit", same and rows_a == rows_b)
else:  # 5. the same scene on one rank
    d1 = f"{out}/round3d_np1"
    run(exe, 1, base, d1)
    rows1 = stages(d1)
    for key in ("membrane_settlement", "surface_settlement", "peak_strain", "max_slip"):
        a = np.array([float(r[key]) for r in rows1[1:]])
        b = np.array([float(r[key]) for r in rows3[1:]])
        c.le(f"{np_} ranks against 1: {key} per stage (relative to its largest)",
             np.max(np.abs(a - b)) / np.max(np.abs(a)), 1e-8)
    # the deck graded along z (part 3c) on NP ranks, cut in y and z where the waste is stretched
    # and the cover lifted (Scene::extruded_height decides each particle's owner)
    gz = ["-options_file", "tests/cover_column.opts", "-dim", "3", "-cover_shrink_mode",
          "isotropic", "-cover_width", "0.5", "-depth", "4", "-cover_deck_grade_z", "5"]
    cut = {2: ["-da_processors_x", "1", "-da_processors_y", "2", "-da_processors_z", "1"],
           4: ["-da_processors_x", "1", "-da_processors_y", "2", "-da_processors_z", "2"]}[np_]
    run(exe, 1, gz, f"{out}/graded_z_np1")
    run(exe, np_, gz + cut, f"{out}/graded_z")
    ga, gb = stages(f"{out}/graded_z_np1"), stages(f"{out}/graded_z")
    for key in ("membrane_settlement", "surface_settlement", "peak_strain", "max_slip"):
        a = np.array([float(r[key]) for r in ga])
        b = np.array([float(r[key]) for r in gb])
        c.le(f"deck graded along z, {np_} ranks against 1: {key} per stage (relative to its "
             f"largest)", np.max(np.abs(a - b)) / np.max(np.abs(a)), 1e-5)
    p1 = np.genfromtxt(f"{d1}/sheet_hdpe.csv", delimiter=",", names=True)
    pn = np.genfromtxt(f"{d3}/sheet_hdpe.csv", delimiter=",", names=True)
    c.le(f"{np_} ranks against 1: the sheet's displacements (relative to the largest)",
         max(np.max(np.abs(p1[k] - pn[k])) for k in ("ux", "uy", "uz")) /
         max(np.max(np.abs(p1[k])) for k in ("ux", "uy", "uz")), 1e-8)
c.done()
