"""Transient rolling with creepage and spin on a grid that moves with the contact (theory.md §6, §11.5, §5.1).

The same problem as `world` (its docstring: Kalker's shift problem per step, the rigid creep slip, the initial
states, Kalker's convention for the results), solved on a grid fixed to the contact instead of the substrate. The
grid's x axis runs along the rolling direction, x = 0 at the contact centre; the profile does not move on it. Over
one step the contact rolls `step` = k dx (k whole elements) along +x of the world, so the material of both surfaces
moves by k elements towards -x of the grid: the element that sits at grid column i after the step sat at column
i + k before it. The previous step's tractions, the memory tau' of the shift problem, are therefore the previous
solution moved by k columns towards -x (`carried_field`), and the slip over the step is

    s = A (tau - tau') - W + rigid creep slip,   u' = A tau' on the new grid,

the displacement difference of the previous step carried as its shift. This is the world-fixed step restricted to
the elements near the contact: outside the contact the traction is zero on both grids, the convolution A tau' sees
the same tractions at the same relative positions (the old contact, moved by a step, lies inside the grid, which is
checked), so the two formulations give the same tractions up to the solvers' tolerance (tests/solver/
test_creep_moving.py). Only a step of whole elements keeps the cells of consecutive steps on one lattice; any
other step would need interpolation of tau' and is refused (the world-fixed grid takes any step).

What the moving grid leaves out, and so where `world` is the model: a state of the substrate that must stay where
the contact left it (the traction-free material behind the contact is dropped after a step, ahead of it enters
virgin), e.g. a history that outlives the passage of the contact, fields wanted in world coordinates over the rolled
track, or a step that is not a whole number of elements.

The grid need only cover the contact and the previous step's contact: its cost per step is that of the contact
area, not of the distance rolled (the world-fixed grid grows with it). Units: mm, N, MPa.
"""
from __future__ import annotations

import math
import time
from typing import Iterator

import numpy as np

from rollcontact.bem.errors import ContactEdgeError, GrossSlidingError, InputError
from rollcontact.solver.creep.steady import SPIN_OFFSET
from rollcontact.solver.creep.world import INITIAL_STATES, CreepStep, rolling_steps
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.rolling.stepping import StepParams, check_contact_inside

#: Largest |step / dx - k| accepted as a step of k whole elements (relative round-off of the scene's numbers).
WHOLE_CELLS_TOL = 1e-9


def whole_cells(step: float, dx: float) -> int:
    """The number k >= 1 of elements of size dx (mm) in a rolling step (mm); InputError unless step = k dx."""
    k = round(step / dx)
    if k < 1 or abs(step / dx - k) > WHOLE_CELLS_TOL * max(1.0, step / dx):
        raise InputError(f"[rolling] step = {step!r} mm is {step / dx:.6g} elements of dx = {dx!r} mm: the grid "
                         "that moves with the contact ([rolling] grid = 'contact') needs a whole number of elements "
                         "per step; set step = k dx or grid = 'world'")
    return k


def carried_field(field: np.ndarray, cells: int, what: str) -> np.ndarray:
    """The field (..., ny, nx) of the previous step on the grid after a step of `cells` elements along +x: moved by
    `cells` columns towards -x, zero in the columns entering at the leading edge. ContactEdgeError if a nonzero value
    would leave through the trailing edge (the grid must hold the previous step's contact)."""
    if np.any(field[..., :cells]):
        raise ContactEdgeError(f"the previous step's {what} reaches the last {cells} column(s) at the trailing edge "
                               "of the grid that moves with the contact: the grid does not hold the contact of the "
                               "previous step; enlarge grid.margin (or use [rolling] grid = 'world')")
    out = np.zeros_like(field)
    out[..., :-cells] = field[..., cells:]
    return out


