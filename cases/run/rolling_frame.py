"""The rolling frame of a [rolling] scene: its x axis along [rolling] direction, y to its left, the origin at the
contact centre. The scene's profile (any shape the scene allows: cases.scene.geometry) turned into that frame, and
the grid over the contact there (contact-fixed for the steady state, lengthened ahead for the world-fixed grid of a
transient). Units: mm.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.grid import Grid
from rollcontact.cases.scene.extent import rolling_frame_grid
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep import linear_creep_forces


def creep_grid(scene: Scene, travel: float = 0.0, trail: float = 0.0) -> Grid:
    """Grid of the rolling frame over the contact plus the scene's margin, lengthened ahead by `travel` (mm) for the
    world-fixed grid of a transient, with at least `trail` (mm) behind the contact for the grid that moves with it
    (cases.scene.extent.rolling_frame_grid)."""
    return rolling_frame_grid(scene, travel, trail)


def rolling_semi_axes(scene: Scene) -> tuple[float, float] | None:
    """The contact's semi-axes (mm) for Kalker's linear theory: a along the rolling direction, b across it (the
    scene's semi-axes: exact for the sphere and the axisymmetric shapes, estimated for an ellipse, the cylinder and a
    file profile, whose contacts the theory's ellipses only approximate). None for an elongated contact rolled
    obliquely to its axes: the theory's ellipses roll along an axis."""
    sa, sb = scene.semi_axes
    turned = scene.rolling.direction % 180.0
    if sa == sb or turned == 0.0:
        return sa, sb
    if turned == 90.0:
        return sb, sa
    return None


def linear_forces(scene: Scene, xi: float, eta: float, phi: float) -> tuple[float, float]:
    """Kalker's linear (Fx, Fy) (N, on the sphere) at the rolling semi-axes, or (nan, nan) without them."""
    axes = rolling_semi_axes(scene)
    if axes is None:
        return math.nan, math.nan
    pair = scene.material_pair
    fx, fy, _ = linear_creep_forces(*axes, pair.G, min(max(pair.nu, 0.0), 0.5), xi, eta, phi)
    return fx, fy


def rolling_frame_gap(scene: Scene):
    """The undeformed gap h(x, y) (mm) of the scene's profile as a function of the rolling frame's coordinates
    (mm) about the contact centre: the scene's axes turned by [rolling] direction."""
    t = math.radians(scene.rolling.direction)
    c, s = math.cos(t), math.sin(t)
    profile = scene.profile

    def gap(X, Y):
        return profile(X * c - Y * s, X * s + Y * c)
    return gap


def rolling_frame_profile(scene: Scene, grid: Grid) -> np.ndarray:
    """The gap (mm) at the cells of `grid`, whose x axis is the rolling direction."""
    return rolling_frame_gap(scene)(*grid.mesh())
