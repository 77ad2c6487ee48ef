"""Creep-force curves: steady rolling solved over a range of creepages, each solution the warm start of the next
(docs/theory.md §7.3, §11.5), and the curves they are drawn against.

Kalker's sign convention (`solver.creep.kalker`): forces on body 1, opposing the creepages. The reference curves
are the linear theory F = G c^2 C11 xi (and C22, C23) and the saturation model of Vermeulen & Johnson (1964):
with t = |F_linear| / (mu Fn), |F| / (mu Fn) = t - t^2/3 + t^3/27 for t < 3 and 1 beyond.
"""
from dataclasses import dataclass
import time

import numpy as np

from rollcontact.solver.creep.steady import SteadyParams, SteadyRolling, solve_steady


@dataclass
class CreepCurve:
    """Per creepage point: creepages (n, 3) (xi, eta, phi in 1/mm), force (n, 2) N and moment (n,) N mm on body
    1, stick_fraction (n,) (stick cells / contact cells), sweeps (n,); the last point's SteadyResult; the process
    CPU time of each point's solve (n,) s."""
    creepages: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    stick_fraction: np.ndarray
    sweeps: np.ndarray
    last: object
    cpu_time: np.ndarray = None


def creep_curve(problem: SteadyRolling, pressure, mu, creepages, *,
                params: SteadyParams = SteadyParams(), solve=solve_steady) -> CreepCurve:
    """Steady states at the creepages (a sequence of (xi, eta, phi)) under `pressure` (MPa) with friction `mu`,
    in the given order, each started from the traction of the one before, scaled by the ratio of the creepages
    when the two are parallel (exact in full adhesion, where the traction is linear in the creepage; the solver
    clips it to the Coulomb bound). solve: the steady solver, with solve_steady's arguments (a friction law's:
    solver.friction.solve_steady_friction with its LocalFriction in place of mu)."""
    creepages = np.atleast_2d(np.asarray(creepages, dtype=float))
    n = len(creepages)
    force, moment = np.zeros((n, 2)), np.zeros(n)
    stick, sweeps, seconds = np.zeros(n), np.zeros(n, dtype=np.int64), np.zeros(n)
    previous = None
    for k, (xi, eta, phi) in enumerate(creepages):
        c0 = time.process_time()
        if previous is not None:
            previous = previous * _parallel_ratio(creepages[k - 1], creepages[k])
        res = solve(problem, pressure, mu, xi, eta, phi, initial=previous, params=params)
        seconds[k] = time.process_time() - c0
        force[k], moment[k] = res.force, res.moment
        stick[k] = res.stick.sum() / res.contact.sum()
        sweeps[k] = res.sweeps
        previous = res.traction
    return CreepCurve(creepages, force, moment, stick, sweeps, res, seconds)


def _parallel_ratio(before, after):
    """|after| / |before| when the two creepage vectors point the same way, else 1."""
    nb, na = np.linalg.norm(before), np.linalg.norm(after)
    if nb == 0.0 or na == 0.0 or abs(before @ after - nb * na) > 1e-9 * nb * na:
        return 1.0
    return na / nb


def vermeulen_johnson(linear_force_ratio):
    """|F|/(mu Fn) of the Vermeulen-Johnson saturation model for t = |F_linear|/(mu Fn) (array or float)."""
    t = np.minimum(np.abs(np.asarray(linear_force_ratio, dtype=float)), 3.0)
    return t - t ** 2 / 3.0 + t ** 3 / 27.0


def saturation_creepage(G, c, coefficient, mu, normal_force):
    """The creepage at which the linear force G c^2 C reaches mu Fn (for spin, pass c * C23 as `coefficient`
    to get 1/mm): CONTACT's normalising creepage (docs/theory.md §7.3)."""
    return mu * normal_force / (G * c * c * coefficient)
