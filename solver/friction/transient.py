"""One step of a stepped run (oscillating rolling, shifts, transient rolling on the world-fixed grid) with a friction
law: the slip-velocity iteration around the step's contact solve (docs/friction.md, "Solving with a friction law").

The step's slip velocity is its slip over its duration, s = |slip| / dt (mm/s; dt = the step's displacement over
the speed, LoadPath.step_time). The coefficient that bounds the step's traction is the law's at that slip velocity,
or with memory the relaxed value at the end of the step from the previous step's (solver.friction.memory); with
temperatures (the temperature law), the law's at the contact temperature of the step's frictional heat (quasi-steady:
the heat flux of the step as if the contact had carried it for long, solver.friction.thermal). Units: mm, s, MPa.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from rollcontact.solver.friction.iteration import consistent_coefficient, feedback_regime
from rollcontact.solver.friction.model import FrictionState, LocalFriction
from rollcontact.solver.friction.thermal import frictional_flux
from rollcontact.solver.rolling.stepping import shifted_field


class LastSolve:
    """The previous solve of a step's iteration, as the warm start of the next (`warm_start`), and the products of
    all its solves (the step's cost)."""

    def __init__(self):
        self.traction = self.pressure = self.region = None
        self.normal_products = self.tangential_products = self.steps = 0

    def record(self, normal, tangential):
        self.traction, self.pressure, self.region = tangential.traction, normal.pressure, tangential.region
        self.normal_products += normal.iterations
        self.tangential_products += tangential.iterations
        self.steps += tangential.steps

    def warm_start(self, pressure_guess=None) -> dict:
        """solve_coupled_step's warm-start arguments: the last traction with its stick/slip division (its slip
        elements start on their new bound) and pressure; before the first solve, the step's own pressure guess."""
        if self.traction is None:
            return {"pressure_guess": pressure_guess}
        return {"pressure_guess": self.pressure, "initial_traction": self.traction, "initial_region": self.region}


def friction_step(friction: LocalFriction, solve, *, grid, dt, previous_mu, self_coefficient, thermal=None,
                  moved=(0, 0), previous_residual=None):
    """Solve one step consistently with the law: (normal, tangential, outer, FrictionState).

    solve(mu, last, accuracy) -> (NormalResult, TangentialResult, outer iterations): the step's contact solve on
    `grid` (bem.Grid) with the coefficient field mu (ny, nx), warm-started from `last` (a LastSolve: its
    warm_start(pressure_guess) gives solve_coupled_step's warm-start arguments), to the relative accuracy `accuracy`
    where that is looser than the solvers' tolerance (None: their tolerance). dt (s): the step's duration
    (None without a speed: Coulomb and the temperature law need none). previous_mu: the coefficient field at the end
    of the previous step (None: mu_static everywhere, surfaces at rest). self_coefficient: the element's own
    tangential influence (mm/MPa). thermal: a solver.friction.thermal.ContactTemperature on the grid (temperatures;
    needed by the temperature law). moved: (rows, cols), the contact's move since the previous step in whole cells:
    without memory the coefficient field moves with the slip pattern, and the first iterate is the previous one
    moved along (with memory the coefficient belongs to the material, which stays). previous_residual: the residual of
    the previous step's first iterate (its FrictionState.first_residual; None: unknown), the one this step's first
    coefficient field is expected to have: its first solve asks for no more accuracy than that
    (solver.friction.iteration.consistent_coefficient)."""
    law, memory = friction.law, friction.memory
    shape = grid.shape
    mu_static = law.mu_static
    previous = np.full(shape, mu_static) if previous_mu is None else np.asarray(previous_mu, dtype=float)
    last = LastSolve()

    def run(mu, accuracy):
        normal, tang, outer = solve(mu, last, accuracy)
        last.record(normal, tang)
        return normal, tang, outer

    def velocity(tang):
        return np.hypot(tang.slip[0], tang.slip[1]) / dt if dt else np.zeros(shape)

    def target(solution, mu):
        normal, tang, _ = solution
        s = velocity(tang)
        p = normal.pressure
        if law.velocity_dependent:
            value, slope = law.coefficient(s), law.slope(s)
            T = memory.step(previous, value, s, dt)
            dT = memory.step_slope(previous, value, slope, s, dt)
            J = np.where(tang.region == 2, -dT * self_coefficient * p / dt, 0.0)
        elif law.temperature_dependent:
            temps = thermal.solve(frictional_flux(tang.traction, s), normal.contact)
            T = np.where(normal.contact, law.of_temperature(0.5 * (temps.T1 + temps.T2)), mu_static)
            J = np.zeros(shape)
        else:
            T, J = np.full(shape, law.mu), np.zeros(shape)
        return T, J, _bound_weight(tang, p, T)

    if law.kind == "coulomb":
        start = np.full(shape, law.mu)
    elif not memory.active and tuple(moved) != (0, 0):
        start = mu_static + shifted_field(previous - mu_static, *moved)
    else:
        start = previous
    where = f"slip velocity over a step of {dt:.6g} s" if dt else "no speed"
    done = consistent_coefficient(run, target, start, mu_static=mu_static, bounds=friction.bounds,
                                  params=friction.params, regime=lambda J: feedback_regime(law, J, where),
                                  expected_residual=previous_residual)
    normal, tang, outer = done.solution
    # the cost of the step: the products of every solve of the iteration
    normal = replace(normal, iterations=last.normal_products)
    tang = replace(tang, iterations=last.tangential_products, steps=last.steps)
    s = velocity(tang)
    flux = frictional_flux(tang.traction, s)
    temps = thermal.solve(flux, normal.contact) if thermal is not None else None
    # the uniqueness indicator: the steepest fall of the law against the stiffest element's own slip per bound
    feedback = law.steepest_slope() * self_coefficient * float(normal.pressure.max()) / dt if dt else 0.0
    state = FrictionState(done.mu, s, done.iterations, float(flux.sum()) * grid.cell_area, temps, feedback,
                          done.first_residual)
    return normal, tang, outer, state


def _bound_weight(tang, p, T):
    """The weight of each element's coefficient residual (CoefficientUpdate.observe): p / p_max where the
    coefficient bounds the traction, 0 at a sticking element whose traction lies within the law's bound T p. There
    the solution does not depend on the coefficient it was solved with (the same traction meets the conditions of
    the problem with bound T p), so that coefficient needs no further solve: it is taken as the law's."""
    weight = p / max(float(p.max()), 1e-300)
    tx, ty = tang.traction
    bound = T * p
    inside = (tang.region == 1) & (tx * tx + ty * ty <= bound * bound)
    return np.where(inside, 0.0, weight)
