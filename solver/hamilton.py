"""Stresses below a sliding Hertz sphere in closed form (Hamilton 1983; docs/theory.md §11.6).

Hertz pressure p = p0 (1 - r^2/a^2)^(1/2) on the substrate and, in full slip, the traction q_x = mu p on it (along +x,
the convention of docs/theory.md §0; q_y = 0). Frame x, y on the surface, z >= 0 the depth into the substrate, tension
positive. Stresses depend on the substrate's Poisson ratio nu only.

Hamilton's variables (G. M. Hamilton, "Explicit equations for the stresses beneath a sliding spherical contact",
Proc. IMechE C 197 (1983) 53-59):

    r^2 = x^2 + y^2,  A = r^2 + z^2 - a^2,  S = (A^2 + 4 a^2 z^2)^(1/2),  M = ((S + A)/2)^(1/2),  N = ((S - A)/2)^(1/2),
    phi = atan(a/M),  G = M^2 - N^2 + z M - a N,  H = 2 M N + a M + z N      (M N = a z, M^2 - N^2 = A)

(M^2 is the ellipsoidal coordinate of the point: r^2/(a^2 + M^2) + z^2/M^2 = 1). Every stress is p0/a (pressure) or
mu p0/a (traction) times a sum of these functions:

  pressure (Hamilton's normal-load equations), T = (1 - nu) N z^2 - (1 - 2 nu)/3 (N S + 2 A N + a^3) - nu M z a:
    s_xx = (1 + nu) z phi + [ (y^2 - x^2)/r^2 T - N (x^2 + 2 nu y^2) - M x^2 z a/S ] / r^2,  s_yy: x <-> y
    s_zz = -N + a z M/S
    s_xy = x y (1 - 2 nu)/r^4 [-N r^2 + 2/3 N (S + 2 A) - z (z N + a M) + 2/3 a^3] + x y z/r^4 [a M (1 - r^2/S) - z N]
    s_xz = -z x (N/S - z H/(G^2 + H^2)),  s_yz: x -> y
  on the axis r = 0: s_xx = s_yy = (1 + nu)(z phi - a) + a^3/(2 (a^2 + z^2)), s_zz = -a^3/(a^2 + z^2), shears 0.

  traction q_x = mu p: with K = a^3 z M/((a^2 + M^2)^2 S),
    s_zz = s_xz of the pressure (the kernels of q_x -> s_zz and p -> s_xz are the same, bem/subsurface.py)
    s_xz = -N - 3/8 a z M/S + 3/2 z phi - 1/8 a z M/(a^2 + M^2) - K (5 x^2 - 3 y^2)/8
    s_yz = -x y K
    s_xx, s_yy, s_xy = F(P, w) with (P, w) = (x, x), (x, y), (y, x) and the coefficient rows c of `_ROWS` below:
    F = c_phi P phi + a M P/r^4 [c_MS S + c_MA A + c_Mr r^2 + W_M] + z N P/r^4 [c_NS S + c_Nz z^2 + c_Nr r^2 + W_N]
        + a^3 z P/r^4 [c_a + (16 nu - 8)/3 w^2/r^2]
    W_M = w^2 [-2 nu + (5/3 - 4/3 nu) S/r^2 + (10/3 nu - 5/3) A/r^2 + z^2/S]
    W_N = w^2 [-1/3 - 4/3 nu - (2/3 + 2/3 nu) S/r^2 + (2/3 - 4/3 nu) z^2/r^2 + a^2/S]
  on the axis (r = 0) these vanish but s_xz.

How the traction terms were obtained (Hamilton's printed tangential equations were not at hand): the field is a
combination of Hamilton's functions above (the Newtonian potential of the Hertz layer gives V_r/r ~ phi - a M/(a^2 +
M^2) and (V_r/r)_r/r ~ K); the rational coefficients, linear in nu, were identified by least squares against the
independent quadrature of the Boussinesq-Cerruti point-load solution over the Hertz distribution
(tests/bem/test_subsurface.py, `_sliding_hertz_reference`, 1e-14 accurate) at nu = 0.1 and 0.3 (residual 4e-13 p0,
every coefficient within 1e-9 of the rational printed here), and then checked on other points at nu = 0.45
and on the surface conditions (tests/solver/test_hamilton.py). The grouping differs from Hamilton's printed one by
the identities M N = a z, M^2 - N^2 = A; the functions are the same.
"""
from __future__ import annotations

import numpy as np

