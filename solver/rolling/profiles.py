"""Undeformed gap profiles h(x, y) of the sphere relative to the flat, shifted with the sphere centre.

The seed's Eq. 7 (perpendicular rolling) is h(x, y - nW): the profile moved with the centre. Here the
centre c = (cx, cy) may move in any direction and the profile may be a quadric, any function, or an
array sampled on its own grid (interpolated). Lengths in mm.
"""
from dataclasses import dataclass
import math
from typing import Callable

import numpy as np

from rollcontact.bem.errors import InputError


@dataclass(frozen=True)
class QuadricProfile:
    """h = x^2/(2 Rx) + y^2/(2 Ry) about the sphere centre (docs/theory.md §6.1, seed Eq. 6)."""

    Rx: float
    Ry: float

    def __post_init__(self):
        if not (self.Rx > 0 and self.Ry > 0):
            raise InputError(f"profile radii Rx = {self.Rx}, Ry = {self.Ry} mm: must be > 0")

    def __call__(self, X, Y, centre=(0.0, 0.0)):
        x, y = X - centre[0], Y - centre[1]
        return x * x / (2.0 * self.Rx) + y * y / (2.0 * self.Ry)


@dataclass(frozen=True)
class FunctionProfile:
    """Any profile given as a function h(x, y) of coordinates relative to the centre (mm -> mm)."""

    function: Callable

    def __call__(self, X, Y, centre=(0.0, 0.0)):
        h = np.asarray(self.function(X - centre[0], Y - centre[1]), dtype=float)
        if h.shape != np.shape(X) or not np.all(np.isfinite(h)):
            raise InputError("profile function must return finite values of the shape of its inputs")
        return h


class ArrayProfile:
    """A profile sampled on its own regular grid (x, y relative to the centre, h of shape (ny, nx)),
    evaluated by cubic interpolation; outside its grid the profile is extrapolated linearly, so the
    sampled region must cover every point that can come into contact."""

    def __init__(self, x, y, h):
        h = np.asarray(h, dtype=float)
        if h.shape != (len(y), len(x)) or not np.all(np.isfinite(h)):
            raise InputError(f"array profile: h must be finite with shape (len(y), len(x)) = "
                             f"({len(y)}, {len(x)}), got {h.shape}")
        method = "cubic" if min(h.shape) >= 4 else "linear"
        from scipy.interpolate import RegularGridInterpolator  # 0.5 s to import: only for sampled profiles
        self._interp = RegularGridInterpolator((np.asarray(y, float), np.asarray(x, float)), h,
                                               method=method, bounds_error=False, fill_value=None)

    def __call__(self, X, Y, centre=(0.0, 0.0)):
        pts = np.stack([np.ravel(Y - centre[1]), np.ravel(X - centre[0])], axis=-1)
        return self._interp(pts).reshape(np.shape(X))


@dataclass(frozen=True)
class RollerProfile:
    """A cylindrical roller of radius R whose axis lies along x (axis = "x") or y, with a straight part of
    `length` and ends rounded with radius edge_R (to the leading order of the circle): along the axis t and across
    it n (relative to the centre), h = n^2/(2R) + max(|t| - length/2, 0)^2/(2 edge_R). Lengths in mm."""

    R: float
    length: float
    edge_R: float
    axis: str = "x"

    def __post_init__(self):
        for name in ("R", "length", "edge_R"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise InputError(f"roller {name} = {value!r} mm: must be finite and > 0")
        if self.axis not in ("x", "y"):
            raise InputError(f"roller axis = {self.axis!r}: allowed values are 'x', 'y'")

    def __call__(self, X, Y, centre=(0.0, 0.0)):
        x, y = X - centre[0], Y - centre[1]
        t, n = (x, y) if self.axis == "x" else (y, x)
        end = np.maximum(np.abs(t) - 0.5 * self.length, 0.0)
        return n * n / (2.0 * self.R) + end * end / (2.0 * self.edge_R)
