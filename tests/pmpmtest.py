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
    # one rank runs the binary itself (an MPI singleton): mpiexec's start-up is 2.5 s of waiting
    # per launch, minutes over the suite's few hundred one-rank runs
    launcher = [mpiexec, "-n", str(np)] if np > 1 else []
    cmd = launcher + [exe] + list(args) + ["-output_dir", out, "-quiet"]
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


def waste_column_tops(out, nstages):
    """A 3D run's waste (material 0) by particle column (the same initial x and z): the heights y
    of every particle (sorted by id) at the end of each of nstages stages, their initial
    positions, and the mask of each column's top particle."""
    import h5py
    import numpy as np
    y = []
    for k in range(nstages):
        with h5py.File(os.path.join(out, f"series/stage_{k:03d}.h5"), "r") as f:
            o = np.argsort(f["particles/id"][:].ravel())
            y.append(f["particles/position"][:][o][:, 1])
            x0 = f["particles/position0"][:][o]
            mat = f["particles/material"][:].ravel()[o]
    waste = mat == 0
    key = np.round(x0[:, 0], 6) * 1e6 + np.round(x0[:, 2], 6)  # a particle column
    top = np.zeros(len(x0), bool)
    for kk in np.unique(key[waste]):
        col = np.where(waste & (key == kk))[0]
        top[col[np.argmax(x0[col, 1])]] = True
    return y, x0, top


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


def compare_extruded(c, name, p2, p3, nz, length, unit):
    """-dim 3 against 2D: every particle of the 3D run (p3 = particles(dir, fields) with position,
    position0 and stress; nz along z per 2D particle, id // nz its 2D parent) against its parent
    in the 2D run p2: x, y to 1e-10 of `length`, z unchanged, the stresses xx yy zz xy to 1e-10 of
    the largest and yz, xz zero. Returns the 2D run's (position, position0) rows in the 3D run's
    order, or None if the particles do not match."""
    import numpy as np
    ids2, f2 = p2
    ids3, f3 = p3
    parent = np.searchsorted(ids2, ids3 // nz)
    ok = len(ids3) == nz * len(ids2) and np.all(ids2[np.minimum(parent, len(ids2) - 1)]
                                                 == ids3 // nz)
    c.check(f"{name}: {nz} particles along z per 2D particle", ok, f"({len(ids3)}, {len(ids2)})")
    if not ok:
        return None
    x2, s2 = f2["position"][parent], f2["stress"][parent]
    x3, s3 = f3["position"], f3["stress"]
    smax = np.abs(s2).max()
    c.le(f"{name}: x, y equal the 2D run's (/{unit})", np.abs(x3[:, :2] - x2).max() / length,
         1e-10)
    c.le(f"{name}: z unchanged (/{unit})", np.abs(x3[:, 2] - f3["position0"][:, 2]).max() / length,
         1e-10)
    c.le(f"{name}: xx yy zz xy equal the 2D run's (/max |stress|)",
         np.abs(s3[:, :4] - s2).max() / smax, 1e-10)
    c.le(f"{name}: yz, xz zero (/max |stress|)", np.abs(s3[:, 4:]).max() / smax, 1e-10)
    return x2, f2["position0"][parent]


def uniaxial_bar(c, d, t=100.0, E=1e7, nu=0.3):
    """The bar (options/bar.opts) in d, run in 3D with a free z face: the summary reports uniaxial
    stress, its tip displacement is t x / E within 1e-4 and the least-squares slopes of u_y in y
    and u_z in z are -nu t / E within 1e-4 (the state is uniform, so only the solver's
    tolerance is left; plane strain is 9.9 % and 30 % away)."""
    import numpy as np
    ru = summary(d)["results"]
    c.check("bar: uniaxial stress reported", ru.get("state") == "uniaxial stress")
    c.le("uniaxial bar: tip displacement against t x / E", ru["tip_displacement_error_rel"], 1e-4)
    _, f = particles(d, ("position", "position0"))
    u, x0 = f["position"] - f["position0"], f["position0"]
    for axis, name in ((1, "y"), (2, "z")):
        slope = np.polyfit(x0[:, axis], u[:, axis], 1)[0]
        c.le(f"uniaxial bar: du_{name}/d{name} against -nu t / E", abs(slope / (-nu * t / E) - 1),
             1e-4)


def degradation_stages(c, what, d, rows, strain, tol):
    """Stages 1 and 2 of a uniform-degradation run in d (stages.csv rows): the top row of waste
    settles by y (1 - exp(-strain)) of its height before the stage within tol (relative), the
    membrane by the waste's settlement within 2 %, its strain stays zero (< 1e-5). Returns the
    waste's settlement per stage."""
    import math
    y = [waste_top(d, k) for k in range(3)]
    settled = []
    for k in (1, 2):
        exact = y[k - 1] * (1 - math.exp(-strain))
        sim = y[k - 1] - y[k]
        settled.append(sim)
        c.le(f"{what}, stage {k}: waste settlement against the closed form (relative)",
             abs(sim / exact - 1), tol)
        ms = float(rows[k]["membrane_settlement"]) - float(rows[k - 1]["membrane_settlement"])
        c.le(f"{what}, stage {k}: membrane settlement against the waste's (relative)",
             abs(ms / sim - 1), 0.02)
        c.le(f"{what}, stage {k}: membrane strain stays zero",
             abs(float(rows[k]["peak_strain"])), 1e-5)
    return settled


def uniform_degradation(c, exe, np_, out, extra=(), label=""):
    """tests/cover_column.opts (4 m of linear elastic waste under 0.5 m of soil on a sheet, e_v =
    0.05 per stage in two stages), vertical and isotropic eigenstrain, with `extra` options: each
    stage's settlement of the top row of waste against the uniaxial-strain closed form within
    0.5 %, the sheet's settlement against the waste's within 2 %, its strain zero (< 1e-5), every
    stage converged (tests/test_cover.py's docstring says why)."""
    nu, ev = 0.3, 0.05  # per stage
    for mode, factor in (("vertical", 1.0), ("isotropic", (1 + nu) / (1 - nu) / 3)):
        d = f"{out}/degradation_{mode}"
        run(exe, np_, ["-options_file", "tests/cover_column.opts", "-cover_shrink_mode", mode] +
            list(extra), d)
        rows = stages(d)
        what = f"{label}{mode}"
        c.check(f"{what}: three stages recorded, all converged",
                len(rows) == 3 and all(r["converged"] == "1" for r in rows),
                f"({[r['steps'] for r in rows]} steps)")
        degradation_stages(c, what, d, rows, factor * ev, 0.005)
