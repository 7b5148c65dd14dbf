"""-solver newton with plastic materials (von Mises, Drucker-Prager) against closed forms, the
relaxation answer of the same scene, finite differences and the other rank count.

usage: test_newton_plastic.py EXE NP OUTDIR

The problem: options/column.opts (H = 1 m, E = 1e7 Pa, nu = 0.3, gamma = 2e4 N/m^3, sides on
rollers, base fixed) with a plastic material whose lower part yields. Uniaxial strain (e_xx =
e_zz = 0) under gravity, loaded proportionally (Newton's load steps), small strain:
  sigma_yy = -gamma d (depth d = H - Y, equilibrium, any material);
  elastic:   sigma_xx = sigma_zz = k0 sigma_yy, k0 = nu / (1 - nu), e_yy = sigma_yy / M;
  von Mises (sigma_y0, linear hardening H): yield at |sigma_yy| = S1 = sigma_y0 (1 - nu) / (1 - 2nu)
             (q = |sigma_yy - sigma_xx| = (1 - 2nu) / (1 - nu) |sigma_yy|); beyond it the deviator
             grows with 2 G_t, G_t = G H / (3G + H), and the volume with K:
             d sigma_yy = (K + 4 G_t / 3) d e_yy, q = sigma_y0 + 2 G_t |e_yy - e_yy(S1)|,
             sigma_xx = sigma_zz = sigma_yy + q (perfectly plastic: sigma_yy + sigma_y0, modulus K);
  Drucker-Prager (outer match, c, phi, psi = 0, H = 0): yield where the elastic K0 state reaches
             the cone, |sigma_yy| = S1 = xi c / ((1 - k0) / sqrt3 - eta (1 + 2 k0) / 3); beyond it
             the stress stays on the cone with sigma_xx = sigma_zz:
             sigma_xx = (xi c + sigma_yy (1/sqrt3 - eta/3)) / (1/sqrt3 + 2 eta/3)
             (independent of psi and of the path), and with psi = 0 (flow s / (2 sqrt J2)) the
             lateral constraint gives d e_yy / d sigma_yy = (1 - 2 nu a + 2 (a - nu (1 + a))) / E,
             a = d sigma_xx / d sigma_yy = (1/sqrt3 - eta/3) / (1/sqrt3 + 2 eta/3).
  u_y(Y) = -int_0^Y |e_yy| dy.
Bounds. sigma_xx, sigma_zz: Newton reaches the plateau on the monotonic load path exactly (the
return is exact for linear hardening), measured 2e-10 (von Mises) and 3e-16 (DP) of max|sigma_yy|,
bound 1e-6; relaxation's dynamic path overshoots and unloads (2.2e-3, 2.9e-4), so only Newton is
held to the closed form. Displacements: the discretisation (the elastic column: 1.5e-4), bound
2e-3. Against relaxation (same discrete equations, relaxation's path): stress L2 measured 2.3e-3,
bound 1e-2; positions 1.7e-3 of the settlement, bound 1e-2. Newton: at most 8 iterations per load
step (measured <= 7), and on the solves run to their absolute tolerance (see convergence()) the
last residual reduction at or below 1e-3 and the order of convergence of the last three norms,
log(r_n / r_n-1) / log(r_n-1 / r_n-2), at least 1.5 (1 is linear convergence, the mark of an
inconsistent tangent; 2 quadratic): measured 3.9, 12 and 5.2 on the columns, 1.87 on the 2D
landfill. -snes_test_jacobian inside a plastic solve
(iteration >= 1) measured 6e-6 to 1e-5 (forward differences across the returns' curvature),
bound 1e-4 (a missing term gives >= 1e-3); at a step's first iteration the plastic particles sit
on the yield surface, where the return has a kink and the forward differences mix the loading and
unloading branches (reported, not bounded).
"""
import re
import sys
import numpy as np
from pmpmtest import Checks, particles, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"newton_plastic_np{np_}")
NEWTON = ["-solver", "newton", "-snes_monitor", "-snes_converged_reason"]
COLUMN = ["-options_file", "options/column.opts"]
E, NU, GAMMA, H = 1e7, 0.3, 2e4, 1.0
G, K = E / (2 * (1 + NU)), E / (3 * (1 - 2 * NU))
M = K + 4 * G / 3
K0 = NU / (1 - NU)
SQ3 = np.sqrt(3.0)


