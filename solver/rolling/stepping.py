"""Quasi-static time stepping of oscillating rolling on a world-fixed grid (docs/theory.md §6).

One step n, as in docs/theory.md §6.2 (Kalker 1990; CONTACT's nested iteration):

    1. h_n = the undeformed profile shifted to the current sphere centre c_n (seed Eq. 7, any direction);
    2. normal problem with Fn (constant, or the step's Fn of an oscillating load), warm-started from p_{n-1}
                                                                            -> p_n, approach d_n;
       for uncoupled elastic materials it depends on h_n and Fn alone, and a centre and Fn met before (the sphere
       comes back to the same positions every period) take the solution found then (`run_path`);
    3. bound g = mu p_n; tangential shift problem with the force F_n and the previous traction
       tau_{n-1} as memory                                                  -> tau_n, dU_n; U_n = U_{n-1} + dU_n;
    4. coupled materials only: repeat 2-3 with the coupling terms until both settle (solver.rolling.coupled).
    With viscoelastic bodies (a `memory`, solver.visco.ViscoMemory) steps 2-3 see the history displacement of the
    bodies' element states (the normal problem as an extra displacement, the tangential one the change of its
    tangential part as extra slip), and the states then take the step's tractions.

The path is prescribed: a loading phase (Fn alone, then the tangential force in `ramp_steps` increments,
then any further force levels) followed by `periods` triangle-wave periods of the centre (loads that oscillate
within each period: solver.rolling.schedule; the frictional work of each step: solver.rolling.energy),
0 -> +W -> 0 -> -W -> 0, in steps of W/ceil(W/dW) along the rolling direction. Rolling is pure rolling of a
rigid sphere: only the profile moves, there is no rigid creepage (docs/theory.md §5.1 note v).

Units mm, N, MPa. U is the rigid shift of the sphere relative to the substrate far field, so that
U.F > 0 under a steady force (docs/theory.md §0).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
import math
import time
from typing import Iterator

import numpy as np

from rollcontact.bem.errors import ContactEdgeError, InputError
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.normal.normcg import NormalParams, NormalResult, solve_normal
from rollcontact.solver.rolling.energy import frictional_work
from rollcontact.solver.rolling.schedule import LoadOscillation, check_schedule
from rollcontact.solver.tangential.shift import TangentialParams, TangentialResult

#: largest memory (bytes: the gaps and pressures) of the normal solutions a path keeps for the centres it comes back to
NORMAL_MEMO_BYTES = 64 * 2 ** 20


@dataclass(frozen=True)
class LoadPath:
    """The prescribed sequence of steps: sphere centre (mm), tangential force (N), period index.

    period[n] = 0 during the loading phase and k during the k-th oscillation period; `reversal[n]` is
    True at the reversal points (+W, -W) and at the end of each period. `step_time` (s) is the duration of every
    step of a scene rolled at a speed (time-dependent friction and materials): step n ends at time n step_time.
    """

    centres: np.ndarray      # (n, 2) mm
    forces: np.ndarray       # (n, 2) N
    period: np.ndarray       # (n,) int
    reversal: np.ndarray     # (n,) bool
    dW: float = 0.0          # rolling step actually used (mm)
    normal_forces: np.ndarray | None = None   # (n,) N, Fn per step; None: the run's constant Fn
    step_time: float | None = None   # s, duration of every step (step n ends at n step_time); None: no time

    @property
    def n_steps(self) -> int:
        return len(self.period)

    def period_ends(self) -> np.ndarray:
        """Step indices at which U is compared period to period: end of loading, then each period end."""
        ends = [int(np.flatnonzero(self.period == 0)[-1])]
        for k in range(1, int(self.period.max()) + 1):
            ends.append(int(np.flatnonzero(self.period == k)[-1]))
        return np.array(ends)


def build_path(*, force, ramp_steps=1, levels=(), rolling_direction=(1.0, 0.0), amplitude=0.0,
               max_step=0.2, periods=0, normal_force=None, oscillation: LoadOscillation | None = None,
               step_time=None) -> LoadPath:
    """Loading phase then oscillation (docs/theory.md §6.1), with loads that may oscillate within each period
    (docs/theory.md §11.2-11.3).

    force: final tangential force vector (N) of the ramp; levels: further force vectors (N), each reached
    in `ramp_steps` equal increments (unloading, reversal); amplitude W and max_step dW in mm.
    normal_force: the mean Fn (N), needed with an active `oscillation` (solver.rolling.schedule.LoadOscillation):
    then the path carries Fn per step (`normal_forces`), the ramp goes to the schedule's start value, and without
    rolling (amplitude 0) a period has `oscillation.steps_per_period` steps at rest. Without an active
    oscillation the path is the constant-load path and `normal_forces` is None (the run's Fn).
    step_time: the duration (s) of every step, None for a time-independent run (LoadPath.step_time).
    """
    if int(ramp_steps) < 1:
        raise InputError(f"load.ramp_steps = {ramp_steps}: must be an integer >= 1")
    if amplitude < 0 or not math.isfinite(amplitude):
        raise InputError(f"motion.W = {amplitude} mm: must be finite and >= 0")
    if amplitude > 0 and not max_step > 0:
        raise InputError(f"motion.dW = {max_step} mm: must be > 0")
    if int(periods) < 0:
        raise InputError(f"motion.periods = {periods}: must be >= 0")
    if step_time is not None and not (math.isfinite(step_time) and step_time > 0):
        raise InputError(f"step_time = {step_time!r} s: must be finite and > 0 (the step over motion.speed)")
    oscillating = oscillation is not None and oscillation.active
    if oscillating:
        if len(levels):
            raise InputError("load.levels cannot be combined with oscillating loads (load.ft_amplitude, "
                             "load.fn_amplitude): give one or the other")
        if normal_force is None:
            raise InputError("build_path: an oscillating load needs the mean normal force (normal_force, N)")
        mean_force = np.asarray(force, dtype=float)
        normal_start, start = oscillation.loads(normal_force, mean_force, [0], 1)
        force = start[0]
    force = np.asarray(force, dtype=float)
    forces = [np.zeros(2)]
    if np.any(force != 0):
        forces += [force * (k + 1) / ramp_steps for k in range(ramp_steps)]
    for level in levels:
        start = forces[-1]
        level = np.asarray(level, dtype=float)
        forces += [start + (level - start) * (k + 1) / ramp_steps for k in range(ramp_steps)]
    n_load = len(forces)
    centres = [np.zeros((n_load, 2))]
    forces = [np.array(forces)]
    period = [np.zeros(n_load, dtype=int)]
    reversal = [np.zeros(n_load, dtype=bool)]
    normal = [np.full(n_load, normal_start[0])] if oscillating else None
    dW = 0.0
    if amplitude > 0 and periods > 0:
        nq = math.ceil(amplitude / max_step - 1e-9)
        dW = amplitude / nq
        e = np.asarray(rolling_direction, dtype=float)
        e = e / np.linalg.norm(e)
        # one period: 0 -> +W -> 0 -> -W -> 0, positions s_k = dW * tri(k), k = 1..4 nq (vectorised: a
        # long path costs memory in proportion to its steps, nothing more)
        k = np.arange(1, 4 * nq + 1)
        s = np.where(k <= nq, k, np.where(k <= 3 * nq, 2 * nq - k, k - 4 * nq)) * dW
        rev = (k == nq) | (k == 3 * nq) | (k == 4 * nq)
        periods = int(periods)
        centres.append(np.tile(s[:, None] * e[None, :], (periods, 1)))
        if oscillating:
            _append_loads(oscillation, normal_force, mean_force, forces, normal, k, periods)
            rev = rev | oscillation.reversals(k.size)
        else:
            forces.append(np.repeat(forces[0][-1:], periods * s.size, axis=0))
        period.append(np.repeat(np.arange(1, periods + 1), s.size))
        reversal.append(np.tile(rev, periods))
    elif oscillating and periods > 0:   # loads oscillating at rest: steps_per_period steps per period
        k = np.arange(1, oscillation.steps_per_period + 1)
        periods = int(periods)
        centres.append(np.zeros((periods * k.size, 2)))
        _append_loads(oscillation, normal_force, mean_force, forces, normal, k, periods)
        period.append(np.repeat(np.arange(1, periods + 1), k.size))
        reversal.append(np.tile(oscillation.reversals(k.size), periods))
    return LoadPath(np.concatenate(centres), np.concatenate(forces), np.concatenate(period),
                    np.concatenate(reversal), dW, None if normal is None else np.concatenate(normal),
                    None if step_time is None else float(step_time))


def _append_loads(oscillation, normal_force, mean_force, forces, normal, k, periods):
    """Append `periods` periods of the schedule at steps k = 1..N (mean loads normal_force, mean_force) to the
    lists of force and normal-force blocks."""
    fn, f = oscillation.loads(normal_force, mean_force, k, k.size)
    forces.append(np.tile(f, (periods, 1)))
    normal.append(np.tile(fn, periods))


@dataclass
class StepState:
    """What the next step needs: the last completed step's fields and the accumulated rigid shift.

    A run continued from a stored StepState reproduces the uninterrupted run to solver tolerance.
    """

    step: int                       # index of the last completed step (-1: nothing done yet)
    pressure: np.ndarray            # (ny, nx) MPa
    traction: np.ndarray            # (2, ny, nx) MPa
    rigid_shift: np.ndarray         # (2,) mm, U
    approach: float = 0.0           # mm
    mu: np.ndarray | None = None    # (ny, nx) local friction coefficient at the end of the step (a friction law's
                                    # memory state, solver.friction); None: Coulomb's constant mu

    @classmethod
    def initial(cls, shape) -> "StepState":
        return cls(-1, np.zeros(shape), np.zeros((2,) + tuple(shape)), np.zeros(2), 0.0)


@dataclass(frozen=True)
class StepParams:
    normal: NormalParams = field(default_factory=NormalParams)
    tangential: TangentialParams = field(default_factory=TangentialParams)
    coupling_tol: float = 1e-8
    max_outer: int = 30

    def loosened(self, accuracy):
        """The tangential parameters for a solve of a friction law's iteration (solver.friction.iteration) asking for
        the relative accuracy `accuracy` (None: as they are): their tolerance raised to it in the inexact early
        solves (at most 1e-3), lowered to it (at least a tenth of theirs) where the iteration's own residual has come
        down to its tolerance and the solve's noise would hold it there."""
        if accuracy is None or accuracy == self.tangential.tol:
            return self.tangential
        return TangentialParams(tol=min(max(accuracy, 0.1 * self.tangential.tol), 1e-3),
                                max_iter=self.tangential.max_iter)


@dataclass
class StepRecord:
    """The outcome of one step: the solver results and the state after it."""

    step: int
    centre: np.ndarray
    normal: NormalResult
    tangential: TangentialResult
    state: StepState
    outer_iterations: int
    wall_time: float
    dissipation: float = 0.0      # frictional work of the step (N mm), solver.rolling.energy.frictional_work
    viscous_dissipation: float = 0.0   # work the viscous dashpots of viscoelastic bodies dissipated (N mm)
    memory_states: dict | None = None  # the viscoelastic element states after the step (MPa), by name
    friction: object = None       # with a friction law: its solver.friction.FrictionState (local mu, slip velocity)


def run_path(op, profile, path: LoadPath, *, Fn, mu, params: StepParams = StepParams(),
             state: StepState | None = None, memory=None, friction=None) -> Iterator[StepRecord]:
    """Step along `path` from `state` (default: unloaded), yielding one StepRecord per step.

    op: bem.HalfSpaceOperator; profile: callable profile(X, Y, centre) -> h (mm), see solver.rolling.profiles;
    Fn (N) the normal force, constant unless the path carries one per step (`path.normal_forces`, checked here
    before any work: InputError if Fn <= 0 or |F| >= mu Fn at a step); mu friction coefficient. Each record
    carries the frictional work of its step (solver.rolling.energy.frictional_work). memory: the element states of
    viscoelastic bodies (solver.visco.ViscoMemory, of op's effective pair and path.step_time; restored to `state` by
    the caller), None for elastic bodies. friction: a friction law (solver.friction.LocalFriction; mu is then its
    static coefficient): each step is solved consistently with it (solver.friction.transient.friction_step, the
    slip velocity over path.step_time) and its record carries the FrictionState, its state the local coefficient;
    not with `memory` (InputError). Raises ContactEdgeError if
    the contact reaches the edge of the grid, GrossSlidingError if the force exceeds mu Fn, ConvergenceError if a
    solver fails.

    For uncoupled elastic materials (op.coupled False, no memory) the normal problem of a step is the frictionless
    contact of the gap h_n under Fn, whatever the tractions and the history: its solution is kept by the exact bytes of h_n and Fn (at most
    NORMAL_MEMO_BYTES), and a step with the same gap and force takes it instead of solving again (its
    NormalResult's `iterations` 0). An oscillating path comes back to the same centres every period (the paper's
    scenes: 13 distinct centres in 242 steps), so its normal problems are solved in the first period only. A restart
    (`state`) first solves the normal problems of the steps before it as the run it continues did, so that it
    continues that run to round-off.
    """
    if not (Fn > 0):
        raise InputError(f"load.Fn = {Fn} N: must be > 0")
    if not (mu > 0):
        raise InputError(f"load.mu = {mu}: must be > 0")
    if memory is not None and friction is not None:
        raise InputError("run_path: a friction law (friction) with viscoelastic bodies (memory) is not supported; "
                         "give one of them")
    if path.normal_forces is not None:
        check_schedule(path.normal_forces, path.forces, mu)
    X, Y = op.grid.mesh()
    grid = op.grid
    state = StepState.initial(grid.shape) if state is None else state
    known = None if (op.coupled or memory is not None) else _KnownNormals(op, params.normal)
    if known is not None and state.step >= 0:
        # a restart: the normal solutions of the steps before it, as the run that stored it had them
        pressure = np.zeros(grid.shape)
        for m in range(state.step + 1):
            guess = None if m == 0 else _moved(pressure, path.centres[m] - path.centres[m - 1], grid)
            pressure = known.solution(profile(X, Y, path.centres[m]), _force(path, Fn, m), pressure, guess).pressure
    local = None
    for n in range(state.step + 1, path.n_steps):
        t0 = time.perf_counter()
        centre = path.centres[n]
        h = profile(X, Y, centre)
        guess, cells = None, (0, 0)
        if state.step >= 0:
            # the pressure moves with the sphere: start the normal solve from the previous pressure
            # translated by the centre's move rounded to whole cells (exact when dW is a multiple of dx;
            # a bilinear sub-cell shift smears the contact edge and measured worse: 10.0 vs 9.0 it/step)
            move = centre - path.centres[state.step]
            cells = (round(move[1] / grid.dy), round(move[0] / grid.dx))
            guess = shifted_field(state.pressure, *cells)
        Fn_n = _force(path, Fn, n)
        normal = None if known is None else known.solution(h, Fn_n, state.pressure, guess)
        if friction is None:
            extra_n, extra_t = (None, None) if memory is None else memory.terms()
            normal, tangential, outer = solve_coupled_step(
                op, h, Fn_n, path.forces[n], state.pressure, state.traction, mu=mu,
                normal_params=params.normal, tangential_params=params.tangential,
                coupling_tol=params.coupling_tol, max_outer=params.max_outer, pressure_guess=guess,
                extra_slip=extra_t, extra_displacement=extra_n, normal=normal)
            local = None
        else:
            normal, tangential, outer, local = friction.step(
                lambda m, last, accuracy, previous=state, h=h, F=path.forces[n], Fn_n=Fn_n, guess=guess, known=normal:
                solve_coupled_step(op, h, Fn_n, F, previous.pressure, previous.traction, mu=m,
                                   normal_params=params.normal, tangential_params=params.loosened(accuracy),
                                   coupling_tol=params.coupling_tol, max_outer=params.max_outer, normal=known,
                                   **last.warm_start(guess)),
                op=op, dt=path.step_time, previous_mu=state.mu, moved=cells,
                previous_residual=None if local is None else local.first_residual)
        check_contact_inside(normal.contact, n, centre)
        viscous, states = 0.0, None
        if memory is not None:
            total = memory.advance(normal.pressure, tangential.traction, tangential.displacement)
            tangential = replace(tangential, displacement=total)
            viscous, states = memory.dissipation, memory.states()
        state = StepState(n, normal.pressure, tangential.traction,
                          state.rigid_shift + tangential.shift_increment, normal.approach,
                          None if local is None else local.mu)
        work = frictional_work(tangential.traction, tangential.slip, grid.cell_area)
        yield StepRecord(n, centre, normal, tangential, state, outer, time.perf_counter() - t0, work, viscous, states,
                         local)


def _force(path, Fn, n) -> float:
    """The normal force of step n (N): the path's, or the constant Fn."""
    return Fn if path.normal_forces is None else float(path.normal_forces[n])


def _moved(pressure, move, grid):
    """The pressure translated by the centre's move (mm) rounded to whole cells (None for no whole cell)."""
    return shifted_field(pressure, round(move[1] / grid.dy), round(move[0] / grid.dx))


class _KnownNormals:
    """Uncoupled materials: the normal solutions of the gaps and forces met along a path (`run_path`), by the exact
    bytes of the gap and the force, up to NORMAL_MEMO_BYTES."""

    def __init__(self, op, params):
        self.op, self.params, self.solved, self.held = op, params, {}, 0

    def solution(self, h, fn, previous, guess):
        """The NormalResult of gap h (mm) under fn (N): the one found before (its `iterations` 0), or solved from
        `guess` (or the previous pressure, as solve_coupled_step starts it) and kept."""
        key = (fn, np.ascontiguousarray(h, dtype=float).tobytes())
        normal = self.solved.get(key)
        if normal is not None:
            return normal
        initial = previous if np.any(previous) else None
        if guess is not None and np.any(guess):
            initial = guess
        normal = solve_normal(self.op, h, force=fn, initial=initial, params=self.params)
        if self.held + 2 * len(key[1]) <= NORMAL_MEMO_BYTES:
            self.solved[key] = replace(normal, iterations=0)
            self.held += 2 * len(key[1])
        return normal


def shifted_field(field, rows, cols):
    """field translated by (rows, cols) whole cells, zero-filled where it enters; None if no move."""
    if rows == 0 and cols == 0:
        return None
    ny, nx = field.shape
    out = np.zeros_like(field)
    if abs(rows) < ny and abs(cols) < nx:
        out[max(rows, 0):ny + min(rows, 0), max(cols, 0):nx + min(cols, 0)] = \
            field[max(-rows, 0):ny + min(-rows, 0), max(-cols, 0):nx + min(-cols, 0)]
    return out


def check_contact_inside(contact, step, centre):
    """ContactEdgeError when the contact (bool (ny, nx)) of `step` touches the grid's edge (centre: mm, for the
    message)."""
    edge = contact[0, :].any() or contact[-1, :].any() or contact[:, 0].any() or contact[:, -1].any()
    if edge:
        raise ContactEdgeError(
            f"step {step}: the contact (sphere centre at ({centre[0]:.4g}, {centre[1]:.4g}) mm) reached the "
            "edge of the grid; enlarge grid.margin or check the load (a larger Fn than the grid was "
            "sized for)")
