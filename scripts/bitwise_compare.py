#!/usr/bin/env python3
"""Run short scenes with two pmpm binaries and compare their outputs bit for bit.

usage: /usr/bin/python3 scripts/bitwise_compare.py BEFORE AFTER [OUTDIR] [-k SUBSTRING]

For a refactoring that must not change any result: every options/*.opts capped at a few hundred
steps (coarser cells for the slow ones), the materials under -solver newton, and two scenes on 2
ranks, each run with both binaries into OUTDIR/before/<case> and OUTDIR/after/<case>. Every HDF5
dataset must be identical (max |difference| = 0, same shape and dtype), every CSV, XMF and text file
byte-equal, and summary.json equal except its timing fields (wall-clock seconds, rates, dates). Prints
one line per case and exits 1 on any difference. Run from the repository root.
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")

# Options that make each shipped scene run in seconds: a step cap, and coarser cells where the
# shipped ones are fine.
SHORT = ["-max_steps", "300", "-ramp_steps", "100"]
COARSE = {"landfill": ["-cell_size", "0.001"], "landfill_friction": ["-cell_size", "0.001"],
          "landfill_load1": ["-cell_size", "0.001"], "cover_degradation": ["-cell_size", "1"],
          "cover_sinkhole": ["-cell_size", "0.5"], "cover_slope": ["-cell_size", "1"],
"trench": ["-cell_size", "0.25"],
          "footing": ["-cell_size", "0.125"], "footing_cphi": ["-cell_size", "0.125"],
          "trapdoor": ["-cell_size", "0.125"]}
COLUMN = ["-options_file", "options/column.opts", "-cell_size", "0.125", "-solver", "newton",
          "-newton_load_steps", "3"]


def cases():
    out = []
    for f in sorted(glob.glob("options/*.opts")):
        name = os.path.basename(f)[:-5]
        out.append((name, 1, ["-options_file", f] + SHORT + COARSE.get(name, [])))
    # every material law's Newton tangent (the consistent tangents of newton.cpp)
    out.append(("newton_linear_elastic", 1, COLUMN))
    out.append(("newton_neo_hookean", 1, COLUMN + ["-mat_column_model", "neo_hookean"]))
    out.append(("newton_von_mises", 1, COLUMN + ["-mat_column_model", "von_mises",
                                                 "-mat_column_yield_stress", "1e4",
                                                 "-mat_column_hardening", "1e5"]))
    out.append(("newton_drucker_prager", 1, COLUMN + ["-mat_column_model", "drucker_prager",
                                                      "-mat_column_cohesion", "2e3",
                                                      "-mat_column_friction_angle", "20",
                                                      "-mat_column_dilation_angle", "5"]))
    out.append(("newton_footing", 1, ["-options_file", "options/footing.opts", "-cell_size",
                                      "0.125", "-fbar", "0", "-footing_pressures", "48846",
                                      "-solver", "newton", "-newton_load_steps", "2"]))
    # two ranks
    out.append(("landfill_np2", 2, ["-options_file", "options/landfill.opts"] + SHORT +
                COARSE["landfill"]))
    out.append(("cover_slope_np2", 2, ["-options_file", "options/cover_slope.opts"] + SHORT +
                COARSE["cover_slope"]))
    return out


# summary.json fields that measure the machine, not the result
TIMING = ("seconds", "wall", "time_per", "rate", "date", "host", "elapsed", "throughput",
          "per_second", "memory", "version", "git", "command", "output_dir")


def timing_key(k):
    return any(t in k.lower() for t in TIMING)


def json_diff(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        d = []
        for k in sorted(set(a) | set(b)):
            if timing_key(k):
                continue
            if k not in a or k not in b:
                d.append(f"{path}/{k}: only in one")
            else:
                d += json_diff(a[k], b[k], f"{path}/{k}")
        return d
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: lengths {len(a)} != {len(b)}"]
        return sum((json_diff(x, y, f"{path}[{i}]") for i, (x, y) in enumerate(zip(a, b))), [])
    return [] if a == b or (a != a and b != b) else [f"{path}: {a!r} != {b!r}"]


def h5_diff(fa, fb):
    d = []
    with h5py.File(fa, "r") as A, h5py.File(fb, "r") as B:
        na, nb = [], []
        A.visit(na.append)
        B.visit(nb.append)
        if sorted(na) != sorted(nb):
            return [f"{fa}: different objects {sorted(set(na) ^ set(nb))}"]
        for n in na:
            if not isinstance(A[n], h5py.Dataset):
                continue
            x, y = A[n][()], B[n][()]
            if isinstance(x, np.ndarray) and x.dtype.kind in "fiu":
                if x.shape != y.shape or x.dtype != y.dtype:
                    d.append(f"{n}: shape/dtype {x.shape} {x.dtype} != {y.shape} {y.dtype}")
                elif x.tobytes() != y.tobytes():
                    m = np.nanmax(np.abs(x.astype(float) - y.astype(float))) if x.size else 0
                    d.append(f"{n}: max |difference| {m:.3e}")
            elif np.asarray(x).tobytes() != np.asarray(y).tobytes():
                d.append(f"{n}: differs")
    return d


def csv_diff(fa, fb):
    """Text equal, except the columns whose header names a timing (wall_seconds, ...)."""
    with open(fa) as x, open(fb) as y:
        la, lb = x.read().splitlines(), y.read().splitlines()
    if len(la) != len(lb):
        return [f"{len(la)} != {len(lb)} lines"]
    if not la:
        return []
    head = la[0].split(",")
    keep = [i for i, h in enumerate(head) if not timing_key(h)]
    for k, (ra, rb) in enumerate(zip(la, lb)):
        ca, cb = ra.split(","), rb.split(",")
        if len(ca) != len(cb) or any(ca[i] != cb[i] for i in keep if i < len(ca)):
            return [f"line {k + 1} differs:\n        {ra}\n        {rb}"]
    return []


def compare_dirs(da, db):
    fa = sorted(os.path.relpath(p, da) for p in glob.glob(da + "/**/*", recursive=True)
                if os.path.isfile(p))
    fb = sorted(os.path.relpath(p, db) for p in glob.glob(db + "/**/*", recursive=True)
                if os.path.isfile(p))
    if fa != fb:
        return [f"different files: {sorted(set(fa) ^ set(fb))}"], len(fa)
    d = []
    for f in fa:
        a, b = os.path.join(da, f), os.path.join(db, f)
        if f.endswith(".h5"):
            d += [f"{f}: {x}" for x in h5_diff(a, b)]
        elif f.endswith(".json"):
            with open(a) as x, open(b) as y:
                d += [f"{f}{x}" for x in json_diff(json.load(x), json.load(y))]
        elif f.endswith(".log"):
            continue
        elif f.endswith(".csv"):
            d += [f"{f}: {x}" for x in csv_diff(a, b)]
        else:
            with open(a, "rb") as x, open(b, "rb") as y:
                if x.read() != y.read():
                    d.append(f"{f}: bytes differ")
    return d, len(fa)


def run(exe, np_, args, out):
    if os.path.isdir(out):
        shutil.rmtree(out)
    cmd = ["mpiexec", "-n", str(np_), exe] + args + ["-output_dir", out, "-quiet"]
    t = time.time()
    p = subprocess.run(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "run.log"), "w") as f:
        f.write(" ".join(cmd) + "\n" + p.stdout)
    return p.returncode, time.time() - t


def main():
    argv = sys.argv[1:]
    only = None
    if "-k" in argv:
        i = argv.index("-k")
        only = argv[i + 1]
        del argv[i:i + 2]
    before, after = os.path.abspath(argv[0]), os.path.abspath(argv[1])
    outdir = argv[2] if len(argv) > 2 else "/tmp/pmpm_bitwise"
    bad = 0
    for name, np_, args in cases():
        if only and only not in name:
            continue
        ra, ta = run(before, np_, args, f"{outdir}/before/{name}")
        rb, tb = run(after, np_, args, f"{outdir}/after/{name}")
        if ra != rb:
            d, n = [f"exit codes {ra} != {rb}"], 0
        elif ra not in (0, 3):  # 3: a stage stopped at the step cap, as these runs do
            d, n = [f"the case itself fails (exit {ra}): see {outdir}/before/{name}/run.log"], 0
        else:
            d, n = compare_dirs(f"{outdir}/before/{name}", f"{outdir}/after/{name}")
        bad += bool(d)
        print(f"{'SAME' if not d else 'DIFF'} {name} (np {np_}, exit {ra}, {n} files, "
              f"{ta:.1f} s / {tb:.1f} s)", flush=True)
        for x in d[:10]:
            print("     ", x)
    print(f"bitwise_compare: {bad} case(s) differ")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
