"""Kalker's creep coefficients C11, C22, C23 of the linear theory of steady rolling (docs/theory.md §7.3).

Kalker's sign convention (the field's habit, used everywhere in `solver.creep`): body 1 rolls in +x over body 2,
the creepages are the rigid slip velocities of body 1 relative to body 2 divided by the rolling speed,
xi (longitudinal, along the rolling direction), eta (lateral), phi (spin, 1/mm), and the forces are those ON
BODY 1; they oppose the creepages:

    Fx = -G c^2 C11 xi,   Fy = -G c^2 C22 eta - G c^3 C23 phi,   Mz = G c^3 C23 eta - G c^4 C33 phi

with c = sqrt(a b) (a: semi-axis along the rolling direction, b: lateral), G Kalker's combined shear modulus
(`bem.materials.MaterialPair.G`). The table (Kalker 1967, Table E.3 of Kalker 1990) is indexed by g = a/b for
a <= b and by b/a for a > b; the coefficients are interpolated as in CONTACT: linearly in g between rows,
quadratically (Lagrange through nu = 0, 0.25, 0.5) in 1/C over nu; outside the table (g < 0.1) the slender-ellipse
asymptotes. C33 is not in that table: `C33_PUBLISHED` holds the few values of the one public transcription of
Kalker's full table (docs/theory.md §7.3), for comparison only.
"""
import math

import numpy as np

from rollcontact.bem.errors import InputError

#: Poisson ratios of the table's columns.
NU_COLUMNS = (0.0, 0.25, 0.5)

#: Rows (g, C11 at nu = 0/0.25/0.5, C22 at ..., C23 at ...) for a <= b, g = a/b (docs/theory.md §7.3).
_ROWS_A_LE_B = (
    (0.1, 2.51, 3.31, 4.85, 2.51, 2.52, 2.53, 0.334, 0.473, 0.731),
    (0.2, 2.59, 3.37, 4.81, 2.59, 2.63, 2.66, 0.483, 0.603, 0.809),
    (0.3, 2.68, 3.44, 4.80, 2.68, 2.75, 2.81, 0.607, 0.715, 0.889),
    (0.4, 2.78, 3.53, 4.82, 2.78, 2.88, 2.98, 0.720, 0.823, 0.977),
    (0.5, 2.88, 3.62, 4.83, 2.88, 3.01, 3.14, 0.827, 0.929, 1.07),
    (0.6, 2.98, 3.72, 4.91, 2.98, 3.14, 3.31, 0.930, 1.03, 1.18),
    (0.7, 3.09, 3.81, 4.97, 3.09, 3.28, 3.48, 1.03, 1.14, 1.29),
    (0.8, 3.19, 3.91, 5.05, 3.19, 3.41, 3.65, 1.13, 1.25, 1.40),
    (0.9, 3.29, 4.01, 5.12, 3.29, 3.54, 3.82, 1.23, 1.36, 1.51),
    (1.0, 3.40, 4.12, 5.20, 3.40, 3.67, 3.98, 1.33, 1.47, 1.63),
)
#: Rows for a > b, g = b/a.
_ROWS_A_GT_B = (
    (0.9, 3.51, 4.22, 5.30, 3.51, 3.81, 4.16, 1.44, 1.59, 1.77),
    (0.8, 3.65, 4.36, 5.42, 3.65, 3.99, 4.39, 1.58, 1.75, 1.94),
    (0.7, 3.82, 4.54, 5.58, 3.82, 4.21, 4.67, 1.76, 1.95, 2.18),
    (0.6, 4.06, 4.78, 5.80, 4.06, 4.50, 5.04, 2.01, 2.23, 2.50),
    (0.5, 4.37, 5.10, 6.11, 4.37, 4.90, 5.56, 2.35, 2.62, 2.96),
    (0.4, 4.84, 5.57, 6.57, 4.84, 5.48, 6.31, 2.88, 3.24, 3.70),
    (0.3, 5.57, 6.34, 7.34, 5.57, 6.40, 7.51, 3.79, 4.32, 5.01),
    (0.2, 6.96, 7.78, 8.82, 6.96, 8.14, 9.79, 5.72, 6.63, 7.89),
    (0.1, 10.7, 11.7, 12.9, 10.7, 12.8, 16.0, 12.2, 14.6, 18.0),
)

