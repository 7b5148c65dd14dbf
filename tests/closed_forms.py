"""Closed-form solutions for the field-scale cover scenes (membrane chain, anchorage, veneer,
arching, sheet over a void, shrinkage of a restrained layer).

Sources: docs/method.md, sections 1.3 and 6 (cited per
function). SI units throughout (m, N, Pa, N/m^3); plane strain, per metre of width, so a sheet's
force T and stiffness J are per metre (N/m) and a load w on a sheet is N/m per metre of sheet
(N/m^2). Strains are fractions, not per cent. Angles are given in degrees where the name says
``_deg``.

Importable by the scene tests (they run with PYTHONPATH=tests); ``/usr/bin/python3
tests/closed_forms.py`` runs a self-check against the check values printed in docs/method.md
(sections 1.3 and 6).
"""
import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["catenary", "pullout", "terzaghi_arching", "terzaghi_arching_ktan",
           "arching_pressure_paper", "giroud_omega", "giroud_strain", "giroud_paper_form",
           "giroud_self_consistent", "veneer_infinite", "koerner_soong", "koerner_soong_fs",
           "uniaxial_strain_shrinkage", "neo_hookean_bar"]


def _positive(name, v):
    if not (v > 0 and math.isfinite(v)):
        raise ValueError(f"{name} must be positive and finite, got {v!r}")


def _nonnegative(name, v):
    if not (v >= 0 and math.isfinite(v)):
        raise ValueError(f"{name} must be >= 0 and finite, got {v!r}")


# ------------------------------------------------------------------------------------------------
# docs/method.md, section 6.1: elastic catenary
def catenary(l, L0, w, J):
    """Elastic catenary: a sheet alone under its own weight, pinned ends at equal height.

    docs/method.md, section 6.1 (Irvine, Cable Structures, 1981, ch. 1). Span l (m), unstretched length L0 (m),
    weight w per unstretched length (N/m per metre of width, w = gamma t), axial stiffness J (N/m),
    linear law T = J eps with eps = current / initial length - 1. Lagrangian coordinate s in
    [0, L0] from the left support; horizontal tension H; end reaction V = w L0 / 2.

        x(s) = H s / J + (H / w) [asinh((w s - V) / H) + asinh(V / H)]
        y(s) = (w s^2 / 2 - V s) / J + (H / w) [sqrt(1 + ((w s - V) / H)^2) - sqrt(1 + (V / H)^2)]

    H is the root of x(L0) = l, i.e. H L0 / J + (2 H / w) asinh(w L0 / (2 H)) = l. The left side
    increases strictly with H (asinh(z) > z / sqrt(1 + z^2)) from 0 (H -> 0) past l at
    H = J l / L0, so the root is unique and bracketed; brentq finds it to round-off.

    Returns a dict: H, V (N/m); sag (m, positive, mid-span depth below the supports);
    tension_mid = H and tension_support = sqrt(H^2 + V^2) (N/m); strain_mid, strain_support
    (= tension / J); and vectorised callables of s (m, array-like): x(s), y(s) (m; y is negative
    below the chord through the supports), tension(s) = sqrt(H^2 + (w s - V)^2), strain(s).
    Check (docs/method.md, section 6.1): l = L0 = 10, w = 100, J = 1e5: H = 1586.2, sag = 0.7819, strain 1.586 %
    mid-span, 1.663 % at the supports.
    """
    for name, v in (("l", l), ("L0", L0), ("w", w), ("J", J)):
        _positive(name, v)
    V = 0.5 * w * L0

    def span(H):
        return H * L0 / J + (2.0 * H / w) * math.asinh(V / H) - l

    hi = J * l / L0  # span(hi) > 0
    lo = hi
    while span(lo) >= 0.0:  # span -> -l as H -> 0
        lo *= 1e-3
    H = brentq(span, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)

    def x(s):
        s = np.asarray(s, dtype=float)
        return H * s / J + (H / w) * (np.arcsinh((w * s - V) / H) + math.asinh(V / H))

    def y(s):
        s = np.asarray(s, dtype=float)
        return ((0.5 * w * s * s - V * s) / J
                + (H / w) * (np.sqrt(1.0 + ((w * s - V) / H) ** 2) - math.sqrt(1.0 + (V / H) ** 2)))

    def tension(s):
        s = np.asarray(s, dtype=float)
        return np.sqrt(H * H + (w * s - V) ** 2)

    def strain(s):
        return tension(s) / J

    sag = w * L0 * L0 / (8.0 * J) + (H / w) * (math.sqrt(1.0 + (V / H) ** 2) - 1.0)
    T_sup = math.hypot(H, V)
    return dict(H=H, V=V, sag=sag, tension_mid=H, tension_support=T_sup, strain_mid=H / J,
                strain_support=T_sup / J, x=x, y=y, tension=tension, strain=strain)


