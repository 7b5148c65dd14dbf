"""The membrane of revolution clamped at its rim under its own weight, solved as a boundary-value
problem (scipy's solve_bvp, 1e-10): the reference of the axisymmetric catenary
(test_membrane_axisymmetric.py, whose docstring derives the equations) and of the 3D sheet
(test_sheet.py). Reference radius R, current (r, z), eps = |(r', z')| - 1, th = r / R - 1,
N = J (eps + nu th), N_th = J (th + nu eps)."""
import numpy as np
from scipy.integrate import solve_bvp


def membrane_bvp(a, q, J, nu, n=2001):
    """The membrane of revolution (docstring, 1.): sag, centre strain, rim strain and tensions."""
    d = 1e-6 * a
    R = np.linspace(d, a, n)

    def f(R, y):
        r, z, Hr = y
        Hz = 0.5 * q * R**2
        RN = np.hypot(Hr, Hz)
        th = r / R - 1
        eps = RN / R / J - nu * th
        return np.vstack([(1 + eps) * Hr / RN, (1 + eps) * Hz / RN, J * (th + nu * eps)])

    def bc(ya, yb):
        return np.array([ya[2] - J * (1 + nu) * (ya[0] - d), yb[0] - a, yb[1]])

    w0 = 0.662 * a * (q * a / (J * (1 - nu**2)))**(1 / 3)
    e0 = 0.4 * (w0 / a)**2
    y0 = np.vstack([R * (1 + e0), -w0 * (1 - (R / a)**2), R * J * (1 + nu) * e0])
    s = solve_bvp(f, bc, R, y0, tol=1e-10, max_nodes=200000)
    assert s.success, s.message
    y = s.sol(R)
    N = np.hypot(y[2], 0.5 * q * R**2) / R
    th = y[0] / R - 1
    eps = N / J - nu * th
    return {"sag": -y[1][0], "strain_centre": eps[0], "strain_rim": eps[-1], "tension_rim": N[-1],
            "tension_hoop_rim": J * (th[-1] + nu * eps[-1])}
