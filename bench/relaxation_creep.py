#!/usr/bin/python3
"""Is a stage that stops at its step cap still moving, and where? Reads the checkpoints a run
wrote (-checkpoint_every K) and prints, between each pair: the largest particle displacement
and where, the plastic strain gathered and by how many particles, and the first chain's peak
strain, largest tension and the settlement of its right end. A stall whose increments fall is
converging slowly; one whose increments stay the same from interval to interval is a mechanism
(of the physics or of the discretisation: docs/benchmarks/relaxation_steps.md, "The slope's
stage 2").

    /usr/bin/python3 bench/relaxation_creep.py DIR [FIRST.h5]

DIR holds checkpoint_<step>.h5; FIRST, an earlier checkpoint (e.g. a stage's start), is put
before them. Measured for relaxation_steps.md with
    build/pmpm -options_file options/cover_slope.opts -cell_size 0.25 -cover_strain_gauge 1.0 \\
        -cover_shrink_total 0.1 -cover_shrink_stages 2 -checkpoint_at_stage_end -output_dir A
    build/pmpm ... (the same) -restart A/checkpoint_9757.h5 -checkpoint_every 3000 -output_dir B
    /usr/bin/python3 bench/relaxation_creep.py B A/checkpoint_9757.h5
(the first two stages of the slope example exactly, stage 2 resumed from its start).
"""
import glob
import re
import sys

import h5py
import numpy as np


def step_of(path):
    return int(re.findall(r"(\d+)\.h5$", path)[0])


def load(path):
    with h5py.File(path, "r") as f:
        pid = f["particles/pid"][:].astype(np.int64)
        o = np.argsort(pid)
        x = f["particles/DMSwarmPIC_coor"][:].reshape(-1, 2)[o]
        ep = f["particles/eps_p"][:][o]
        mat = f["particles/mat"][:][o]
        ch = None
        if "chains/0/eps" in f:  # checkpoint arrays lead with their length (checkpoint.cpp)
            ch = dict(eps=f["chains/0/eps"][1:], T=f["chains/0/T"][1:],
                      x=f["chains/0/x"][1:].reshape(-1, 2))
    return dict(step=step_of(path), pid=pid[o], x=x, ep=ep, mat=mat, chain=ch)


def main():
    files = sorted(glob.glob(sys.argv[1] + "/checkpoint_*.h5"), key=step_of)
    if len(sys.argv) > 2:
        files = [sys.argv[2]] + files
    prev = None
    for path in files:
        s = load(path)
        ch = s["chain"]
        line = f"step {s['step']:7d}"
        if ch is not None:
            i = int(np.argmax(ch["eps"]))
            line += (f"  chain: peak strain {ch['eps'][i]:.6f} at x = {ch['x'][i, 0]:.3f} m, "
                     f"largest tension {ch['T'].max():.2f} N/m, right end y = {ch['x'][-1, 1]:.5f} m")
        print(line)
        if prev is not None and np.array_equal(prev["pid"], s["pid"]):
            du = np.hypot(*(s["x"] - prev["x"]).T)
            i = int(np.argmax(du))
            dep = s["ep"] - prev["ep"]
            j = int(np.argmax(dep))
            print(f"  since step {prev['step']}: largest displacement {du[i]:.3e} m at "
                  f"({s['x'][i, 0]:.2f}, {s['x'][i, 1]:.2f}) m (material {int(s['mat'][i])}); "
                  f"plastic strain: largest gain {dep[j]:.3e} at ({s['x'][j, 0]:.2f}, "
                  f"{s['x'][j, 1]:.2f}) m (material {int(s['mat'][j])}), {(dep > 1e-5).sum()} "
                  f"particles gained more than 1e-5")
        prev = s


if __name__ == "__main__":
    main()
