"""The steady state of a [rolling] scene (solver.creep.steady; docs/theory.md §7.3, §11.5): the normal problem on the
contact-fixed grid of the rolling frame (NormCG) and the steady tangential problem on the same grid (Kalker's
Gauss-Seidel in traction differences), alternated for coupled materials (Kalker's K != 0, [solver] coupling) until
neither the pressure (relative to its maximum) nor the traction (relative to mu p_max) changes by more than the
solver tolerance: the tangential traction's normal displacement enters the normal problem, the pressure's
tangential displacement the slip. Used by the steady run (cases.run.creep_run) and beside a transient
(cases.run.creep_transient). Units: mm, N, MPa.
"""
from __future__ import annotations

import numpy as np

from rollcontact.bem.errors import ConvergenceError
from rollcontact.cases.run.discretise import scene_operator
from rollcontact.cases.run.rolling_frame import creep_grid, rolling_frame_profile
from rollcontact.cases.run.viscoelastic import steady_visco
from rollcontact.cases.scene.friction import local_friction
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.creep import SteadyParams, SteadyRolling, solve_for_forces, solve_steady
from rollcontact.solver.friction import solve_steady_friction
from rollcontact.solver.normal import NormalParams, solve_normal

#: Outer iterations (normal, then steady tangential) allowed for coupled materials.
MAX_OUTER = 30


def steady_state(scene: Scene, visco=None):
    """The steady state of the scene on its contact-fixed grid: (normal, steady, outer, creepages), as `solve_scene`
    (visco: a viscoelastic scene's steady operator to use, cases.run.viscoelastic.steady_visco, built if not given)."""
    grid = creep_grid(scene)
    if scene.viscoelastic:
        visco = steady_visco(scene, grid) if visco is None else visco
        return solve_scene(scene, grid, visco.operator, scene.material_pair, visco)
    op = scene_operator(scene, grid)
    return solve_scene(scene, grid, op, scene.material_pair)


def solve_scene(scene, grid, op, pair, visco=None):
    """Normal and steady tangential problems, alternated for coupled materials: (normal, steady, outer, creepages).
    visco: the steady operator of viscoelastic bodies (solver.visco.SteadyVisco; `op` is then its operator): its
    non-symmetric normal solver and its tangential problem replace NormCG and the elastic one."""
    tol = scene.solver.tol
    profile = rolling_frame_profile(scene, grid)
    nparams = NormalParams(tol=tol, max_iter=scene.solver.max_iter)
    sparams = SteadyParams(tol=tol, max_sweeps=max(scene.solver.max_iter, 100))
    if visco is None:
        problem = SteadyRolling(grid, pair, coupled=op.coupled, operator=op)
        solve = solve_normal
    else:
        problem = visco.tangential_problem

        def solve(_, profile, force, initial=None, extra_displacement=None, params=nparams):
            return visco.solve_normal(profile, force, initial=initial, extra_displacement=extra_displacement,
                                      params=params)
    normal = solve(op, profile, force=scene.load.Fn, params=nparams)
    friction = local_friction(scene, grid)         # None without [friction] and [thermal]
    steady, creep = _tangential(scene, problem, normal.pressure, None, sparams, friction)
    outer = 1
    while op.coupled:
        extra = op.normal_from_tangential(-steady.traction[0], -steady.traction[1])  # substrate convention
        again = solve(op, profile, force=scene.load.Fn, initial=normal.pressure, extra_displacement=extra,
                      params=nparams)
        change = float(np.max(np.abs(again.pressure - normal.pressure)) / np.max(again.pressure))
        normal, before = again, steady.traction
        steady, creep = _tangential(scene, problem, normal.pressure, steady.traction, sparams, friction,
                                    None if steady.friction is None else steady.friction.mu)
        outer += 1
        moved = float(np.max(np.abs(steady.traction - before)) / (scene.load.mu * np.max(normal.pressure)))
        change = max(change, moved)          # neither the pressure nor the traction moves any more
        if change <= max(tol, 1e-10):
            break
        if outer >= MAX_OUTER:
            raise ConvergenceError("coupled normal / steady rolling iteration did not converge",
                                   solver="creep_run", iterations=outer, residual=change, tol=max(tol, 1e-10))
    return normal, steady, outer, creep


def _tangential(scene, problem, pressure, initial, params, friction=None, mu_initial=None):
    """The steady state at the scene's creepages, or at the creepages that give its prescribed forces (Fx, Fy on the
    sphere, solver.creep.solve_for_forces): (SteadyResult, (xi, eta, phi)). With `friction` (a
    solver.friction.LocalFriction: a friction law or temperatures) the state is consistent with its law, its
    `friction` the FrictionState."""
    xi, eta, phi = scene.creepages
    forces = scene.prescribed_forces
    if friction is not None and forces is None:
        return solve_steady_friction(problem, pressure, friction, xi, eta, phi, initial=initial,
                                     mu_initial=mu_initial, params=params), (xi, eta, phi)
    if forces is None:
        return solve_steady(problem, pressure, scene.load.mu, xi, eta, phi, initial=initial, params=params), \
            (xi, eta, phi)
    found = solve_for_forces(problem, pressure, scene.load.mu, *forces, phi, params=params)
    if friction is not None:      # Coulomb's law with temperatures: the state found, with its FrictionState
        return solve_steady_friction(problem, pressure, friction, found.xi, found.eta, phi,
                                     initial=found.steady.traction, params=params), (found.xi, found.eta, phi)
    return found.steady, (found.xi, found.eta, phi)