def von_mises(sy, hard):
    """(S1, plastic modulus, sigma_xx(sigma_yy)) of the von Mises column."""
    s1 = sy * (1 - NU) / (1 - 2 * NU)
    gt = G * hard / (3 * G + hard)
    mp = K + 4 * gt / 3

    def sxx(syy):
        de = np.maximum(-syy - s1, 0) / mp  # plastic part of |e_yy|
        return np.where(-syy > s1, syy + sy + 2 * gt * de, K0 * syy)
    return s1, mp, sxx


def drucker_prager(coh, phi_deg):
    phi = np.radians(phi_deg)
    eta = 6 * np.sin(phi) / (SQ3 * (3 - np.sin(phi)))
    xi = 6 * np.cos(phi) / (SQ3 * (3 - np.sin(phi)))
    s1 = xi * coh / ((1 - K0) / SQ3 - eta * (1 + 2 * K0) / 3)
    a = (1 / SQ3 - eta / 3) / (1 / SQ3 + 2 * eta / 3)
    mp = E / (1 - 2 * NU * a + 2 * (a - NU * (1 + a)))

    def sxx(syy):
        cone = (xi * coh + syy * (1 / SQ3 - eta / 3)) / (1 / SQ3 + 2 * eta / 3)
        return np.where(-syy > s1, cone, K0 * syy)
    return s1, mp, sxx


def u_exact(Y, s1, mp):
    """u_y at initial height Y: -int_0^Y |e_yy| dy, |e_yy| piecewise linear in the depth."""
    y = np.linspace(0.0, H, 200001)
    s = GAMMA * (H - y)
    e = np.where(s > s1, s1 / M + (s - s1) / mp, s / M)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (e[1:] + e[:-1]) * np.diff(y))])
    return -np.interp(Y, y, cum)


def histories(log):
    """The SNES residual histories of a run, one list per solve, and each solve's SNES reason
    (-snes_converged_reason)."""
    solves, reasons = [], []
    for k, r, why in re.findall(r"^\s*(\d+) SNES Function norm ([0-9.eE+-]+)|Nonlinear solve "
                                r"(?:converged|did not converge) due to (\w+)", log, re.M):
        if why:
            reasons.append(why)
        elif int(k) == 0:
            solves.append([float(r)])
        else:
            solves[-1].append(float(r))
    return solves, reasons


def convergence(name, log, plastic_its):
    h, why = histories(log)
    its = [len(s) - 1 for s in h]
    c.check(f"{name}: SNES histories read", len(h) >= 10, f"({len(h)} solves)")
    c.le(f"{name}: most Newton iterations in a load step", max(its), 8)
    c.ge(f"{name}: a load step needing the plastic zone found (iterations)", max(its), plastic_its)
    hardest = h[int(np.argmax(its))]
    print(f"     {name}: iterations per solve {its}")
    print(f"     {name}: hardest solve |R| " + " ".join(f"{r:.2e}" for r in hardest))
    # The rate shows on solves run to their absolute tolerance (CONVERGED_FNORM_ABS; an
    # equilibrium step stops at a 1e-2 reduction, CONVERGED_FNORM_RELATIVE) above round-off:
    # 1e-12 of the run's largest initial |R| (measured floors 5e-14 to 1e-14 of it). Judged: those
    # starting at >= 1e-3 of that |R| with three norms above the floor (a residual of 1e-5 to 1e-3
    # of it is a grid reset's, where particles on the yield surface may unload: a kink, e.g.
    # 0.56 -> 7e-3 -> 2e-5 on the landfill).
    big = max(s[0] for s in h)
    above = [[r for r in s if r > 1e-12 * big] for s in h]
    c.check(f"{name}: a SNES reason per solve", len(why) == len(h), f"({len(why)}, {len(h)})")
    judged = [s for s, w in zip(above, why) if len(s) >= 3 and s[0] >= 1e-3 * big
              and w == "CONVERGED_FNORM_ABS"]
    c.check(f"{name}: solves judged", len(judged) >= 1, f"({len(judged)})")
    worst_last = max((s[-1] / s[-2] for s in judged), default=np.inf)
    c.le(f"{name}: last residual ratio of those solves", worst_last, 1e-3)
    # the order of convergence from the last three norms, log(r_n / r_n-1) / log(r_n-1 / r_n-2):
    # 1 for linear convergence, 2 for quadratic
    orders = [np.log(s[-1] / s[-2]) / np.log(s[-2] / s[-3]) for s in judged if s[-2] < s[-3]]
    c.ge(f"{name}: smallest order of convergence over those solves ({len(orders)})",
         min(orders, default=0.0), 1.5)


