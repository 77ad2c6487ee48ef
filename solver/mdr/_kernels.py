"""Compiled MDR step (numba, cached): the kernels behind `solver.mdr.simulate_mdr` (docs/theory.md §8.2).

Numba twins of `solver.mdr.step` for the gaps g_i of the springs (the sphere's (s - centre)^2 / R, or any
axisymmetric profile's MDR profile g(s - centre) computed by the caller; s, centre, R, d, U, anchors and bounds
in mm; the force targets are Fn/(E* ds) and Ft/(G* ds), mm), and one whole step of the spring row in place on
the anchors.  Errors are returned as status codes, not raised.
"""
import numpy as np
from rollcontact.bem.compiled import kernel


# ------------------------------------------------------------------- compiled step (numba, cached)
@kernel("Tuple((f8, i8))(f8[::1], f8, f8)")
def _approach_kernel(gap, target, d_guess):
    """Numba twin of `approach_for_force` for the gaps g_i (mm); returns (d, n_contact) or (nan, -1).

    Starts from d_guess (the previous step's approach): from the left, the first Newton step of the convex
    force-approach function lands right of the root; from there the iterates decrease monotonically.
    """
    gmin = np.inf
    for i in range(gap.size):
        if gap[i] < gmin:
            gmin = gap[i]
    d = d_guess if d_guess > gmin else gmin + target
    count = -1
    for _ in range(200):
        n = 0
        acc = 0.0
        for i in range(gap.size):
            if gap[i] < d:
                n += 1
                acc += gap[i]
        if n == count:
            return d, n
        count = n
        d = (target + acc) / n
    return np.nan, -1


@kernel("Tuple((f8, i8))(f8[::1], f8[::1], f8, f8)")
def _rigid_shift_kernel(v, b, target, U_guess):
    """Numba root of sum clip(U - v_i, -b_i, b_i) = target (all b_i > 0); returns (U, status).

    status 0: solved; 1: |target| > sum b (gross sliding).  A few Newton steps from the previous U shrink a
    bracket (usually they already land on the exact linear piece, `_newton_bracket`); the break points left
    inside the bracket are then sorted and walked (`_walk_break_points`), which makes the result exact like
    `rigid_shift`.
    """
    m = v.size
    cap = 0.0
    xmin = np.inf
    xmax = -np.inf
    for i in range(m):
        cap += b[i]
        xmin = min(xmin, v[i] - b[i])
        xmax = max(xmax, v[i] + b[i])
    if abs(target) > cap * (1.0 + 1e-12):
        return np.nan, 1
    if m == 0 or target <= -cap:
        return (xmin if m else U_guess), 0
    if target >= cap:
        return xmax, 0
    solved, U, lo, flo, hi = _newton_bracket(v, b, target, cap, min(max(U_guess, xmin), xmax), xmin, xmax)
    if solved:
        return U, 0
    return _walk_break_points(v, b, target, lo, flo, hi), 0


@kernel("Tuple((b1, f8, f8, f8, f8))(f8[::1], f8[::1], f8, f8, f8, f8, f8)")
def _newton_bracket(v, b, target, cap, U, lo, hi):
    """At most six Newton steps on F(U) = sum clip(U - v_i, -b_i, b_i) = target from U inside the bracket
    (lo, hi) = (min(v - b), max(v + b)), where F(lo) = -cap = -sum b; every iterate shrinks the bracket.

    Returns (solved, U, lo, F(lo), hi): solved when F(U) = target to 1e-14 cap; otherwise the bracket for
    `_walk_break_points`, left when a step would leave it or meets a flat piece.
    """
    flo = -cap
    for _ in range(6):
        F = 0.0
        k_right = 0
        k_left = 0
        for i in range(v.size):
            x = U - v[i]
            if x >= b[i]:
                F += b[i]
            elif x <= -b[i]:
                F -= b[i]
            else:
                F += x
            if -b[i] <= x < b[i]:
                k_right += 1
            if -b[i] < x <= b[i]:
                k_left += 1
        if abs(F - target) <= 1e-14 * cap:
            return True, U, lo, flo, hi
        if F < target:
            if U > lo:
                lo, flo = U, F
            slope = k_right
        else:
            hi = min(hi, U)
            slope = k_left
        if slope == 0:
            break
        Un = U + (target - F) / slope
        if not (lo < Un < hi):
            break
        U = Un
    return False, U, lo, flo, hi


