"""The vertical balance of one wheel (docs/wheelrail.md, §4): a patch being solved (its frame, grid, operator, the
rail's distance along its normal and the latest normal and tangential states), and the lowering dz of the wheel at
which the patches' normal forces carry a given vertical load. Units: mm, N, MPa.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.normal import NormalParams, solve_normal
from rollcontact.solver.wheelrail.patch import patch_gap, rail_distance
from rollcontact.solver.wheelrail.search import ContactSearch, PatchFrame


class PatchState:
    """A patch being solved: its frame (side frame), grid, operator, the rail's distance along n, and the state."""

    def __init__(self, search: ContactSearch, frame: PatchFrame, grid: Grid, materials, params):
        """params: solver.wheelrail.solve.WheelRailParams (tol, max_iter, threads, planner)."""
        self.frame, self.grid, self.params, self.rail = frame, grid, params, search.rail
        self.rail_t = rail_distance(search.rail, frame, grid.y)
        if np.any(np.isnan(self.rail_t)):
            raise InputError(search._uncovered(float(frame.point(0.0, grid.y[0])[1]), 0.0))
        self.operator = HalfSpaceOperator(grid, materials, threads=params.threads, coupling=False,
                                          planner=params.planner)
        self.materials = materials
        self.normal = None
        self.t_w = None
        self.gap = None
        self.tangential = None
        self.problem = None
        self.dz_last = 0.0

    def solve_normal(self, wheel):
        gap, t_w = patch_gap(self.rail_t, wheel, self.frame, self.grid.x, self.grid.y, start=self.t_w)
        if np.any(np.isnan(gap)):
            raise InputError("a patch grid leaves the wheel profile: the wheel profile does not cover the contact")
        p = self.params
        initial = None if self.normal is None or not np.any(self.normal.pressure > 0) else self.normal.pressure
        self.normal = solve_normal(self.operator, gap, approach=0.0, initial=initial,
                                   params=NormalParams(tol=p.tol, max_iter=p.max_iter))
        self.t_w, self.gap = t_w, gap
        return self.normal.force

    def wheel_t_at_origin(self, wheel) -> float:
        """t_wheel (mm) at the reference point: the wheel's surface point O + t e_n."""
        return float(wheel.distance_along(self.frame.origin.reshape(3, 1), self.frame.e_n, start=[0.0])[0])

    @property
    def loaded(self) -> bool:
        return self.normal is not None and bool(np.any(self.normal.pressure > 0))

    def on_border(self) -> bool:
        p = self.normal.pressure > 0
        return bool(p[0].any() or p[-1].any() or p[:, 0].any() or p[:, -1].any())


def vertical(search, patches, factors, Fz, dz, params):
    """dz (mm) with sum_k factors[k] Fn_k(dz) = Fz, and the normal solves it took. Power-law steps
    dz (Fz / F)^(2/3) (exact for one Hertzian patch) until two points bracket Fz, then the secant on F^(2/3)
    safeguarded by bisection."""
    def total(dz):
        wheel = search.wheel(dz)
        return sum(c * p.solve_normal(wheel) for p, c in zip(patches, factors))

    solves = 0
    lo, hi = (0.0, 0.0), None          # (dz, F) below and above Fz
    F = total(dz)
    solves += 1
    while F <= 0.0:
        lo = (dz, F)
        dz *= 2.0
        F, solves = total(dz), solves + 1
        if solves > 40:
            raise ConvergenceError("no load found while lowering the wheel", solver="wheel-rail vertical",
                                   iterations=solves)
    last = None
    for _ in range(80):
        if abs(F - Fz) <= params.force_tol * Fz:
            for p in patches:
                p.dz_last = dz
            return dz, solves
        if F < Fz:
            lo = (dz, F)
        else:
            hi = (dz, F)
        psi, target = F ** (2.0 / 3.0), Fz ** (2.0 / 3.0)
        if last is not None and last[1] > 0 and last[0] != dz:
            psi0 = last[1] ** (2.0 / 3.0)
            slope = (psi - psi0) / (dz - last[0])
            new = dz + (target - psi) / slope if slope > 0 else math.nan
        else:
            new = dz * (Fz / F) ** (2.0 / 3.0)
        if hi is not None and not (lo[0] < new < hi[0]):
            new = 0.5 * (lo[0] + hi[0])
        last = (dz, F)
        dz = new
        F, solves = total(dz), solves + 1
    raise ConvergenceError("the vertical force balance did not converge", solver="wheel-rail vertical",
                           iterations=solves, residual=abs(F - Fz) / Fz, tol=params.force_tol)
