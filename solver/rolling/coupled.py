"""One step of normal + tangential contact for coupled materials (docs/theory.md §6.2 step 5).

For beta != 0 (dissimilar materials, `op.coupled` True) the pressure displaces the surface tangentially
(A^tz) and the tractions displace it normally (A^zt). Panagiotopoulos' process alternates the two
problems, each seeing the other's current solution as a given field:

    normal:      h* = h + A^zt tau                      (extra_displacement of solve_normal)
    tangential:  bound mu p,  s = A^tt (tau - tau') + A^tz (p - p') - dU   (extra_slip of solve_tangential)

until neither p nor tau changes by more than `coupling_tol` (relative to max p and max mu p), which is a
contraction for |beta| mu well below 1 (Kalker 1990, §5; CONTACT user guide, "solution processes").
For uncoupled materials (beta = 0 or below the operator's threshold) one normal and one tangential solve
are exact ("Johnson's process") and no coupling product is formed.

Units: mm, N, MPa. Signs as in docs/theory.md §0.
"""
from dataclasses import replace

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.normal.normcg import NormalParams, solve_normal
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential


def solve_coupled_step(op, profile, Fn, F, previous_pressure, previous_traction, *, mu,
                       normal_params=NormalParams(), tangential_params=TangentialParams(),
                       coupling_tol=1e-8, max_outer=50, pressure_guess=None, shift=None, extra_slip=None,
                       extra_displacement=None, initial_traction=None, initial_region=None, normal=None):
    """Solve one load step of the coupled normal/tangential problem.

    Parameters
    ----------
    op : bem.HalfSpaceOperator; its `coupled` flag selects the nested loop.
    profile : (ny, nx) undeformed gap h (mm).
    Fn : normal force (N). F : (Fx, Fy) tangential force on the substrate (N), or None with `shift`.
    previous_pressure : (ny, nx) p' of the previous step (MPa), or None for zero (virgin contact).
    previous_traction : (2, ny, nx) tau' of the previous step (MPa).
    mu : Coulomb friction coefficient (the bound is g = mu p), or a local coefficient per element (ny, nx), as a
        friction law gives it (solver.friction).
    normal_params, tangential_params : the inner solvers' tolerances.
    coupling_tol : stop when max|p_k - p_{k-1}| <= coupling_tol max p_k and
        max|tau_k - tau_{k-1}| <= coupling_tol mu max p_k.
    max_outer : Panagiotopoulos iterations before ConvergenceError.
    pressure_guess : (ny, nx) warm start of the normal solve (MPa), e.g. the previous pressure moved with
        the sphere (`shifted_field`); default the previous pressure. Only the start changes, not the solution.
    shift : (dUx, dUy) mm, a prescribed rigid-shift increment in place of the force F (solve_tangential's
        `shift`; the force is then an output), e.g. (0, 0) for rolling with prescribed creepages.
    extra_slip : (2, ny, nx) mm, a given slip of the step added to the tangential problem's (solve_tangential's
        `extra_slip`), e.g. the rigid creep slip of a rolling step (solver.creep.world); it is not part of the
        returned `displacement`.
    extra_displacement : (ny, nx) mm, a given normal displacement of the step added to the normal problem's
        (solve_normal's `extra_displacement`), e.g. the history displacement of viscoelastic bodies (solver.visco); it
        is part of the returned NormalResult's `displacement`.
    initial_traction : (2, ny, nx) MPa, a warm start of the tangential solve (default: the previous traction), e.g.
        the last iterate of a friction law's iteration (solver.friction.transient). Only the start changes.
    initial_region : (ny, nx) int8, the stick/slip division of the solve that gave `initial_traction`
        (solve_tangential's `previous_region`: its slip elements start on the new bound).
    normal : a NormalResult of this profile and Fn solved before, taken as the normal solution (uncoupled materials
        without an extra_displacement only, whose normal problem depends on the gap and Fn alone; ignored when
        coupled; InputError with an extra_displacement).

    Returns (NormalResult, TangentialResult, outer_iterations): the results of the last outer iteration,
    with `iterations` the products of every outer iteration summed (the cost of the step; the last outer
    iteration alone often needs one product each, since it starts from the converged fields). The
    TangentialResult's `displacement` is the surface displacement A^tt tau + A^tz p (mm), so that
    s = u - u' - dU between two steps.
    """
    local = np.ndim(mu) > 0
    if not (np.all(np.asarray(mu) > 0) if local else mu > 0):
        raise InputError(f"mu = {mu!r}: the friction coefficient must be > 0")
    mu_max = float(np.max(mu)) if local else mu
    shape = op.grid.shape
    p_prev = np.zeros(shape) if previous_pressure is None else np.asarray(previous_pressure, dtype=float)
    tau_prev = np.asarray(previous_traction, dtype=float)
    if p_prev.shape != shape or tau_prev.shape != (2,) + shape:
        raise InputError(f"previous_pressure {p_prev.shape} / previous_traction {tau_prev.shape} do not "
                         f"match the grid {shape}")
    initial_p = p_prev if np.any(p_prev) else None
    if pressure_guess is not None and np.any(pressure_guess):
        initial_p = np.asarray(pressure_guess, dtype=float)
    if (F is None) == (shift is None):
        raise InputError("solve_coupled_step: give exactly one of F = (Fx, Fy) N or shift = (dUx, dUy) mm")
    given = None if extra_slip is None else np.asarray(extra_slip, dtype=float)
    given_normal = None if extra_displacement is None else np.asarray(extra_displacement, dtype=float)
    if not op.coupled:
        if normal is None:
            normal = solve_normal(op, profile, force=Fn, initial=initial_p, extra_displacement=given_normal,
                                  params=normal_params)
        elif given_normal is not None:
            raise InputError("solve_coupled_step: a normal solution given with an extra_displacement (its normal "
                             "problem depends on it)")
        tang = solve_tangential(op, mu * normal.pressure, tau_prev, force=F, shift=shift, extra_slip=given,
                                initial=initial_traction, previous_region=initial_region, params=tangential_params)
        if given is not None:
            tang = replace(tang, displacement=tang.displacement - given)
        return normal, tang, 1

    tau = (tau_prev if initial_traction is None else np.asarray(initial_traction, dtype=float)).copy()
    p = p_prev.copy()
    p_guess = initial_p
    change = np.inf
    n_products = t_products = t_steps = 0
    for outer in range(1, max_outer + 1):
        coupling = op.normal_from_tangential(tau[0], tau[1])
        normal = solve_normal(op, profile, force=Fn, initial=p_guess,
                              extra_displacement=coupling if given_normal is None else coupling + given_normal,
                              params=normal_params)
        extra = op.tangential_from_pressure(normal.pressure - p_prev)
        if given is not None:
            extra = extra + given
        tang = solve_tangential(op, mu * normal.pressure, tau_prev, force=F, shift=shift, initial=tau,
                                extra_slip=extra,
                                previous_region=initial_region if outer == 1 else tang.region,
                                params=tangential_params)
        n_products += normal.iterations
        t_products += tang.iterations
        t_steps += tang.steps
        pmax = float(normal.pressure.max())
        dp = float(np.abs(normal.pressure - p).max()) / pmax
        dt = float(np.abs(tang.traction - tau).max()) / (mu_max * pmax)
        change = max(dp, dt)
        p, tau, p_guess = normal.pressure, tang.traction, normal.pressure
        if outer > 1 and change <= coupling_tol:
            # the solve's displacement is A^tt tau + A^tz (p - p'), the part that makes this step's slip; the
            # surface displacement is A^tt tau + A^tz p (one coupling product per step)
            total = tang.displacement - extra + op.tangential_from_pressure(normal.pressure)
            return (replace(normal, iterations=n_products),
                    replace(tang, iterations=t_products, steps=t_steps, displacement=total), outer)
    raise ConvergenceError("Panagiotopoulos loop (coupled normal/tangential) did not converge",
                           solver="coupled", iterations=max_outer, residual=change, tol=coupling_tol,
                           regime=f"beta = {op.materials.beta:.4g}, mu = {mu_max}{' (largest local)' if local else ''}, "
                                  + (f"f_t = {float(np.hypot(*np.asarray(F, float))) / (mu_max * Fn):.4g}"
                                     if F is not None else f"prescribed shift {tuple(shift)} mm"))