@kernel("f8(f8[::1], f8[::1], f8, f8, f8, f8)")
def _walk_break_points(v, b, target, lo, flo, hi):
    """Exact root of F(U) = target in (lo, hi), F(lo) = flo < target: the break points v_i -+ b_i inside the
    bracket are sorted and F, linear between them, is followed until it reaches the target."""
    m = v.size
    xs = np.empty(2 * m)
    ks = np.empty(2 * m)
    n = 0
    slope = 0.0
    for i in range(m):
        if v[i] - b[i] <= lo < v[i] + b[i]:
            slope += 1.0
        for x, kink in ((v[i] - b[i], 1.0), (v[i] + b[i], -1.0)):
            if lo < x < hi:
                xs[n] = x
                ks[n] = kink
                n += 1
    order = np.argsort(xs[:n])
    x_prev = lo
    F = flo
    for j in range(n):
        x = xs[order[j]]
        F_next = F + slope * (x - x_prev)
        if F_next >= target:
            return x_prev + (target - F) / slope
        F = F_next
        slope += ks[order[j]]
        x_prev = x
    if slope > 0.0:
        return min(x_prev + (target - F) / slope, hi)
    return hi


@kernel("Tuple((f8, f8, i8, i8, i8))(f8[::1], f8[::1], f8, f8, f8, f8, f8, f8, f8, f8[::1], f8[::1], f8[::1])")
def _step_kernel(s, anchor, centre, R, target_n, d_guess, ratio, target_t, U_guess, v_buf, b_buf, gap_buf):
    """One MDR step of the sphere, gap (s - centre)^2/R (in gap_buf), in place on `anchor`: `_step_gap_kernel`."""
    for i in range(s.size):
        gap_buf[i] = (s[i] - centre) ** 2 / R
    return _step_gap_kernel(gap_buf, anchor, target_n, d_guess, ratio, target_t, U_guess, v_buf, b_buf)


@kernel("Tuple((f8, f8, i8, i8, i8))(f8[::1], f8[::1], f8, f8, f8, f8, f8, f8[::1], f8[::1])")
def _step_gap_kernel(gap, anchor, target_n, d_guess, ratio, target_t, U_guess, v_buf, b_buf):
    """One MDR step for the gaps g_i (mm) of the springs in place on `anchor`; returns (d, U, n_contact,
    n_stick, status).

    status 0 ok, 1 gross sliding (anchor untouched), 2 normal problem did not settle.
    """
    d, n_contact = _approach_kernel(gap, target_n, d_guess)
    if n_contact < 0:
        return np.nan, np.nan, 0, 0, 2
    m = 0
    for i in range(gap.size):
        uz = d - gap[i]
        if uz > 0.0:
            v_buf[m] = anchor[i]
            b_buf[m] = ratio * uz
            m += 1
    U, status = _rigid_shift_kernel(v_buf[:m], b_buf[:m], target_t, U_guess)
    if status != 0:
        return d, np.nan, n_contact, 0, status
    n_stick = 0
    for i in range(gap.size):
        uz = d - gap[i]
        bound = ratio * uz if uz > 0.0 else 0.0
        defl = min(max(U - anchor[i], -bound), bound)
        anchor[i] = U - defl
        if uz > 0.0 and abs(defl) < bound * (1.0 - 1e-12):
            n_stick += 1
    return d, U, n_contact, n_stick, 0
