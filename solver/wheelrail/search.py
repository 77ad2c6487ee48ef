"""The contact search of one wheel on its rail (docs/wheelrail.md, §4): the vertical gap along the profiles, the
regions where the profiles interpenetrate when the wheel is lowered by dz beyond its first touch, and the contact
patches made of them, each with its reference point, contact angle and tangent plane.

The rail does not vary along x, so wheel and rail can only touch where the wheel's normal is perpendicular to x: on
its silhouette seen along x (solver.wheelrail.wheel), the "contact locus". The vertical gap at the lateral position y
is g(y) = z_silhouette(y) - z_rail(y) (side frame, sampled every `step` mm); the wheel first touches at the minimum
of g, and lowered by dz it interpenetrates the rail where g - min g < dz. Each connected interval of that set is an
interpenetration region; regions closer than `combine` (mm) form one patch (their elastic interaction is then
solved, on one tangent plane), the others are separate patches (solved independently).

A patch's reference (CONTACT's "weighted centre, weighted angle", Vollebregt 2020): y_ref, the mean of y over its
regions weighted by the interpenetration depth dz - (g - min g); the contact angle delta, the same weighted mean of
the rail's surface angle atan(dz_rail/dy); the reference point O on the rail at y_ref, at the x of the contact
locus there. Its tangent plane has the axes e_x = (1, 0, 0), e_n = (0, -sin delta, cos delta) (into the wheel) and
e_s = e_n x e_x = (0, cos delta, sin delta) (side frame). Units: mm, rad.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.wheelrail.placement import RailPlacement, WheelPlacement
from rollcontact.solver.wheelrail.wheel import Wheel, WheelPosition

#: Lateral sampling of the profiles in the search (mm). The linear interpolation of the silhouette between
#: samples errs by step^2 kappa / 8: 5e-6 mm at curvature 0.1/mm, against approaches of 0.01-0.1 mm. The patch gaps
#: themselves are computed exactly (solver.wheelrail.patch).
SEARCH_STEP = 0.02
#: Regions closer than this (mm) form one patch (CONTACT's D_COMB in the Manchester benchmark decks).
COMBINE_DISTANCE = 4.0


@dataclass(frozen=True)
class PatchFrame:
    """A contact patch's reference point `origin` (side frame, mm, on the rail surface), contact angle `angle`
    (rad, side frame: e_n = (0, -sin, cos)), and the lateral extent [y_lo, y_hi] (mm) of its interpenetration
    regions at the dz of the search."""

    origin: np.ndarray
    angle: float
    y_lo: float
    y_hi: float

    @property
    def e_x(self) -> np.ndarray:
        return np.array([1.0, 0.0, 0.0])

    @property
    def e_n(self) -> np.ndarray:
        return np.array([0.0, -math.sin(self.angle), math.cos(self.angle)])

    @property
    def e_s(self) -> np.ndarray:
        return np.array([0.0, math.cos(self.angle), math.sin(self.angle)])

    def point(self, x, s, n=0.0) -> np.ndarray:
        """Side-frame points (3, ...) of the patch coordinates (x, s, n) (mm)."""
        x, s, n = np.broadcast_arrays(np.asarray(x, float), np.asarray(s, float), np.asarray(n, float))
        o = self.origin.reshape((3,) + (1,) * x.ndim)
        return (o + x[None] * self.e_x.reshape(o.shape) + s[None] * self.e_s.reshape(o.shape)
                + n[None] * self.e_n.reshape(o.shape))


class ContactSearch:
    """The vertical gap of a placed wheel at a lateral position, yaw and roll over a placed rail, and its patches.

    rail: RailPlacement; wheel: WheelPlacement; y, yaw, roll: the wheelset in the side frame (mm, rad). The wheel's
    height is measured by `dz`, its lowering (mm) beyond the first touch; `position(dz)` is the WheelPosition.
    InputError when the profiles do not overlap or never touch."""

    def __init__(self, rail: RailPlacement, wheel: WheelPlacement, y: float, yaw: float = 0.0, roll: float = 0.0,
                 step: float = SEARCH_STEP):
        self.rail, self.wheel_placement, self.step = rail, wheel, float(step)
        nominal = WheelPosition(float(y), wheel.radius, float(yaw), float(roll))
        profile = wheel.profile
        n = max(int(math.ceil((profile.hi - profile.lo) / step)), 8)
        sil = Wheel(wheel, nominal).silhouette(np.linspace(profile.lo, profile.hi, n + 1))
        keep = _increasing_run(sil.y)
        sil_y, sil_z, sil_x, sil_w = sil.y[keep], sil.z[keep], sil.x[keep], sil.y_w[keep]
        surface = rail.surface
        lo, hi = max(surface.lo, sil_y[0]), min(surface.hi, sil_y[-1])
        if not hi - lo > 4 * step:
            raise InputError(f"the wheel (y = {sil_y[0]:.5g} to {sil_y[-1]:.5g} mm over the track) and the rail "
                             f"(y = {surface.lo:.5g} to {surface.hi:.5g} mm) do not overlap at the wheelset's "
                             f"lateral position {y:.5g} mm: check gauge, back_to_back and flange_back")
        ys = np.linspace(lo, hi, int(math.ceil((hi - lo) / step)) + 1)
        self.y = ys
        self.rail_z = surface(ys)
        self.locus_x = np.interp(ys, sil_y, sil_x)
        self.locus_y_w = np.interp(ys, sil_y, sil_w)
        nominal_gap = np.interp(ys, sil_y, sil_z) - self.rail_z
        k = int(np.argmin(nominal_gap))
        #: the wheelset centre's height at the first touch (mm)
        self.z_touch = wheel.radius - float(nominal_gap[k])
        #: g - min g (mm) along self.y: how far the wheel must be lowered for the profiles to touch there
        self.gap = nominal_gap - nominal_gap[k]
        self.y_touch = float(ys[k])
        self._wheel_range = (float(sil_y[0]), float(sil_y[-1]))
        self.yaw, self.roll, self.y_wheelset = float(yaw), float(roll), float(y)

    def position(self, dz: float) -> WheelPosition:
        """The wheelset lowered by dz (mm) beyond the first touch."""
        return WheelPosition(self.y_wheelset, self.z_touch - dz, self.yaw, self.roll)

    def wheel(self, dz: float) -> Wheel:
        return Wheel(self.wheel_placement, self.position(dz))

    def regions(self, dz: float) -> list[tuple[int, int]]:
        """Index ranges [i0, i1] (inclusive) of self.y where the profiles interpenetrate at dz (mm). InputError when
        a region reaches the end of the sampled overlap (a profile does not cover the contact)."""
        inside = self.gap < dz
        if not inside.any():
            return []
        edges = np.flatnonzero(np.diff(inside.astype(np.int8)))
        starts = [0] if inside[0] else []
        starts += [int(e) + 1 for e in edges if not inside[e]]
        ends = [int(e) for e in edges if inside[e]]
        if inside[-1]:
            ends.append(inside.size - 1)
        out = list(zip(starts, ends))
        for i0, i1 in out:
            for i, end in ((i0, 0), (i1, inside.size - 1)):
                if i == end:
                    raise InputError(self._uncovered(float(self.y[i]), dz))
        return out

    def _uncovered(self, y: float, dz: float) -> str:
        surface = self.rail.surface
        which = []
        if abs(y - surface.lo) < 2 * self.step or abs(y - surface.hi) < 2 * self.step:
            y_r = self.rail.to_profile(y, surface(y))[0]
            which.append(f"the rail profile (its end at y_r = {float(y_r):.5g} mm)")
        if abs(y - self._wheel_range[0]) < 2 * self.step or abs(y - self._wheel_range[1]) < 2 * self.step:
            y_w = float(np.interp(y, self.y, self.locus_y_w))
            which.append(f"the wheel profile (its end at y_w = {y_w:.5g} mm)")
        what = " and ".join(which) or "the profiles"
        return (f"the contact at the wheelset's lateral position {self.y_wheelset:.5g} mm (lowered {dz:.3g} mm "
                f"beyond the first touch) reaches the end of {what}: the profile does not cover the contact; "
                "extend it, or check the wheelset position and the track dimensions")

    def patches(self, dz: float, combine: float = COMBINE_DISTANCE) -> list[PatchFrame]:
        """The contact patches at dz (mm), in increasing y (module docstring)."""
        groups = []
        for i0, i1 in self.regions(dz):
            if groups and self.y[i0] - self.y[groups[-1][-1][1]] < combine:
                groups[-1].append((i0, i1))
            else:
                groups.append([(i0, i1)])
        surface = self.rail.surface
        frames = []
        for group in groups:
            idx = np.concatenate([np.arange(i0, i1 + 1) for i0, i1 in group])
            y = self.y[idx]
            w = dz - self.gap[idx]
            y_ref = float(np.sum(w * y) / np.sum(w))
            angle = float(np.sum(w * np.arctan(surface.slope(y))) / np.sum(w))
            origin = np.array([float(np.interp(y_ref, self.y, self.locus_x)), y_ref, float(surface(y_ref))])
            frames.append(PatchFrame(origin, angle, float(y[0]), float(y[-1])))
        return frames

    def depth(self, frame: PatchFrame, dz: float) -> float:
        """The largest interpenetration (mm, vertical) within a patch's lateral extent at dz."""
        inside = (self.y >= frame.y_lo) & (self.y <= frame.y_hi)
        return float(dz - np.min(self.gap[inside]))

    def locus_spread(self, frame: PatchFrame) -> float:
        """The largest |x| (mm) of the contact locus about the patch's reference within its lateral extent."""
        inside = (self.y >= frame.y_lo) & (self.y <= frame.y_hi)
        return float(np.max(np.abs(self.locus_x[inside] - frame.origin[0])))

    def curvature_estimate(self) -> float:
        """d2g/dy2 (1/mm) at the first touch, from the sampled gap (lateral relative curvature of the profiles)."""
        k = int(np.argmin(self.gap))
        k = min(max(k, 2), self.gap.size - 3)
        h = 2 * self.step
        return float((self.gap[k + 2] - 2 * self.gap[k] + self.gap[k - 2]) / (h * h))


def _increasing_run(v) -> slice:
    """The longest run of strictly increasing values of v (a slice)."""
    up = np.diff(v) > 0
    best, start, best_len = (0, 1), 0, 0
    for i, u in enumerate(np.append(up, False)):
        if not u:
            if i + 1 - start > best_len:
                best, best_len = (start, i + 1), i + 1 - start
            start = i + 1
    return slice(*best)