from rollcontact.bem.errors import InputError

#: nu-linear coefficients (constant, per nu) of the traction terms of s_xx, s_yy, s_xy (module docstring)
_ROWS = {
    "s_xx": {"phi": (-1.0, -0.25), "MS": (-1.25, 1.0), "MA": (1.25, -2.5), "Mr": (1.0, 1.75),
             "NS": (0.5, 0.5), "Nz": (-0.5, 1.0), "Nr": (-1.5, 0.75), "a": (2.0, -4.0)},
    "s_yy": {"phi": (0.0, -0.75), "MS": (-5 / 12, 1 / 3), "MA": (5 / 12, -5 / 6), "Mr": (0.0, 1.25),
             "NS": (1 / 6, 1 / 6), "Nz": (-1 / 6, 1 / 3), "Nr": (-1 / 6, -5 / 12), "a": (2 / 3, -4 / 3)},
    "s_xy": {"phi": (-0.5, 0.25), "MS": (-5 / 12, 1 / 3), "MA": (5 / 12, -5 / 6), "Mr": (0.5, 0.25),
             "NS": (1 / 6, 1 / 6), "Nz": (-1 / 6, 1 / 3), "Nr": (-2 / 3, 7 / 12), "a": (2 / 3, -4 / 3)},
}


def _variables(x, y, z, a):
    r2 = x * x + y * y
    A = r2 + z * z - a * a
    S = np.sqrt(A * A + 4.0 * a * a * z * z)
    M = np.sqrt(np.maximum(0.5 * (S + A), 0.0))
    N = np.sqrt(np.maximum(0.5 * (S - A), 0.0))
    phi = np.arctan2(a, M)
    return r2, A, S, M, N, phi


def _pressure_part(x, y, z, a, nu, v):
    """The six components (per p0/a) of Hertz's pressure, off the axis (r > 0)."""
    r2, A, S, M, N, phi = v
    G = M * M - N * N + z * M - a * N
    H = 2.0 * M * N + a * M + z * N
    T = (1 - nu) * N * z * z - (1 - 2 * nu) / 3 * (N * S + 2 * A * N + a**3) - nu * M * z * a
    xx = (1 + nu) * z * phi + ((y * y - x * x) / r2 * T - N * (x * x + 2 * nu * y * y) - M * x * x * z * a / S) / r2
    yy = (1 + nu) * z * phi + ((x * x - y * y) / r2 * T - N * (y * y + 2 * nu * x * x) - M * y * y * z * a / S) / r2
    zz = -N + a * z * M / S
    r4 = r2 * r2
    xy = (x * y * (1 - 2 * nu) / r4 * (-N * r2 + 2 / 3 * N * (S + 2 * A) - z * (z * N + a * M) + 2 / 3 * a**3)
          + x * y * z / r4 * (a * M * (1 - r2 / S) - z * N))
    w = N / S - z * H / (G * G + H * H)
    return np.array([xx, yy, zz, -z * y * w, -z * x * w, xy])


def _traction_part(x, y, z, a, nu, v, pressure):
    """The six components (per mu p0/a) of the traction q_x = mu p, off the axis (r > 0)."""
    r2, A, S, M, N, phi = v
    r4 = r2 * r2
    K = a**3 * z * M / ((a * a + M * M) ** 2 * S)
    out = np.empty_like(pressure)
    for name, (P, w2) in (("s_xx", (x, x * x)), ("s_yy", (x, y * y)), ("s_xy", (y, x * x))):
        c = {k: c0 + c1 * nu for k, (c0, c1) in _ROWS[name].items()}
        WM = w2 * (-2 * nu + (5 / 3 - 4 / 3 * nu) * S / r2 + (10 / 3 * nu - 5 / 3) * A / r2 + z * z / S)
        WN = w2 * (-1 / 3 - 4 / 3 * nu - (2 / 3 + 2 / 3 * nu) * S / r2 + (2 / 3 - 4 / 3 * nu) * z * z / r2 + a * a / S)
        f = (c["phi"] * P * phi + a * M * P / r4 * (c["MS"] * S + c["MA"] * A + c["Mr"] * r2 + WM)
             + z * N * P / r4 * (c["NS"] * S + c["Nz"] * z * z + c["Nr"] * r2 + WN)
             + a**3 * z * P / r4 * (c["a"] + (16 * nu - 8) / 3 * w2 / r2))
        out[{"s_xx": 0, "s_yy": 1, "s_xy": 5}[name]] = f
    out[2] = pressure[4]
    out[3] = -x * y * K
    out[4] = _traction_xz(x, y, z, a, v)
    return out


