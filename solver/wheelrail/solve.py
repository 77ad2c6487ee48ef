"""One wheel on its rail (docs/wheelrail.md, §6): the contact search, the vertical position that carries the load,
and each patch's normal and steady tangential problem in its own tangent plane.

Algorithm, for the wheelset at (y, yaw, roll) with the vertical load Fz on this wheel:
1. the contact search (solver.wheelrail.search) and a Hertz estimate of the lowering dz beyond the first touch;
2. a coarse pass: the patches at twice that estimate on grids of about WheelRailParams.coarse_cells cells across,
   and the dz at which their normal forces carry Fz; a second one over the patches at 1.1 times that dz, their
   references moved to the load centres of the first, gives the load centres of the patches (solver.wheelrail.layout);
3. the patches at 1.1 times the coarse dz, with those references, each on a grid of the scene's dx, dy over its
   interpenetration region there plus one cell (the contact lies inside the interpenetration region, since the
   elastic displacements of a compressive pressure are positive); built again, larger, should the final dz exceed it;
4. vertical balance (solver.wheelrail.balance): sum over the patches of (Fn cos delta + Fs sin delta) = Fz (side frame; Fs the lateral
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
from rollcontact.solver.wheelrail.balance import PatchState, vertical
from rollcontact.solver.wheelrail.layout import centred, coarse_pass, hertz_estimate, patch_grid
from rollcontact.solver.wheelrail.patch import creepages
from rollcontact.solver.wheelrail.placement import RailPlacement, WheelPlacement
from rollcontact.solver.wheelrail.search import COMBINE_DISTANCE, SEARCH_STEP, ContactSearch, PatchFrame

SIDES = ("left", "right")


@dataclass(frozen=True)
class WheelRailParams:
    """tol: relative tolerance of the normal (NormCG) and steady tangential solvers; max_iter: their iteration
    budget; force_tol: the vertical force balance, relative to Fz; combine: interpenetration regions closer than this
    (mm) form one patch; coarse_cells: cells across a patch in the coarse pass; max_outer: normal / tangential
    alternations; threads: FFTW threads; fidelity: the tangential solver of each patch (PATCH_SOLVERS); planner: the
    FFTW planner of the patch operators (and of a transient's world grids). FFTW_ESTIMATE: every position has patch
    grids of new shapes, and measuring their plans cost 0.4-1.2 s per position (Manchester profiles, 0.2 mm grid,
    the wisdom cache empty) against runs of 0.05-0.3 s; estimated plans run those positions 5-30 % slower once
    measured plans are cached."""
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


def _fast_steady(model: str) -> Callable:
    """The patch solver of a fast model ("fastsim", "fastrip"; solver.fastsim, docs/theory.md §12.4) on the patch grid
    with the patch's own pressure as the traction bound and the flexibilities of its equivalent ellipse."""
    def solve(problem: PatchProblem, initial) -> SteadyResult:
        from rollcontact.solver.fastsim import fast_patch
        m = problem.materials
        state = fast_patch(model, creepages=problem.creepages, mu=problem.mu, G=m.G, nu=m.nu, grid=problem.grid,
                           pressure=problem.pressure).state
        return SteadyResult(state.traction, state.slip, state.contact, state.stick, tuple(state.force),
                            float(state.moment), sweeps=1, change=0.0, stick_slip=0.0, creepages=state.creepages)
    return solve


#: The tangential solver of a patch by [solver] fidelity: callable(PatchProblem, initial traction or None) ->
#: SteadyResult (traction on the wheel, Kalker's convention, moment about the grid origin): Kalker's exact steady
#: theory, or a fast model (the normal problem and the contact search stay exact).
PATCH_SOLVERS: dict[str, Callable] = {"bem": _exact_steady, "fastsim": _fast_steady("fastsim"),
                                      "fastrip": _fast_steady("fastrip")}


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
    point and angle in the side frame (solver.wheelrail.search.PatchFrame; a right wheel's is the mirror image's);
    transient: the patch rolled from an initial state (solver.wheelrail.transient.PatchTransient) when asked, else
    None; the forces above are then still the steady state's."""
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
    transient: object = None


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


def solve_wheel(rail: RailPlacement, wheel: WheelPlacement, side: str, y: float, Fz: float, omega_per_speed: float,
                materials: MaterialPair, mu: float, dx: float, dy: float, *, yaw: float = 0.0, roll: float = 0.0,
                params: WheelRailParams = WheelRailParams(), transient=None, progress=None) -> WheelRailResult:
    """Solve one wheel (module docstring). side: 'left' or 'right'; y: the wheelset's lateral position towards the
    field side of this rail (mm); yaw, roll: the wheelset's angles in the track frame (rad); Fz: the vertical load
    on this wheel (N); omega_per_speed: the wheelset's rotation over its forward speed (rad/mm,
    solver.wheelrail.patch.omega_per_speed); mu: friction coefficient; dx, dy: the patch grids' cells along x and s
    (mm). transient: a solver.wheelrail.transient.TransientSpec to roll each patch from its initial state after the
    steady solution (its forces then in PatchResult.transient and in the total), or None. progress: callable(message)
    or None."""
    if side not in SIDES:
        raise InputError(f"side = {side!r}: allowed values are {list(SIDES)}")
    for name, v in (("Fz", Fz), ("mu", mu), ("dx", dx), ("dy", dy), ("omega_per_speed", omega_per_speed)):
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"{name} = {v!r}: must be finite and > 0")
    sign = 1.0 if side == "left" else -1.0
    search = ContactSearch(rail, wheel, y, sign * yaw, sign * roll, step=params.search_step)
    estimate = hertz_estimate(search, wheel.radius, materials.E_star, Fz)
    coarse, rows = coarse_pass(search, materials, Fz, 2.0 * estimate, params)
    coarse, rows = coarse_pass(search, materials, Fz, 1.1 * coarse, params, rows)
    dz_grid, grids = 1.1 * coarse, 0
    for _ in range(6):
        frames = centred(search, search.patches(dz_grid, params.combine), rows)
        patches = [PatchState(search, f, patch_grid(search, f, dz_grid, dx, dy), materials, params) for f in frames]
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
    dz, outer, normal_solves = state
    wheel_now = search.wheel(dz)
    loaded = [p for p in patches if p.loaded]
    results = [_patch_result(search, wheel_now, p, omega_per_speed) for p in loaded]
    if transient is not None:
        from rollcontact.solver.wheelrail.transient import roll_patch
        for p, r in zip(loaded, results):
            if progress:
                progress(f"wheel-rail: rolling the patch at y = {p.frame.origin[1]:.2f} mm from the {transient.initial} "
                         "state")
            r.transient = roll_patch(p, wheel_now, mu, transient, params)
    force = np.zeros(3)
    for p, r in zip(loaded, results):
        fx, fs = r.transient.force if r.transient is not None else (r.Fx, r.Fs)
        force += fx * p.frame.e_x + fs * p.frame.e_s + r.Fn * p.frame.e_n
    if sign < 0:
        results = [_mirrored(r) for r in results]
    return WheelRailResult(side, results, (float(force[0]), float(sign * force[1]), float(force[2])), float(dz),
                           float(search.position(dz).z_centre), outer, normal_solves, grids)