# ------------------------------------------------------------------------------------------------
# docs/method.md, section 6.2: pull-out of an anchored sheet
def pullout(P, sigma_n, mu_t, mu_b, J, L):
    """Pull-out of an anchored sheet from rigid soil with a rigid-plastic Coulomb interface.

    docs/method.md, section 6.2. Sheet of anchored length L (m) under normal stress sigma_n (Pa), friction
    coefficients mu_t above and mu_b below, axial stiffness J (N/m), pulled at its end (x = 0) by
    P (N/m) at or below the capacity (mu_t + mu_b) sigma_n L. With m = (mu_t + mu_b) sigma_n
    (shear per metre of sheet, N/m^2), the interface slips (at full friction) over the mobilised
    length x_a = P / m and is at rest beyond it:

        T(x) = P - m x  for x < x_a,  0 beyond;   u(x) = (P - m x)^2 / (2 m J)  for x < x_a,
        end displacement u0 = P^2 / (2 m J)   (u = integral of T / J from x to x_a).

    Returns a dict: capacity (N/m), m (N/m^2), x_a (m), u0 (m), and vectorised callables of x
    (distance from the pulled end, m): tension(x) (N/m), strain(x) = T / J, displacement(x) (m,
    towards the pull). Raises ValueError above capacity (the sheet pulls out: no static answer).
    """
    _nonnegative("P", P)
    _positive("sigma_n", sigma_n)
    _nonnegative("mu_t", mu_t)
    _nonnegative("mu_b", mu_b)
    _positive("J", J)
    _positive("L", L)
    m = (mu_t + mu_b) * sigma_n
    _positive("(mu_t + mu_b) sigma_n", m)
    capacity = m * L
    if P > capacity:
        raise ValueError(f"pullout: P = {P} exceeds the capacity (mu_t + mu_b) sigma_n L = "
                         f"{capacity}: the sheet pulls out")
    x_a = P / m

    def tension(x):
        x = np.asarray(x, dtype=float)
        return np.clip(P - m * x, 0.0, None)

    def strain(x):
        return tension(x) / J

    def displacement(x):
        return tension(x) ** 2 / (2.0 * m * J)

    return dict(capacity=capacity, m=m, x_a=x_a, u0=P * P / (2.0 * m * J), tension=tension,
                strain=strain, displacement=displacement)


# ------------------------------------------------------------------------------------------------
# docs/method.md, sections 6.4 and 1.3: Terzaghi arching over a long void
def terzaghi_arching_ktan(gamma, B, H, ktan, c=0.0, q=0.0):
    """Terzaghi's arching pressure with the product K tan(phi) given directly (docs/method.md, section 6.4).

        sigma_v = (gamma B / 2 - c) / (K tan phi) (1 - exp(-2 K tan phi H / B))
                  + q exp(-2 K tan phi H / B)

    gamma unit weight (N/m^3), B void width (m), H cover height (m), ktan = K tan(phi) (-),
    c cohesion (Pa), q surcharge (Pa). Returns the vertical stress on the void (Pa). ktan = 0 is
    the no-arching limit gamma H - 2 c H / B + q (continuous). A bracket, not an exact answer
    (docs/method.md, section 6.4: trapdoor tests give a K unlike the textbook value).
    """
    _nonnegative("gamma", gamma)
    _positive("B", B)
    _nonnegative("H", H)
    _nonnegative("K tan(phi)", ktan)
    x = 2.0 * ktan * H / B
    if x == 0.0:
        return gamma * H - 2.0 * c * H / B + q
    # -expm1(-x) = 1 - exp(-x) without cancellation for small x
    return (0.5 * gamma * B - c) / ktan * (-math.expm1(-x)) + q * math.exp(-x)


