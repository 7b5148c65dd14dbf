"""The output contract of docs/outputs.md: summary keys, particles.h5 datasets and shapes, the
XDMF beside it, the -output_every time series, and no temporary files left behind.

usage: test_output.py EXE NP OUTDIR
"""
import glob
import json
import os
import sys
import h5py
from pmpmtest import Checks, run

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"output_np{np}")
d = f"{out}/column"
run(exe, np, ["-options_file", "options/column.opts", "-cell_size", "0.0625", "-output_every", "200"], d)
s = json.load(open(f"{d}/summary.json"))
for key in ("scene", "ranks", "particles", "cells", "h", "steps", "wall_seconds", "converged",
            "unbalanced_force_ratio", "results"):
    c.check(f"summary has {key}", key in s)
n = s["particles"]
with h5py.File(f"{d}/particles.h5", "r") as f:
    shapes = {"position": (n, 2), "position0": (n, 2), "displacement": (n, 2), "velocity": (n, 2),
              "stress": (n, 4), "F": (n, 4), "volume": (n,), "volume0": (n,), "halfsize": (n, 2),
              "mass": (n,),
              "eps_p": (n,), "colour": (n,), "material": (n,), "id": (n,)}
    for name, shape in shapes.items():
        ok = f"particles/{name}" in f and f[f"particles/{name}"].shape == shape
        c.check(f"particles.h5 /particles/{name} has shape {shape}", ok)
    ids = sorted(int(i) for i in f["particles/id"][:])
    c.check("particle ids are unique", len(set(ids)) == n)
xmf = open(f"{d}/particles.xmf").read()
c.check("particles.xmf points into particles.h5", "particles.h5:/particles/position" in xmf)
frames = sorted(glob.glob(f"{d}/series/particles_*.h5"))
c.check("time series frames every 200 steps", len(frames) == s["steps"] // 200,
        f"({len(frames)} frames, {s['steps']} steps)")
series = open(f"{d}/series/particles_series.xmf").read()
c.check("series .xmf lists every frame", all(os.path.basename(fr) in series for fr in frames))
c.check("no temporary files left", not glob.glob(f"{d}/**/*.tmp", recursive=True))
c.done()
