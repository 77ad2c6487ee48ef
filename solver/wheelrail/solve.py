"""One wheel on its rail (docs/wheelrail.md, §6): the contact search, the vertical position that carries the load,
and each patch's normal and steady tangential problem in its own tangent plane.

Algorithm, for the wheelset at (y, yaw, roll) with the vertical load Fz on this wheel:
1. the contact search (solver.wheelrail.search) and a Hertz estimate of the lowering dz beyond the first touch;
2. a coarse pass: the patches at twice that estimate on grids of about PatchParams.coarse_cells cells across, and
   the dz at which their normal forces carry Fz; a second one over the patches at 1.1 times that dz, their
   references moved to the load centres of the first (`_centred`), gives the load centres of the patches;
3. the patches at 1.1 times the coarse dz, with those references, each on a grid of the scene's dx, dy over its interpenetration region
   there plus one cell (the contact lies inside the interpenetration region, since the elastic displacements of a
   compressive pressure are positive); the grids are built again, larger, should the final dz exceed it;
4. vertical balance: sum over the patches of (Fn cos delta + Fs sin delta) = Fz (side frame; Fs the lateral
   tangential force, delta the contact angle). For fixed ratios Fs/Fn the normal problems alone fix dz (NormCG with
   the gap of the lowered wheel, recomputed exactly for every trial dz; a power-law and secant iteration on the total
   force); then each patch's steady tangential problem (the `fidelity` solver of PATCH_SOLVERS) gives new ratios,
   and the two alternate until the vertical force is within force_tol of Fz.
Normal and tangential problems are uncoupled (Kalker's K = 0, identical materials: the caller refuses K != 0 unless
asked). Patches do not interact elastically (they are separate half-space problems).

The right wheel is solved as the mirror image of a left one (yaw and roll change sign in the side frame) and mirrored
back: its lateral creepage, spin, lateral force, moment, contact angle and the s axis of its grid change sign.
Results are in the track frame (x forward, y left, z up), each patch in its own axes (x, s, n): n the rail's
normal into the wheel, s = n x x. Forces and moments are those on the wheel (Kalker's body 1). Units: mm, N, MPa, rad.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import Callable

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.materials import MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.creep.steady import SteadyParams, SteadyResult, SteadyRolling, solve_steady
from rollcontact.solver.normal import NormalParams, solve_normal
from rollcontact.solver.wheelrail.patch import creepages, patch_gap, rail_distance
from rollcontact.solver.wheelrail.placement import RailPlacement, WheelPlacement
from rollcontact.solver.wheelrail.search import COMBINE_DISTANCE, SEARCH_STEP, ContactSearch, PatchFrame

SIDES = ("left", "right")


@dataclass(frozen=True)
class WheelRailParams:
    """tol: relative tolerance of the normal (NormCG) and steady tangential solvers; max_iter: their iteration
    budget; force_tol: the vertical force balance, relative to Fz; combine: interpenetration regions closer than this
    (mm) form one patch; coarse_cells: cells across a patch in the coarse pass; max_outer: normal / tangential
    alternations; threads: FFTW threads; fidelity: the tangential solver of each patch (PATCH_SOLVERS); planner: the
    FFTW planner of the patch operators. FFTW_ESTIMATE: every position has patch grids of new shapes, and measuring
    their plans cost 0.4-1.2 s per position (Manchester profiles, 0.2 mm grid, the wisdom cache empty) against
    runs of 0.05-0.3 s; estimated plans run those positions 5-30 % slower once measured plans are cached."""
    tol: float = 1e-8
    max_iter: int = 500
    force_tol: float = 1e-6
    combine: float = COMBINE_DISTANCE
    coarse_cells: int = 16
    max_outer: int = 30
    threads: int = 1
    fidelity: str = "bem"
    search_step: float = SEARCH_STEP
    planner: str = "FFTW_ESTIMATE"

    def __post_init__(self):
        if not (0 < self.tol < 1e-2):
            raise InputError(f"tol = {self.tol!r}: allowed range 0 < tol < 0.01")
        if not (0 < self.force_tol < 1e-2):
            raise InputError(f"force_tol = {self.force_tol!r}: allowed range 0 < force_tol < 0.01")
        if self.fidelity not in PATCH_SOLVERS:
            raise InputError(f"fidelity = {self.fidelity!r}: allowed values are {sorted(PATCH_SOLVERS)}")


@dataclass
class PatchProblem:
    """What a patch's tangential solver gets: the grid and the operator on it (HalfSpaceOperator), the steady
    problem's set-up (SteadyRolling, built on first use), the pressure (MPa, (ny, nx)), friction coefficient and the
    creepages (xi, eta, phi) in the patch's axes (Kalker's convention), and the solver parameters."""
    grid: Grid
    operator: HalfSpaceOperator
    materials: MaterialPair
    pressure: np.ndarray
    mu: float
    creepages: tuple
    params: WheelRailParams
    _steady: SteadyRolling | None = field(default=None, repr=False)

    @property
    def steady(self) -> SteadyRolling:
        if self._steady is None:
            self._steady = SteadyRolling(self.grid, self.materials, coupled=False, operator=self.operator)
        return self._steady


def _exact_steady(problem: PatchProblem, initial) -> SteadyResult:
    """Kalker's exact steady rolling (solver.creep.steady) on the patch grid."""
    p = problem.params
    return solve_steady(problem.steady, problem.pressure, problem.mu, *problem.creepages, initial=initial,
                        params=SteadyParams(tol=max(p.tol, 1e-12), max_sweeps=max(p.max_iter, 100)))


