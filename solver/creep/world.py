"""Transient rolling with creepage and spin on a world-fixed grid, from an initial state (docs/theory.md §6, §11.5,
§5.1).

The grid is fixed to body 2 (the substrate), its x axis along the rolling direction. Body 1's profile moves by
`step` (mm) along x per step (the paper's Eq. 7, docs/theory.md §6.1: h_k(x, y) = h(x - c_k, y), c_k = k step). In
rolling,
the surface material of both bodies that is in contact stays at the same world position while the contact passes
over it (up to the creep slip itself, first order in the creepages), so the displacement difference u = u1 - u2 at a
world-fixed element belongs to the same pair of material points at consecutive steps, and each step is Kalker's
shift problem (docs/theory.md §5.1) with the rigid slip of body 1 relative to body 2 over the step

    step * (xi - phi (y - c_y), eta + phi (x - c_x + SPIN_OFFSET step))        (mm; c = (c_k, 0) the contact centre)

Kalker's convention (`solver.creep.kalker`): xi, eta (dimensionless) and phi (1/mm) are the rigid slip of body 1
relative to body 2 per unit rolling distance, the spin about the moving contact centre (evaluated at x + step/6 as
in `steady`, CONTACT's 1/6 dq). The tangential solver's slip is the substrate's relative to body 1, so this rigid
slip enters with the opposite sign: as extra slip with the shift fixed at zero (prescribed creepages), or, with
prescribed forces (Fx, Fy) on body 1, as the unknown rigid-shift increment dU of the force-controlled problem
(docs/theory.md §5.2: (xi, eta) = dU / step, the spin part still as extra slip). One step is
`solver.rolling.coupled.solve_coupled_step`: normal then tangential problem, nested until both settle for coupled
materials (the pressure's tangential displacement A^tz (p - p') enters the slip), the pressure warm-started from
the previous one moved by whole cells (`stepping.shifted_field`), the contact checked to stay inside the grid.

Initial state (step 0, centre 0, `INITIAL_STATES`):
    rest      the normal load at rest with zero tangential force (zero traction for uncoupled materials; coupled
              ones keep the traction of normal loading, whose sum is zero); rolling then switches the creepages on.
    cattaneo  after `rest`, still at rest, the tangential load: the rigid slip of one step (a Cattaneo-Mindlin
              shift problem, with spin a twist), or the prescribed forces (Cattaneo's state under (Fx, Fy)).
Both roll into the same steady state (the memory of the initial state leaves the contact with its material).

With step = dx and uncoupled materials every step is the steady problem's one-cell shift (`steady`'s upwind
difference, the same spin offset), so after a few contact lengths the forces converge to `solve_steady`'s;
coupled materials converge to the coupled steady state (cases.run.creep_run alternates it with the normal problem).

Viscoelastic bodies (a `memory`, solver.visco.ViscoMemory): each solve sees the history displacement of the bodies'
element states and advances them (step 0 ends at t = 0; with `cattaneo` the tangential load at rest takes one more
step time, so step k ends at (k + 1) dt).

Results in Kalker's convention (forces and moment on body 1; the moment about the contact centre), the solver
results in the substrate convention of docs/theory.md §0. Units: mm, N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
import math
import time
from typing import Iterator

import numpy as np

from rollcontact.bem.errors import ContactEdgeError, GrossSlidingError, InputError
from rollcontact.solver.creep.steady import SPIN_OFFSET
from rollcontact.solver.normal.normcg import NormalResult
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.rolling.stepping import StepParams, check_contact_inside, shifted_field
from rollcontact.solver.tangential.shift import TangentialResult

#: The initial states of `roll_world` (module docstring).
INITIAL_STATES = ("rest", "cattaneo")


@dataclass
class CreepStep:
    """One step of `roll_world` (step 0: the initial state, at rest).

    centre: the contact centre c_k (mm along the grid's x, the rolling direction); normal, tangential: the solvers'
    results (substrate convention: `tangential.traction` on the substrate, `tangential.slip` the substrate's slip
    relative to body 1 over the step, mm); force (Fx, Fy) N and moment Mz (N mm, about the contact centre) on body 1;
    creepages (xi, eta, phi) of the step: the prescribed ones, or with prescribed forces (xi, eta) = dU / step (at
    step 0: zero for `rest`, the shift at rest over one step length for `cattaneo`); rigid_shift: the accumulated
    rigid slip of body 1 relative to body 2 (mm, sum of step (xi, eta)); outer iterations of the coupled loop, the
    wall and process CPU time of the step (s); the work the viscous dashpots of viscoelastic bodies dissipated in it.
    """
    step: int
    centre: float
    normal: NormalResult
    tangential: TangentialResult
    force: np.ndarray
    moment: float
    creepages: tuple
    rigid_shift: np.ndarray
    outer_iterations: int
    wall_time: float
    cpu_time: float
    viscous_dissipation: float = 0.0      # N mm dissipated by viscoelastic bodies' dashpots in the step
    friction: object = None     # with a friction law: its solver.friction.FrictionState (local mu, slip velocity, ...)

    @property
    def stick_cells(self) -> int:
        return int((self.tangential.region == 1).sum())


def rolling_steps(distance: float, step: float) -> int:
    """Steps of length `step` (mm) that roll at least `distance` (mm): ceil(distance / step)."""
    for name, value in (("distance", distance), ("step", step)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise InputError(f"[rolling] {name} = {value!r} mm: must be finite and > 0")
    return max(1, math.ceil(distance / step - 1e-9))


def roll_world(op, profile, *, Fn, mu, distance, step, xi=0.0, eta=0.0, phi=0.0, forces=None, initial="rest",
               params: StepParams = StepParams(), memory=None, friction=None) -> Iterator[CreepStep]:
    """Roll body 1 along +x of the world-fixed grid of `op` (bem.HalfSpaceOperator) from the initial state, in
    steps of `step` mm over at least `distance` mm (`rolling_steps`), yielding the initial state (step 0) and each
    step. profile(X, Y, centre) -> h (mm), the undeformed gap about the contact centre (solver.rolling.profiles);
    Fn (N) and mu as in `run_path`; creepages xi, eta and spin phi (1/mm), or forces = (Fx, Fy) N on body 1 in place
    of xi, eta; memory: the element states of viscoelastic bodies (solver.visco.ViscoMemory on op's effective pair, its
    step time step / V), None for elastic ones; friction: a friction law (solver.friction.LocalFriction, its speed
    the rolling speed; mu is then its static coefficient): every step is solved consistently with it over the step's
    time step / speed, and carries its FrictionState (local mu, slip velocity, temperatures); not both (elastic bodies
    only). Raises InputError for bad arguments, ContactEdgeError for a grid too short for the distance (after
    the initial state, before rolling) or when the contact reaches the grid's edge, GrossSlidingError for
    |F| >= mu Fn, ConvergenceError if a solver fails."""
    n = rolling_steps(distance, step)
    if initial not in INITIAL_STATES:
        raise InputError(f"[rolling] initial = {initial!r}: allowed values are {list(INITIAL_STATES)}")
    if not (Fn > 0 and mu > 0):
        raise InputError(f"Fn = {Fn!r} N, mu = {mu!r}: must be > 0")
    if memory is not None and friction is not None:
        raise InputError("roll_world: a friction law (friction) with viscoelastic bodies (memory) is not supported; "
                         "give one of them")
    for name, v in (("xi", xi), ("eta", eta), ("phi", phi)):
        if not math.isfinite(v):
            raise InputError(f"[rolling] {name} = {v!r}: must be finite")
    grid = op.grid
    if forces is not None:
        forces = np.asarray(forces, dtype=float)
        if forces.shape != (2,) or not np.all(np.isfinite(forces)) or xi != 0.0 or eta != 0.0:
            raise InputError("roll_world: forces = (Fx, Fy) N, finite, in place of the creepages xi, eta")
        if math.hypot(*forces) >= mu * Fn:
            raise GrossSlidingError(f"prescribed |F| = {math.hypot(*forces):.6g} N >= mu Fn = {mu * Fn:.6g} N: full "
                                    "sliding, no rolling state carries it")
    X, Y = grid.mesh()
    dA = grid.cell_area

    def creep_slip(centre, creep):
        """The substrate's rigid slip relative to body 1 over a step ending at `centre` (mm), for (xi, eta)."""
        return -step * np.stack([creep[0] - phi * Y, creep[1] + phi * (X - centre + SPIN_OFFSET * step)])

    def solve(k, centre, previous, load, guess=None) -> CreepStep:
        """Step k with the gap about `centre` from the previous step's record (None: unloaded) under load = 'rest'
        (zero tangential force) or 'creep' (the creep slip of a step, or the prescribed forces); its rigid_shift is
        that of the step alone (the caller accumulates)."""
        t0, c0 = time.perf_counter(), time.process_time()
        h = profile(X, Y, (centre, 0.0))
        p_prev, tau_prev = ((None, np.zeros((2,) + grid.shape)) if previous is None
                            else (previous.normal.pressure, previous.tangential.traction))
        F, kw = np.zeros(2), {}
        if load == "creep" and forces is None:
            F, kw = None, dict(shift=(0.0, 0.0), extra_slip=creep_slip(centre, (xi, eta)))
        elif load == "creep":
            F = -forces                                                       # on the substrate
            kw = dict(extra_slip=creep_slip(centre, (0.0, 0.0))) if phi != 0.0 else {}
        if memory is not None:
            extra_n, extra_t = memory.terms()
            kw["extra_slip"] = extra_t if "extra_slip" not in kw else kw["extra_slip"] + extra_t
            kw["extra_displacement"] = extra_n
        if friction is None:
            normal, tang, outer = solve_coupled_step(
                op, h, Fn, F, p_prev, tau_prev, mu=mu, normal_params=params.normal,
                tangential_params=params.tangential, coupling_tol=params.coupling_tol, max_outer=params.max_outer,
                pressure_guess=guess, **kw)
            local = None
        else:
            normal, tang, outer, local = friction.step(
                lambda m, last, accuracy: solve_coupled_step(
                    op, h, Fn, F, p_prev, tau_prev, mu=m, normal_params=params.normal,
                    tangential_params=params.loosened(accuracy), coupling_tol=params.coupling_tol,
                    max_outer=params.max_outer, **last.warm_start(guess), **kw),
                op=op, dt=step / friction.speed if friction.speed else None,
                previous_mu=None if previous is None else previous.friction.mu,
                moved=(0, 0) if previous is None else (0, round((centre - previous.centre) / grid.dx)),
                previous_residual=None if previous is None else previous.friction.first_residual)
        check_contact_inside(normal.contact, k, (centre, 0.0))
        viscous = 0.0
        if memory is not None:
            total = memory.advance(normal.pressure, tang.traction, tang.displacement)
            tang, viscous = replace(tang, displacement=total), memory.dissipation
        tau = tang.traction
        moment = -float(((X - centre) * tau[1] - Y * tau[0]).sum() * dA)
        if load == "rest":
            creep = (0.0, 0.0)
        elif forces is None:
            creep = (xi, eta)
        else:
            creep = (float(tang.shift_increment[0]) / step, float(tang.shift_increment[1]) / step)
        return CreepStep(k, centre, normal, tang, -np.asarray(tang.force, dtype=float), moment, (*creep, phi),
                         np.array(creep) * step, outer, time.perf_counter() - t0, time.process_time() - c0, viscous,
                         local)

    rec = solve(0, 0.0, None, "rest")
    if initial == "cattaneo":
        rest, rec = rec, solve(0, 0.0, rec, "creep")
        rec.outer_iterations += rest.outer_iterations
        rec.wall_time += rest.wall_time
        rec.cpu_time += rest.cpu_time
        rec.viscous_dissipation += rest.viscous_dissipation
    cols = np.nonzero(rec.normal.contact.any(axis=0))[0]
    if cols.size and cols[-1] + math.ceil(n * step / grid.dx - 1e-9) >= grid.nx - 1:
        end, front = grid.x[-1] + grid.dx / 2, grid.x[cols[-1]] + grid.dx / 2
        raise ContactEdgeError(f"the grid (x to {end:.6g} mm along the rolling direction) is too short for the "
                               f"contact (x up to {front:.6g} mm at rest) rolled {n * step:.6g} mm ([rolling] distance,"
                               f" {n} steps of {step:.6g} mm) with a free cell ahead")
    shift = rec.rigid_shift.copy()
    yield rec
    cells = round(step / grid.dx)
    for k in range(1, n + 1):
        centre = k * step
        rec = solve(k, centre, rec, "creep", shifted_field(rec.normal.pressure, 0, cells))
        shift += rec.rigid_shift
        rec.rigid_shift = shift.copy()
        yield rec