def terzaghi_arching(gamma, B, H, K, phi_deg, c=0.0, q=0.0):
    """Terzaghi's arching pressure on a long void (trapdoor) of width B under cover H.

    docs/method.md, section 6.4: lateral earth pressure ratio K, soil friction phi_deg (degrees), cohesion c (Pa),
    surcharge q (Pa), unit weight gamma (N/m^3). Returns sigma_v (Pa); see terzaghi_arching_ktan.
    """
    _nonnegative("K", K)
    return terzaghi_arching_ktan(gamma, B, H, K * math.tan(math.radians(phi_deg)), c, q)


def arching_pressure_paper(gamma, b, H, q=0.0):
    """The seed paper's eq. (21), sign corrected (docs/method.md, section 1.3): Terzaghi with
    K tan(phi) = 0.25, B = b and c = 0 (Giroud et al. 1990's choice):

        p = 2 gamma b (1 - exp(-0.5 H / b)) + q exp(-0.5 H / b)   (Pa)

    Check (docs/method.md, section 1.3, load II): gamma = 1.5e9, b = 6e-3, H = 8e-3: p = 8.758e6 Pa.
    """
    return terzaghi_arching_ktan(gamma, b, H, 0.25, 0.0, q)


# ------------------------------------------------------------------------------------------------
# docs/method.md, sections 1.3 and 6.5: Giroud's tensioned membrane over a void
def giroud_omega(y, b):
    """Tension factor Omega = (1/4) (2y/b + b/(2y)) of a circular arc of chord b and sag y
    (docs/method.md, section 1.3; Giroud et al. 1990). The arc's radius is b Omega, so T = p b Omega."""
    _positive("y", y)
    _positive("b", b)
    return 0.25 * (2.0 * y / b + b / (2.0 * y))


def giroud_strain(y, b):
    """Strain of the arc (arc length / chord - 1), docs/method.md, section 1.3:

        eps = 2 Omega asin(1/(2 Omega)) - 1          (y/b <= 0.5)
        eps = 2 Omega (pi - asin(1/(2 Omega))) - 1   (y/b >  0.5)
    """
    Om = giroud_omega(y, b)
    a = math.asin(min(1.0, 1.0 / (2.0 * Om)))
    if y / b <= 0.5:
        return 2.0 * Om * a - 1.0
    return 2.0 * Om * (math.pi - a) - 1.0


def giroud_paper_form(p, b, y):
    """The paper's use of Giroud's solution (docs/method.md, section 1.3): a given sag y (m) plugged into the
    geometry, pressure p (Pa), void width b (m). Returns dict(y, Omega, eps, T) with
    T = p b Omega (N/m); stress is T / t. Stress and strain are not linked by a modulus here.
    Check: load II (p = 8.758e6, b = 6e-3), y = 2e-3: Omega = 0.5417, eps = 27.40 %,
    T / t = 28.47 MPa with t = 1e-3.
    """
    Om = giroud_omega(y, b)
    return dict(y=y, Omega=Om, eps=giroud_strain(y, b), T=p * b * Om)


