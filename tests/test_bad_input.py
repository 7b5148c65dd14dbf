"""Bad input: each case must exit with code 1, name the offending option or file in one line (no
PETSc traceback), and leave no output; a misspelled option or one no part of the run reads is bad
input too, and so are options files PETSc cannot read (include cycles, garbage, directories),
numbers that are not numbers or not finite, and a restart that changes its checkpoint's model; on
2 ranks an error all ranks meet is one line.

usage: test_bad_input.py EXE OUTDIR
"""
import os
import sys
from concurrent.futures import ThreadPoolExecutor

from pmpmtest import Checks, run

exe, out = sys.argv[1], sys.argv[2]
c = Checks("bad_input")
# Options files for the cases below (outside every case's output directory): one including
# itself, two including each other, a line that is only "-", a binary file, a directory.
files = f"{out}/options_files"
os.makedirs(files, exist_ok=True)
for name, text in [("self.opts", f"-scene bar\n-options_file {files}/self.opts\n"),
                   ("ping.opts", f"-options_file {files}/pong.opts\n"),
                   ("pong.opts", f"-options_file {files}/ping.opts\n"),
                   ("dash.opts", "-scene bar\n-\n")]:
    with open(f"{files}/{name}", "w") as f:
        f.write(text)
with open(f"{files}/garbage.opts", "wb") as f:
    f.write(bytes(range(256)) * 4)
os.makedirs(f"{files}/a_directory.opts", exist_ok=True)
# A checkpoint of the void cover (step 100) to restart with a changed model option; its run may
# stop at -max_steps (not converged): only the checkpoint is wanted.
ck = f"{out}/void_checkpoint"
run(exe, 1, ["-options_file", "tests/cover_void.opts", "-checkpoint_every", "100", "-max_steps",
             "150"], ck, expect_ok=False)
