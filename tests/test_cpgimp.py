"""cpGIMP (-shape cpgimp, shape_cpgimp.hpp): the bar past 60 % stretch and the column past 40 %
compression converge within 1 % of their exact solutions; uGIMP (-shape pmpm) on the same runs
is measured too and must stop or be worse than 1 %, so the comparison is real.

usage: test_cpgimp.py EXE NP OUTDIR

Bar: options/bar_large.opts, neo-Hookean, -bar_traction 4.63e6, -bar_box_length 2, -ppc 4.
Exact (closed_forms.neo_hookean_bar): homogeneous F = diag(l1, l2), l1 = 1.6006 (60.1 %
stretch), sigma_xx = t / l2; u = ((l1 - 1) X, (l2 - 1) Y) from the rollers at x = 0 and y = 0.
Errors are L2 over the particles (equal initial volumes), relative to the exact field's norm.
Measured (1 and 2 ranks alike): cpgimp 2244 steps, tip stretch 1.6008, stress 0.72 %,
displacement 0.025 %; pmpm stops at step 1540 (J <= 0 at the loaded end, stretch about 1.4), a
clean failure that counts as its degradation here. At -ppc 3
pmpm converges with 9.0 % stress error and cpgimp with 0.71 %. At -ppc 2 both shapes stop
("particle speed exceeds the material wave speed", the loaded end's corner, at about 40 %
stretch), and at -ppc 1 both stop even at 10 % stretch: not a block-size effect, left open.

Column: options/column_large.opts (neo-Hookean, nu = 0) with -mat_column_gamma 6e5: exact
J = 0.566 at the base (43 % compression); the scene's exact solution gives the errors.
Measured: cpgimp 2232 steps, stress 0.40 %, displacement 0.0095 %; pmpm 4.4 % and 0.86 %.

Rotation: the free block spinning at 10 rad/s (options/block.opts -block_velocity 0,0
-block_period 0 -block_omega 10, undamped; on 2 ranks it straddles the split) for 800 steps, past
a half turn: V = sqrt(F F^T) ignores the rotation, so every block keeps its initial half-size
h/4 up to the spinning block's elastic strain: measured 0.999-1.009 of it in every frame (one per
100 steps; F_xx passes 0 at step 400). Bound 2 %. A half-size from F's diagonal shrinks the blocks
by cos(theta) and inverted a particle at step 389, a quarter turn.

Bounds: 1 % (the issue's "within 1 %") for cpgimp's stress and displacement errors, and the
tip's stretch within 1 % of l1; the measured errors are 0.4 and 0.7 % of stress (bar, column), so a
regression in the block size, the traction face or the support would show. pmpm must fail
cleanly or exceed 1 % stress error (column: 4.4 %), or this test would not show what cpGIMP
changes.
"""
import glob
import re
import sys
import h5py
import numpy as np
from closed_forms import neo_hookean_bar
from pmpmtest import Checks, particles, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"cpgimp_np{np_}")
ERR = re.compile(r"^pmpm: error(?: on rank \d+)?: (.*)$")


def run_shape(args, d, shape):
    """cpgimp must run; pmpm may stop with pmpm's one-line error (that is its degradation)."""
    code, text = run(exe, np_, args + ["-shape", shape], d, expect_ok=shape == "cpgimp",
                     timeout=300)
    if code == 0:
        return True
    msg = next((m.group(1) for m in map(ERR.match, text.splitlines()) if m), "")
    print(f"     {shape}: exit {code}: {msg[:160]}")
    c.check(f"{d.split('/')[-1]}: fails with pmpm's one-line error", bool(msg))
    return False


# --- bar, 60 % stretch ------------------------------------------------------------------------
T, E, NU = 4.63e6, 1e7, 0.3
ex = neo_hookean_bar(T, E, NU)
c.ge("bar: exact stretch past 60 %", ex["l1"], 1.60)
bar = ["-options_file", "options/bar_large.opts", "-mat_bar_model", "neo_hookean", "-bar_traction",
       repr(T), "-bar_box_length", "2.0", "-ppc", "4"]
