"""Hertz's elliptic contact between the curvatures of the undeformed distance and the semi-axes of the contact, as
the reference program's Hertzian options need it (IPOTCN = -1: curvatures A1, B1; -2: A1 and the ratio a/b; -3:
the semi-axes a, b under a normal force).

With h = A x^2 + B y^2, the Hertz pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2), Fn = 2/3 pi a b p0 and, for a >= b,
e^2 = 1 - b^2/a^2 (K, E the complete elliptic integrals of modulus e):

    A = 3 Fn (K - E) / (2 pi e^2 a^3 E*),    B = 3 Fn ((a/b)^2 E - K) / (2 pi e^2 a^3 E*)

(K. L. Johnson, "Contact Mechanics", Cambridge University Press, 1985, §4.2 and eq. 3.58), with E* the plane-strain
modulus of the pair, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (= G / (1 - nu) for CONTACT's combined G, nu). For a
circle (a = b) both are 3 Fn / (8 a^3 E*). Units: mm, N, MPa; curvatures 1/mm.
"""
from __future__ import annotations

import math


def _integrals(e2: float) -> tuple[float, float]:
    from scipy.special import ellipe, ellipk  # scipy's parameter is m = e^2
    return float(ellipk(e2)), float(ellipe(e2))


def curvature_ratio(ratio: float) -> float:
    """B/A for the semi-axis ratio a/b >= 1 (a along x)."""
    if ratio == 1.0:
        return 1.0
    e2 = 1.0 - 1.0 / ratio ** 2
    K, E = _integrals(e2)
    return (ratio ** 2 * E - K) / (K - E)


def curvatures(a: float, b: float, Fn: float, E_star: float) -> tuple[float, float]:
    """(A, B) (1/mm) whose Hertz contact under Fn (N) has the semi-axes a along x and b along y (mm)."""
    if a < b:
        B, A = curvatures(b, a, Fn, E_star)
        return A, B
    if a == b:
        c = 3.0 * Fn / (8.0 * a ** 3 * E_star)
        return c, c
    e2 = 1.0 - (b / a) ** 2
    K, E = _integrals(e2)
    scale = 3.0 * Fn / (2.0 * math.pi * e2 * a ** 3 * E_star)
    return scale * (K - E), scale * ((a / b) ** 2 * E - K)


def axis_ratio(A: float, B: float) -> float:
    """a/b of the Hertz contact of the curvatures A (along x) and B (along y): the root of curvature_ratio."""
    if A == B:
        return 1.0
    if A > B:
        return 1.0 / axis_ratio(B, A)
    target = B / A
    lo, hi = 1.0, 2.0
    while curvature_ratio(hi) < target:
        lo, hi = hi, 2.0 * hi
        if hi > 1e8:
            raise ValueError(f"B/A = {target:g}: too slender an ellipse")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if curvature_ratio(mid) < target:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-14 * hi:
            break
    return 0.5 * (lo + hi)


def semi_axes(A: float, B: float, Fn: float, E_star: float) -> tuple[float, float]:
    """(a, b) (mm) of the Hertz contact of the curvatures A, B (1/mm) under Fn (N)."""
    r = axis_ratio(A, B)
    if r == 1.0:
        a = (3.0 * Fn / (8.0 * A * E_star)) ** (1.0 / 3.0)
        return a, a
    a_unit, b_unit = (r, 1.0) if r > 1 else (1.0, 1.0 / r)
    A1, _ = curvatures(a_unit, b_unit, Fn, E_star)   # A scales as a^-3 at a fixed ratio
    s = (A1 / A) ** (1.0 / 3.0)
    return a_unit * s, b_unit * s


def b_curvature(A: float, ratio: float) -> float:
    """B (1/mm) of the ellipse with the curvature A along x and the semi-axis ratio a/b (IPOTCN = -2)."""
    return A * (curvature_ratio(ratio) if ratio >= 1.0 else 1.0 / curvature_ratio(1.0 / ratio))
