"""Shared helpers for pmpm's scene tests: run the binary (optionally under mpiexec), read results."""
import json
import os
import shutil
import subprocess
import sys

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


# pmpm's exit codes (docs/outputs.md, exit codes)
EXIT_OK, EXIT_BAD_INPUT, EXIT_FAILED, EXIT_NOT_CONVERGED, EXIT_INCONCLUSIVE = 0, 1, 2, 3, 4


def run(exe, np, args, out, mpiexec="mpiexec", expect_ok=True, timeout=1200, capped=False):
    """Run pmpm on np ranks writing into out (removed first); return (returncode, output).
    expect_ok: stop the test unless pmpm exits 0, or 3 (a stage stopped at its step cap) when
    capped is True (runs bounded by -max_steps on purpose)."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    cmd = [mpiexec, "-n", str(np), exe] + list(args) + ["-output_dir", out, "-quiet"]
    p = subprocess.run(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=timeout)
    ok = (EXIT_OK, EXIT_NOT_CONVERGED) if capped else (EXIT_OK,)
    if expect_ok and p.returncode not in ok:
        print(p.stdout)
        sys.exit(f"FAIL: {' '.join(cmd)} exited with {p.returncode}")
    return p.returncode, p.stdout


def expected_verdict(value, error, allowable):
    """The verdict design.cpp's judge() must give: value +- error against the allowable."""
    if value + error <= allowable:
        return "PASS"
    return "EXCEEDED" if value - error > allowable else "INCONCLUSIVE: refine"


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def particles(out, fields=("position", "stress")):
    """Particle fields sorted by particle id (rank-independent order)."""
    import h5py
    import numpy as np
    with h5py.File(os.path.join(out, "particles.h5"), "r") as f:
        ids = f["particles/id"][:].astype(np.int64).ravel()
        order = np.argsort(ids)
        return ids[order], {k: f["particles/" + k][:][order] for k in fields}


class Checks:
    """Collects named checks; prints one line each and the closing count line."""

    def __init__(self, name):
        self.name, self.passed, self.failed = name, 0, 0

    def check(self, what, ok, detail=""):
        print(f"{'ok  ' if ok else 'FAIL'} {what} {detail}")
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def le(self, what, value, bound):
        self.check(what, value is not None and value <= bound, f"({value:.6g} <= {bound:.6g})")

    def ge(self, what, value, bound):
        self.check(what, value is not None and value >= bound, f"({value:.6g} >= {bound:.6g})")

    def done(self):
        print(f"{self.name}: {self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed or not self.passed else 0)


def stages(out):
    """The rows of a staged run's stages.csv."""
    import csv
    with open(os.path.join(out, "stages.csv")) as f:
        return list(csv.DictReader(f))


def waste_top(out, k):
    """Mean height of the top row of waste particles (material 0) at the end of stage k."""
    import h5py
    import numpy as np
    with h5py.File(os.path.join(out, f"series/stage_{k:03d}.h5"), "r") as f:
        x = f["particles/position"][:]
        x0 = f["particles/position0"][:]
        m = f["particles/material"][:].ravel()
    w = m == 0
    top = x0[w, 1].max()
    sel = w & (np.abs(x0[:, 1] - top) < 1e-9)
    return x[sel, 1].mean()