#: The tangential solver of a patch by [solver] fidelity: callable(PatchProblem, initial traction or None) ->
#: SteadyResult (traction on the wheel, Kalker's convention). A faster model (FASTSIM) registers itself here.
PATCH_SOLVERS: dict[str, Callable] = {"bem": _exact_steady}


@dataclass
class PatchResult:
    """One solved patch, in the track frame and the patch's axes (x along the track, s = n x x, n into the wheel).

    Reference: x_track (mm, the reference point's x in the track frame), y_rail, y_wheel (mm: the reference point in
    the rail's and the wheel's profile coordinates), contact_angle (rad, the rotation about x from the track's z to
    n), rolling_radius (mm, the wheel's radius at y_wheel). grid: the patch grid (x, s; mm). Fields on it: pressure
    (MPa), u_z (mm, normal displacement), traction (2, ny, nx) on the wheel (MPa), slip (2, ny, nx) of the wheel
    relative to the rail per unit rolled distance, u12 (2, ny, nx) the tangential displacement difference wheel minus
    rail (mm), contact, stick (bool), gap (the undeformed h, mm). creepages (xi, eta, phi) (-, -, 1/mm); forces Fn,
    Fx, Fs (N) and moment Mz about the reference point (N mm) on the wheel; pmax (MPa); length, width: the contact's
    extent along x and s (mm); penetration: the largest interpenetration of the undeformed surfaces along n (mm);
    angle_spread: how much the rail's surface angle varies across the contact (rad, its largest less its smallest
    over the contact's lateral extent): the planar patch takes one angle for all (docs/wheelrail.md, "Where the
    planar patch becomes inaccurate"); normal_iterations, sweeps: of the last solves; frame: the patch's reference
    point and angle in the side frame (solver.wheelrail.search.PatchFrame; a right wheel's is the mirror image's)."""
    x_track: float
    y_rail: float
    y_wheel: float
    contact_angle: float
    rolling_radius: float
    grid: Grid
    pressure: np.ndarray
    u_z: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    u12: np.ndarray
    contact: np.ndarray
    stick: np.ndarray
    gap: np.ndarray
    creepages: tuple
    Fn: float
    Fx: float
    Fs: float
    Mz: float
    pmax: float
    length: float
    width: float
    penetration: float
    angle_spread: float
    normal_iterations: int
    sweeps: int
    frame: PatchFrame


