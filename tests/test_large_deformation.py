"""Large deformation: the column compressed past 30 % at the base and the bar stretched past 50 %,
PMPM against standard MPM. A run either ends converged with every particle kept (summary count =
initial count, unique ids), J = det F > 0 everywhere and finite output, or stops with pmpm's
one-line error and writes nothing. Where PMPM must converge is stated per case.

usage: test_large_deformation.py EXE NP OUTDIR

Column: options/column_large.opts (neo-Hookean, nu = 0) with -mat_column_gamma 4.5e5: exact
J = 0.647 at the base (35 % compression). PMPM must converge: measured 3453 steps, min J 0.628,
L2 stress error 3.4 % (bound 6 %, as test_column.py's large case), displacement 0.79 % (bound
2 %). MPM fails: "Instability at step 265" (energy created as particles cross cell faces; before
the energy test of relaxation.cpp it failed at step 2322, and at -cfl 0.25 / 0.1 it inverts a
particle at step ~7500: it is not a time-step instability).

Bar: options/bar_large.opts with -mat_bar_model neo_hookean, -bar_box_length 2 (room to stretch).
The exact state is homogeneous, Cauchy sigma_xx = t / F_yy (dead load t per reference area), so
the cell-crossing noise is the spread of sigma_xx F_yy / t over the particles (0 exactly).
- t = 3e6 (exact stretch 1.3453, closed_forms.neo_hookean_bar; measured tip stretch 1.3475 (+0.17 %), F_xx
  1.30-1.42, the tip within 1 % of the exact stretch asserted): PMPM must converge:
  measured 2743 steps, std(sigma_xx F_yy / t) = 0.120 (bound 0.2), std(sigma_xx / t) = 0.138,
  mean(sigma_xx F_yy / t) - 1 = -0.8 % (bound 3 %). MPM inverts a particle at the first cell
  crossing of the loaded end (step ~147): clean failure.
- t = 4.63e6 (exact stretch 1.6006): measured, both shapes stop with the one-line error: PMPM at step
  1498 (load 0.72, stretch about 1.4: "particle speed exceeds the material wave speed"; the
  loaded end's corner particle is thrown off), MPM at step 119 (J <= 0). Accepted here as a
  clean failure; see the report: uGIMP keeps each particle's half-size at its undeformed value
  while the stress acts on the current volume, so at the loaded face the internal force is
  sigma J A0 against the traction t A0 = sigma F_yy A0, off by F_xx, and the leading node holds
  a sliver of mass. cpGIMP (-shape cpgimp, half-size stretched with the deformation) is the
  cure: tests/test_cpgimp.py runs this bar at -ppc 4 within 1 % of the exact solution; at -ppc 2,
  as here, cpgimp stops as well (docs/limitations.md), so REQUIRE_BAR_60 stays False.
"""
import os
import re
import sys
import numpy as np
from closed_forms import neo_hookean_bar
from pmpmtest import Checks, run, summary

REQUIRE_BAR_60 = False
exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"large_deformation_np{np_}")
ERR = re.compile(r"^pmpm: error(?: on rank \d+)?: (.*)$")


def load(d):
    import h5py
    with h5py.File(os.path.join(d, "particles.h5"), "r") as f:
        p = {k: f["particles/" + k][:] for k in ("id", "F", "stress", "position", "position0")}
    F = p["F"]
    p["J"] = F[:, 0] * F[:, 3] - F[:, 1] * F[:, 2]
    p["finite"] = all(np.all(np.isfinite(v)) for v in p.values() if hasattr(v, "dtype"))
    return p


