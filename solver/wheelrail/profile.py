"""A lateral profile of a wheel or a rail: the surface height z(y) (mm) as a C2 cubic spline through the given
points (y strictly increasing), with its slope and curvature, and the same profile turned and shifted.

Convention (docs/wheelrail.md): y lateral, positive towards the field side; z positive upwards (the rail head's top
surface; the wheel's running surface relative to its rolling circle, so the flange has z < 0). The spline is
scipy's not-a-knot CubicSpline; outside [y[0], y[-1]] every value is NaN (the callers check the coverage).
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import InputError

#: Fewest points a profile may have.
MIN_POINTS = 4


class Profile:
    """z(y) (mm) through the points (y, z); `name` names it in error messages ('rail profile', ...).

    InputError when the arrays are not 1-D of one length >= MIN_POINTS, not finite, or y is not strictly increasing
    (naming the first point where it is not)."""

    def __init__(self, y, z, name: str = "profile"):
        y = np.array(y, dtype=float)
        z = np.array(z, dtype=float)
        if y.ndim != 1 or z.shape != y.shape or y.size < MIN_POINTS:
            raise InputError(f"{name}: expected two 1-D arrays y, z of one length >= {MIN_POINTS}, got shapes "
                             f"{y.shape}, {z.shape}")
        for label, v in (("y", y), ("z", z)):
            bad = np.flatnonzero(~np.isfinite(v))
            if bad.size:
                raise InputError(f"{name}: {label} is not finite at point {int(bad[0])}")
        step = np.diff(y)
        bad = np.flatnonzero(step <= 0)
        if bad.size:
            i = int(bad[0])
            raise InputError(f"{name}: y must increase strictly (the profile a function z(y)); it does not at points "
                             f"{i} and {i + 1} (y = {y[i]:.6g}, {y[i + 1]:.6g} mm)")
        from scipy.interpolate import CubicSpline
        self.name = name
        self.y, self.z = y, z
        self._spline = CubicSpline(y, z, extrapolate=False)
        self._slope = self._spline.derivative(1)
        self._curvature = self._spline.derivative(2)

    @property
    def lo(self) -> float:
        """First y (mm)."""
        return float(self.y[0])

    @property
    def hi(self) -> float:
        """Last y (mm)."""
        return float(self.y[-1])

    def __call__(self, y):
        """z(y) (mm); NaN outside [lo, hi]."""
        return self._spline(y)

    def slope(self, y):
        """dz/dy; NaN outside [lo, hi]."""
        return self._slope(y)

    def curvature(self, y):
        """d2z/dy2 (1/mm); NaN outside [lo, hi]."""
        return self._curvature(y)

    def turned(self, angle: float, shift_y: float = 0.0, shift_z: float = 0.0, name: str | None = None) -> "Profile":
        """The profile turned by `angle` (rad, counter-clockwise in the (y, z) plane: z towards -y for angle > 0)
        about its origin, then shifted by (shift_y, shift_z) mm. Where the turned points no longer increase in y
        (a near-vertical side face leaning over), only the longest increasing run through the highest point is
        kept: what lies beyond faces downwards and cannot be touched from above."""
        c, s = math.cos(angle), math.sin(angle)
        y = c * self.y - s * self.z
        z = s * self.y + c * self.z
        top = int(np.argmax(z))
        up = np.diff(y) > 0
        lo = top
        while lo > 0 and up[lo - 1]:
            lo -= 1
        hi = top
        while hi < y.size - 1 and up[hi]:
            hi += 1
        if hi - lo + 1 < MIN_POINTS:
            raise InputError(f"{self.name}: turned by {angle:.6g} rad it keeps only {hi - lo + 1} points increasing "
                             "in y about its highest point")
        return Profile(y[lo:hi + 1] + shift_y, z[lo:hi + 1] + shift_z, name or self.name)
