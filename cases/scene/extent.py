"""The region a scene's contact covers, which sizes its grids: the contact's semi-axes with an allowance where they
are estimates (`contact_extent`), and the grid of the rolling frame of a [rolling] scene (`rolling_frame_grid`:
contact-fixed for the steady state and a transient on the grid moving with the contact, lengthened ahead for the
world-fixed grid of a transient), which the scene's
checks size before any run (cases.scene.limits) and the runs build (cases.run.rolling_frame). Units: mm.
"""
from __future__ import annotations

import math

from rollcontact.bem.grid import Grid


def estimated(scene) -> bool:
    """True when the scene's contact semi-axes are estimates (an ellipse's, the cylinder's, a file profile's)."""
    return scene.shape in ("cylinder", "file") or (scene.shape == "ellipsoid" and len(set(scene.radii)) > 1)


def contact_extent(scene) -> tuple[float, float]:
    """Semi-axes (mm, along x and y) a grid must cover: the scene's, with a 10 % allowance where they are
    estimates (`estimated`)."""
    semi_x, semi_y = scene.semi_axes
    return (1.1 * semi_x, 1.1 * semi_y) if estimated(scene) else (semi_x, semi_y)


def rolling_frame_box(scene, travel: float = 0.0, trail: float = 0.0) -> tuple[float, float, float, float]:
    """(xmin, xmax, ymin, ymax) (mm) of the rolling frame's grid: the contact (`contact_extent`) turned into the
    frame (the turned ellipse's extent, or the turned rectangle's for the cylinder and a file profile, whose contacts
    are not elliptic), plus the scene's margin (at least one element: the steady upwind difference needs a free cell
    ahead), lengthened ahead by `travel` (mm) for the contact rolled from x = 0 to x = travel, and with at least
    `trail` (mm) behind the contact (the grid that moves with a transient's contact holds the previous step's
    contact, a step behind)."""
    (sa, sb), (dx, dy) = contact_extent(scene), scene.spacing
    t = math.radians(scene.rolling.direction)
    c, s = abs(math.cos(t)), abs(math.sin(t))
    if scene.shape in ("cylinder", "file"):
        half_x, half_y = sa * c + sb * s, sa * s + sb * c
    else:
        half_x, half_y = math.hypot(sa * c, sb * s), math.hypot(sa * s, sb * c)
    margin = max(scene.grid.margin, dx, dy)
    return -half_x - max(margin, trail), travel + half_x + margin, -half_y - margin, half_y + margin


def rolling_frame_grid(scene, travel: float = 0.0, trail: float = 0.0) -> Grid:
    """The grid of `rolling_frame_box`; InputError (bem.grid) when it exceeds the element limit."""
    dx, dy = scene.spacing
    return Grid.covering(*rolling_frame_box(scene, travel, trail), dx, dy)
