"""Transient rolling of a wheel's patches (docs/wheelrail.md, §4): each patch of the steady solution rolled on a
world-fixed grid of its tangent plane from an initial state over a distance (solver.creep.world, docs/theory.md §6,
§11.5), with the normal force the steady vertical balance gave it and the creepages of its reference point.

The world grid spans the patch's steady grid and, ahead of it along x, the distance rolled; the wheel's gap moves
with the contact: at step k the undeformed gap is the patch's h(x - k step, s), computed exactly for the wheel at
its solved position (solver.wheelrail.patch). Each patch rolls alone (the vertical balance is the steady one's).
Forces in Kalker's convention (on the wheel), fields in the solvers' substrate convention (the rail). Units: mm, N,
MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
import time

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.creep.world import INITIAL_STATES, roll_world, rolling_steps
from rollcontact.solver.normal import NormalParams
from rollcontact.solver.rolling.stepping import StepParams
from rollcontact.solver.tangential import TangentialParams
from rollcontact.solver.wheelrail.patch import patch_gap, rail_distance

#: the distance rolled when none is given, in contact lengths of the patch
DEFAULT_LENGTHS = 4.0


@dataclass(frozen=True)
class TransientSpec:
    """distance (mm, default DEFAULT_LENGTHS times the patch's contact length), step (mm, default the grid's dx), the
    initial state ('rest' or 'cattaneo', solver.creep.world)."""
    distance: float | None = None
    step: float | None = None
    initial: str = "rest"

    def __post_init__(self):
        if self.initial not in INITIAL_STATES:
            raise InputError(f"initial = {self.initial!r}: allowed values are {list(INITIAL_STATES)}")


@dataclass
class PatchTransient:
    """A patch rolled: its world grid (the patch's axes; x along the track), the step and the distance rolled (mm),
    the last step's fields (pressure, u_z; traction (2, ny, nx) on the rail, MPa; slip (2, ny, nx) of the rail
    relative to the wheel over the step, mm; u (2, ny, nx) the rail's displacement relative to the wheel, mm; region
    0 / 1 / 2), its force (Fx, Fs) and moment Mz about the contact centre on the wheel (N, N mm), and the history
    per step (step, centre, Fn, Fx, Fs, Mz, stick_area, iterations, cpu_time)."""
    grid: Grid
    step: float
    distance: float
    pressure: np.ndarray
    u_z: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    u: np.ndarray
    region: np.ndarray
    force: tuple
    moment: float
    history: dict


class _MovingGap:
    """profile(X, Y, centre) of solver.creep.world: the patch's gap about the contact centre, on the world grid."""

    def __init__(self, patch, wheel, grid: Grid):
        self.patch, self.wheel, self.grid = patch, wheel, grid
        self.rail_t = rail_distance(patch.rail, patch.frame, grid.y)

    def __call__(self, X, Y, centre):
        gap, _ = patch_gap(self.rail_t, self.wheel, self.patch.frame, self.grid.x - centre[0], self.grid.y)
        if np.any(np.isnan(gap)):
            raise InputError("the rolled patch's grid leaves a profile: the profiles do not cover it")
        return gap


def roll_patch(patch, wheel, mu: float, spec: TransientSpec, params) -> PatchTransient:
    """Roll one solved patch (solver.wheelrail.balance.PatchState, its steady normal and tangential state set) of the
    wheel at its solved position (solver.wheelrail.wheel.Wheel) from spec.initial over spec.distance; params: the
    solve's WheelRailParams (tolerances, threads, planner)."""
    t0 = time.process_time()
    g = patch.grid
    contact = patch.normal.pressure > 0
    X = g.mesh()[0]
    length = float(X[contact].max() - X[contact].min() + g.dx)
    step = spec.step if spec.step is not None else g.dx
    distance = spec.distance if spec.distance is not None else DEFAULT_LENGTHS * length
    n = rolling_steps(distance, step)
    world = Grid(g.nx + math.ceil(n * step / g.dx - 1e-9) + 1, g.ny, g.dx, g.dy, g.i0, g.j0)
    op = HalfSpaceOperator(world, patch.materials, threads=params.threads, coupling=False, planner=params.planner)
    steps = StepParams(normal=NormalParams(tol=params.tol, max_iter=params.max_iter),
                       tangential=TangentialParams(tol=params.tol, max_iter=params.max_iter),
                       coupling_tol=max(params.tol, 1e-10))
    xi, eta, phi = patch.tangential.creepages
    rows = []
    last = None
    for rec in roll_world(op, _MovingGap(patch, wheel, world), Fn=patch.normal.force, mu=mu, distance=distance,
                          step=step, xi=xi, eta=eta, phi=phi, initial=spec.initial, params=steps):
        rows.append((rec.step, rec.centre, rec.normal.force, rec.force[0], rec.force[1], rec.moment,
                     rec.stick_cells * world.cell_area, rec.normal.iterations + rec.tangential.iterations,
                     rec.cpu_time))
        last = rec
    names = ("step", "centre", "Fn", "Fx", "Fs", "Mz", "stick_area", "iterations", "cpu_time")
    history = {name: np.array([r[k] for r in rows]) for k, name in enumerate(names)}
    nr, tr = last.normal, last.tangential
    history["total_cpu_time"] = np.array([time.process_time() - t0])
    return PatchTransient(world, step, float(last.centre), nr.pressure, nr.displacement, tr.traction, tr.slip,
                          tr.displacement, tr.region, (float(last.force[0]), float(last.force[1])),
                          float(last.moment), history)


def mirrored(t: PatchTransient) -> PatchTransient:
    """The mirror image y -> -y (a right wheel's patch): the s axis and the s components change sign."""
    g = t.grid
    grid = Grid(g.nx, g.ny, g.dx, g.dy, g.i0, -(g.j0 + g.ny - 1))
    flip = lambda a: np.ascontiguousarray(a[..., ::-1, :])        # noqa: E731
    vec = lambda a: np.stack([flip(a[0]), -flip(a[1])])           # noqa: E731
    history = dict(t.history)
    history["Fs"], history["Mz"] = -t.history["Fs"], -t.history["Mz"]
    return PatchTransient(grid, t.step, t.distance, flip(t.pressure), flip(t.u_z), vec(t.traction), vec(t.slip),
                          vec(t.u), flip(t.region), (t.force[0], -t.force[1]), -t.moment, history)