def compare(a, b):
    ia, fa = particles(a)
    ib, fb = particles(b)
    assert (ia == ib).all(), "different particles"
    dx = np.abs(fa["position"] - fb["position"]).max()
    sa, sb = fa["stress"], fb["stress"]
    return dx, np.linalg.norm(sa - sb) / np.linalg.norm(sb)


CASES = [
    ("von Mises, perfectly plastic", ["-mat_column_model", "von_mises",
                                      "-mat_column_yield_stress", "5000"], von_mises(5000, 0), 4),
    ("von Mises, hardening H = 1e6 Pa", ["-mat_column_model", "von_mises",
                                         "-mat_column_yield_stress", "5000",
                                         "-mat_column_hardening", "1e6"], von_mises(5000, 1e6), 3),
    ("Drucker-Prager, c = 400 Pa, phi = 20", ["-mat_column_model", "drucker_prager",
                                              "-mat_column_cohesion", "400",
                                              "-mat_column_friction_angle", "20"],
     drucker_prager(400, 20), 2),
]
for i, (name, mat, (s1, mp, sxx_of), plastic_its) in enumerate(CASES):
    d = f"{out}/case{i}"
    _, log = run(exe, np_, COLUMN + mat + NEWTON, d)
    run(exe, np_, COLUMN + mat, d + "_relax")
    s = summary(d)
    c.check(f"{name}: converged under Newton", s["converged"] is True and s["solver"] == "newton")
    ids, f = particles(d, ("position0", "displacement", "stress", "eps_p"))
    st, syy = f["stress"], f["stress"][:, 1]
    smax = np.abs(syy).max()
    plastic = -syy > s1
    yielded = f["eps_p"][:, 0] > 0 if f["eps_p"].ndim > 1 else f["eps_p"] > 0
    c.check(f"{name}: the lower part yields (closed form: depth > {s1 / GAMMA:.3f} m)",
            0.3 * len(syy) < plastic.sum() < 0.7 * len(syy) and (plastic == yielded).all(),
            f"({plastic.sum()} of {len(syy)} particles, eps_p > 0 on {yielded.sum()})")
    c.le(f"{name}: sigma_yy L2 error (scene)", s["results"]["stress_l2_error_rel"], 0.02)
    sxx = sxx_of(syy)
    c.le(f"{name}: max|sigma_xx - closed form| / max|sigma_yy|",
         np.abs(st[:, 0] - sxx).max() / smax, 1e-6)
    c.le(f"{name}: max|sigma_zz - closed form| / max|sigma_yy|",
         np.abs(st[:, 2] - sxx).max() / smax, 1e-6)
    ue = u_exact(f["position0"][:, 1], s1, mp)
    c.le(f"{name}: u_y L2 error against the closed form",
         np.linalg.norm(f["displacement"][:, 1] - ue) / np.linalg.norm(ue), 2e-3)
    rel = summary(d + "_relax")
    fr = particles(d + "_relax", ("stress",))[1]["stress"]
    print(f"     {name}: relaxation's sigma_xx off the closed form by "
          f"{np.abs(fr[:, 0] - sxx_of(fr[:, 1])).max() / smax:.2e} of max|sigma_yy| "
          f"({rel['steps']} explicit steps)")
    dx, ds = compare(d, d + "_relax")
    settle = np.abs(ue).max()
    c.le(f"{name}: vs relaxation, positions / settlement", dx / settle, 1e-2)
    c.le(f"{name}: vs relaxation, stress (L2, relative)", ds, 1e-2)
    convergence(name, log, plastic_its)

# a 2D plastic problem: the bonded landfill (test_newton.py's, h = 1 mm) with the waste von Mises
# at sigma_y = 9 MPa (the median of its elastic q: 2,300 of 3,488 particles yield, eps_p up to
# 0.4 at the membrane's ends). Stress directions rotate with the load, so the iterations show the
# tangent's quadratic rate (measured order >= 1.86, at most 5 iterations per load step). Against
# relaxation (its dynamic path): settlement 0.13 % (bound 2 %), peak membrane strain 0.49 % (bound
# 5 %; with the step-start gradient 0.8 % and 1.5 %). 1 rank (as test_newton.py's landfill).
if np_ == 1:
    LANDFILL = ["-options_file", "options/landfill.opts", "-cell_size", "0.001",
                "-mat_waste_model", "von_mises", "-mat_waste_yield_stress", "9e6"]
    _, log = run(exe, np_, LANDFILL + NEWTON, f"{out}/landfill")
    run(exe, np_, LANDFILL, f"{out}/landfill_relax")
    s, sr = summary(f"{out}/landfill"), summary(f"{out}/landfill_relax")
    c.check("plastic landfill converged under Newton", s["converged"] is True)
    yielded = (particles(f"{out}/landfill", ("eps_p",))[1]["eps_p"] > 0).sum()
    c.ge("plastic landfill: yielded particles", yielded, 1000)
    for key, bound in (("settlement_centre", 0.02), ("peak_axial_strain", 0.05)):
        c.le(f"plastic landfill: {key} against relaxation ({s['results'][key]:.4g}, "
             f"{sr['results'][key]:.4g})", abs(s["results"][key] / sr["results"][key] - 1), bound)
    convergence("plastic landfill", log, 4)