def giroud_self_consistent(p, b, J):
    """Self-consistent Giroud membrane: close docs/method.md, section 1.3 with T = J eps and solve

        p b Omega(y) = J eps(y)

    for the sag y (m). p arching pressure on the sheet (Pa), b void width (m), J axial stiffness
    (N/m, e.g. E t). With theta = 2 atan(2y/b) in (0, pi), Omega = 1 / (2 sin theta) and
    eps = theta / sin(theta) - 1 on both branches, so the equation is
    theta - sin(theta) = p b / (2 J): one root iff p b / (2 J) < pi (else ValueError: a linear
    sheet cannot carry the load). brentq on theta; y = (b/2) tan(theta/2).

    Returns dict(y, eps, T, Omega, theta): T = p b Omega = J eps (N/m); stress is T / t.
    Check (docs/method.md, section 1.3): p = 8.758e6 (load II), b = 6e-3, J = 0.207e9 * 1e-3:
    y = 1.498e-3 m, eps = 15.9 %, T / t = 32.9 MPa (t = 1e-3); load I (gamma 7.5e8):
    y = 1.149e-3, eps = 9.5 %, 19.7 MPa.
    """
    _positive("p", p)
    _positive("b", b)
    _positive("J", J)
    kappa = p * b / (2.0 * J)
    if not kappa < math.pi:
        raise ValueError(f"giroud_self_consistent: p b / (2 J) = {kappa} >= pi: no equilibrium "
                         "sag for a linear sheet")

    def h(th):  # theta - sin(theta), series below 1e-3 to keep relative accuracy
        if th < 1e-3:
            return th ** 3 / 6.0 * (1.0 - th * th / 20.0) - kappa
        return th - math.sin(th) - kappa

    theta = brentq(h, 0.0, math.pi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)
    y = 0.5 * b * math.tan(0.5 * theta)
    Om = giroud_omega(y, b)
    return dict(y=y, eps=giroud_strain(y, b), T=p * b * Om, Omega=Om, theta=theta)


# ------------------------------------------------------------------------------------------------
# docs/method.md, section 6.3: veneer stability
def veneer_infinite(beta_deg, delta_deg, g=9.81):
    """Cohesionless cover on an infinite slope of angle beta_deg sliding on an interface of
    friction angle delta_deg (docs/method.md, section 6.3; docs/method.md, section 2.5 for the block):

        FS = tan(delta) / tan(beta)
        when it slides (FS < 1): a = g (sin beta - tan delta cos beta)

    Returns dict(FS, a, slides): a (m/s^2, down the slope) is 0 when FS >= 1 (a cover at rest
    stays at rest).
    """
    b = math.radians(beta_deg)
    d = math.radians(delta_deg)
    _positive("beta", b)
    FS = math.tan(d) / math.tan(b)
    slides = FS < 1.0
    a = g * (math.sin(b) - math.tan(d) * math.cos(b)) if slides else 0.0
    return dict(FS=FS, a=a, slides=slides)