@dataclass
class WheelRailResult:
    """One wheel solved: its patches (in increasing y of the side frame), the total force on the wheel in the track
    frame `force_track` (Fx, Fy, Fz; N), the lowering dz beyond the first touch (mm), the wheelset centre's height
    z_centre above the top of the rail (mm), and the iteration counts: outer (normal / tangential alternations),
    vertical (normal solves of every patch), grids (patch grids built)."""
    side: str
    patches: list
    force_track: tuple
    dz: float
    z_centre: float
    outer: int
    vertical: int
    grids: int


class _Patch:
    """A patch being solved: its frame (side frame), grid, operator, the rail's distance along n, and the state."""

    def __init__(self, search: ContactSearch, frame: PatchFrame, grid: Grid, materials, params):
        self.frame, self.grid, self.params = frame, grid, params
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


def solve_wheel(rail: RailPlacement, wheel: WheelPlacement, side: str, y: float, Fz: float, omega_per_speed: float,
                materials: MaterialPair, mu: float, dx: float, dy: float, *, yaw: float = 0.0, roll: float = 0.0,
                params: WheelRailParams = WheelRailParams(), progress=None) -> WheelRailResult:
    """Solve one wheel (module docstring). side: 'left' or 'right'; y: the wheelset's lateral position towards the
    field side of this rail (mm); yaw, roll: the wheelset's angles in the track frame (rad); Fz: the vertical load
    on this wheel (N); omega_per_speed: the wheelset's rotation over its forward speed (rad/mm,
    solver.wheelrail.patch.omega_per_speed); mu: friction coefficient; dx, dy: the patch grids' cells along x and s
    (mm). progress: callable(message) or None."""
    if side not in SIDES:
        raise InputError(f"side = {side!r}: allowed values are {list(SIDES)}")
    for name, v in (("Fz", Fz), ("mu", mu), ("dx", dx), ("dy", dy), ("omega_per_speed", omega_per_speed)):
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"{name} = {v!r}: must be finite and > 0")
    sign = 1.0 if side == "left" else -1.0
    search = ContactSearch(rail, wheel, y, sign * yaw, sign * roll, step=params.search_step)
    estimate = _hertz_estimate(search, wheel.radius, materials.E_star, Fz)
    coarse, rows = _coarse_pass(search, materials, Fz, 2.0 * estimate, params)
    coarse, rows = _coarse_pass(search, materials, Fz, 1.1 * coarse, params, rows)
    dz_grid, grids = 1.1 * coarse, 0
    for _ in range(6):
        frames = _centred(search, search.patches(dz_grid, params.combine), rows)
        patches = [_Patch(search, f, _patch_grid(search, f, dz_grid, dx, dy), materials, params) for f in frames]
        grids += len(patches)
        if progress:
            progress("wheel-rail: " + "; ".join(
                f"patch at y = {f.origin[1]:.2f} mm, contact angle {sign * f.angle:+.4f} rad, grid {p.grid.nx} x "
                f"{p.grid.ny}" for f, p in zip(frames, patches)))
        state = _balance(search, patches, Fz, coarse, mu, omega_per_speed, params)
        if state is not None and state[0] <= dz_grid:
            break
        dz_grid = 1.25 * max(dz_grid, max(p.dz_last for p in patches))
    else:
        raise ConvergenceError("the patch grids kept growing: the contact left every grid built for it",
                               solver="wheel-rail search", iterations=6)
    dz, outer, vertical = state
    wheel_now = search.wheel(dz)
    results = [_patch_result(search, wheel_now, p, omega_per_speed) for p in patches if p.loaded]
    force = np.zeros(3)
    for p, r in zip([p for p in patches if p.loaded], results):
        force += r.Fx * p.frame.e_x + r.Fs * p.frame.e_s + r.Fn * p.frame.e_n
    if sign < 0:
        results = [_mirrored(r) for r in results]
    return WheelRailResult(side, results, (float(force[0]), float(sign * force[1]), float(force[2])), float(dz),
                           float(search.position(dz).z_centre), outer, vertical, grids)


