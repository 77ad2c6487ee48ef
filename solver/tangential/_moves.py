"""Moves of the tangential tractions that keep them on the Coulomb discs |tau| <= g: the CG step with its
renormalisations and projections (`step`), the restoration of the total force by the stick tractions
(`restore_force`), and the turns of slip elements whose slip points along their traction (`flip_direction`,
`shift_stick`, `apply_flip`). Numba kernels of `solver.tangential._tangcg` and `solver.tangential._force_projection`; conventions and
notation in `solver.tangential._common`.

Tractions and bounds MPa, displacements and slips mm, forces as sums of tractions over the elements
(MPa x elements).
"""
from rollcontact.bem.compiled import inline, kernel

from rollcontact.solver.tangential._common import _mag


@inline
def _reversed_large(tau, nrm, g, region, w, dux, duy, big, j, i):
    """(turn?, sx, sy, |s|) of element (j, i): a slip element whose slip s = w - dU points along its traction
    (s.n > 0) and exceeds big g."""
    if region[j, i] != 2:
        return False, 0.0, 0.0, 0.0
    sx = w[0, j, i] - dux
    sy = w[1, j, i] - duy
    m = _mag(sx, sy)
    return sx * nrm[0, j, i] + sy * nrm[1, j, i] > 0.0 and m > big * g[j, i], sx, sy, m


@kernel("Tuple((i8, f8, f8))(f8[:, :, ::1], f8[:, :, ::1], f8[:, ::1], i1[:, ::1], f8[:, :, ::1], f8, f8, "
        "f8, f8[:, :, ::1])")
def flip_direction(tau, nrm, g, region, w, dux, duy, big, d):
    """d <- the change that turns each slip element whose slip points along its traction and is large
    (s.n > 0, |s| > big g, big in mm/MPa) to oppose its slip: d = -g s/|s| - tau there, 0 elsewhere.
    Returns (number of such elements, sum d_x, sum d_y); d is written only when there is one (a first pass
    counts, without writing a grid buffer in the common case of none)."""
    ny, nx = region.shape
    n = 0
    for j in range(ny):
        for i in range(nx):
            if _reversed_large(tau, nrm, g, region, w, dux, duy, big, j, i)[0]:
                n += 1
    cx = 0.0
    cy = 0.0
    if n == 0:
        return n, cx, cy
    for j in range(ny):
        for i in range(nx):
            turn, sx, sy, m = _reversed_large(tau, nrm, g, region, w, dux, duy, big, j, i)
            if turn:
                d[0, j, i] = -g[j, i] * sx / m - tau[0, j, i]
                d[1, j, i] = -g[j, i] * sy / m - tau[1, j, i]
                cx += d[0, j, i]
                cy += d[1, j, i]
            else:
                d[0, j, i] = 0.0
                d[1, j, i] = 0.0
    return n, cx, cy


@kernel("void(f8[:, :, ::1], i1[:, ::1], f8, f8)")
def shift_stick(d, region, cx, cy):
    """d += (cx, cy) on the stick elements (the force-neutral part of a flip direction)."""
    ny, nx = region.shape
    for j in range(ny):
        for i in range(nx):
            if region[j, i] == 1:
                d[0, j, i] += cx
                d[1, j, i] += cy


@kernel("i8(f8[:, :, ::1], f8[:, :, ::1], f8, f8[:, :, ::1], f8[:, :, ::1], b1, f8[:, ::1], i1[:, ::1], f8, f8)")
def apply_flip(tau, d, t, u, ad, exact, g, region, axx, ayy):
    """tau += t d for a flip direction from `flip_direction` (+ `shift_stick`); u += t A d (ad = A d) if exact,
    else u += t diag(a_xx, a_yy) d (self coefficients, the caller re-synchronises).

    A turned slip element stays on its rim (renormalised) when t = 1; for t < 1 it lies on the chord inside its
    disc and becomes stick. Stick elements pushed out of their disc by the force-neutral shift are projected
    onto it and become slip (u by the self coefficients there). Returns the number of elements projected."""
    ny, nx = region.shape
    n_proj = 0
    for j in range(ny):
        for i in range(nx):
            if exact:  # on the whole grid (see `step`)
                u[0, j, i] += t * ad[0, j, i]
                u[1, j, i] += t * ad[1, j, i]
            r = region[j, i]
            if r == 0:
                continue
            dx = d[0, j, i]
            dy = d[1, j, i]
            if not exact:
                u[0, j, i] += t * axx * dx
                u[1, j, i] += t * ayy * dy
            if dx == 0.0 and dy == 0.0:
                continue
            tx = tau[0, j, i] + t * dx
            ty = tau[1, j, i] + t * dy
            m = _mag(tx, ty)
            gi = g[j, i]
            if r == 2:
                if t >= 1.0:
                    tx *= gi / m
                    ty *= gi / m
                else:
                    region[j, i] = 1
            elif m > gi:
                f = gi / m
                u[0, j, i] += axx * (tx * f - tx)
                u[1, j, i] += ayy * (ty * f - ty)
                tx *= f
                ty *= f
                region[j, i] = 2
                n_proj += 1
            tau[0, j, i] = tx
            tau[1, j, i] = ty
    return n_proj