#: C33 at (a/b, nu) from the one public transcription of Kalker's full table (docs/theory.md §7.3); not CONTACT's.
C33_PUBLISHED = {
    (0.5, 0.0): 1.74, (0.5, 0.25): 1.93, (0.5, 0.5): 2.22,
    (1.0, 0.0): 1.21, (1.0, 0.25): 1.19, (1.0, 0.5): 1.16,
    (2.0, 0.0): 0.958, (2.0, 0.25): 0.819, (2.0, 0.5): 0.650,
    (0.1, 0.0): 6.42, (0.1, 0.25): 8.28, (0.1, 0.5): 11.7,
    (10.0, 0.0): 0.795, (10.0, 0.25): 0.526, (10.0, 0.5): 0.228,
}


def _lagrange_inverse(values, nu):
    """Quadratic Lagrange interpolation of 1/C through nu = 0, 0.25, 0.5, returned as C."""
    n0, n1, n2 = NU_COLUMNS
    inv = [1.0 / v for v in values]
    l0 = (nu - n1) * (nu - n2) / ((n0 - n1) * (n0 - n2))
    l1 = (nu - n0) * (nu - n2) / ((n1 - n0) * (n1 - n2))
    l2 = (nu - n0) * (nu - n1) / ((n2 - n0) * (n2 - n1))
    return 1.0 / (l0 * inv[0] + l1 * inv[1] + l2 * inv[2])


def _asymptotes(ratio, nu):
    """C11, C22, C23 outside the table (g = min(a/b, b/a) < 0.1), CONTACT's slender-ellipse forms
    (docs/theory.md §7.3)."""
    if ratio <= 1.0:
        g = ratio
        c23 = math.pi * math.sqrt(g) / (3 * (1 - nu)) * (1 + nu * (math.log(16 / g) - 5))
        return math.pi ** 2 / (4 * (1 - nu)), math.pi ** 2 / 4, c23
    g = 1.0 / ratio
    L = math.log(16 / g ** 2)
    c11 = 2 * math.pi / ((L - 2 * nu) * g) * (1 + (3 - math.log(4)) / (L - 2 * nu))
    d = (1 - nu) * L + 2 * nu
    c22 = 2 * math.pi / g * (1 + (1 - nu) * (3 - math.log(4)) / d) / d
    c23 = 2 * math.pi / (3 * g ** 1.5 * ((1 - nu) * L - 2 + 4 * nu))
    return c11, c22, c23


def kalker_coefficients(a_over_b: float, nu: float) -> tuple[float, float, float]:
    """(C11, C22, C23) for an ellipse with semi-axes ratio a/b (a along the rolling direction) and Kalker's
    combined Poisson ratio nu (0 <= nu <= 0.5), interpolated as CONTACT does (module docstring)."""
    ratio, nu = float(a_over_b), float(nu)
    if not (ratio > 0 and math.isfinite(ratio)):
        raise InputError(f"a/b = {a_over_b!r}: must be a positive finite ratio of the semi-axes")
    if not (0.0 <= nu <= 0.5):
        raise InputError(f"nu = {nu!r}: Kalker's table covers 0 <= nu <= 0.5")
    g = ratio if ratio <= 1.0 else 1.0 / ratio
    if g < 0.1:
        return _asymptotes(ratio, nu)
    rows = np.array(_ROWS_A_LE_B if ratio <= 1.0 else ((1.0,) + _ROWS_A_LE_B[-1][1:],) + _ROWS_A_GT_B)
    order = np.argsort(rows[:, 0])
    rows = rows[order]
    table = np.array([np.interp(g, rows[:, 0], rows[:, k]) for k in range(1, 10)])
    return tuple(float(_lagrange_inverse(table[3 * m:3 * m + 3], nu)) for m in range(3))


def linear_creep_forces(a, b, G, nu, xi, eta=0.0, phi=0.0, C33=None):
    """Kalker's linear creep forces on body 1: (Fx, Fy) in N and Mz in N mm (None without C33).

    a, b: semi-axes (mm; a along the rolling direction); G: combined shear modulus (MPa); xi, eta
    dimensionless, phi in 1/mm. Valid for |F| << mu Fn (full adhesion limit, docs/theory.md §7.3).
    """
    c11, c22, c23 = kalker_coefficients(a / b, nu)
    c = math.sqrt(a * b)
    fx = -G * c * c * c11 * xi
    fy = -G * c * c * c22 * eta - G * c ** 3 * c23 * phi
    mz = None if C33 is None else G * c ** 3 * c23 * eta - G * c ** 4 * C33 * phi
    return fx, fy, mz
