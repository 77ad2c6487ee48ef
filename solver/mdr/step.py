"""One step of the 1-D MDR spring row, exact, in plain numpy (solver.mdr; docs/theory.md §8.2).

Steps 1 and 3 of the MDR step (see `solver.mdr`): the approach d (mm) that carries the normal force Fn (N)
on springs of stiffness E* ds (E* in MPa, ds in mm), and the rigid tangential displacement U (mm) of springs
with slip anchors v_i and Coulomb bounds b_i (mm).  Both are piecewise-linear root problems solved exactly.
These are the reference versions, with errors raised; `solver.mdr.simulate_mdr` runs their compiled twins
in `solver.mdr._kernels`.
"""
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, GrossSlidingError


# --------------------------------------------------------------------------------------- one step
def approach_for_force(gap, Fn, E_star, ds):
    """Approach d (mm) with E* ds sum_i max(0, d - gap_i) = Fn, exact for the discrete springs.

    gap: undeformed gaps g_i (mm).  Newton on the convex piecewise-linear force-approach function
    (equivalently the fixed point d = (Fn/(E* ds) + sum_C g_i)/|C| over the contact set C); it converges
    monotonically after the first step and stops when C repeats, so the result is exact to round-off.
    """
    target = Fn / (E_star * ds)
    d = float(np.min(gap)) + target  # one spring carrying everything: an upper bound of d
    count = -1
    for _ in range(200):
        in_contact = gap < d
        n = int(np.count_nonzero(in_contact))
        if n == count:
            return d
        count = n
        d = (target + float(np.sum(gap[in_contact]))) / n
    raise ConvergenceError("MDR normal problem: contact set did not settle", solver="approach_for_force",
                           iterations=200)


def rigid_shift(anchor, bound, target):
    """Rigid displacement U (mm) with sum_i clip(U - anchor_i, -bound_i, bound_i) = target (mm).

    target = Ft/(G* ds).  The left side is non-decreasing and piecewise linear in U with break points
    anchor_i -+ bound_i; sorting them gives the exact root (the smallest one if the function is flat
    there, which only happens at target = sum bound, i.e. Ft = mu Fn).  Springs with bound_i = 0 carry no
    force and are skipped.  Raises GrossSlidingError if |target| > sum bound (no equilibrium).
    """
    loaded = bound > 0.0
    v = anchor[loaded]
    b = bound[loaded]
    capacity = float(np.sum(b))
    if abs(target) > capacity * (1.0 + 1e-12):
        raise GrossSlidingError(
            f"no tangential equilibrium: |Ft|/(G* ds) = {abs(target):.6g} mm exceeds the friction capacity "
            f"sum mu (E*/G*) u_z = {capacity:.6g} mm (f_t = {abs(target) / capacity if capacity else math.inf:.6g}"
            f" > 1)")
    x = np.concatenate((v - b, v + b))
    order = np.argsort(x, kind="stable")
    xs = x[order]
    kinks = np.concatenate((np.ones(v.size), -np.ones(v.size)))[order]
    slope = np.cumsum(kinks)                      # slope on [xs[k], xs[k+1]]
    force = np.empty_like(xs)                     # function value at xs[k]
    force[0] = -capacity
    np.cumsum(slope[:-1] * np.diff(xs), out=force[1:])
    force[1:] -= capacity
    k = int(np.searchsorted(force, target, side="left"))
    if k == 0:
        return float(xs[0])
    if k >= xs.size:
        return float(xs[-1])
    U = xs[k - 1] + (target - force[k - 1]) / slope[k - 1]
    return float(min(U, xs[k]))
