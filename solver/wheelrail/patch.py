"""A contact patch in its tangent plane (docs/wheelrail.md, §5): the undeformed gap h(x, s) between wheel and rail on
a grid of the plane, and the creepages the wheelset's motion gives at the patch's reference point.

Planar gap: at the plane point B = O + x e_x + s e_s (solver.wheelrail.search.PatchFrame), h is the distance along
the normal e_n from the rail surface to the wheel surface, t_wheel(x, s) - t_rail(s) (both measured from B along
e_n; the rail does not vary along x). h < 0 where the undeformed surfaces interpenetrate. Computed exactly (Newton's
method on the splines of the profiles), so that the gap keeps the profiles' non-Hertzian shape, the wheel's rolling
radius varying across the patch and the skew of a yawed wheel; the plane itself is the approximation ("planar
contact"): the half-space solved on it ignores how the surfaces curve away from it.

Creepages (Kalker's convention, docs/theory.md §11.5; body 1 the wheel, body 2 the rail at rest): the wheel's material
point O_w at the patch's reference (its undeformed surface point O + t_wheel(0, 0) e_n: the rolling radius is the
wheel's radius there) moves with v = V e_x + Omega x (O_w - C) (V the forward speed, Omega = omega a the wheelset's
rotation about its axle a, C its centre); relative to the contact, which travels with the wheelset, the rail's
material moves at -V e_x and the wheel's at Omega x (O_w - C). With u = (Omega x (O_w - C)) . e_x (< 0 rolling forward)
the rolling speed is V_r = (V - u) / 2, and
    xi = v . e_x / V_r,   eta = v . e_s / V_r,   phi = (Omega . e_n) / V_r,
so that the rigid slip at O_w + x e_x + s e_s is (xi - phi s, eta + phi x), the form the steady solver takes (the
rigid slip of the wheel evaluated on the plane through O_w parallel to the tangent plane, CONTACT's planar rigid slip).
Every
term is proportional to V: only omega / V enters. Units: mm, rad, 1/mm.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError
from rollcontact.solver.wheelrail.placement import RailPlacement
from rollcontact.solver.wheelrail.search import PatchFrame
from rollcontact.solver.wheelrail.wheel import MAX_NEWTON, NEWTON_TOL, Wheel, WheelPosition


def rail_distance(rail: RailPlacement, frame: PatchFrame, s) -> np.ndarray:
    """t_rail(s) (mm): the rail surface point O + s e_s + t e_n, by Newton's method; NaN off the rail profile."""
    s = np.asarray(s, dtype=float)
    ny, nz = -math.sin(frame.angle), math.cos(frame.angle)
    by = frame.origin[1] + s * math.cos(frame.angle)
    bz = frame.origin[2] + s * math.sin(frame.angle)
    surface = rail.surface
    t = np.zeros_like(s)
    for _ in range(MAX_NEWTON):
        y = by + t * ny
        f = bz + t * nz - surface(y)
        step = f / (nz - surface.slope(y) * ny)
        t = t - step
        if np.all(np.isnan(step) | (np.abs(step) <= NEWTON_TOL)):
            return t
    raise ConvergenceError("distance to the rail surface did not converge", solver="rail Newton",
                           iterations=MAX_NEWTON, residual=float(np.nanmax(np.abs(step))), tol=NEWTON_TOL)


def patch_gap(rail_t: np.ndarray, wheel: Wheel, frame: PatchFrame, x, s, start=None) -> np.ndarray:
    """h(x, s) (mm), shape (len(s), len(x)): t_wheel - t_rail along e_n, given t_rail(s) (`rail_distance`, shape
    (len(s),)) and a Wheel at its position. start: t_wheel to start Newton from (default t_rail)."""
    X, S = np.meshgrid(np.asarray(x, float), np.asarray(s, float))
    base = frame.point(X, S)
    rail = np.broadcast_to(np.asarray(rail_t, float)[:, None], X.shape)
    t_w = wheel.distance_along(base, frame.e_n, start=rail if start is None else start)
    return t_w - rail, t_w


def creepages(position: WheelPosition, omega_per_speed: float, frame: PatchFrame, point=None) -> tuple:
    """(xi, eta, phi) (-, -, 1/mm) for the wheelset rotating at omega / V = omega_per_speed (rad/mm) about its axle
    while moving forward (module docstring), at the wheel's material point `point` (side frame, mm; default the
    patch's reference point O); in the patch's axes."""
    point = frame.origin if point is None else np.asarray(point, dtype=float)
    spin = omega_per_speed * position.axle                       # Omega / V
    carried = np.cross(spin, point - position.centre)           # (Omega x (O - C)) / V
    v = np.array([1.0, 0.0, 0.0]) + carried
    rolling = 0.5 * (1.0 - carried[0])                          # V_r / V
    return (float(v @ frame.e_x / rolling), float(v @ frame.e_s / rolling), float(spin @ frame.e_n / rolling))


def omega_per_speed(radius: float, xi: float) -> float:
    """omega / V (rad/mm) giving the longitudinal creepage xi at the rolling radius `radius` (mm) of an upright,
    unyawed wheel: xi = (V - omega r) / ((V + omega r) / 2)."""
    return (2.0 - xi) / (radius * (2.0 + xi))
