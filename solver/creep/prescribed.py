"""Steady rolling with prescribed creep forces: the creepages xi, eta solved for (docs/theory.md §7.3, §11.5).

Kalker's convention (`kalker`): Fx, Fy are the forces on body 1 (N), opposing the creepages; the spin phi (1/mm) is
given. The map (xi, eta) -> (Fx, Fy) of `solve_steady` is monotone (the forces oppose the creepages) and saturates
at |F| = mu Fn, so a force with |F| >= mu Fn has no finite creepage (GrossSlidingError). Solved by Broyden's
method started from Kalker's linear theory (Jacobian -G c^2 diag(C11, C22) with the contact's equivalent c from its
area and the table's coefficients), each steady solve warm-started from the previous traction; a step that does
not reduce the force error is halved (up to 30 times). Stops when |F - F_target| <= tol mu Fn.
"""
from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, GrossSlidingError, InputError
from rollcontact.solver.creep.kalker import kalker_coefficients
from rollcontact.solver.creep.steady import SteadyParams, SteadyRolling, SteadyResult, solve_steady


@dataclass
class PrescribedForceResult:
    """The creepages (xi, eta) found, the steady state there and the steady solves used (iterations)."""
    xi: float
    eta: float
    steady: SteadyResult
    solves: int


def solve_for_forces(problem: SteadyRolling, pressure, mu, Fx, Fy, phi=0.0, *, tol=1e-6, max_solves=60,
                     params: SteadyParams = SteadyParams()) -> PrescribedForceResult:
    """Creepages (xi, eta) at which the steady state under `pressure` (MPa) has the forces (Fx, Fy) on body 1 (N)
    with spin phi (1/mm). GrossSlidingError if |F| >= mu Fn (Fn = sum p dA), ConvergenceError after max_solves."""
    grid = problem.grid
    pressure = np.asarray(pressure, dtype=float)
    capacity = mu * float(pressure.sum()) * grid.cell_area
    target = np.array([Fx, Fy], dtype=float)
    if not np.all(np.isfinite(target)):
        raise InputError(f"prescribed forces Fx = {Fx!r}, Fy = {Fy!r} N: must be finite")
    if math.hypot(*target) >= capacity:
        raise GrossSlidingError(f"prescribed |F| = {math.hypot(*target):.6g} N >= mu Fn = {capacity:.6g} N: full "
                                "sliding, no finite creepage carries it")
    jac = _linear_jacobian(problem, pressure)
    creep = np.linalg.solve(jac, target - _spin_force(problem, pressure, mu, phi, params))
    state = solve_steady(problem, pressure, mu, creep[0], creep[1], phi, params=params)
    error = np.array(state.force) - target
    solves = 2
    while np.hypot(*error) > tol * capacity:
        step = -np.linalg.solve(jac, error)
        for _ in range(30):                       # halve a step that does not reduce the error
            trial = solve_steady(problem, pressure, mu, creep[0] + step[0], creep[1] + step[1], phi,
                                 initial=state.traction, params=params)
            solves += 1
            new_error = np.array(trial.force) - target
            if np.hypot(*new_error) < np.hypot(*error):
                break
            step *= 0.5
        else:
            raise ConvergenceError("prescribed forces: no step reduces the force error", solver="solve_for_forces",
                                   iterations=solves, residual=float(np.hypot(*error) / capacity), tol=tol)
        # Broyden's update of the Jacobian with the step taken
        jac += np.outer(new_error - error - jac @ step, step) / float(step @ step)
        creep, state, error = creep + step, trial, new_error
        if solves >= max_solves:
            raise ConvergenceError("prescribed forces did not converge", solver="solve_for_forces",
                                   iterations=solves, residual=float(np.hypot(*error) / capacity), tol=tol)
    return PrescribedForceResult(float(creep[0]), float(creep[1]), state, solves)


def _linear_jacobian(problem, pressure):
    """d(Fx, Fy)/d(xi, eta) of Kalker's linear theory for the contact's bounding ellipse (area-equivalent c)."""
    grid, mats = problem.grid, problem.materials
    contact = pressure > 0
    X, Y = grid.mesh()
    a = 0.5 * (X[contact].max() - X[contact].min() + grid.dx)
    b = 0.5 * (Y[contact].max() - Y[contact].min() + grid.dy)
    c2 = contact.sum() * grid.cell_area / math.pi
    c11, c22, _ = kalker_coefficients(a / b, min(max(mats.nu, 0.0), 0.5))
    return -mats.G * c2 * np.diag([c11, c22])


def _spin_force(problem, pressure, mu, phi, params):
    """The forces of the spin alone (0 without spin): a first estimate of what the creepages must balance."""
    if phi == 0.0:
        return np.zeros(2)
    return np.array(solve_steady(problem, pressure, mu, 0.0, 0.0, phi, params=params).force)
