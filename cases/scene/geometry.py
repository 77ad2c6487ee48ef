"""The `[geometry]` of a scene: which shape it names, the keys each shape takes, its profile for the solvers and
its closed-form normal and tangential references (docs/theory.md §7.1-7.2 for the sphere, docs/theory.md §11.4 by the
MDR for the
other axisymmetric shapes). Units mm, N, MPa, degrees.

    shape          keys        profile h (r: distance from the centre)
    sphere         R           r^2/(2R)                                    (shape left out, R given)
    ellipsoid      Rx, Ry      x^2/(2Rx) + y^2/(2Ry)                       (shape left out, Rx and Ry given)
    cone           slope       r tan(slope), 0 < slope < 90 deg
    power          n, R        r^n/(n R^(n-1)), 1 <= n <= 20 (n = 2: the sphere)
    flat_rounded   b, R        0 for r <= b, (r - b)^2/(2R) beyond: a flat punch of radius b, edge radius R
    cylinder       R, length, edge_R, axis ("x" or "y", default "x"): a roller along the axis t, n across it,
                               n^2/(2R) + max(|t| - length/2, 0)^2/(2 edge_R): straight part `length`, rounded ends
    file           path, sha256 (optional): h(x, y) sampled in a file, interpolated (cases.scene.profile_file)

A key that does not belong to the chosen shape is refused (SceneError naming it and the keys the shape takes),
as is a shape without one of its keys. The contact radius a that sets the default grid (a/12) and the unit of
w is Hertz's for the sphere and the ellipsoid's equivalent sphere (as before), the MDR's exact radius of
the profile under Fn for the axisymmetric shapes (`solver.mdr.exact.MDRContact`), and for the cylinder the
half-width of the 2-D line contact under the nominal load per length Fn/length (`solver.analytic.HertzLine`).
The cylinder has no closed-form approach (a 2-D approach is not defined): its contact is estimated to reach
length/2 + sqrt(2 edge_R d_est) along the axis with d_est = (2P/(pi E*)) (ln(2 length/a) + 1) (the run measured
0.215 mm where d_est = 0.268 mm for R = 40, length = 40, edge_R = 5 mm under the seed's load), and the run
summary takes its approach d (and U0) from the solved first step.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
import math
from pathlib import Path

import numpy as np

from rollcontact.bem.errors import SceneError
from rollcontact.solver.analytic import CattaneoMindlin, HertzLine, HertzSphere
from rollcontact.solver.mdr.exact import MDRContact, MDRTangential
from rollcontact.solver.rolling.axisymmetric import ConeProfile, PowerProfile, RoundedFlatProfile
from rollcontact.solver.rolling.profiles import ArrayProfile, QuadricProfile, RollerProfile
from rollcontact.cases.scene.profile_file import (
    allowed_digest, check_coverage, envelope_contact_radius, read_profile_file)

#: the keys of each shape (besides `shape` itself)
SHAPE_KEYS = {"sphere": ("R",), "ellipsoid": ("Rx", "Ry"), "cone": ("slope",), "power": ("n", "R"),
              "flat_rounded": ("b", "R"), "cylinder": ("R", "length", "edge_R", "axis"), "file": ("path", "sha256")}
#: keys a shape may leave out (their default; the file's sha256 is filled in from the file)
OPTIONAL = {"axis": "x", "sha256": None}
#: shapes that are bodies of revolution (the MDR maps them exactly)
AXISYMMETRIC = ("sphere", "cone", "power", "flat_rounded")
_ALL_KEYS = ("R", "Rx", "Ry", "slope", "n", "b", "length", "edge_R", "axis", "path", "sha256")


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
    missing = [k for k in wanted if getattr(g, k) is None and k not in OPTIONAL]
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
    if shape == "cylinder":
        return RollerProfile(g.R, g.length, g.edge_R, g.axis or OPTIONAL["axis"])
    if shape == "file":
        x, y, h, _ = read_profile_file(g.path)
        return ArrayProfile(x, y, h)
    return RoundedFlatProfile(g.b, g.R)


def normal_reference(g, shape: str, E_star: float, Fn: float):
    """Closed-form normal contact (a, approach, p0): Hertz of the (equivalent) sphere for the sphere and the
    ellipsoid, the exact MDR solution for the axisymmetric shapes, the 2-D line contact under Fn/length for the
    cylinder (a the half-width; no approach)."""
    if shape in ("sphere", "ellipsoid"):
        rx, ry = (g.R, g.R) if shape == "sphere" else (g.Rx, g.Ry)
        R = math.sqrt(rx) * math.sqrt(ry)   # as Scene.equivalent_radius, to the last bit (sqrt(R)^2 != R)
        return HertzSphere(R, E_star, Fn)
    if shape == "cylinder":
        return HertzLine(g.R, E_star, Fn / g.length)
    if shape == "file":
        x, y, h, digest = read_profile_file(g.path)
        return EstimatedContact(envelope_contact_radius(x, y, h, E_star, Fn, key=digest), Fn)
    return MDRContact(shape_profile(g, shape), E_star, Fn)


@dataclass(frozen=True)
class EstimatedContact:
    """A contact without closed form (the file profile): the estimated radius a (mm) and p0 = 3 Fn/(2 pi a^2)."""

    a: float
    Fn: float

    @property
    def p0(self) -> float:
        return 1.5 * self.Fn / (math.pi * self.a ** 2)


def cylinder_semi_axes(g, E_star: float, Fn: float) -> tuple[float, float]:
    """Estimated semi-axes (along x, along y; mm) of the cylinder's contact: the nominal half-width a across the
    axis and length/2 + sqrt(2 edge_R d_est) along it (cases.run.discretise adds 10 %: the pressure, and with it
    the width, rises near the rounded ends)."""
    line = HertzLine(g.R, E_star, Fn / g.length)
    d_est = 2.0 * line.P / (math.pi * E_star) * (math.log(2.0 * g.length / line.a) + 1.0)
    along, across = 0.5 * g.length + math.sqrt(2.0 * g.edge_R * d_est), line.a
    return (along, across) if (g.axis or OPTIONAL["axis"]) == "x" else (across, along)


def tangential_reference(normal, mu: float, G_star: float):
    """Cattaneo-type reference (U0, stick_radius, shift) of a `normal_reference`; None for the cylinder and the
    file (no closed-form approach)."""
    if isinstance(normal, (HertzLine, EstimatedContact)):
        return None
    if isinstance(normal, HertzSphere):
        return CattaneoMindlin(normal, mu, G_star)
    return MDRTangential(normal, mu, G_star)


def checked_file_geometry(g):
    """The Geometry of a file shape with its path made absolute and its sha256 filled in (or checked: SceneError
    when the file changed), and whether sha256 was filled in (a derived key)."""
    path = str(Path(g.path).expanduser().resolve())
    digest = read_profile_file(path)[3]
    allowed_digest(g.sha256, digest, path)
    return replace(g, path=path, sha256=digest), g.sha256 is None


def check_file_coverage(scene):
    """SceneError unless the file covers what the run evaluates about the centre (cases.scene.profile_file)."""
    x, y = read_profile_file(scene.geometry.path)[:2]
    (sx, sy), (dx, dy) = scene.semi_axes, scene.spacing
    margin = max(scene.grid.margin, dx, dy)
    W = scene.amplitude * np.abs(np.array(scene.rolling_direction)) if scene.motion.periods > 0 else np.zeros(2)
    check_coverage(x, y, 1.1 * sx + margin + dx + 2 * W[0], 1.1 * sy + margin + dy + 2 * W[1], scene.geometry.path)