# the strip footing (options/footing.opts, von Mises, Prandtl's q_u = (2 + pi) c) in one stage: a
# single pressure (-footing_pressures q: no later stages, which Newton does not run yet) and
# without F-bar (which Newton does not have yet), so the locked discretisation of the footing
# test's "without F-bar" case (relaxation holds 1.05 q_u and collapses at 1.15 q_u). At 0.95 q_u
# Newton holds with relaxation's settlement (measured 0.14 %, bound 2 %); at 1.15 q_u its load
# steps stop converging (the mesh's collapse load), test_newton_robust.py. On 2 ranks: 0.95 q_u against relaxation on 2 ranks and
# against Newton on 1 (the solver's tolerance times the plastic tangent's conditioning: 1e-6).
FOOT = ["-options_file", "options/footing.opts", "-fbar", "0"]
run(exe, np_, FOOT + ["-footing_pressures", "48846", "-solver", "newton"], f"{out}/footing")
run(exe, np_, FOOT + ["-footing_pressures", "48846"], f"{out}/footing_relax")
s, sr = summary(f"{out}/footing"), summary(f"{out}/footing_relax")
st, sst = s["results"]["stages"][0], sr["results"]["stages"][0]
c.check("footing at 0.95 q_u holds under Newton", s["converged"] is True and st["holds"])
c.le(f"footing at 0.95 q_u: settlement against relaxation ({st['settlement']:.5g}, "
     f"{sst['settlement']:.5g} m)", abs(st["settlement"] / sst["settlement"] - 1), 0.02)
if np_ == 2:
    run(exe, 1, FOOT + ["-footing_pressures", "48846", "-solver", "newton"], f"{out}/footing_np1")
    s1 = summary(f"{out}/footing_np1")["results"]["stages"][0]
    c.le("footing at 0.95 q_u: Newton on 1 against 2 ranks (settlement)",
         abs(st["settlement"] / s1["settlement"] - 1), 1e-6)
# (at 1.15 q_u the load steps stop converging: test_newton_robust.py asserts the collapse)

# the assembled plastic Jacobian against PETSc's finite differences on a coarse column
for name, mat, _, _ in CASES[1:]:
    _, log = run(exe, np_, COLUMN + mat + ["-cell_size", "0.125", "-newton_load_steps", "3",
                                           "-snes_test_jacobian"] + NEWTON, f"{out}/fd")
    tests, k = [], None
    for line in log.splitlines():
        m = re.match(r"\s*(\d+) SNES Function norm", line)
        if m:
            k = int(m.group(1))
        m = re.search(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", line)
        if m:
            tests.append((k, float(m.group(1))))
    inner = [r for k, r in tests if k >= 1]
    print(f"     {name}: at a solve's first iteration (kink) "
          + " ".join(f"{r:.1e}" for k, r in tests if k == 0))
    c.check(f"{name}: Jacobian tests inside plastic solves ran", len(inner) >= 2, f"({len(inner)})")
    c.le(f"{name}: max ||J - Jfd||/||J|| at iterations >= 1", max(inner) if inner else None, 1e-4)

# rank invariance: the other rank count to the solver's tolerance (as test_newton.py)
if np_ == 2:
    for i in (0, 2):
        run(exe, 1, COLUMN + CASES[i][1] + NEWTON, f"{out}/case{i}_np1")
        dx, ds = compare(f"{out}/case{i}", f"{out}/case{i}_np1")
        c.le(f"{CASES[i][0]}: 1 vs 2 ranks, positions / 1 mm", dx / 1e-3, 1e-6)
        c.le(f"{CASES[i][0]}: 1 vs 2 ranks, stress (L2, relative)", ds, 1e-6)
c.done()