c.check("void cover checkpoint for the restart case", os.path.isfile(f"{ck}/checkpoint_100.h5"))
CUT = ["-options_file", "options/cover_sinkhole.opts"]
cases = [
    ("unknown shape", ["-options_file", "options/bar.opts", "-shape", "quadratic"], "-shape"),
    ("unknown scene", ["-scene", "tunnel", "-cell_size", "0.1"], "-scene"),
    ("unknown transfer", ["-options_file", "options/bar.opts", "-transfer", "mls"], "-transfer"),
    ("cell pressure without F-bar", ["-options_file", "options/bar.opts", "-fbar_pressure",
                                     "cell"], "add -fbar"),
    ("plain F-bar with a dilatant soil", ["-options_file", "options/footing_cphi.opts",
                                          "-fbar_pressure", "particle"], "-fbar_pressure cell"),
    ("footing soil narrower than the mechanism",
     ["-options_file", "options/footing_cphi.opts", "-footing_soil_width", "3"],
     "-footing_soil_width"),
    ("APIC with MUSL", ["-options_file", "options/bar.opts", "-transfer", "apic", "-musl"],
     "-transfer apic"),
    ("negative modulus", ["-options_file", "options/bar.opts", "-mat_bar_E", "-5"], "-mat_bar_E"),
    ("Poisson ratio 0.5", ["-options_file", "options/bar.opts", "-mat_bar_nu", "0.5"],
     "-mat_bar_nu"),
    ("missing options file", ["-options_file", "options/no_such_scene.opts"], "no_such_scene.opts"),
    ("grid too small for the bar", ["-options_file", "options/bar.opts", "-bar_box_length", "1.0"],
     "-bar_box_length"),
    ("cell larger than the bar", ["-options_file", "options/bar.opts", "-cell_size", "0.3"],
     "-bar_length"),
    ("CFL above 1", ["-options_file", "options/bar.opts", "-cfl", "1.5"], "-cfl"),
    ("ppc out of range", ["-options_file", "options/bar.opts", "-ppc", "0"], "-ppc"),
    ("missing modulus", ["-scene", "column", "-cell_size", "0.125", "-mat_column_nu", "0.3",
                         "-mat_column_gamma", "1"], "-mat_column_E"),
    ("interface tail share out of range", ["-options_file", "options/incline.opts",
                                           "-interface_tail_share", "0.7"], "-interface_tail_share"),
    ("unknown interface normals", ["-options_file", "options/incline.opts",
                                   "-interface_normals", "mass"], "-interface_normals"),
    ("unknown membrane law", ["-options_file", "options/catenary.opts", "-mat_membrane_law",
                              "rubber"], "-mat_membrane_law"),
    ("membrane yield stress missing", ["-options_file", "options/catenary.opts",
                                       "-mat_membrane_law", "elastoplastic"],
     "-mat_membrane_yield_stress"),
    ("interface friction angle above 60", ["-options_file", "options/catenary.opts",
                                           "-chain_membrane_delta_top", "75"],
     "-chain_membrane_delta_top"),
    ("negative adhesion", ["-options_file", "options/catenary.opts",
                           "-chain_membrane_adhesion_bottom", "-1"], "-chain_membrane_adhesion_bottom"),
    ("chain spacing out of range", ["-options_file", "options/catenary.opts", "-chain_spacing", "2"],
     "-chain_spacing"),
    ("zero membrane thickness", ["-options_file", "options/catenary.opts", "-membrane_thickness",
                                 "0"], "-membrane_thickness"),
    ("3D sheet in 2D", ["-options_file", "options/sheet.opts", "-dim", "2"], "-dim 3"),
    ("3D sheet with a depth", ["-options_file", "options/sheet.opts", "-depth", "4"], "-depth"),
    ("3D sheet radius negative", ["-options_file", "options/sheet.opts", "-sheet_radius", "-1"],
     "-sheet_radius"),
    ("3D sheet elastoplastic without a yield stress", ["-options_file", "options/sheet.opts",
                                                       "-mat_membrane_law", "elastoplastic"],
     "-mat_membrane_yield_stress"),
    ("3D sheet uniaxial stiffness", ["-options_file", "options/sheet.opts",
                                     "-mat_membrane_axial_stiffness", "uniaxial"],
     "-mat_membrane_axial_stiffness"),
    ("chain and layers together", ["-options_file", "options/landfill.opts",
                                   "-landfill_membrane_chain", "-landfill_membrane_layers", "1"],
     "-landfill_membrane_chain"),
    ("cover membrane under an unknown layer", ["-options_file", "options/cover_sinkhole.opts",
                                               "-cover_membrane_hdpe_under", "gravel"],
     "-cover_membrane_hdpe_under"),
    ("cover void widths decreasing", ["-options_file", "options/cover_sinkhole.opts",
                                      "-cover_void_widths", "2,1"], "-cover_void_widths"),
    ("cover shrinkage above 0.6", ["-options_file", "options/cover_degradation.opts",
                                   "-cover_shrink_total", "0.9"], "-cover_shrink_total"),
    ("cover layer without thickness", ["-options_file", "options/cover_sinkhole.opts",
                                       "-cover_layer_clay_thickness", "0"],
     "-cover_layer_clay_thickness"),
    ("cover strain gauge below a cell", ["-options_file", "options/cover_sinkhole.opts",
                                         "-cover_strain_gauge", "0.1"], "-cover_strain_gauge"),
    ("cover shrinkage of a hyperelastic waste", ["-options_file", "options/cover_degradation.opts",
                                                 "-mat_waste_model", "neo_hookean"],
     "-cover_shrink_total"),
    # the laws a check allows come from the law table (src/materials/registry.cpp)
    ("cover shrinkage of a hyperelastic waste lists the rate-form laws",
     ["-options_file", "options/cover_degradation.opts", "-mat_waste_model", "neo_hookean"],
     "(linear_elastic, drucker_prager, von_mises)"),
    ("footing in an elastic soil", ["-options_file", "options/footing.opts", "-mat_soil_model",
                                    "linear_elastic"], "plastic law (drucker_prager, von_mises)"),
    ("cover surface not spanning the width", ["-options_file", "options/cover_slope.opts",
                                              "-cover_surface", "0,5,50,8"], "-cover_surface"),
    ("trapdoor displacements decreasing", ["-options_file", "options/trapdoor.opts",
                                           "-trapdoor_displacements", "0.02,0.01"],
     "-trapdoor_displacements"),
    ("trapdoor rate above 0.01", ["-options_file", "options/trapdoor.opts", "-trapdoor_rate",
                                  "0.5"], "-trapdoor_rate"),
    ("trapdoor half-width off the grid lines", ["-options_file", "options/trapdoor.opts",
                                                "-trapdoor_width", "1.1"], "-trapdoor_width"),
    ("trapdoor in an elastic soil", ["-options_file", "options/trapdoor.opts",
                                     "-mat_soil_model", "linear_elastic"], "-mat_soil_model"),
    ("negative checkpoint interval", ["-options_file", "options/bar.opts", "-checkpoint_every",
                                      "-1"], "-checkpoint_every"),
    ("cell size needing more memory than the machine has",
     ["-options_file", "options/bar.opts", "-cell_size", "1e-5"], "-cell_size"),
    # the grid fits in 0.06 GiB, its 75,000 particles do not: the check after generation
    ("particles needing more than -memory_limit", ["-options_file", "options/landfill.opts",
                                                   "-cell_size", "0.00025", "-memory_limit",
                                                   "0.06"], "-memory_limit"),
    # the same footing fits 0.2 GiB under relaxation (0.06 GiB measured): Newton's matrix does not
    ("Newton's matrix needing more than -memory_limit",
     ["-options_file", "options/footing.opts", "-fbar", "0", "-footing_pressures", "30000",
      "-cell_size", "0.015625", "-solver", "newton", "-memory_limit", "0.2"], "Newton's matrix"),
    ("negative memory limit", ["-options_file", "options/bar.opts", "-memory_limit", "-1"],
     "-memory_limit"),
    ("process grid finer than the grid", ["-options_file", "options/bar.opts",
                                          "-da_processors_y", "100"], "-da_processors_y"),
    ("unknown balance mode", ["-options_file", "options/bar.opts", "-balance", "metis"],
     "-balance"),
    ("balance gain out of range", ["-options_file", "options/bar.opts", "-balance_gain", "1"],
     "-balance_gain"),
    ("balance threshold below 1",
     ["-options_file", "options/bar.opts", "-balance_threshold", "0.9"], "-balance_threshold"),
    # -solver newton: what it cannot solve yet is refused, naming what and the way out
    ("unknown solver", ["-options_file", "options/bar.opts", "-solver", "implicit"], "-solver"),
    ("Newton load steps out of range", ["-options_file", "options/bar.opts", "-solver", "newton",
                                        "-newton_load_steps", "0"], "-newton_load_steps"),
    ("Newton small-cut share out of range", ["-options_file", "options/bar.opts", "-solver",
                                             "newton", "-newton_small_cut", "0.5"],
     "-newton_small_cut"),
    ("Newton with a chain in contact", ["-options_file", "options/catenary.opts", "-solver",
                                        "newton"], "-chain_membrane_interface bonded"),
    ("Newton with the landfill chain on paper",
     ["-options_file", "options/landfill.opts", "-landfill_membrane_chain", "-interface_type",
      "paper", "-solver", "newton"], "-chain_membrane_interface bonded"),
    ("Newton with the cover's geostatic paper faces",
     ["-options_file", "tests/cover_column.opts", "-chain_hdpe_interface", "bonded", "-solver",
      "newton"], "-cover_geostatic_paper false"),
    ("Newton with a frictional interface", ["-options_file", "options/incline.opts", "-solver",
                                            "newton"], "-interface_type contact"),
    ("Newton with cpGIMP", ["-options_file", "options/bar.opts", "-solver", "newton", "-shape",
                            "cpgimp"], "-shape cpgimp"),
    ("Newton with load stages", ["-options_file", "options/footing.opts", "-solver", "newton"],
     "stage 0, shrinkage and void stages only"),
    ("Newton with F-bar", ["-options_file", "options/column.opts", "-solver", "newton",
                           "-mat_column_model", "von_mises", "-mat_column_yield_stress", "5000",
                           "-fbar"], "-fbar"),
    # -dim 3 (extrude.hpp): the dimension, the depth, and what the 3D step does not run yet
    ("dimension 4", ["-options_file", "options/column.opts", "-dim", "4"], "-dim must be 2 or 3"),
    ("depth in 2D", ["-options_file", "options/column.opts", "-depth", "0.5"], "-depth"),
    ("3D without a depth", ["-options_file", "options/column.opts", "-dim", "3"], "-depth"),
    ("3D depth not whole cells", ["-options_file", "options/column.opts", "-dim", "3", "-depth",
                                  "0.1"], "-depth"),
    ("3D scene that does not extrude", ["-options_file", "options/trench.opts", "-dim", "3",
                                        "-depth", "1"], "-scene trench"),
    ("cover zone bounded in z in 2D", ["-options_file", "tests/cover_zones.opts",
                                       "-cover_zone_stiff_z", "0,1"], "-cover_zone_stiff_z"),
    ("3D round zone with an x range too", ["-options_file", "tests/cover_zones.opts", "-dim", "3",
                                           "-depth", "1", "-cover_zone_stiff_centre", "1,1",
                                           "-cover_zone_stiff_radius", "0.5"],
     "-cover_zone_stiff_centre"),
    ("round degrading zone in 2D", ["-options_file", "tests/cover_column.opts",
                                    "-cover_shrink_centre", "1,1", "-cover_shrink_radius", "1"],
     "-cover_shrink_centre"),
    ("deck grade along z in 2D", ["-options_file", "tests/cover_column.opts",
                                  "-cover_deck_grade_z", "5"], "-cover_deck_grade_z"),
    ("deck grade along z taking the waste away", ["-options_file", "tests/cover_column.opts",
                                                  "-dim", "3", "-depth", "4",
                                                  "-cover_deck_grade_z", "-60"],
     "-cover_deck_grade_z"),
    ("plan grid of surface heights in 2D", ["-options_file", "tests/cover_column.opts",
                                           "-cover_plan_x", "0,4", "-cover_plan_z", "0,1",
                                           "-cover_plan_heights", "4,4,4,4"], "-cover_plan_x"),
    ("plan grid with a height missing", ["-options_file", "tests/cover_column.opts", "-dim", "3",
                                         "-depth", "1", "-cover_plan_x", "0,4", "-cover_plan_z",
                                         "0,1", "-cover_plan_heights", "4,4,4"],
     "-cover_plan_heights"),
    ("plan grid beside the plane's surface", ["-options_file", "tests/cover_column.opts", "-dim",
                                              "3", "-depth", "1", "-cover_plan_x", "0,4",
                                              "-cover_plan_z", "0,1", "-cover_plan_heights",
                                              "4,4,4,4"], "-cover_waste_height"),
    ("plan grid short of the box's depth", ["-options_file", "tests/cover_plan.opts",
                                            "-cover_plan_z", "0,1,1.5"], "-cover_plan_z"),
    ("plan grid taking most of the waste away", ["-options_file", "tests/cover_plan.opts",
                                                 "-cover_plan_heights",
                                                 "4,4,4,4,1.9,4,4,4,4"], "-cover_plan_heights"),
    ("3D cover's round void outside the box", ["-options_file", "options/cover_sinkhole_3d.opts",
                                               "-cover_void_z", "5"], "-cover_void_z"),
    ("incline azimuth in 2D", ["-options_file", "options/incline.opts", "-incline_azimuth", "30"],
     "-incline_azimuth"),
    ("incline azimuth with the block over the whole depth",
     ["-options_file", "options/incline.opts", "-dim", "3", "-depth", "0.04", "-incline_azimuth",
      "30"], "-incline_block_width"),
    ("incline block outside the depth",
     ["-options_file", "options/incline.opts", "-dim", "3", "-depth", "0.04", "-incline_block_z",
      "0.02", "-incline_block_width", "0.04"], "-incline_block_z"),
    ("3D landfill with a membrane chain", ["-options_file", "options/landfill.opts", "-dim", "3",
                                           "-depth", "0.0005", "-landfill_membrane_chain"],
     "membrane chains"),
    ("3D pull-out uniaxial with nu", ["-options_file", "options/pullout.opts", "-dim", "3",
                                       "-depth", "0.06", "-mat_membrane_nu", "0.3"],
     "-mat_membrane_axial_stiffness"),
    ("3D incline with its chain", ["-options_file", "options/incline_chain.opts", "-dim", "3",
                                   "-depth", "0.1"], "membrane chains"),
    ("3D catenary with a second chain", ["-options_file", "options/catenary.opts", "-dim", "3",
                                         "-depth", "2", "-catenary_second"], "-catenary_second"),
    ("3D catenary narrower than two cells", ["-options_file", "options/catenary.opts", "-dim",
                                             "3", "-depth", "0.5"], "-depth"),
    ("3D catenary uniaxial with nu", ["-options_file", "options/catenary.opts", "-dim", "3",
                                      "-depth", "2", "-mat_membrane_nu", "0.3"],
     "-mat_membrane_axial_stiffness uniaxial"),
    ("3D Newton with a sheet", ["-options_file", "options/pullout.opts", "-dim", "3", "-depth",
                                "0.06", "-solver", "newton"], "3D sheets"),
    ("3D Newton with a rigid z translation", ["-options_file", "options/bar.opts", "-dim", "3",
                                              "-depth", "0.1", "-bc_zmin", "free", "-bc_zmax",
                                              "free", "-solver", "newton"], "-bc_zmin"),
    ("3D process grid finer than the z nodes", ["-options_file", "options/column.opts", "-dim",
                                                "3", "-depth", "0.03125", "-da_processors_z",
                                                "2"],
     "-da_processors_z 2 must be in 1..1"),
    ("3D axisymmetric", ["-options_file", "options/column.opts", "-dim", "3", "-depth", "0.125",
                         "-geometry", "axisymmetric"], "-geometry axisymmetric"),
    ("round column in 2D", ["-options_file", "options/column.opts", "-column_round"],
     "-column_round needs -dim 3"),
    ("round column deeper than the box", ["-options_file", "options/column.opts", "-dim", "3",
                                          "-depth", "0.0625", "-column_round"], "-column_round"),
    ("3D block (does not extrude)", ["-options_file", "options/block.opts", "-dim", "3",
                                     "-depth", "0.5"], "-scene block"),
    ("3D z face misspelled", ["-options_file", "options/column.opts", "-dim", "3", "-depth",
                              "0.125", "-bc_zmin", "clamped"], "-bc_zmin"),
    # -geometry axisymmetric: what it does not support is refused, naming the option
    ("unknown geometry", ["-options_file", "options/bar.opts", "-geometry", "spherical"],
     "-geometry"),
    ("axisymmetric with Newton", ["-options_file", "options/column.opts", "-geometry",
                                  "axisymmetric", "-solver", "newton"], "-solver newton"),
    ("axisymmetric chain, uniaxial stiffness", ["-options_file", "options/catenary.opts",
                                                "-geometry", "axisymmetric"],
     "-mat_membrane_axial_stiffness plane_strain"),
    ("axisymmetric chain, elastoplastic law",
     ["-options_file", "options/catenary.opts", "-geometry", "axisymmetric",
      "-mat_membrane_axial_stiffness", "plane_strain", "-mat_membrane_law", "elastoplastic",
      "-mat_membrane_yield_stress", "1e6"], "-mat_membrane_law linear or tension_only"),
    ("axisymmetric catenary with a second chain",
     ["-options_file", "options/catenary.opts", "-geometry", "axisymmetric",
      "-mat_membrane_axial_stiffness", "plane_strain", "-catenary_second"], "-catenary_second"),
    ("axisymmetric traction on the axis",
     ["-options_file", "options/column.opts", "-geometry", "axisymmetric", "-bc_xmin", "free",
      "-bc_xmin_traction", "1e3,0"], "-bc_xmin_traction"),
    ("cylinder in plane strain", ["-options_file", "tests/cylinder.opts", "-geometry",
                                  "plane_strain"], "-geometry axisymmetric"),
    ("cylinder inner pressure without a bore",
     ["-options_file", "tests/cylinder.opts", "-cylinder_inner_radius", "0"],
     "-cylinder_inner_pressure"),
    ("misspelled option", ["-options_file", "options/bar.opts", "-cell_sise", "0.001"],
     "-cell_sise"),
    # options files: a cycle segfaulted, garbage printed PETSc's 17-line traceback
    ("options file including itself", ["-options_file", f"{files}/self.opts"], "self.opts"),
    ("options files including each other", ["-options_file", f"{files}/ping.opts"],
     "ping.opts -> "),
    ("options file line that is only -", ["-options_file", f"{files}/dash.opts"],
     "dash.opts line 2"),
    ("binary options file", ["-options_file", f"{files}/garbage.opts"], "garbage.opts"),
    ("options file that is a directory", ["-options_file", f"{files}/a_directory.opts"],
     "a_directory.opts is a directory"),
    ("options file without a name", ["-options_file", "options/bar.opts", "-options_file"],
     "-options_file needs a file name"),
    # values that are not numbers, several where one is read, non-finite or absurd
    ("cell size not a number", ["-options_file", "options/bar.opts", "-cell_size", "abc"],
     "-cell_size expects one real number"),
    ("cell size as a list", ["-options_file", "options/bar.opts", "-cell_size", "0.05,0.1"],
     "-cell_size expects one real number"),
    ("ppc not an integer", ["-options_file", "options/bar.opts", "-ppc", "2.5"],
     "-ppc expects one integer"),
    ("modulus as a list", ["-options_file", "options/bar.opts", "-mat_bar_E", "1e7,2e7"],
     "-mat_bar_E expects one real number"),
    ("cover void widths not numbers", CUT + ["-cover_void_widths", "abc"], "-cover_void_widths"),
    ("gravity direction not finite", ["-options_file", "options/bar.opts", "-gravity_dir",
                                      "nan,1"], "-gravity_dir must be finite"),
    ("infinite modulus", ["-options_file", "options/bar.opts", "-mat_bar_E", "inf"],
     "-mat_bar_E must be a finite"),
    ("modulus 1e308", ["-options_file", "options/bar.opts", "-mat_bar_E", "1e308"],
     "-mat_bar_E must be in (0, 1e+13]"),
    ("modulus overflowing to inf", ["-options_file", "options/bar.opts", "-mat_bar_E", "1e400"],
     "-mat_bar_E must be a finite"),
    ("unit weight 1e308", ["-options_file", "options/bar.opts", "-mat_bar_gamma", "1e308"],
     "-mat_bar_gamma must be in [0, 1e+12]"),
    # E = 1e7 Pa over a density of 1e-10 kg/m^3: 3.6e8 m/s, a time step of 7e-11 s
    ("wave speed far above any solid's", ["-options_file", "options/bar.opts", "-mat_bar_gamma",
                                          "1e-9"], "-mat_bar_E 1e+07 Pa over the density"),
    ("traction not a number", ["-options_file", "options/bar.opts", "-bar_traction", "nan"],
     "-bar_traction must be a finite"),
    ("pull-out force infinite", ["-options_file", "options/pullout.opts", "-pullout_force", "inf"],
     "-pullout_force must be a finite"),
    ("face traction not a number", ["-options_file", "options/bar.opts", "-bc_xmax_traction",
                                    "nan,0"], "-bc_xmax_traction must be finite"),
    ("gravity direction with three components", ["-options_file", "options/bar.opts",
                                                 "-gravity_dir", "0,-1,0"],
     "-gravity_dir takes at most 2 values"),
    ("negative progress interval", ["-options_file", "options/bar.opts", "-progress_interval",
                                    "-1"], "-progress_interval must be >= 0"),
    # a given size of 0 or less is refused, not taken for "the default"
    ("trapdoor height 0", ["-options_file", "options/trapdoor.opts", "-trapdoor_height", "0"],
     "-trapdoor_height must be > 0"),
    ("trapdoor height negative", ["-options_file", "options/trapdoor.opts", "-trapdoor_height",
                                  "-5"], "-trapdoor_height must be > 0"),
    ("footing soil depth 0", ["-options_file", "options/footing.opts", "-footing_soil_depth",
                              "0"], "-footing_soil_depth must be > 0"),
    ("circular footing in plane strain", ["-options_file", "options/footing.opts",
                                          "-footing_shape", "circle"],
     "-footing_shape circle needs -geometry axisymmetric or -dim 3"),
    ("strip footing under axisymmetric", ["-options_file", "options/footing.opts", "-geometry",
                                          "axisymmetric"], "-footing_shape strip is plane"),
    ("circular footing's 3D quarter too shallow in z",
     ["-options_file", "options/footing.opts", "-footing_shape", "circle", "-dim", "3",
      "-depth", "1"], "must be at least 1.5 m for -footing_shape circle"),
    ("footing shape misspelled", ["-options_file", "options/footing.opts", "-footing_shape",
                                  "square"], "-footing_shape"),
    ("two membranes under one cover layer",
     CUT + ["-cover_membranes", "hdpe,gcl", "-cover_membrane_gcl_under", "drainage",
            "-cover_membrane_gcl_thickness", "0.005", "-mat_gcl_law", "tension_only",
            "-mat_gcl_E", "1e8", "-mat_gcl_nu", "0.3", "-mat_gcl_gamma", "1e4"],
     "-cover_membrane_gcl_under drainage: membrane hdpe already lies under"),
    ("cover zone without depth", ["-options_file", "tests/cover_zones.opts",
                                  "-cover_zone_stiff_depth", "1,0.5"], "-cover_zone_stiff_depth"),
    ("cover zone outside the width", ["-options_file", "tests/cover_zones.opts",
                                      "-cover_zone_stiff_x", "0,5"], "-cover_zone_stiff_x"),
    ("cover zones overlapping",
     ["-options_file", "tests/cover_zones.opts", "-cover_zones", "stiff,soft",
      "-cover_zone_soft_x", "1,2", "-cover_zone_soft_depth", "1,2",
      "-cover_zone_soft_material", "waste"], "zones stiff and soft overlap"),
    ("cover zone of a layer's material", ["-options_file", "tests/cover_zones.opts",
                                          "-cover_zone_stiff_material", "soil"],
     "-cover_zone_stiff_material soil is a cover layer's material"),
    # a restart refuses a changed model option, naming it
    ("restart with the void moved", ["-options_file", "tests/cover_void.opts", "-restart",
                                     f"{ck}/checkpoint_100.h5", "-cover_void_x", "5"],
     "-cover_void_x changed from 6"),
    ("an option of another material model", ["-options_file", "options/bar.opts",
                                             "-mat_bar_cohesion", "5e3"], "-mat_bar_cohesion"),
]
# Each case is a short launch that stops at its check: twelve at a time (a launch is mostly
# mpiexec's start-up, 2.5 s of waiting for 0.1 s of CPU: four at a time took 106 s of the suite),
# the checks in the list's order.