def roll_moving(op, profile, *, Fn, mu, distance, step, xi=0.0, eta=0.0, phi=0.0, forces=None, initial="rest",
                params: StepParams = StepParams()) -> Iterator[CreepStep]:
    """Roll body 1 along +x from the initial state on the contact-fixed grid of `op` (bem.HalfSpaceOperator, x along
    the rolling direction, 0 at the contact centre), in steps of `step` = k grid.dx (mm) over at least `distance` mm
    (`rolling_steps`), yielding the initial state (step 0) and each step. Arguments and results as `world.roll_world`
    (CreepStep.centre is the contact centre's distance rolled, mm; the fields are on the moving grid); profile(X, Y,
    centre) -> h (mm) is evaluated once, about centre (0, 0). Raises InputError for bad arguments or a step that is
    not a whole number of elements, ContactEdgeError when the contact reaches the grid's edge or the previous step's
    contact leaves it, GrossSlidingError for |F| >= mu Fn, ConvergenceError if a solver fails."""
    n = rolling_steps(distance, step)
    if initial not in INITIAL_STATES:
        raise InputError(f"[rolling] initial = {initial!r}: allowed values are {list(INITIAL_STATES)}")
    if not (Fn > 0 and mu > 0):
        raise InputError(f"Fn = {Fn!r} N, mu = {mu!r}: must be > 0")
    for name, v in (("xi", xi), ("eta", eta), ("phi", phi)):
        if not math.isfinite(v):
            raise InputError(f"[rolling] {name} = {v!r}: must be finite")
    grid = op.grid
    cells = whole_cells(step, grid.dx)
    if cells >= grid.nx:
        raise InputError(f"[rolling] step = {step!r} mm spans {cells} elements, the grid only {grid.nx}")
    if forces is not None:
        forces = np.asarray(forces, dtype=float)
        if forces.shape != (2,) or not np.all(np.isfinite(forces)) or xi != 0.0 or eta != 0.0:
            raise InputError("roll_moving: forces = (Fx, Fy) N, finite, in place of the creepages xi, eta")
        if math.hypot(*forces) >= mu * Fn:
            raise GrossSlidingError(f"prescribed |F| = {math.hypot(*forces):.6g} N >= mu Fn = {mu * Fn:.6g} N: full "
                                    "sliding, no rolling state carries it")
    X, Y = grid.mesh()
    dA = grid.cell_area
    h = profile(X, Y, (0.0, 0.0))
    # the substrate's rigid slip relative to body 1 over a step, per unit creepage pair (spin about the centre)
    spin = np.stack([phi * Y, -phi * (X + SPIN_OFFSET * step)])

    def creep_slip(creep):
        """The substrate's rigid slip relative to body 1 over one step (mm) for the creepages (xi, eta)."""
        out = spin * step
        out[0] -= step * creep[0]
        out[1] -= step * creep[1]
        return out

    def solve(k, previous, load, carried) -> CreepStep:
        """Step k from the previous step's record (None: unloaded) under load = 'rest' (zero tangential force) or
        'creep' (the creep slip of a step, or the prescribed forces); `carried`: the previous fields have moved by
        a step on the grid. Its rigid_shift is that of the step alone (the caller accumulates)."""
        t0, c0 = time.perf_counter(), time.process_time()
        if previous is None:
            p_prev, tau_prev = None, np.zeros((2,) + grid.shape)
        elif carried:
            p_prev = carried_field(previous.normal.pressure, cells, "pressure")
            tau_prev = carried_field(previous.tangential.traction, cells, "traction")
        else:
            p_prev, tau_prev = previous.normal.pressure, previous.tangential.traction
        F, kw = np.zeros(2), {}
        if load == "creep" and forces is None:
            F, kw = None, dict(shift=(0.0, 0.0), extra_slip=creep_slip((xi, eta)))
        elif load == "creep":
            F = -forces                                                       # on the substrate
            kw = dict(extra_slip=creep_slip((0.0, 0.0))) if phi != 0.0 else {}
        guess = None if previous is None else previous.normal.pressure       # the contact stays on the grid
        normal, tang, outer = solve_coupled_step(
            op, h, Fn, F, p_prev, tau_prev, mu=mu, normal_params=params.normal, tangential_params=params.tangential,
            coupling_tol=params.coupling_tol, max_outer=params.max_outer, pressure_guess=guess, **kw)
        check_contact_inside(normal.contact, k, (k * step, 0.0))
        tau = tang.traction
        moment = -float((X * tau[1] - Y * tau[0]).sum() * dA)
        if load == "rest":
            creep = (0.0, 0.0)
        elif forces is None:
            creep = (xi, eta)
        else:
            creep = (float(tang.shift_increment[0]) / step, float(tang.shift_increment[1]) / step)
        return CreepStep(k, k * step, normal, tang, -np.asarray(tang.force, dtype=float), moment, (*creep, phi),
                         np.array(creep) * step, outer, time.perf_counter() - t0, time.process_time() - c0)

    rec = solve(0, None, "rest", False)
    if initial == "cattaneo":
        rest, rec = rec, solve(0, rec, "creep", False)
        rec.outer_iterations += rest.outer_iterations
        rec.wall_time += rest.wall_time
        rec.cpu_time += rest.cpu_time
    shift = rec.rigid_shift.copy()
    yield rec
    for k in range(1, n + 1):
        rec = solve(k, rec, "creep", True)
        shift += rec.rigid_shift
        rec.rigid_shift = shift.copy()
        yield rec