def _hertz_estimate(search: ContactSearch, radius: float, E_star: float, Fz: float) -> float:
    """The approach (mm) of a Hertz contact with the wheel's radius along x and the gap's curvature across it at the
    first touch (limited to 1/50 of the wheel's radius: a flat tread), carrying Fz: the search's starting guess."""
    from rollcontact.solver.analytic import HertzEllipse
    k = max(search.curvature_estimate(), 1.0 / (50.0 * radius))
    return HertzEllipse(radius, 1.0 / k, E_star, Fz).approach


def _coarse_pass(search, materials, Fz, dz, params, rows=None):
    """dz (mm) carrying Fz on coarse grids over the patches at `dz` (module docstring, step 2), centred by the row
    loads `rows` of an earlier pass if given, and the load of their rows (`_row_loads`)."""
    frames = search.patches(dz, params.combine)
    if rows is not None:
        frames = _centred(search, frames, rows)
    if not frames:
        raise InputError("the contact search found no interpenetration")
    patches = []
    for f in frames:
        sx, ss = _extent(search, f, dz)
        h = max(min(2 * sx, 2 * ss) / params.coarse_cells, 1e-6)
        patches.append(_Patch(search, f, _patch_grid(search, f, dz, h, h), materials, params))
    found, _ = _vertical(search, patches, [math.cos(p.frame.angle) for p in patches], Fz, 0.5 * dz, params)
    rows = [_row_loads(search, p) for p in patches if p.loaded]
    return found, tuple(np.concatenate([r[k] for r in rows]) for k in range(4))


def _row_loads(search: ContactSearch, patch) -> tuple:
    """Per row of a solved patch's grid: its normal load (N), the lateral position y of the rail point below it and
    the rail's surface angle there, and its load's mean x (side frame; mm, rad)."""
    frame, grid, p = patch.frame, patch.grid, patch.normal.pressure
    load = p.sum(axis=1) * grid.cell_area
    c, s = math.cos(frame.angle), math.sin(frame.angle)
    y = frame.origin[1] + grid.y * c - patch.rail_t * s
    x = frame.origin[0] + (p * grid.x[None, :]).sum(axis=1) / np.where(load > 0, p.sum(axis=1), 1.0)
    keep = load > 0
    return load[keep], y[keep], np.arctan(search.rail.surface.slope(y[keep])), x[keep]


def _centred(search: ContactSearch, frames: list, rows) -> list:
    """The frames moved to their load centres: each coarse row's load goes to the frame whose lateral extent is
    nearest to the row's y; a frame's reference becomes the load-weighted mean x, y of its rows and its contact angle
    the load-weighted mean of the rail's surface angle (the load centre, weighted angle). A frame without load keeps
    the search's reference."""
    load, y, angle, x = rows
    if not frames or load.size == 0:
        return frames
    lo = np.array([f.y_lo for f in frames])
    hi = np.array([f.y_hi for f in frames])
    distance = np.maximum(lo[None, :] - y[:, None], 0.0) + np.maximum(y[:, None] - hi[None, :], 0.0)
    owner = np.argmin(distance, axis=1)
    out = []
    for k, f in enumerate(frames):
        w = load[owner == k]
        if w.sum() <= 0:
            out.append(f)
            continue
        yk = float(np.dot(w, y[owner == k]) / w.sum())
        xk = float(np.dot(w, x[owner == k]) / w.sum())
        ak = float(np.dot(w, angle[owner == k]) / w.sum())
        out.append(PatchFrame(np.array([xk, yk, float(search.rail.surface(yk))]), ak, f.y_lo, f.y_hi))
    return out


