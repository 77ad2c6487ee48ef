"""The wheel as a body of revolution at a wheelset position, in the side frame (solver.wheelrail.placement): its
silhouette seen along the track (the contact locus on a rail that does not vary along x) and the distance from a
point to its surface along a direction (docs/wheelrail.md, §3).

The wheelset centre lies at (0, y, z_centre); its orientation is the roll angle about x, then the yaw angle about the
rolled vertical axis (intrinsic roll-yaw; the pitch of a body of revolution does not matter). The wheel's axle
direction is a = R_x(roll) R_z(yaw) e_y; the point of the wheel profile y_w is the ring of radius
r(y_w) = radius - z_w(y_w) about the axle point C + (arm + y_w) a. Units: mm, rad.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.wheelrail.placement import WheelPlacement

#: Newton iterations allowed for a distance to the wheel surface; it converges quadratically (4-6 iterations).
MAX_NEWTON = 30
#: Stop when every update is below this (mm).
NEWTON_TOL = 1e-11


@dataclass(frozen=True)
class WheelPosition:
    """The wheelset in the side frame: lateral position `y` (mm, towards the field side), height `z_centre` of the
    wheelset centre (axle) above z = 0 (mm), `yaw` and `roll` (rad, right-hand rule in the side frame)."""

    y: float
    z_centre: float
    yaw: float = 0.0
    roll: float = 0.0

    @property
    def rotation(self) -> np.ndarray:
        """R_x(roll) R_z(yaw): wheelset axes -> side frame."""
        cr, sr = math.cos(self.roll), math.sin(self.roll)
        cy, sy = math.cos(self.yaw), math.sin(self.yaw)
        rx = np.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
        rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
        return rx @ rz

    @property
    def centre(self) -> np.ndarray:
        return np.array([0.0, self.y, self.z_centre])

    @property
    def axle(self) -> np.ndarray:
        """Unit vector along the axle, towards the field side."""
        return self.rotation[:, 1]

    def lowered(self, dz: float) -> "WheelPosition":
        return WheelPosition(self.y, self.z_centre - dz, self.yaw, self.roll)


@dataclass(frozen=True)
class Silhouette:
    """The wheel's silhouette seen along x: per sampled y_w, the surface point (x, y, z) whose normal is
    perpendicular to x (the lower one), in the side frame (mm)."""

    y_w: np.ndarray
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray


class Wheel:
    """A placed wheel (WheelPlacement) at a WheelPosition."""

    def __init__(self, placement: WheelPlacement, position: WheelPosition):
        self.placement, self.position = placement, position
        self.centre, self.axle = position.centre, position.axle
        down = np.array([0.0, 0.0, -1.0])
        u = down - (down @ self.axle) * self.axle
        self._down = u / np.linalg.norm(u)                  # radial direction pointing down
        self._side = np.cross(self.axle, self._down)        # completes (down, side) in the wheel's plane

    def silhouette(self, y_w) -> Silhouette:
        """The silhouette points of the rings at the profile coordinates y_w (mm): where the outward normal
        e_rho - r'(y_w) a is perpendicular to x, on the lower half of the ring."""
        y_w = np.asarray(y_w, dtype=float)
        pl = self.placement
        r, dr = pl.rolling_radius(y_w), pl.radius_slope(y_w)
        A, B = self._down[0], self._side[0]
        C = dr * self.axle[0]
        R = math.hypot(A, B)
        alpha = math.atan2(B, A)
        beta = np.arccos(np.clip(C / R, -1.0, 1.0))
        t1, t2 = alpha - beta, alpha + beta
        theta = np.where(np.cos(t1) >= np.cos(t2), t1, t2)            # the lower of the two
        ring = self.centre[:, None] + (pl.arm + y_w)[None, :] * self.axle[:, None]
        point = ring + r[None, :] * (np.cos(theta)[None, :] * self._down[:, None]
                                     + np.sin(theta)[None, :] * self._side[:, None])
        return Silhouette(y_w, point[0], point[1], point[2])

    def profile_coordinate(self, points) -> np.ndarray:
        """y_w (mm) of side-frame points (3, ...): their axial coordinate less the arm."""
        rel = points - self.centre.reshape((3,) + (1,) * (points.ndim - 1))
        return np.tensordot(self.axle, rel, axes=1) - self.placement.arm

    def distance_along(self, base, direction, start=None) -> np.ndarray:
        """t (mm) such that base + t direction lies on the wheel surface, for points `base` (3, ...) and one unit
        `direction` (3,) pointing into the wheel (towards its axle); the root near `start` (default 0) of
        F(t) = r(y_w(t)) - rho(t), rho the distance from the axle. Newton's method, to NEWTON_TOL. NaN where the
        line leaves the wheel profile's range; ConvergenceError if it does not converge."""
        base = np.asarray(base, dtype=float)
        shape = base.shape[1:]
        P0 = base.reshape(3, -1) - self.centre[:, None]
        d = np.asarray(direction, dtype=float)
        a = self.axle
        da = float(d @ a)
        t = np.zeros(P0.shape[1]) if start is None else np.array(start, dtype=float).reshape(-1).copy()
        pl = self.placement
        for _ in range(MAX_NEWTON):
            P = P0 + t[None, :] * d[:, None]
            eta = a @ P
            radial = P - eta[None, :] * a[:, None]
            rho = np.sqrt(np.sum(radial * radial, axis=0))
            y_w = eta - pl.arm
            F = pl.rolling_radius(y_w) - rho
            dF = pl.radius_slope(y_w) * da - (d @ radial) / rho
            step = F / dF
            t -= step
            if np.all(np.isnan(step) | (np.abs(step) <= NEWTON_TOL)):
                break
        else:
            worst = float(np.nanmax(np.abs(step)))
            raise ConvergenceError("distance to the wheel surface did not converge", solver="wheel Newton",
                                   iterations=MAX_NEWTON, residual=worst, tol=NEWTON_TOL)
        return t.reshape(shape)


def check_roll_yaw(yaw: float, roll: float):
    """InputError for a yaw or roll that is not finite."""
    for name, v in (("yaw", yaw), ("roll", roll)):
        if not math.isfinite(v):
            raise InputError(f"{name} = {v!r} rad: must be finite")
