"""Steady rolling with a friction law: Kalker's steady problem (solver.creep.steady) with the local coefficient made
consistent with the steady slip velocity (docs/friction.md, "Solving with a friction law").

The slip velocity of steady rolling is the rolling speed times the slip per unit rolled distance, s = V |sigma| (mm/s;
Kalker's convention, sigma dimensionless). The law gives the coefficient at s, with memory the coefficient relaxed
along the material's path through the contact-fixed grid (solver.friction.memory.FrictionMemory.steady_rows), with
temperatures the law's at the contact temperature of the frictional heat (solver.friction.thermal). An element's
own feedback (solver.friction.iteration) is through its self-influence on the upwind slip, b = (A_xx(0) - A_xx(-dx))
/ dx (mm/MPa per mm; the mean of the xx and yy components): raising its bound by p dmu lowers its slip by
b p dmu per unit distance. Units: mm, N, MPa, mm/s.
"""
from __future__ import annotations

import numpy as np

from rollcontact.solver.creep.steady import SteadyParams, SteadyRolling, solve_steady
from rollcontact.bem.errors import ConvergenceError
from rollcontact.solver.friction.iteration import CoefficientUpdate, feedback_regime
from rollcontact.solver.friction.model import FrictionState, LocalFriction
from rollcontact.solver.friction.thermal import frictional_flux


def upwind_self_coefficient(problem: SteadyRolling) -> float:
    """b (1/MPa): the change of an element's upwind slip per unit traction change of its own (module docstring)."""
    nx = problem.grid.nx
    row_xx, row_yy = problem.rows
    i0, i1 = nx - 1, max(nx - 2, 0)
    return 0.5 * ((row_xx[i0] - row_xx[i1]) + (row_yy[i0] - row_yy[i1])) / problem.grid.dx


def solve_steady_friction(problem: SteadyRolling, pressure, friction: LocalFriction, xi=0.0, eta=0.0, phi=0.0, *,
                          initial=None, mu_initial=None, params: SteadyParams = SteadyParams()):
    """The steady state at creepages xi, eta and spin phi (1/mm) under `pressure` (MPa) with the friction law of
    `friction` (its speed V in mm/s): the SteadyResult, its `friction` the FrictionState. initial: a traction to
    start from (2, ny, nx, Kalker's convention); mu_initial: a coefficient field to start from (default mu_static).
    With friction.thermal (a ContactTemperature on the grid) the temperatures are computed too (the temperature law
    needs them).

    The coefficient is updated after every Gauss-Seidel sweep from that sweep's slip (solve_steady's bound_update:
    the law's value, Newton's step on each element's own feedback, solver.friction.iteration.CoefficientUpdate), so
    that the sweeps converge the traction and the coefficient together; the solve stops when a sweep changes no
    traction beyond params.tol and the coefficient is the law's within friction.params.tol. Raises what solve_steady
    raises; its ConvergenceError then names the feedback of falling friction."""
    law, memory, V, thermal = friction.law, friction.memory, friction.speed, friction.thermal
    grid = problem.grid
    pressure = np.asarray(pressure, dtype=float)
    contact = pressure > 0
    mu_static = law.mu_static
    b = upwind_self_coefficient(problem)
    update = CoefficientUpdate(mu_static, friction.bounds, friction.params)
    weight = pressure / pressure.max()
    start = law.mu if law.kind == "coulomb" else mu_static
    state = {"mu": np.full(grid.shape, start) if mu_initial is None else np.array(mu_initial, dtype=float),
             "J": np.zeros(grid.shape), "updates": 0}

    def velocity(slip):
        return np.where(contact, (V if V is not None else 0.0) * np.hypot(slip[0], slip[1]), 0.0)

    def target(slip, traction, stick):
        s = velocity(slip)
        if law.velocity_dependent:
            value, slope = law.coefficient(s), law.slope(s)
            if memory.active:
                T, dT = memory.steady_rows(value, slope, s, grid.dx, V, mu_static)
            else:
                T, dT = value, slope
            return T, np.where(contact & ~stick, -dT * V * b * pressure, 0.0)
        if law.temperature_dependent:
            temps = thermal.solve(frictional_flux(traction, s), contact)
            return np.where(contact, law.of_temperature(0.5 * (temps.T1 + temps.T2)), mu_static), np.zeros(grid.shape)
        return np.full(grid.shape, law.mu), np.zeros(grid.shape)

    def bound_update(slip, traction, stick):
        T, state["J"] = target(slip, traction, stick)
        if update.observe(state["mu"], T, weight):
            state["mu"] = np.where(contact, state["mu"], T)     # outside the contact: the law's (memory) value
            return None
        state["mu"] = update.step(state["mu"], T, state["J"])
        state["updates"] += 1
        return np.where(contact, state["mu"] * pressure, 0.0)

    where = f"steady rolling at V = {V:.6g} mm/s" if V is not None else "steady rolling"
    try:
        res = solve_steady(problem, pressure, np.where(contact, state["mu"], mu_static), xi, eta, phi,
                           initial=initial, params=params,
                           bound_update=None if law.kind == "coulomb" else bound_update)  # Coulomb's: no update
    except ConvergenceError as exc:
        raise ConvergenceError("steady rolling with a friction law did not converge", solver="solve_steady_friction",
                               iterations=exc.iterations, residual=max(exc.residual or 0.0, update.residual),
                               tol=exc.tol, regime=feedback_regime(law, state["J"], where)) from None
    s = np.where(contact, (V if V is not None else 0.0) * np.hypot(res.slip[0], res.slip[1]), 0.0)
    flux = frictional_flux(res.traction, s)
    temps = thermal.solve(flux, contact) if thermal is not None else None
    # the uniqueness indicator: the steepest fall of the law against the element's own slip per bound
    feedback = law.steepest_slope() * (V or 0.0) * b * float(pressure.max())
    res.friction = FrictionState(state["mu"], s, state["updates"], float(flux.sum()) * grid.cell_area, temps, feedback)
    return res
