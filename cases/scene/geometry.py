"""The `[geometry]` of a scene: which shape it names, the keys each shape takes, its profile for the solvers and
its closed-form normal and tangential references (theory.md §7.1-7.2 for the sphere, §11.4 by the MDR for the
other axisymmetric shapes). Units mm, N, MPa, degrees.

    shape          keys        profile h (r: distance from the centre)
    sphere         R           r^2/(2R)                                    (shape left out, R given)
    ellipsoid      Rx, Ry      x^2/(2Rx) + y^2/(2Ry)                       (shape left out, Rx and Ry given)
    cone           slope       r tan(slope), 0 < slope < 90 deg
    power          n, R        r^n/(n R^(n-1)), 1 <= n <= 20 (n = 2: the sphere)
    flat_rounded   b, R        0 for r <= b, (r - b)^2/(2R) beyond: a flat punch of radius b, edge radius R

A key that does not belong to the chosen shape is refused (SceneError naming it and the keys the shape takes),
as is a shape without one of its keys. The contact radius a that sets the default grid (a/12) and the unit of
w is Hertz's for the sphere and the ellipsoid's equivalent sphere (as before), and the MDR's exact radius of
the profile under Fn for the other shapes (`solver.mdr.exact.MDRContact`).
"""
from __future__ import annotations

import math

from rollcontact.bem.errors import SceneError
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.mdr.exact import MDRContact, MDRTangential
from rollcontact.solver.rolling.axisymmetric import ConeProfile, PowerProfile, RoundedFlatProfile
from rollcontact.solver.rolling.profiles import QuadricProfile

#: the keys of each shape (besides `shape` itself)
SHAPE_KEYS = {"sphere": ("R",), "ellipsoid": ("Rx", "Ry"), "cone": ("slope",), "power": ("n", "R"),
              "flat_rounded": ("b", "R")}
#: shapes that are bodies of revolution (the MDR maps them exactly)
AXISYMMETRIC = ("sphere", "cone", "power", "flat_rounded")
_ALL_KEYS = ("R", "Rx", "Ry", "slope", "n", "b")


def resolve_shape(g) -> str:
    """The shape a Geometry names, its keys checked: SceneError naming a missing key or one that does not belong."""
    if g.shape is None:
        if g.R is not None and (g.Rx is not None or g.Ry is not None):
            raise SceneError("[geometry] give either R, or Rx and Ry, not both")
        if g.R is None and (g.Rx is None) != (g.Ry is None):
            raise SceneError("[geometry] Rx and Ry must be given together")
        if g.R is None and g.Rx is None:
            raise SceneError("[geometry] R (or Rx and Ry, or a shape with its keys) is required, in mm; shapes: "
                             + ", ".join(f"{s} ({', '.join(k)})" for s, k in SHAPE_KEYS.items()))
        shape = "sphere" if g.R is not None else "ellipsoid"
    else:
        shape = g.shape
    wanted = SHAPE_KEYS[shape]
    extra = [k for k in _ALL_KEYS if k not in wanted and getattr(g, k) is not None]
    if extra:
        raise SceneError(f"[geometry] shape = {shape!r} takes the key(s) {list(wanted)}; {', '.join(extra)} does "
                         "not belong to it")
    missing = [k for k in wanted if getattr(g, k) is None]
    if missing:
        raise SceneError(f"[geometry] shape = {shape!r} needs {', '.join(missing)} (keys of this shape: "
                         f"{list(wanted)})")
    return shape


def shape_profile(g, shape: str):
    """The solver profile (callable h(X, Y, centre), mm) of a checked Geometry."""
    if shape == "sphere":
        return QuadricProfile(g.R, g.R)
    if shape == "ellipsoid":
        return QuadricProfile(g.Rx, g.Ry)
    if shape == "cone":
        return ConeProfile(g.slope)
    if shape == "power":
        return PowerProfile(g.n, g.R)
    return RoundedFlatProfile(g.b, g.R)


def normal_reference(g, shape: str, E_star: float, Fn: float):
    """Closed-form normal contact (a, approach, p0): Hertz of the (equivalent) sphere for the sphere and the
    ellipsoid, the exact MDR solution for the other shapes."""
    if shape in ("sphere", "ellipsoid"):
        rx, ry = (g.R, g.R) if shape == "sphere" else (g.Rx, g.Ry)
        R = math.sqrt(rx) * math.sqrt(ry)   # as Scene.equivalent_radius, to the last bit (sqrt(R)^2 != R)
        return HertzSphere(R, E_star, Fn)
    return MDRContact(shape_profile(g, shape), E_star, Fn)


def tangential_reference(normal, mu: float, G_star: float):
    """Cattaneo-type reference (U0, stick_radius, shift) of a `normal_reference`."""
    if isinstance(normal, HertzSphere):
        return CattaneoMindlin(normal, mu, G_star)
    return MDRTangential(normal, mu, G_star)
