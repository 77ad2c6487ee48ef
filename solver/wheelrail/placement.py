"""The rail in the track and the wheel on its wheelset, in the side frame of one rail (docs/wheelrail.md, §2).

Side frame: x along the direction of travel, y lateral from the track centre line, positive towards the field side
of this rail, z upwards, z = 0 at the top of the rail. For the left rail it is the track frame itself (x forward, y
to the left, z up); the right rail is solved as its mirror image (solver.wheelrail.solve).

Rail: its profile is inclined by `inclination` (rad, the rail's vertical axis leaning towards the track centre, 0.025
for 1:40), then shifted so that its highest point lies at z = 0 and its gauge point (the point of the inner face
`gauge_height` below that top, the first one met coming from the track centre) at y = gauge / 2. gauge_height = 0:
no gauge point; the inclined profile's origin is placed at y = gauge / 2.
Wheel: its profile's reference point (y_w = 0) lies on the axle at the lateral distance back_to_back / 2 -
flange_back from the wheelset centre (flange_back: the flange back's y in the wheel profile's coordinates, e.g.
-70 mm for S1002), on the rolling circle of radius `radius`: the wheel's radius at y_w is radius - z_w(y_w).
Units: mm, rad.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.wheelrail.profile import Profile


@dataclass(frozen=True)
class RailPlacement:
    """The rail in the side frame: `surface` z(y) there, and the map from the rail profile's own coordinates
    (turned by `inclination`, then shifted by (shift_y, shift_z))."""

    surface: Profile
    inclination: float
    shift_y: float
    shift_z: float

    def to_profile(self, y, z):
        """Side-frame points (mm) -> the rail profile's own coordinates (mm)."""
        y, z = np.asarray(y, dtype=float) - self.shift_y, np.asarray(z, dtype=float) - self.shift_z
        c, s = math.cos(self.inclination), math.sin(self.inclination)
        return c * y + s * z, -s * y + c * z


def place_rail(profile: Profile, inclination: float, gauge: float, gauge_height: float) -> RailPlacement:
    """The rail profile inclined and placed in the side frame (module docstring). InputError when the profile does not
    reach `gauge_height` below its top on the track centre's side."""
    turned = profile.turned(inclination)
    top = float(np.max(turned.z))
    if gauge_height > 0:
        level = top - gauge_height
        below = turned.z < level
        if not below[0]:
            raise InputError(f"rail profile: its track-centre end (y = {turned.lo:.4g} mm, inclined) lies "
                             f"{top - turned.z[0]:.4g} mm below its top, above the gauge height {gauge_height:.4g} "
                             "mm: the gauge point is not on the profile (extend the profile down the gauge face, "
                             "or set gauge_height = 0 to place the profile's origin at gauge / 2)")
        k = int(np.argmin(below))                      # first point at or above the level
        y0, y1, z0, z1 = turned.y[k - 1], turned.y[k], turned.z[k - 1], turned.z[k]
        gauge_point = y0 + (level - z0) * (y1 - y0) / (z1 - z0)
    else:
        gauge_point = 0.0
    shift_y, shift_z = 0.5 * gauge - gauge_point, -top
    surface = Profile(turned.y + shift_y, turned.z + shift_z, profile.name)
    return RailPlacement(surface, float(inclination), float(shift_y), float(shift_z))


@dataclass(frozen=True)
class WheelPlacement:
    """The wheel on its wheelset: the wheel `profile` (z_w(y_w), mm), the nominal rolling radius `radius` (mm) at
    y_w = 0 and the lateral distance `arm` (mm) of the profile's reference point from the wheelset centre."""

    profile: Profile
    radius: float
    arm: float

    def __post_init__(self):
        if not (self.radius > 0 and math.isfinite(self.radius)):
            raise InputError(f"wheel radius = {self.radius!r} mm: must be > 0 and finite")
        r = self.radius - self.profile.z
        if np.any(r <= 0):
            raise InputError(f"wheel profile: z_w reaches {float(np.max(self.profile.z)):.4g} mm, at or above the "
                             f"axle of a wheel of radius {self.radius:.6g} mm")

    @classmethod
    def on_wheelset(cls, profile: Profile, radius: float, back_to_back: float, flange_back: float):
        """The placement given the wheelset's back-to-back distance and the flange back's y in the wheel profile."""
        return cls(profile, float(radius), 0.5 * back_to_back - flange_back)

    def rolling_radius(self, y_w):
        """The wheel's radius (mm) at the profile coordinate y_w (mm)."""
        return self.radius - self.profile(y_w)

    def radius_slope(self, y_w):
        """d(radius)/d(y_w)."""
        return -self.profile.slope(y_w)