def koerner_soong(gamma, h, L, beta_deg, phi_deg, delta_deg):
    """Koerner and Soong (1998) two-wedge veneer analysis, cohesion and adhesion zero
    (docs/method.md, section 6.3). gamma unit weight (N/m^3), h cover thickness (m, perpendicular to the slope),
    L slope length (m, along the slope), beta slope angle, phi soil friction, delta interface
    friction (degrees):

        W_A = gamma h^2 (L/h - 1/sin beta - tan(beta)/2),  N_A = W_A cos beta,
        W_P = gamma h^2 / sin(2 beta)
        a = (W_A - N_A cos beta) cos beta
        b = -[(W_A - N_A cos beta) sin beta tan phi + N_A tan delta sin beta cos beta
              + W_P tan phi sin beta]
        c = N_A tan delta sin^2 beta tan phi
        FS = (-b + sqrt(b^2 - 4 a c)) / (2 a)

    Returns dict(FS, W_A, N_A, W_P, a, b, c) (forces in N/m). A limit-equilibrium estimate, not an
    exact solution; FS tends to tan(delta)/tan(beta) as L/h -> infinity (the toe wedge's share
    vanishes).
    """
    _positive("gamma", gamma)
    _positive("h", h)
    _positive("L", L)
    be, ph, de = (math.radians(v) for v in (beta_deg, phi_deg, delta_deg))
    _positive("beta", be)
    sb, cb = math.sin(be), math.cos(be)
    tp, td = math.tan(ph), math.tan(de)
    W_A = gamma * h * h * (L / h - 1.0 / sb - math.tan(be) / 2.0)
    if not W_A > 0:
        raise ValueError("koerner_soong: slope too short for the wedge geometry (W_A <= 0)")
    N_A = W_A * cb
    W_P = gamma * h * h / math.sin(2.0 * be)
    a = (W_A - N_A * cb) * cb
    b = -((W_A - N_A * cb) * sb * tp + N_A * td * sb * cb + W_P * tp * sb)
    c = N_A * td * sb * sb * tp
    FS = (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
    return dict(FS=FS, W_A=W_A, N_A=N_A, W_P=W_P, a=a, b=b, c=c)


def koerner_soong_fs(gamma, h, L, beta_deg, phi_deg, delta_deg):
    """Factor of safety of koerner_soong (docs/method.md, section 6.3, cohesion and adhesion zero)."""
    return koerner_soong(gamma, h, L, beta_deg, phi_deg, delta_deg)["FS"]


# ------------------------------------------------------------------------------------------------
def uniaxial_strain_shrinkage(e, H, nu, isotropic=True):
    """Settlement (m, positive down) of a linear elastic layer of height H (m) on a fixed base,
    laterally restrained (rollers; plane strain, so the out-of-plane strain is zero too), free top,
    that shrinks by an eigenstrain of magnitude e (e > 0 contracts; e < 0 swells):

      isotropic eigenstrain -e I:      settlement = (1 + nu) / (1 - nu) e H
      vertical eigenstrain -e (yy):    settlement = e H

    Derivation (isotropic): sigma_yy = 0 at the free top and everywhere (no body force);
    lateral strain zero gives sigma_xx = sigma_zz = E e / (1 - nu) (tension), and
    eps_yy = -e - 2 nu sigma_xx / E = -e (1 + nu) / (1 - nu). Independent of E. Small strain;
    superposes on the self-weight settlement gamma H^2 / (2 M) (docs/method.md, section 2.2).
    """
    _positive("H", H)
    if isotropic:
        if not -1.0 < nu < 1.0:
            raise ValueError(f"nu = {nu} outside (-1, 1)")
        return (1.0 + nu) / (1.0 - nu) * e * H
    return e * H


# ------------------------------------------------------------------------------------------------
# The bar (docs/method.md, section 2.1) at large stretch: compressible neo-Hookean (elastic.hpp,
# sigma = (mu (B - I) + lambda ln J I) / J), plane strain, dead load t per reference area on the
# end, free top: a homogeneous state F = diag(l1, l2, 1) with
#   sigma_yy = 0:           mu (l2^2 - 1) + lambda ln(l1 l2) = 0,
#   sigma_xx l2 = t:        (mu (l1^2 - 1) + lambda ln(l1 l2)) / l1 = t.
def neo_hookean_bar(t, E, nu):
    """Stretches (l1 along the bar, l2 across) and Cauchy sigma_xx = t / l2 of the plane-strain
    neo-Hookean bar under a dead end load t (Pa per reference area, tension > 0)."""
    _positive("E", E)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu = {nu} outside (-1, 0.5)")
    mu, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))

    def l2_of(l1):  # sigma_yy = 0 for l2; mu l2^2 + lambda ln l2 increases with l2
        return brentq(lambda l2: mu * (l2 * l2 - 1) + lam * math.log(l1 * l2), 1e-6, 10.0,
                      xtol=1e-15, rtol=1e-15)

    def nominal(l1):
        return mu * (l1 * l1 - 1) / l1 - mu * (l2_of(l1) ** 2 - 1) / l1 - t

    hi = 1.0 + 1e-12
    while nominal(hi) * nominal(1.0) > 0:  # t >= 0 or < 0: bracket the stretch
        hi = hi * 2 if t > 0 else hi / 2
    l1 = brentq(nominal, min(1.0, hi), max(1.0, hi), xtol=1e-15, rtol=1e-15)
    l2 = l2_of(l1)
    return {"l1": l1, "l2": l2, "sigma_xx": t / l2}


