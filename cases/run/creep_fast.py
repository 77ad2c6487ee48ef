"""A [rolling] scene on the fast models ([solver] fidelity = "fastsim" or "fastrip"; solver.fastsim;
docs/creep_fidelity.md): the normal problem on the scene's grid by the boundary elements (NormCG, no coupling: the
simplified theory has none), then the tangential state by the fast model on the same grid.

The traction bound ([solver] traction_bound): 'scene' (default) mu times the pressure just solved; 'ellipsoid' or
'parabolic' mu times Hertz's semi-ellipsoid or Kalker's parabola over the Hertz ellipse of the rolling semi-axes
carrying Fn, with the strips' exact edges. The flexibilities come from Kalker's coefficients of the contact ellipse:
the rolling semi-axes of a sphere or an ellipsoid rolling along an axis, else the equivalent ellipse of the contact
found (solver.fastsim.strips.equivalent_ellipse). Steady: one pass over the strips. Transient (FASTSIM only): the
world-fixed grid of cases.run.creep_transient, the normal problem solved at every step (warm-started from the
previous pressure moved by whole cells) and FASTSIM's transient step (solver.fastsim.FastsimRolling), yielded as
the records the transient run stores. Kalker's convention for the forces (on the sphere); the records carry the
substrate's traction and slip as every run file does. Units: mm, N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
import time

import numpy as np

from rollcontact.bem.errors import ContactEdgeError
from rollcontact.bem.grid import Grid
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.cases.run.rolling_frame import creep_grid, rolling_frame_gap, rolling_semi_axes
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep.world import CreepStep, rolling_steps
from rollcontact.solver.fastsim import (FastsimRolling, ellipse_edges, ellipse_pressure, equivalent_ellipse,
                                        kalker_flexibilities, solve_fastrip, solve_fastsim)
from rollcontact.solver.normal import NormalParams, solve_normal
from rollcontact.solver.rolling.stepping import check_contact_inside, shifted_field

SOLVERS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}


@dataclass
class FastSteady:
    """The steady state of a scene on a fast model: the normal problem's result, the model's state
    (solver.fastsim.FastResult), the ellipse (a, b) of its flexibilities (mm), the bound's name and the CPU time of
    the fast model alone (s)."""
    normal: object
    state: object
    ellipse: tuple
    bound: str
    model_cpu_time: float

    @property
    def creepages(self):
        return self.state.creepages


@dataclass
class FastTangential:
    """A fast model's step in the shape the transient run stores (cases.run.creep_transient): traction (2, ny, nx)
    MPa and slip over the step (mm) of the substrate relative to the sphere, the displacement L tau (mm), region,
    force (N, on the substrate), the flexibility L (mm/MPa), one pass (iterations), no residual."""
    traction: np.ndarray
    slip: np.ndarray
    displacement: np.ndarray
    region: np.ndarray
    force: np.ndarray
    flexibility: float
    iterations: int = 1
    residual: float = 0.0


def fast_operator(scene: Scene, grid: Grid) -> HalfSpaceOperator:
    """The normal problem's operator of a fast model's run: the scene's threads, no coupling."""
    return HalfSpaceOperator(grid, scene.material_pair, threads=scene.solver.threads, coupling=False)


def contact_ellipse(scene: Scene, grid: Grid, pressure) -> tuple[float, float]:
    """Semi-axes (mm; a along the rolling direction) of the ellipse whose Kalker coefficients give the flexibilities
    (module docstring)."""
    axes = rolling_semi_axes(scene)
    if axes is not None and scene.shape in ("sphere", "ellipsoid"):
        return axes
    return equivalent_ellipse(grid, pressure)


def bound_pressure(scene: Scene, grid: Grid, pressure, centre: float = 0.0):
    """The pressure whose mu-multiple bounds the traction, and the strips' edges (None: extrapolated from it), for the
    scene's traction_bound with the contact centre at x = centre (mm)."""
    bound = scene.traction_bound
    if bound == "scene":
        return pressure, None
    a, b = rolling_semi_axes(scene)
    p = ellipse_pressure(grid, a, b, scene.load.Fn, bound, centre=centre)
    return p, ellipse_edges(grid, a, b, p > 0, centre=centre)


