"""Influence coefficients of a uniformly loaded rectangular element (docs/theory.md §2).

Displacement at an observation point offset (X, Y) (mm) from the centre of a dx x dy element carrying a
unit uniform traction (1 MPa), for two bodies with Kalker's combined constants G, nu, K
(see `bem.materials.MaterialPair`). Units: mm per MPa.

Conventions (docs/theory.md §0): pressure p presses on the substrate, tractions tau act on the substrate;
w (u_z) is the loss of separation (positive into the bodies), (u_x, u_y) the substrate displacement
relative to the sphere.

    zz = (1-nu)/(pi G) [[J3]]              w   from p          (Love 1929)
    xx = 1/(pi G) [[J1 + (1-nu) J2]]       u_x from tau_x      (Cerruti)
    yy = 1/(pi G) [[J2 + (1-nu) J1]]       u_y from tau_y
    xy = nu/(pi G) [[J4]]                  u_x from tau_y = u_y from tau_x
    xz = +K/(pi G) [[J5]],  yz = +K/(pi G) [[J6]]       u_x, u_y from p   (coupling)
    zx = -xz,  zy = -yz                                  w from tau_x, tau_y (Betti)

with [[F]](X, Y) = F(X+hx, Y+hy) - F(X+hx, Y-hy) - F(X-hx, Y+hy) + F(X-hx, Y-hy) and the corner
functions J1 = Y ln(X + r), J2 = X ln(Y + r), J3 = J1 + J2, J4 = -r, J5 = Y ln r + X atan(Y/X),
J6 = X ln r + Y atan(X/Y). The sign of the coupling terms follows from the Boussinesq radial
displacement (points move toward a normal load) of each body with the traction counted on the
substrate; it vanishes when K = 0.
"""
import numpy as np

COMPONENTS = ("zz", "xx", "yy", "xy", "xz", "yz")


def _log_x_plus_r(X, Y, r):
    """ln(X + r), evaluated without cancellation for X < 0 as 2 ln|Y| - ln(r - X) (docs/theory.md §2.2a)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        pos = np.log(np.where(X >= 0, X + r, 1.0))
        neg = 2.0 * np.log(np.abs(np.where(X < 0, Y, 1.0))) - np.log(np.where(X < 0, r - X, 1.0))
    return np.where(X >= 0, pos, neg)


def _y_log_x_plus_r(X, Y, r):
    """Y ln(X + r), with the limit 0 where Y = 0 (a corner on the element's axis)."""
    safe_Y = np.where(Y == 0, 1.0, Y)
    safe_r = np.where(Y == 0, np.abs(X) + 1.0, r)
    val = Y * _log_x_plus_r(X, safe_Y, safe_r)
    return np.where(Y == 0, 0.0, val)


def _x_atan_y_over_x(X, Y):
    """X atan(Y/X) with the limit 0 at X = 0 (not arctan2: that breaks the [[.]] cancellation)."""
    safe_X = np.where(X == 0, 1.0, X)
    return np.where(X == 0, 0.0, X * np.arctan(Y / safe_X))


def _y_log_r(Y, r):
    with np.errstate(divide="ignore"):
        return np.where(Y == 0, 0.0, Y * np.log(np.where(r == 0, 1.0, r)))


def _corner_functions(X, Y):
    """J1, J2, J4, J5, J6 at corner offsets (X, Y)."""
    r = np.hypot(X, Y)
    J1 = _y_log_x_plus_r(X, Y, r)
    J2 = _y_log_x_plus_r(Y, X, r)
    J4 = -r
    J5 = _y_log_r(Y, r) + _x_atan_y_over_x(X, Y)
    J6 = _y_log_r(X, r) + _x_atan_y_over_x(Y, X)
    return J1, J2, J4, J5, J6


def element_integrals(X, Y, dx, dy):
    """[[J1]], [[J2]], [[J4]], [[J5]], [[J6]] for observation offsets X, Y (mm; broadcastable arrays)."""
    hx, hy = 0.5 * dx, 0.5 * dy
    X = np.asarray(X, dtype=float)
    Y = np.asarray(Y, dtype=float)
    out = None
    for sx, sy, sign in ((hx, hy, 1.0), (hx, -hy, -1.0), (-hx, hy, -1.0), (-hx, -hy, 1.0)):
        terms = _corner_functions(X + sx, Y + sy)
        if out is None:
            out = [sign * t for t in terms]
        else:
            for k, t in enumerate(terms):
                out[k] += sign * t
    return tuple(out)


def influence_coefficients(X, Y, dx, dy, G, nu, K=0.0, components=COMPONENTS):
    """Influence coefficients (mm/MPa) at offsets (X, Y) of a dx x dy element, as a dict by component.

    G (MPa), nu, K: Kalker's combined constants (`MaterialPair.G`, `.nu`, `.K`). Components are named
    by (displacement, traction): 'zz', 'xx', 'yy', 'xy' (= 'yx'), 'xz', 'yz' (u_x, u_y from p); the
    transposed coupling blocks are zx = -xz and zy = -yz.
    """
    I1, I2, I4, I5, I6 = element_integrals(X, Y, dx, dy)
    c = 1.0 / (np.pi * G)
    table = {
        "zz": lambda: c * (1.0 - nu) * (I1 + I2),
        "xx": lambda: c * (I1 + (1.0 - nu) * I2),
        "yy": lambda: c * (I2 + (1.0 - nu) * I1),
        "xy": lambda: c * nu * I4,
        "xz": lambda: c * K * I5,
        "yz": lambda: c * K * I6,
    }
    unknown = set(components) - set(table)
    if unknown:
        raise ValueError(f"unknown influence components {sorted(unknown)}; known: {COMPONENTS}")
    return {name: table[name]() for name in components}
