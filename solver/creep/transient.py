"""Transient rolling with creepage and spin: from rest to the steady state, one element per step (theory.md §11.5).

On the contact-fixed grid (x along the rolling direction), both bodies' material moves one cell (dx) backwards
per step of rolling distance dq = dx; the displacement difference a material point had at the previous step is
the one of the upstream cell, u'_I = u_old(I + 1). With a Toeplitz influence matrix that is exactly A tau' for
the traction tau'_I = tau_old(I + 1) shifted one cell back, so each step is Kalker's transient shift problem
(theory.md §5.1) solved by `solver.tangential.solve_tangential` with that shifted previous traction, no rigid
shift, and the rigid creep slip of the step as extra slip (CONTACT's "T=2" on a grid moving with the contact).
Its fixed point is exactly the steady state of `steady` (same discrete equations, same spin offset), so rolling
several contact lengths converges to `solve_steady`'s answer.

Conventions: `solve_tangential` works with the project's substrate traction (theory.md §0), the opposite of
Kalker's traction on body 1; the results here are in Kalker's convention (forces on body 1, `kalker`).
Units: mm, N, MPa.
"""
from dataclasses import dataclass

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.creep.steady import SteadyRolling
from rollcontact.solver.tangential import TangentialParams, solve_tangential


@dataclass
class TransientRolling:
    """Per step k (rolled distance (k + 1) dx): force (n, 2) N and moment (n,) N mm on body 1, stick cells (n,),
    products (n,) of the tangential solver; the final traction on body 1 (2, ny, nx) MPa and its region."""
    distance: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    stick_cells: np.ndarray
    products: np.ndarray
    traction: np.ndarray
    region: np.ndarray


def roll_transient(op, problem: SteadyRolling, pressure, mu, xi=0.0, eta=0.0, phi=0.0, *, steps: int,
                   initial=None, params: TangentialParams = TangentialParams()) -> TransientRolling:
    """Roll `steps` elements (distance steps * dx) with the creepages xi, eta and spin phi (1/mm) from the traction
    `initial` (on body 1, MPa; default zero: rolling starts from rest with the creepages switched on). `op` (a
    bem HalfSpaceOperator) and `problem` share the grid; pressure (MPa) and mu as in `solve_steady`."""
    grid = op.grid
    if problem.grid != grid:
        raise InputError("roll_transient: op and problem must be built on the same grid")
    if int(steps) != steps or steps < 1:
        raise InputError(f"roll_transient: steps = {steps!r}, must be an integer >= 1")
    pressure = np.asarray(pressure, dtype=float)
    contact = pressure > 0
    if contact[:, -1].any() or contact[:, 0].any():
        raise InputError("roll_transient: the contact reaches the grid's first or last column; one free column "
                         "ahead of and behind it is needed")
    bound = np.where(contact, mu * pressure, 0.0)
    extra = -problem.rigid_slip(xi, eta, phi, pressure) * grid.dx   # the step's creep slip, substrate convention
    extra[:, ~contact] = 0.0
    tau = np.zeros((2,) + grid.shape) if initial is None else -np.array(initial, dtype=float)
    X, Y = grid.mesh()
    dA = grid.cell_area
    force, moment = np.zeros((steps, 2)), np.zeros(steps)
    stick, products = np.zeros(steps, dtype=np.int64), np.zeros(steps, dtype=np.int64)
    for k in range(steps):
        previous = np.zeros_like(tau)
        previous[:, :, :-1] = tau[:, :, 1:]                           # the material came from the cell ahead
        res = solve_tangential(op, bound, previous, shift=(0.0, 0.0), extra_slip=extra, params=params)
        tau = res.traction
        force[k] = -res.force
        moment[k] = -float(((X * tau[1] - Y * tau[0]).sum()) * dA)
        stick[k] = int((res.region == 1).sum())
        products[k] = res.iterations
    return TransientRolling((np.arange(steps) + 1) * grid.dx, force, moment, stick, products, -tau, res.region)