@kernel("Tuple((i8, f8, f8, f8, i8))(f8[:, :, ::1], f8[:, :, ::1], f8, f8[:, :, ::1], f8[:, :, ::1], f8[:, "
        "::1], i1[:, ::1], f8, f8, f8)")
def step(tau, v, alpha, u, av, g, region, axx, ayy, max_turn):
    """tau += alpha v, u += alpha A v, then back onto the discs.

    Slip elements are renormalised to |tau| = g (the linearised step moves along the tangent);
    stick elements that leave their disc are projected radially onto it and become slip. The
    displacement of these small local corrections is added with the self coefficients only (the
    caller re-synchronises u = A tau exactly before accepting convergence). Returns
    (number of stick elements clipped, max |correction| in MPa, and for
    `restore_force`: sum tau x, y and the number of stick elements after the step).
    """
    ny, nx = g.shape
    n_clip = 0
    dmax = 0.0
    fx = 0.0
    fy = 0.0
    n_stick = 0
    for j in range(ny):
        for i in range(nx):
            # u = A tau on the whole grid, outside the contact too: the returned displacement and the product
            # memo hand it to the next step, whose contact may cover these elements (a stale exterior made the
            # next step converge to a wrong answer when no re-synchronisation happened, e.g. an all-stick step)
            u[0, j, i] += alpha * av[0, j, i]
            u[1, j, i] += alpha * av[1, j, i]
            r = region[j, i]
            if r == 0:
                continue
            gi = g[j, i]
            ax = alpha * v[0, j, i]
            ay = alpha * v[1, j, i]
            if r == 2:
                # trust region on the rotation of a slip traction: the linearisation about the current
                # direction is only valid for small angles (a large tangent step would also be
                # shortened arbitrarily by the renormalisation); counted as a projection event
                am = _mag(ax, ay)
                if am > max_turn * gi:
                    f = max_turn * gi / am
                    u[0, j, i] += axx * (ax * f - ax)
                    u[1, j, i] += ayy * (ay * f - ay)
                    ax *= f
                    ay *= f
                    n_clip += 1
            tx = tau[0, j, i] + ax
            ty = tau[1, j, i] + ay
            m = _mag(tx, ty)
            if r == 2 or m > gi:
                if r == 1:
                    n_clip += 1
                    region[j, i] = 2
                f = gi / m
                dx = tx * f - tx
                dy = ty * f - ty
                tx += dx
                ty += dy
                u[0, j, i] += axx * dx
                u[1, j, i] += ayy * dy
                d = _mag(dx, dy)
                if d > dmax:
                    dmax = d
            else:
                n_stick += 1
            tau[0, j, i] = tx
            tau[1, j, i] = ty
            fx += tx
            fy += ty
    return n_clip, dmax, fx, fy, n_stick


@kernel("i8(f8[:, :, ::1], i1[:, ::1], f8[:, ::1], f8, f8, f8[:, :, ::1], f8, f8, f8, f8, f8, i8)")
def restore_force(tau, region, g, fx, fy, u, axx, ayy, tol_abs, sx, sy, n_stick):
    """Put the total force back on (fx, fy) (MPa x elements) by uniform shifts of the stick tractions.

    (sx, sy) = sum tau and n_stick are the current ones (from `step`, or summed by the caller). Stick elements
    pushed out of their disc are projected and become slip, and the shift is repeated for the remainder (at
    most 20 times); the displacement of the shift is added with the self coefficients. Returns 0 when
    |sum tau - f| <= tol_abs, 1 when no stick element is left or the remainder persists (the caller then
    projects onto the force).
    """
    ny, nx = region.shape
    for _ in range(20):
        dx = fx - sx
        dy = fy - sy
        if _mag(dx, dy) <= tol_abs:
            return 0
        if n_stick == 0:
            return 1
        lx = dx / n_stick
        ly = dy / n_stick
        sx = 0.0
        sy = 0.0
        n_stick = 0
        for j in range(ny):
            for i in range(nx):
                r = region[j, i]
                if r == 1:
                    tx = tau[0, j, i] + lx
                    ty = tau[1, j, i] + ly
                    m = _mag(tx, ty)
                    if m > g[j, i]:
                        f = g[j, i] / m
                        tx *= f
                        ty *= f
                        region[j, i] = 2
                    else:
                        n_stick += 1
                    u[0, j, i] += axx * (tx - tau[0, j, i])
                    u[1, j, i] += ayy * (ty - tau[1, j, i])
                    tau[0, j, i] = tx
                    tau[1, j, i] = ty
                if r != 0:
                    sx += tau[0, j, i]
                    sy += tau[1, j, i]
    dx = fx - sx
    dy = fy - sy
    return 0 if _mag(dx, dy) <= tol_abs else 1