for shape in ("cpgimp", "pmpm"):
    d = f"{out}/bar_{shape}"
    if not run_shape(bar, d, shape):
        continue
    s = summary(d)
    _, p = particles(d, ("position", "position0", "stress"))
    X, x, sxx = p["position0"], p["position"], p["stress"][:, 0]
    ue = np.column_stack(((ex["l1"] - 1) * X[:, 0], (ex["l2"] - 1) * X[:, 1]))
    es = float(np.sqrt(np.mean((sxx - ex["sigma_xx"]) ** 2)) / ex["sigma_xx"])
    eu = float(np.sqrt(np.sum((x - X - ue) ** 2) / np.sum(ue ** 2)))
    tip = X[:, 0] > X[:, 0].max() - 1e-9
    stretch = float(np.mean(x[tip, 0] / X[tip, 0]))
    print(f"     bar_{shape}: converged={s['converged']} after {s['steps']} steps, tip stretch "
          f"{stretch:.4f} (exact {ex['l1']:.4f}), L2 stress error {es:.3e}, displacement {eu:.3e}")
    if shape == "cpgimp":
        c.check("bar_cpgimp: converged", s["converged"] is True)
        c.le("bar_cpgimp: |tip stretch / exact - 1|", abs(stretch / ex["l1"] - 1), 0.01)
        c.le("bar_cpgimp: L2 stress error", es, 0.01)
        c.le("bar_cpgimp: L2 displacement error", eu, 0.01)
    else:
        c.ge("bar_pmpm: L2 stress error (uGIMP degrades)", es, 0.01)

# --- column, 43 % compression at the base -----------------------------------------------------
G, MU = 6e5, 0.5e6  # nu = 0: mu = E / 2
a = G * 1.0 / MU
c.le("column: exact base compression past 40 % (J at the base)", 0.5 * (-a + np.sqrt(a * a + 4)),
     0.60)
col = ["-options_file", "options/column_large.opts", "-mat_column_gamma", repr(G)]
for shape in ("cpgimp", "pmpm"):
    d = f"{out}/column_{shape}"
    if not run_shape(col, d, shape):
        continue
    s = summary(d)
    r = s["results"]
    _, p = particles(d, ("F",))
    J = p["F"][:, 0] * p["F"][:, 3] - p["F"][:, 1] * p["F"][:, 2]
    print(f"     column_{shape}: converged={s['converged']} after {s['steps']} steps, min J "
          f"{J.min():.3f}, L2 stress error {r['stress_l2_error_rel']:.3e}, displacement "
          f"{r['displacement_l2_error_rel']:.3e}")
    if shape == "cpgimp":
        c.check("column_cpgimp: converged", s["converged"] is True)
        c.le("column_cpgimp: min J below 0.60 (past 40 % compression)", float(J.min()), 0.60)
        c.le("column_cpgimp: L2 stress error", r["stress_l2_error_rel"], 0.01)
        c.le("column_cpgimp: L2 displacement error", r["displacement_l2_error_rel"], 0.01)
    else:
        c.ge("column_pmpm: L2 stress error (uGIMP degrades)", r["stress_l2_error_rel"], 0.01)

# --- rotation: the blocks keep their size ------------------------------------------------------
d = f"{out}/block_rotation"
run(exe, np_, ["-options_file", "options/block.opts", "-block_velocity", "0,0", "-block_period",
               "0", "-block_omega", "10", "-max_steps", "800", "-output_every", "100", "-shape",
               "cpgimp"], d, timeout=300)
s = summary(d)
c.check("block_rotation: 800 steps", s["steps"] == 800, f"({s['steps']})")
lo, hi, fxx = 1.0, 1.0, []
L0 = 0.03125 / 4  # block.opts: h = 1/32 m, ppc 2
frames = sorted(glob.glob(f"{d}/series/*.h5"))
for fn in frames:
    with h5py.File(fn, "r") as f:
        r = f["particles/halfsize"][:] / L0
        fxx.append(float(np.mean(f["particles/F"][:, 0])))
    lo, hi = min(lo, float(r.min())), max(hi, float(r.max()))
print(f"     block_rotation: {len(frames)} frames, mean F_xx {min(fxx):.3f}..{max(fxx):.3f}, "
      f"half-size / l0 {lo:.4f}..{hi:.4f}")
c.check("block_rotation: 8 frames, past a half turn (mean F_xx < -0.9)", len(frames) == 8 and
        min(fxx) < -0.9)
c.le("block_rotation: max |half-size / l0 - 1| over every frame", max(hi - 1, 1 - lo), 0.02)
c.done()