def launch(case):
    what, args, _ = case
    return run(exe, 1, args, f"{out}/{what.replace(' ', '_')}", expect_ok=False)


with ThreadPoolExecutor(max_workers=12) as pool:
    results = list(pool.map(launch, cases))
for (what, args, needle), (code, text) in zip(cases, results):
    d = f"{out}/{what.replace(' ', '_')}"
    msg = next((l for l in text.splitlines() if l.startswith("pmpm: error") and needle in l), "")
    c.check(f"{what}: exit code 1", code == 1, f"(exit {code})")
    c.check(f"{what}: message names {needle}", bool(msg), f"[{msg.strip()[:110]}]")
    c.check(f"{what}: one error line, no PETSc traceback",
            sum(l.startswith("pmpm: error") for l in text.splitlines()) == 1 and
            "PETSC ERROR" not in text, f"({len(text.splitlines())} lines)")
    c.check(f"{what}: no output written", not os.path.exists(d))

# -output_dir that cannot be used: checked before the run (one line naming -output_dir and the
# path), not after it in HDF5. Each is passed as the run's output directory.
os.makedirs(out, exist_ok=True)
afile = f"{out}/a_file"
with open(afile, "w") as f:
    f.write("not a directory\n")
for what, path in [("an existing file", afile), ("a path under a file", f"{afile}/sub/run"),
                   ("a directory that cannot be created", "/proc/pmpm_no_such_dir/run")]:
    code, text = run(exe, 1, ["-options_file", "options/bar.opts"], path, expect_ok=False)
    lines = [l for l in text.splitlines() if l.startswith("pmpm: error")]
    c.check(f"-output_dir {what}: non-zero exit", code != 0, f"(exit {code})")
    c.check(f"-output_dir {what}: one line naming -output_dir and the path",
            len(lines) == 1 and "-output_dir" in lines[0] and path in lines[0],
            f"[{lines[0][:110] if lines else ''}]")
    c.check(f"-output_dir {what}: nothing written", os.path.isfile(afile) and
            open(afile).read() == "not a directory\n" and not os.path.exists(f"{afile}/sub"))