def _traction_xz(x, y, z, a, v):
    r2, A, S, M, N, phi = v
    K = a**3 * z * M / ((a * a + M * M) ** 2 * S)
    return (-N - 0.375 * a * z * M / S + 1.5 * z * phi - 0.125 * a * z * M / (a * a + M * M)
            - K * (5 * x * x - 3 * y * y) / 8)


def _off_axis(x, y, z, a, mu, nu):
    """(6, n) per p0/a at points off the axis (r > 0)."""
    v = _variables(x, y, z, a)
    pressure = _pressure_part(x, y, z, a, nu, v)
    return pressure + mu * _traction_part(x, y, z, a, nu, v, pressure)


def _on_axis(z, a, mu, nu):
    """(6, n) per p0/a on the axis r = 0: the pressure's limits; of the traction only s_xz survives."""
    zero = np.zeros_like(z)
    v = _variables(zero, zero, z, a)
    out = np.zeros((6, z.size))
    out[0] = out[1] = (1 + nu) * (z * v[5] - a) + a**3 / (2 * (a * a + z * z))
    out[2] = -a**3 / (a * a + z * z)
    out[4] = mu * _traction_xz(zero, zero, z, a, v)
    return out


#: within this distance of the axis (times a) the 1/r^4 terms cancel: interpolate (module docstring)
NEAR_AXIS = 0.01


def hamilton_stresses(x, y, z, a: float, p0: float, mu: float, nu: float) -> np.ndarray:
    """Stresses (MPa, shape (6,) + broadcast shape, order s_xx, s_yy, s_zz, s_yz, s_xz, s_xy) at (x, y, z) (mm; z >= 0
    the depth) below Hertz's pressure p0 (1 - r^2/a^2)^(1/2) (a mm, p0 MPa) with the full-slip traction q_x = mu p
    on the substrate; nu: the substrate's Poisson ratio. At z = 0 the edge r = a (where S = 0) is refused.

    Round-off: the terms in 1/r^4 cancel near the axis (error ~ 1e-16 (a/r)^3 p0: 8e-11 p0 at r = 0.01 a), so for
    0 < r < 0.01 a the stresses are the cubic through the axis value and the values at 0.01 a, 0.02 a, 0.03 a on the
    same ray (the field is smooth there: truncation ~ (0.01)^4 p0). Far below, near the axis the same terms cancel
    against a small field: 6e-10 p0 absolute (3e-7 relative) at r = 0.22 a, z = 20 a; 4e-9 relative at r = 100 a."""
    if not (a > 0 and np.isfinite(a)):
        raise InputError(f"contact radius a = {a!r} mm: must be > 0")
    if not (-1.0 < nu <= 0.5):
        raise InputError(f"Poisson ratio nu = {nu!r}: allowed range is -1 < nu <= 0.5")
    x, y, z = np.broadcast_arrays(*(np.asarray(t, dtype=float) for t in (x, y, z)))
    if np.any(z < 0):
        raise InputError("depth z: must be >= 0 mm (z is measured into the substrate)")
    shape = x.shape
    x, y, z = x.ravel(), y.ravel(), z.ravel()
    r = np.hypot(x, y)
    if np.any((z == 0) & (r == a)):
        raise InputError("hamilton_stresses: the point z = 0, r = a (the contact edge) is singular; move off it")
    out = np.zeros((6, x.size))
    rs = NEAR_AXIS * a
    far, axis = r >= rs, r == 0
    near = ~far & ~axis
    if np.any(far):
        out[:, far] = _off_axis(x[far], y[far], z[far], a, mu, nu)
    if np.any(axis):
        out[:, axis] = _on_axis(z[axis], a, mu, nu)
    if np.any(near):
        rn, zn = r[near], z[near]
        ex, ey = x[near] / rn, y[near] / rn
        t = rn / rs
        value = _on_axis(zn, a, mu, nu) * ((t - 1) * (t - 2) * (t - 3) / -6)
        for k, w in ((1, t * (t - 2) * (t - 3) / 2), (2, t * (t - 1) * (t - 3) / -2), (3, t * (t - 1) * (t - 2) / 6)):
            value += _off_axis(k * rs * ex, k * rs * ey, zn, a, mu, nu) * w
        out[:, near] = value
    return p0 / a * out.reshape((6,) + shape)
