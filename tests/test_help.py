"""-help lists a scene's options without a complete scene (PETSc's convention: list, run nothing,
exit 0): for every scene, `pmpm -scene X -help` alone, with no options file, must exit 0, write
nothing, and list the global options, the scene's own (-X_...), its materials' (-mat_..._model and
every material law's options) and the Newton solver's. The scenes are the ones pmpm names when -scene is
unknown; every options/*.opts must use one of them. `pmpm -help` without a scene lists the global
options and the scenes. A cover whose membrane's material is wrong still lists that membrane's
material and face options.

usage: test_help.py EXE OUTDIR
"""
import glob
import os
import re
import shutil
import subprocess
import sys

from pmpmtest import ENV, Checks

exe, out = os.path.abspath(sys.argv[1]), sys.argv[2]
c = Checks("help")
if os.path.isdir(out):
    shutil.rmtree(out)
os.makedirs(out)


def listed(log, opt):
    """-help's entry for opt: "  -opt <default>..." (booleans "  -opt: <...")."""
    return re.search(rf"^  {opt}:? <", log, re.M) is not None


def pmpm(args, cwd=out):
    p = subprocess.run([exe] + args, env=ENV, cwd=cwd, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=300)
    return p.returncode, p.stdout


# the scene list pmpm gives for an unknown scene
code, log = pmpm(["-scene", "no_such_scene", "-cell_size", "0.1"])
m = re.search(r"allowed: ([a-z_, ]+)", log)
c.check("an unknown -scene is refused (exit 1) with the allowed scenes", code == 1 and m is not None,
        f"(exit {code}: {log.strip()[-200:]})")
scenes = [s.strip() for s in m.group(1).split(",")] if m else []
used = set()
for f in glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "options",
                                "*.opts")):
    with open(f) as fh:
        mm = re.search(r"^-scene\s+(\S+)", fh.read(), re.M)
        if mm:
            used.add(mm.group(1))
c.check("every options file's scene is in the list", used and used <= set(scenes),
        f"({sorted(used - set(scenes))} missing from {scenes})")

# the common blocks every -help shows, with no scene
GLOBAL = ["-scene", "-cell_size", "-ppc", "-max_steps", "-tol", "-solver"]
code, log = pmpm(["-help"])
c.check("-help without a scene exits 0 and lists the global options and every scene",
        code == 0 and all(listed(log, o) for o in GLOBAL) and all(s in log for s in scenes),
        f"(exit {code})")

# the laws' own options (src/materials/*.cpp): Drucker-Prager's, von Mises'
LAW_OPTIONS = ["cohesion", "friction_angle", "dilation_angle", "tension_cutoff", "match",
               "yield_stress", "hardening"]
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
code, log = pmpm(["-options_file", os.path.join(ROOT, "options", "column.opts"),
                  "-mat_column_model", "no_such_law"])
c.check("an unknown -mat_<name>_model is refused (exit 1) naming the laws",
        code == 1 and all(x in log for x in ("linear_elastic", "neo_hookean", "drucker_prager",
                                             "von_mises")), f"(exit {code}: {log.strip()[-300:]})")

for s in scenes:
    code, log = pmpm(["-scene", s, "-help"])
    own = sorted(set(re.findall(rf"^  (-{s}_[a-z_0-9]+):? <", log, re.M)))
    mats = sorted(set(re.findall(r"^  (-mat_[a-z_0-9]+_model) <", log, re.M)))
    sheets = re.findall(r"^  -mat_[a-z_0-9]+_law <", log, re.M)  # membrane chains' materials
    ok = (code == 0 and "pmpm: error" not in log and own and (mats or sheets)
          and all(listed(log, o) for o in GLOBAL + ["-newton_load_steps", "-interface_type"])
          and all(listed(log, f"{m[:-6]}_E") for m in mats)
          # every material law's own options for each material (the law table)
          and all(listed(log, f"{m[:-6]}_{o}") for m in mats for o in LAW_OPTIONS))
    c.check(f"-scene {s} -help: exit 0, its {len(own)} -{s}_* options, {len(mats)} materials "
            f"with every law's options ({len(sheets)} membranes), the global and Newton options",
            ok,
            f"(exit {code}{': ' + log.strip()[-300:] if code else ''})")
# a cover with a membrane whose material is wrong: -help still lists the membrane's material and
# both faces' interface options (the chain's checks are skipped, not stopped at)
code, log = pmpm(["-options_file", os.path.join(ROOT, "tests", "cover_column.opts"),
                  "-mat_hdpe_E", "-1", "-help"])
FACES = ["-chain_hdpe_interface", "-chain_hdpe_mu_top", "-chain_hdpe_delta_bottom",
         "-chain_hdpe_adhesion_top", "-mat_hdpe_law", "-mat_hdpe_yield_stress"]
c.check("a cover whose membrane has -mat_hdpe_E -1: -help exits 0 and lists its material's and "
        "faces' options", code == 0 and all(listed(log, o) for o in FACES),
        f"(exit {code}; missing {[o for o in FACES if not listed(log, o)]})")
c.check("-help wrote nothing", os.listdir(out) == [], f"({os.listdir(out)})")
c.done()