# ------------------------------------------------------------------------------------------------
def _self_check():
    def close(name, got, want, tol):
        ok = abs(got - want) <= tol
        print(f"  {name:44s} {got:.6g}  (want {want:.6g} +- {tol:.2g}) {'ok' if ok else 'FAIL'}")
        assert ok, name

    print("catenary (docs/method.md, section 6.1): l = L0 = 10 m, w = 100 N/m^2, J = 1e5 N/m")
    cat = catenary(10.0, 10.0, 100.0, 1e5)
    close("H (N/m)", cat["H"], 1586.2, 0.05)
    close("sag (m)", cat["sag"], 0.7819, 5e-5)
    close("strain mid-span (%)", 100 * cat["strain_mid"], 1.586, 5e-4)
    close("strain supports (%)", 100 * cat["strain_support"], 1.663, 5e-4)
    # internal consistency: ends, mid-span, and the stretch of the curve equals T / J
    s = np.linspace(0.0, 10.0, 20001)
    close("x(L0) - l (m)", float(cat["x"](10.0)) - 10.0, 0.0, 1e-12)
    close("y(0), y(L0) (m)", abs(float(cat["y"](0.0))) + abs(float(cat["y"](10.0))), 0.0, 1e-12)
    close("y(L0/2) + sag (m)", float(cat["y"](5.0)) + cat["sag"], 0.0, 1e-12)
    ds = np.hypot(np.diff(cat["x"](s)), np.diff(cat["y"](s))) / np.diff(s) - 1.0
    close("max |stretch - T/J| (finite diff.)",
          float(np.max(np.abs(ds - cat["strain"](0.5 * (s[1:] + s[:-1]))))), 0.0, 1e-8)

    print("pull-out (docs/method.md, section 6.2): P = 5 kN/m, sigma_n = 20 kPa, mu = 0.3 + 0.4, J = 1e6, L = 2")
    po = pullout(5e3, 20e3, 0.3, 0.4, 1e6, 2.0)
    close("x_a (m)", po["x_a"], 5e3 / 14e3, 1e-15)
    x = np.linspace(0.0, 2.0, 200001)
    u0_num = float(np.sum(0.5 * (po["strain"](x[1:]) + po["strain"](x[:-1])) * np.diff(x)))
    close("u0 vs integral of T/J (m)", po["u0"], u0_num, 1e-9)
    close("T(0) (N/m)", float(po["tension"](0.0)), 5e3, 0.0)

    print("arching (docs/method.md 6.4 = 1.3 with K tan phi = 0.25)")
    pII = arching_pressure_paper(1.5e9, 6e-3, 8e-3)
    pI = arching_pressure_paper(7.5e8, 6e-3, 8e-3)
    close("p load II (MPa)", pII / 1e6, 8.758, 5e-4)
    K = 0.25 / math.tan(math.radians(30.0))
    close("terzaghi(K, phi=30) - paper form (Pa)", terzaghi_arching(1.5e9, 6e-3, 8e-3, K, 30.0)
          - pII, 0.0, 1e-6 * pII)
    close("no arching limit: gamma H + q (Pa)", terzaghi_arching(2e4, 1.0, 3.0, 0.0, 30.0, 0.0,
                                                                 1e3), 6.1e4, 1e-9)

    print("Giroud (docs/method.md, section 1.3), b = 6 mm, t = 1 mm, E = 0.207 GPa")
    t = 1e-3
    pf = giroud_paper_form(pII, 6e-3, 2e-3)
    close("paper form y = 2 mm: Omega", pf["Omega"], 0.5417, 5e-5)
    close("paper form y = 2 mm: eps (%)", 100 * pf["eps"], 27.40, 5e-3)
    close("paper form y = 2 mm: sigma (MPa)", pf["T"] / t / 1e6, 28.47, 5e-3)
    J = 0.207e9 * t
    gII = giroud_self_consistent(pII, 6e-3, J)
    close("self-consistent II: y (mm)", 1e3 * gII["y"], 1.498, 5e-4)
    close("self-consistent II: eps (%)", 100 * gII["eps"], 15.9, 0.05)
    close("self-consistent II: sigma (MPa)", gII["T"] / t / 1e6, 32.9, 0.05)
    close("self-consistent II: T - J eps (N/m)", gII["T"] - J * gII["eps"], 0.0, 1e-9 * gII["T"])
    gI = giroud_self_consistent(pI, 6e-3, J)
    close("self-consistent I: y (mm)", 1e3 * gI["y"], 1.149, 5e-4)
    close("self-consistent I: eps (%)", 100 * gI["eps"], 9.5, 0.05)
    close("self-consistent I: sigma (MPa)", gI["T"] / t / 1e6, 19.7, 0.05)

    print("veneer (docs/method.md, section 6.3)")
    v = veneer_infinite(30.0, math.degrees(math.atan(0.3)))
    close("block mu = 0.3, 30 deg: a (m/s^2)", v["a"], 2.356, 5e-4)  # docs/method.md, section 2.5
    close("FS = 0.3 / tan 30", v["FS"], 0.3 / math.tan(math.radians(30.0)), 1e-15)
    assert veneer_infinite(20.0, 25.0)["a"] == 0.0
    ks = koerner_soong_fs(18e3, 0.3, 30.0, 18.4, 30.0, 22.0)
    inf = veneer_infinite(18.4, 22.0)["FS"]
    print(f"  Koerner-Soong L = 30 m, h = 0.3 m, 18.4 deg, phi 30, delta 22: FS = {ks:.4f} "
          f"(infinite slope {inf:.4f})")
    assert ks > inf, "the toe wedge must add resistance"
    close("Koerner-Soong L/h = 1e6 -> infinite slope", koerner_soong_fs(18e3, 0.3, 3e5, 18.4, 30.0,
                                                                         22.0), inf, 1e-5)

    print("restrained shrinkage")
    close("isotropic e = 1 %, H = 2 m, nu = 0.25 (m)", uniaxial_strain_shrinkage(0.01, 2.0, 0.25),
          0.02 * 1.25 / 0.75, 1e-15)
    close("vertical e = 1 %, H = 2 m (m)", uniaxial_strain_shrinkage(0.01, 2.0, 0.25, False),
          0.02, 0.0)
    print("neo-Hookean bar (plane strain, dead load), E = 1e7, nu = 0.3")
    mu, lam = 1e7 / 2.6, 1e7 * 0.3 / (1.3 * 0.4)
    for t in (4.63e6, -2e6):
        b = neo_hookean_bar(t, 1e7, 0.3)
        l1, l2 = b["l1"], b["l2"]
        close(f"t = {t:g}: sigma_yy (Pa)", mu * (l2 * l2 - 1) + lam * math.log(l1 * l2), 0.0, 1e-6)
        close(f"t = {t:g}: sigma_xx l2 - t (Pa)",
              (mu * (l1 * l1 - 1) + lam * math.log(l1 * l2)) / (l1 * l2) * l2 - t, 0.0, 1e-6)
    close("t = 4.63e6: stretch l1 (past 60 %)", neo_hookean_bar(4.63e6, 1e7, 0.3)["l1"], 1.6006,
          5e-5)
    small = neo_hookean_bar(1e2, 1e7, 0.3)  # small-strain limit: u_x = t (1 - nu^2) x / E
    close("t -> 0: (l1 - 1) E / (t (1 - nu^2))", (small["l1"] - 1) * 1e7 / (1e2 * 0.91), 1.0, 1e-4)
    print("closed_forms self-check: all passed")


if __name__ == "__main__":
    _self_check()