def solve_scene_normal(scene: Scene, op: HalfSpaceOperator, centre: float = 0.0, initial=None):
    """The normal problem of the scene's profile about the contact centre x = centre (mm) on op's grid (NormCG)."""
    grid = op.grid
    X, Y = grid.mesh()
    h = rolling_frame_gap(scene)(X - centre, Y)
    params = NormalParams(tol=scene.solver.tol, max_iter=scene.solver.max_iter)
    return solve_normal(op, h, force=scene.load.Fn, initial=initial, params=params)


def fast_steady(scene: Scene, model: str, grid: Grid | None = None, op=None) -> FastSteady:
    """The steady state of the scene on `model` on its contact-fixed grid (module docstring)."""
    grid = creep_grid(scene) if grid is None else grid
    op = fast_operator(scene, grid) if op is None else op
    normal = solve_scene_normal(scene, op)
    pressure, edges = bound_pressure(scene, grid, normal.pressure)
    a, b = contact_ellipse(scene, grid, normal.pressure)
    pair = scene.material_pair
    flex = kalker_flexibilities(a, b, pair.G, pair.nu)
    c0 = time.process_time()
    state = SOLVERS[model](grid, pressure, scene.load.mu, *scene.creepages, flexibilities=flex, edges=edges)
    return FastSteady(normal, state, (a, b), scene.traction_bound, time.process_time() - c0)


def roll_fast(scene: Scene, op: HalfSpaceOperator, *, distance: float, step: float, initial: str = "rest"):
    """Transient FASTSIM on op's world-fixed grid from the initial state ('rest' or 'cattaneo'), yielding the
    initial state (step 0) and each step as solver.creep.world.CreepStep records (module docstring)."""
    grid = op.grid
    pair = scene.material_pair
    xi, eta, phi = scene.creepages
    n = rolling_steps(distance, step)
    t0, c0 = time.perf_counter(), time.process_time()
    normal = solve_scene_normal(scene, op)
    a, b = contact_ellipse(scene, grid, normal.pressure)
    flex = kalker_flexibilities(a, b, pair.G, pair.nu)
    rolling = FastsimRolling(grid, scene.load.mu, xi, eta, phi, flexibilities=flex)
    pressure, _ = bound_pressure(scene, grid, normal.pressure)
    state = rolling.at_rest(pressure, 0.0, step if initial == "cattaneo" else None)
    shift = np.array([xi, eta]) * step if initial == "cattaneo" else np.zeros(2)
    creep = (xi, eta, phi) if initial == "cattaneo" else (0.0, 0.0, phi)
    check_contact_inside(normal.contact, 0, (0.0, 0.0))
    cols = np.nonzero(normal.contact.any(axis=0))[0]
    if cols.size and cols[-1] + math.ceil(n * step / grid.dx - 1e-9) >= grid.nx - 1:
        raise ContactEdgeError(f"the grid is too short for the contact rolled {n * step:.6g} mm ([rolling] distance, "
                               f"{n} steps of {step:.6g} mm) with a free cell ahead")
    yield _record(0, 0.0, normal, state, grid, creep, shift, t0, c0)
    cells = round(step / grid.dx)
    for k in range(1, n + 1):
        t0, c0 = time.perf_counter(), time.process_time()
        centre = k * step
        normal = solve_scene_normal(scene, op, centre, shifted_field(normal.pressure, 0, cells))
        check_contact_inside(normal.contact, k, (centre, 0.0))
        pressure, _ = bound_pressure(scene, grid, normal.pressure, centre)
        state = rolling.step(pressure, centre, step)
        shift = shift + np.array([xi, eta]) * step
        yield _record(k, centre, normal, state, grid, (xi, eta, phi), shift, t0, c0)


def _record(k, centre, normal, state, grid, creepages, shift, t0, c0) -> CreepStep:
    """A CreepStep of the fast model: the substrate's traction, slip and displacement (L tau), the forces on the
    sphere (Kalker's), the moment about the contact centre."""
    tau_sub = -state.traction
    L = state.flexibility if np.isscalar(state.flexibility) else None
    disp = tau_sub * (L if L is not None else np.array(state.flexibility[:2])[:, None, None])
    force_sub = tau_sub.sum(axis=(1, 2)) * grid.cell_area
    tang = FastTangential(tau_sub, -state.slip, disp, state.region, force_sub, state.flexibility)
    return CreepStep(k, centre, normal, tang, np.asarray(state.force, dtype=float), state.moment, tuple(creepages),
                     np.asarray(shift, dtype=float), 1, time.perf_counter() - t0, time.process_time() - c0)