def _extent(search: ContactSearch, frame: PatchFrame, dz: float) -> tuple[float, float]:
    """Estimated half-extents (mm) along x and s of a patch's interpenetration region at dz: along s from its
    lateral interval, along x from the wheel's radius and the depth (and the spread of the contact locus)."""
    c = math.cos(frame.angle)
    half_s = 0.5 * (frame.y_hi - frame.y_lo) / max(c, 0.2) + 2 * search.step
    depth = search.depth(frame, dz)
    half_x = math.sqrt(2.0 * search.wheel_placement.radius * max(depth, 0.0) / max(c, 0.2))
    return 1.2 * half_x + search.locus_spread(frame), 1.2 * half_s


def _patch_grid(search: ContactSearch, frame: PatchFrame, dz: float, dx: float, dy: float) -> Grid:
    """The grid of cells dx x dy over the interpenetration region h < 0 of the patch at dz, plus one cell on every
    side (the steady solver needs a free cell ahead of and behind the contact)."""
    half_x, half_s = _extent(search, frame, dz)
    half_x, half_s = max(half_x, 2 * dx), max(half_s, 2 * dy)
    wheel = search.wheel(dz)
    for _ in range(8):
        grid = Grid.covering(-half_x, half_x, -half_s, half_s, dx, dy)
        rail_t = rail_distance(search.rail, frame, grid.y)
        gap, _ = patch_gap(rail_t, wheel, frame, grid.x, grid.y)
        inside = np.nan_to_num(gap, nan=1.0) < 0
        if not inside.any():
            raise InputError(f"patch at y = {frame.origin[1]:.4g} mm: no interpenetration on its plane at dz = "
                             f"{dz:.3g} mm")
        grow_x = inside[:, 0].any() or inside[:, -1].any()
        grow_s = inside[0].any() or inside[-1].any()
        if not (grow_x or grow_s):
            break
        half_x *= 1.5 if grow_x else 1.0
        half_s *= 1.5 if grow_s else 1.0
    else:
        raise InputError(f"patch at y = {frame.origin[1]:.4g} mm: its interpenetration region does not close "
                         "within 20 times its estimated size (a conformal or flat contact the planar patch cannot "
                         "hold)")
    cols, rows = np.flatnonzero(inside.any(axis=0)), np.flatnonzero(inside.any(axis=1))
    x, s = grid.x, grid.y
    return Grid.covering(x[cols[0]] - dx, x[cols[-1]] + dx, s[rows[0]] - dy, s[rows[-1]] + dy, dx, dy)


def _vertical(search, patches, factors, Fz, dz, params):
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


def _balance(search, patches, Fz, dz, mu, omega_per_speed, params):
    """Alternate the vertical balance (normal problems) and the tangential problems (module docstring, step 4):
    (dz, outer iterations, normal solves), or None when the contact outgrew the patch grids."""
    ratio = np.zeros(len(patches))
    solver = PATCH_SOLVERS[params.fidelity]
    vertical = 0
    for outer in range(1, params.max_outer + 1):
        factors = [math.cos(p.frame.angle) + r * math.sin(p.frame.angle) for p, r in zip(patches, ratio)]
        if min(factors) <= 0:
            raise ConvergenceError("a patch's tangential force turns its vertical force downwards",
                                   solver="wheel-rail vertical", iterations=outer)
        dz, solves = _vertical(search, patches, factors, Fz, dz, params)
        vertical += solves
        if any(p.loaded and p.on_border() for p in patches):
            return None
        position = search.position(dz)
        total = 0.0
        for k, p in enumerate(patches):
            if not p.loaded:
                p.tangential = None
                continue
            t_w = float(p.wheel_t_at_origin(search.wheel(dz)))
            xi, eta, phi = creepages(position, omega_per_speed, p.frame, p.frame.origin + t_w * p.frame.e_n)
            p.problem = PatchProblem(p.grid, p.operator, p.materials, p.normal.pressure, mu, (xi, eta, phi), params,
                                     _steady=p.problem._steady if p.problem is not None else None)
            initial = None if p.tangential is None else p.tangential.traction
            p.tangential = solver(p.problem, initial)
            Fn, Fs = p.normal.force, p.tangential.force[1]
            ratio[k] = Fs / Fn
            total += Fn * math.cos(p.frame.angle) + Fs * math.sin(p.frame.angle)
        if abs(total - Fz) <= params.force_tol * Fz:
            return dz, outer, vertical
    raise ConvergenceError("the normal / tangential alternation of the vertical balance did not converge",
                           solver="wheel-rail vertical", iterations=params.max_outer, residual=abs(total - Fz) / Fz,
                           tol=params.force_tol)