# -output_dir "" wrote summary.json and particles.h5 into /: refused (run() passes it last)
code, text = run(exe, 1, ["-options_file", "options/bar.opts"], "", expect_ok=False)
lines = [l for l in text.splitlines() if l.startswith("pmpm: error")]
c.check("-output_dir empty: exit code 1", code == 1, f"(exit {code})")
c.check("-output_dir empty: one line naming -output_dir", len(lines) == 1 and
        "-output_dir is empty" in lines[0], f"[{lines[0][:110] if lines else ''}]")
c.check("-output_dir empty: nothing written to / or here",
        not any(os.path.exists(f"{p}/summary.json") for p in ("/", ".")))

# On 2 ranks an error every rank meets is printed once (rank 0), without a rank number: an
# option's, and the options files' (checked before PETSc starts, once printed per rank).
for what, args, needle in [
        ("bad modulus", ["-options_file", "options/bar.opts", "-mat_bar_E", "-1"], "-mat_bar_E"),
        ("missing options file", ["-options_file", "options/no_such_scene.opts"],
         "no_such_scene.opts"),
        ("options file without a name", ["-options_file"], "-options_file needs a file name"),
        ("options files including each other", ["-options_file", f"{files}/ping.opts"],
         "ping.opts")]:
    d = f"{out}/two_ranks"
    code, text = run(exe, 2, args, d, expect_ok=False)
    lines = [l for l in text.splitlines() if l.startswith("pmpm: error")]
    c.check(f"2 ranks, {what}: exit code 1", code == 1, f"(exit {code})")
    c.check(f"2 ranks, {what}: one error line", len(lines) == 1 and needle in lines[0],
            f"({lines})")
    c.check(f"2 ranks, {what}: no output written", not os.path.exists(d))
c.done()
