"""Frictionless normal contact with a non-symmetric operator: the steady rolling of viscoelastic bodies (docs/theory.md
§4.1, §12.3; docs/viscoelastic.md, "The steady normal problem").

Problem (docs/theory.md §4.1) on the contact-fixed grid, element area dA:

    e_I = h_I - d + u_I >= 0,   p_I >= 0,   p_I e_I = 0,   sum_I p_I dA = Fn,   u = K p (+ extra displacement),

with K the steady viscoelastic operator (a bem.ToeplitzOperator from `steady_kernels`): the material's memory makes
it non-symmetric (the displacement at a cell depends on the pressure the material met upstream), so NormCG's
conjugate gradients, which need a symmetric operator, do not apply. K's symmetric part is positive definite (the
symbol of the SLS filter along the rolling direction has a real part >= C_g; docs/viscoelastic.md), so on a fixed
contact set the equations are uniquely solvable and GMRES converges.

Method: the active-set iteration of Kalker's NORM (Kalker 1990, §5.2; a primal-dual active set, Hintermüller, Ito &
Kunisch 2002, SIAM J. Optim. 13:865-888): on the contact set C solve K_CC p = d - h_C with the force constraint (two
GMRES solves, K_CC x = -h_C and K_CC y = 1, and d = (Fn/dA - sum x)/(sum y), p = x + d y; right-preconditioned by the
Strang circulant of K, `ToeplitzOperator.normal_inverse`, restricted to C), then drop the elements with p < 0 and add
those outside with e < 0, until C no longer changes. A set met twice (a cycle) switches to changing one element at a
time, the most negative pressure or the deepest penetration. Units: mm, N, MPa.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.normal.normcg import NormalParams, NormalResult
from rollcontact.solver.visco.gmres import gmres

#: Contact-set changes before ConvergenceError.
MAX_SET_CHANGES = 200
#: GMRES tolerance while the contact set still changes (only the signs of p and e matter then).
LOOSE_TOL = 1e-4


def solve_normal_steady(op, profile, *, force, initial=None, extra_displacement=None,
                        params: NormalParams = NormalParams()) -> NormalResult:
    """The contact of the non-symmetric operator `op` (`normal`, `normal_inverse` products on its grid) under the
    normal force `force` (N) for the undeformed gap `profile` (mm, (ny, nx)); `initial`: a pressure (MPa) whose
    support starts the contact set (e.g. the effective elastic solution), default {h <= the force's rigid estimate};
    `extra_displacement` (mm) added to K p. `params.tol`: GMRES's relative residual, and the pressure (relative to its
    maximum) and gap (relative to the largest displacement) below which a sign does not count; `params.max_iter`: the
    products of one GMRES solve. Returns a NormalResult (iterations: the products used). Raises InputError for bad
    input, ConvergenceError when GMRES or the contact set does not settle."""
    grid = op.grid
    shape, dA = grid.shape, grid.cell_area
    if not (isinstance(force, (int, float)) and math.isfinite(force) and force > 0):
        raise InputError(f"force = {force!r} N: must be a finite positive normal force")
    h = np.asarray(profile, dtype=float)
    if h.shape != shape or not np.all(np.isfinite(h)):
        raise InputError(f"profile: must be a finite array of the grid's shape {shape}")
    extra = None
    if extra_displacement is not None:
        extra = np.asarray(extra_displacement, dtype=float)
        if extra.shape != shape or not np.all(np.isfinite(extra)):
            raise InputError(f"extra_displacement: must be a finite array of the grid's shape {shape}")
    h_eff = h if extra is None else h + extra
    if initial is not None and np.any(np.asarray(initial) > 0):
        contact = np.asarray(initial) > 0
    else:                                     # a flat punch's estimate: a disc around the lowest point
        order = np.sort(h_eff.ravel())
        contact = h_eff <= order[max(1, h_eff.size // 16) - 1]
    products = 0
    seen = set()
    one_at_a_time = False
    p = np.zeros(shape)
    full = np.zeros(shape)
    loose = max(params.tol, LOOSE_TOL)
    tol = loose
    for changes in range(MAX_SET_CHANGES):
        idx = np.flatnonzero(contact.ravel())
        n = idx.size

        def apply(v):                                 # zero-mean v -> the zero-mean part of (K v) on C
            full.ravel()[:] = 0.0
            full.ravel()[idx] = v
            w = op.normal(full).ravel()[idx]
            return w - w.mean()

        def precondition(v):
            full.ravel()[:] = 0.0
            full.ravel()[idx] = v
            w = op.normal_inverse(full).ravel()[idx]
            return w - w.mean()

        base = np.full(n, force / (n * dA))            # carries the force; the unknown part has zero sum
        start = p.ravel()[idx] - base
        start -= start.mean()
        full.ravel()[:] = 0.0
        full.ravel()[idx] = base
        rhs = -(h_eff.ravel()[idx] + op.normal(full).ravel()[idx])
        rhs -= rhs.mean()
        v, used, residual = gmres(apply, precondition, rhs, start, tol=tol, max_products=params.max_iter)
        products += used + 1
        if residual > tol:
            raise ConvergenceError("GMRES of the steady viscoelastic normal problem did not reach tol", solver="normal",
                                   iterations=products, residual=residual, tol=tol,
                                   regime=f"{n} of {h.size} elements in contact")
        p = np.zeros(shape)
        p.ravel()[idx] = base + v
        u = op.normal(p)
        products += 1
        approach = float(np.mean((h_eff + u).ravel()[idx]))
        gap = h_eff - approach + u
        pmax = float(np.max(p))
        umax = float(np.max(np.abs(u[contact])))
        negative = contact & (p < -params.tol * pmax)
        entering = ~contact & (gap < -params.tol * umax)
        if not negative.any() and not entering.any():
            if tol > params.tol:                      # the set settled on loose solves: solve it to tol
                tol = params.tol
                continue
            p = np.maximum(p, 0.0)
            p *= force / (p.sum() * dA)
            displacement = op.normal(p) + (0.0 if extra is None else extra)
            products += 1
            gap = h - approach + displacement
            return NormalResult(pressure=p, approach=approach, displacement=displacement, gap=gap,
                                contact=p > 0.0, force=float(p.sum() * dA), iterations=int(products),
                                residual=float(residual), converged=True)
        tol = loose
        key = np.packbits(contact).tobytes()
        if key in seen:
            one_at_a_time = True
        seen.add(key)
        if one_at_a_time:
            negative, entering = _single(negative, p), _single(entering, gap)
            if negative.any():
                entering[...] = False
        contact = (contact & ~negative) | entering
        if not contact.any():
            raise ConvergenceError("steady viscoelastic normal problem: the contact set became empty",
                                   solver="normal", iterations=products, residual=math.inf, tol=params.tol)
    raise ConvergenceError("steady viscoelastic normal problem: the contact set did not settle", solver="normal",
                           iterations=products, residual=math.inf, tol=params.tol,
                           regime=f"{MAX_SET_CHANGES} contact-set changes")


def _single(mask, values):
    """Only the element of `mask` with the smallest value (the most negative pressure or gap)."""
    if not mask.any():
        return mask
    out = np.zeros_like(mask)
    flat = np.where(mask.ravel(), values.ravel(), np.inf)
    out.ravel()[int(np.argmin(flat))] = True
    return out