def case(name, args, n_init, must_converge):
    """Run; check the invariants of a converged run or of a clean failure. Returns the particle
    fields and the summary of a converged run, else None."""
    d = f"{out}/{name}"
    code, text = run(exe, np_, args, d, expect_ok=False, timeout=300)
    if code != 0:
        msg = next((m.group(1) for m in map(ERR.match, text.splitlines()) if m), "")
        print(f"     {name}: exit {code}: {msg[:160]}")
        c.check(f"{name}: allowed to fail", not must_converge)
        c.check(f"{name}: one-line pmpm error", bool(msg))
        left = [f for _, _, fs in os.walk(d) for f in fs] if os.path.isdir(d) else []
        c.check(f"{name}: no output after the error", not left, str(left[:3]))
        return None, None
    s = summary(d)
    p = load(d)
    print(f"     {name}: converged={s['converged']} after {s['steps']} steps, min J "
          f"{p['J'].min():.3f}")
    c.check(f"{name}: converged", s["converged"] is True)
    c.check(f"{name}: no particle lost", s["particles"] == n_init and
            len(np.unique(p["id"])) == n_init, f"({s['particles']} of {n_init})")
    c.ge(f"{name}: min J", float(p["J"].min()), 1e-12)
    c.check(f"{name}: finite particle output", p["finite"])
    return p, s


# --- column, 35 % compression at the base ----------------------------------------------------
col = ["-options_file", "options/column_large.opts", "-mat_column_gamma", "4.5e5"]
n_col = 4 * 32 * 4
a = 4.5e5 * 1.0 / (0.5 * 1e6)  # gamma H / mu (nu = 0)
J_base = 0.5 * (-a + np.sqrt(a * a + 4))
c.le("column: exact base compression past 30 % (J at the base)", J_base, 0.70)
p, s = case("column_pmpm", col + ["-shape", "pmpm"], n_col, True)
if p is not None:
    r = s["results"]
    c.le("column_pmpm: min J below 0.70 (past 30 % compression)", float(p["J"].min()), 0.70)
    c.le("column_pmpm: L2 stress error", r["stress_l2_error_rel"], 0.06)
    c.le("column_pmpm: L2 displacement error", r["displacement_l2_error_rel"], 0.02)
p, s = case("column_mpm", col + ["-shape", "mpm"], n_col, False)
if p is not None:
    print(f"     column_mpm: L2 stress error {s['results']['stress_l2_error_rel']:.3e}")

# --- bar, 40 % and 60 % stretch -----------------------------------------------------------------
n_bar = 20 * 5 * 4
for t, must in ((3e6, True), (4.63e6, REQUIRE_BAR_60)):
    for shape in ("pmpm", "mpm"):
        name = f"bar_{shape}_t{t:g}"
        args = ["-options_file", "options/bar_large.opts", "-mat_bar_model", "neo_hookean",
                "-bar_traction", repr(t), "-bar_box_length", "2.0", "-shape", shape]
        p, s = case(name, args, n_bar, must and shape == "pmpm")
        if p is None:
            continue
        sxx, Fyy = p["stress"][:, 0], p["F"][:, 3]
        tip = p["position0"][:, 0] > 0.97
        stretch = float(np.mean(p["position"][tip, 0] / p["position0"][tip, 0]))
        noise = float(np.std(sxx * Fyy / t))
        bias = float(np.mean(sxx * Fyy / t) - 1)
        print(f"     {name}: tip stretch {stretch:.3f}, F_xx {p['F'][:, 0].min():.3f}.."
              f"{p['F'][:, 0].max():.3f}, std(sxx Fyy / t) {noise:.3e}, std(sxx / t) "
              f"{np.std(sxx / t):.3e}, mean(sxx Fyy / t) - 1 {bias:.2e}")
        if shape == "pmpm":
            c.ge(f"{name}: tip stretch past 30 %", stretch, 1.30)
            exact = neo_hookean_bar(t, 1e7, 0.3)["l1"]
            c.le(f"{name}: tip stretch against the exact {exact:.4f} (relative)",
                 abs(stretch / exact - 1), 0.01)
            c.le(f"{name}: noise std(sigma_xx F_yy / t)", noise, 0.2)
            c.le(f"{name}: |mean(sigma_xx F_yy / t) - 1|", abs(bias), 0.03)
c.done()