def _balance(search, patches, Fz, dz, mu, omega_per_speed, params):
    """Alternate the vertical balance (normal problems) and the tangential problems (module docstring, step 4):
    (dz, outer iterations, normal solves), or None when the contact outgrew the patch grids."""
    ratio = np.zeros(len(patches))
    solver = PATCH_SOLVERS[params.fidelity]
    normal_solves = 0
    for outer in range(1, params.max_outer + 1):
        factors = [math.cos(p.frame.angle) + r * math.sin(p.frame.angle) for p, r in zip(patches, ratio)]
        if min(factors) <= 0:
            raise ConvergenceError("a patch's tangential force turns its vertical force downwards",
                                   solver="wheel-rail vertical", iterations=outer)
        dz, solves = vertical(search, patches, factors, Fz, dz, params)
        normal_solves += solves
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
            return dz, outer, normal_solves
    raise ConvergenceError("the normal / tangential alternation of the vertical balance did not converge",
                           solver="wheel-rail vertical", iterations=params.max_outer, residual=abs(total - Fz) / Fz,
                           tol=params.force_tol)


def _patch_result(search: ContactSearch, wheel, patch: PatchState, omega_per_speed) -> PatchResult:
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
        normal_iterations=r.normal_iterations, sweeps=r.sweeps, frame=r.frame,
        transient=None if r.transient is None else _mirrored_transient(r.transient))


def _mirrored_transient(t):
    from rollcontact.solver.wheelrail.transient import mirrored
    return mirrored(t)