def _patch_result(search: ContactSearch, wheel, patch: _Patch, omega_per_speed) -> PatchResult:
    """A solved patch in the side frame (mirrored afterwards for a right wheel)."""
    frame, grid, normal, tang = patch.frame, patch.grid, patch.normal, patch.tangential
    origin = frame.origin
    y_rail = float(search.rail.to_profile(origin[1], origin[2])[0])
    t_w = float(wheel.distance_along(origin.reshape(3, 1), frame.e_n, start=[0.0])[0])
    y_wheel = float(wheel.profile_coordinate((origin + t_w * frame.e_n).reshape(3, 1))[0])
    contact = tang.contact
    X, S = grid.mesh()
    length = float(X[contact].max() - X[contact].min() + grid.dx)
    width = float(S[contact].max() - S[contact].min() + grid.dy)
    u12 = patch.operator.tangential(tang.traction[0], tang.traction[1])
    rows = contact.any(axis=1)
    c, s = math.cos(frame.angle), math.sin(frame.angle)
    angles = np.arctan(search.rail.surface.slope(origin[1] + grid.y[rows] * c - patch.rail_t[rows] * s))
    return PatchResult(
        x_track=float(origin[0]), y_rail=y_rail, y_wheel=y_wheel, contact_angle=float(frame.angle),
        rolling_radius=float(search.wheel_placement.rolling_radius(y_wheel)), grid=grid,
        pressure=normal.pressure, u_z=normal.displacement, traction=tang.traction, slip=tang.slip, u12=u12,
        contact=contact, stick=tang.stick, gap=patch.gap, creepages=tuple(tang.creepages), Fn=float(normal.force),
        Fx=float(tang.force[0]), Fs=float(tang.force[1]), Mz=float(tang.moment),
        pmax=float(np.max(normal.pressure)), length=length, width=width,
        penetration=float(-np.min(patch.gap)), angle_spread=float(np.max(angles) - np.min(angles)),
        normal_iterations=int(normal.iterations), sweeps=int(tang.sweeps), frame=frame)


def _mirrored(r: PatchResult) -> PatchResult:
    """The mirror image y -> -y of a side-frame patch: the right wheel's patch in the track frame."""
    g = r.grid
    grid = Grid(g.nx, g.ny, g.dx, g.dy, g.i0, -(g.j0 + g.ny - 1))
    flip = lambda a: np.ascontiguousarray(a[..., ::-1, :])        # noqa: E731  (the s axis)
    vec = lambda a: np.stack([flip(a[0]), -flip(a[1])])           # noqa: E731  (x kept, s component negated)
    xi, eta, phi = r.creepages
    return PatchResult(
        x_track=r.x_track, y_rail=r.y_rail, y_wheel=r.y_wheel, contact_angle=-r.contact_angle,
        rolling_radius=r.rolling_radius, grid=grid, pressure=flip(r.pressure), u_z=flip(r.u_z),
        traction=vec(r.traction), slip=vec(r.slip), u12=vec(r.u12), contact=flip(r.contact), stick=flip(r.stick),
        gap=flip(r.gap), creepages=(xi, -eta, -phi), Fn=r.Fn, Fx=r.Fx, Fs=-r.Fs, Mz=-r.Mz, pmax=r.pmax,
        length=r.length, width=r.width, penetration=r.penetration, angle_spread=r.angle_spread,
        normal_iterations=r.normal_iterations, sweeps=r.sweeps, frame=r.frame)
