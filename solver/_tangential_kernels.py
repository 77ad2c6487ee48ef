"""Element loops of the tangential solver (`solver.tangential`), compiled with numba (cache=True).

All fields are (ny, nx) or (2, ny, nx) float64 arrays on the grid; `region` is int8 with
0 = exterior (bound g = 0), 1 = stick (|tau| < g), 2 = slip (|tau| = g). Nothing here allocates a
grid-sized array; every kernel writes into buffers owned by the caller.

Notation (theory.md §5): w = A(tau - tau') + extra slip (mm), dU the rigid-shift increment (mm),
s = w - dU the slip of the step, n = tau/|tau| and t = (-n_y, n_x) in slip elements. `classify` stores
n of the slip elements in a (2, ny, nx) buffer `nrm` that the kernels of the same iteration read (one
square root per element and iteration instead of one per kernel); entries outside the slip area are not used.
"""
import math

import numba as nb


#: |tau| >= (1 - ON_BOUND) g counts as "on the bound" (slip). Renormalised and clipped elements sit
#: exactly on the bound, so this only absorbs round-off.
ON_BOUND = 1e-12

_jit = nb.njit(cache=True, nogil=True, fastmath=False)


@nb.njit(cache=True, inline="always")
def _mag(x, y):
    """|(x, y)|. Tractions (MPa) and slips (mm) are far from overflow, so the plain root serves: a third of
    the cost of math.hypot in these loops."""
    return math.sqrt(x * x + y * y)


@nb.njit(cache=True, inline="always")
def _a_tt(nrm, axx, ayy, j, i):
    """Self coefficient along the slip tangent t = (-n_y, n_x): t^T diag(a_xx, a_yy) t. The same as
    `_preconditioner.a_tt`, kept here because numba's cache is invalidated per file: an inlined function from
    another module would stay stale in these kernels' cache when it changes."""
    return axx * nrm[1, j, i] * nrm[1, j, i] + ayy * nrm[0, j, i] * nrm[0, j, i]


@nb.njit(cache=True, inline="always")
def _gram_terms(slip, nxv, nyv, wx, wy):
    """One element's terms of the shift fit (see `gram_and_fit`): (Gxx, Gxy, Gyy, bx, by) increments.

    Stick: the identity and w; slip (unit direction n = (nxv, nyv), tangent t = (-n_y, n_x)): t t^T and t (t.w).
    """
    if not slip:
        return 1.0, 0.0, 1.0, wx, wy
    tx = -nyv
    ty = nxv
    ws = tx * wx + ty * wy
    return tx * tx, tx * ty, ty * ty, tx * ws, ty * ws


@_jit
def classify(tau, g, region, nrm, u, u_prev, extra, has_extra, w):
    """Division and shift fit of the current iterate, in one pass.

    region from the traction alone (0 where g = 0, 2 where |tau| is on the bound, else 1); the unit
    direction n = tau/|tau| of the slip elements into nrm; the displacement change of the step
    w = u - u_prev (+ extra if has_extra) everywhere. Returns (n_stick, n_slip) and the sums of
    `gram_and_fit` for this division: (n_stick, n_slip, Gxx, Gxy, Gyy, bx, by).
    """
    ny, nx = g.shape
    n_stick = 0
    n_slip = 0
    gxx = 0.0
    gxy = 0.0
    gyy = 0.0
    bx = 0.0
    by = 0.0
    for j in range(ny):
        for i in range(nx):
            wx = u[0, j, i] - u_prev[0, j, i]
            wy = u[1, j, i] - u_prev[1, j, i]
            if has_extra:
                wx += extra[0, j, i]
                wy += extra[1, j, i]
            w[0, j, i] = wx
            w[1, j, i] = wy
            gi = g[j, i]
            if gi <= 0.0:
                region[j, i] = 0
                continue
            m = _mag(tau[0, j, i], tau[1, j, i])
            slip = m >= (1.0 - ON_BOUND) * gi
            nxv = nyv = 0.0
            if slip:
                region[j, i] = 2
                nxv = tau[0, j, i] / m
                nyv = tau[1, j, i] / m
                nrm[0, j, i] = nxv
                nrm[1, j, i] = nyv
                n_slip += 1
            else:
                region[j, i] = 1
                n_stick += 1
            a, b, c, d, e = _gram_terms(slip, nxv, nyv, wx, wy)
            gxx += a
            gxy += b
            gyy += c
            bx += d
            by += e
    return n_stick, n_slip, gxx, gxy, gyy, bx, by


@_jit
def gram_and_fit(nrm, region, w):
    """Least-squares shift fit: returns (Gxx, Gxy, Gyy, bx, by).

    G = sum_stick I + sum_slip t t^T is the Gram matrix of the force-constraint vectors restricted to
    the free directions; b = sum_stick w + sum_slip t (t.w). dU = G^-1 b makes the stick slip and the
    tangential slip component orthogonal to the constraint (the multiplier of sum tau = F/dA).
    `classify` returns the same sums; this kernel recomputes them after a release changed the division.
    """
    ny, nx = region.shape
    gxx = 0.0
    gxy = 0.0
    gyy = 0.0
    bx = 0.0
    by = 0.0
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r == 0:
                continue
            a, b, c, d, e = _gram_terms(r == 2, nrm[0, j, i], nrm[1, j, i], w[0, j, i], w[1, j, i])
            gxx += a
            gxy += b
            gyy += c
            bx += d
            by += e
    return gxx, gxy, gyy, bx, by


@nb.njit(cache=True, inline="always")
def _reversed_large(tau, nrm, g, region, w, dux, duy, big, j, i):
    """(turn?, sx, sy, |s|) of element (j, i): a slip element whose slip s = w - dU points along its traction
    (s.n > 0) and exceeds big g."""
    if region[j, i] != 2:
        return False, 0.0, 0.0, 0.0
    sx = w[0, j, i] - dux
    sy = w[1, j, i] - duy
    m = _mag(sx, sy)
    return sx * nrm[0, j, i] + sy * nrm[1, j, i] > 0.0 and m > big * g[j, i], sx, sy, m


@_jit
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


@_jit
def shift_stick(d, region, cx, cy):
    """d += (cx, cy) on the stick elements (the force-neutral part of a flip direction)."""
    ny, nx = region.shape
    for j in range(ny):
        for i in range(nx):
            if region[j, i] == 1:
                d[0, j, i] += cx
                d[1, j, i] += cy


@_jit
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


@_jit
def release(nrm, region, w, dux, duy, tol_abs):
    """Slip elements whose slip points along the traction (s.n > tol_abs) return to stick."""
    ny, nx = region.shape
    n = 0
    for j in range(ny):
        for i in range(nx):
            if region[j, i] == 2:
                sn = (w[0, j, i] - dux) * nrm[0, j, i] + (w[1, j, i] - duy) * nrm[1, j, i]
                if sn > tol_abs:
                    region[j, i] = 1
                    n += 1
    return n


@_jit
def residual(nrm, g, region, w, dux, duy, res, kappa, slip, axx, ayy):
    """Projected residual res = -P s (stick: -s; slip: -t (t.s)), curvature kappa = -s.n/g in slip.

    Also writes the slip of the step (s in slip elements, 0 in stick and exterior), and kappa for the
    preconditioner (`solver._preconditioner`). Returns (max |res_I| over stick
    and slip, max positive s.n over slip, stopping residual): the stopping residual is the largest slip error
    expressed through the element's own stiffness, in mm of a_tt: |s| in stick, |t.s| a_tt/(a_tt + kappa)
    in slip, where turning the traction is resisted by a_tt + kappa (kappa = max(-s.n, 0)/g), so that it is a_tt
    times the traction change that would remove the error of that element alone.
    """
    ny, nx = g.shape
    rmax = 0.0
    snmax = 0.0
    rstop = 0.0
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r == 0:
                res[0, j, i] = 0.0
                res[1, j, i] = 0.0
                kappa[j, i] = 0.0
                slip[0, j, i] = 0.0
                slip[1, j, i] = 0.0
                continue
            sx = w[0, j, i] - dux
            sy = w[1, j, i] - duy
            if r == 1:
                res[0, j, i] = -sx
                res[1, j, i] = -sy
                kappa[j, i] = 0.0
                slip[0, j, i] = 0.0
                slip[1, j, i] = 0.0
                a = _mag(sx, sy)
            else:
                nxv = nrm[0, j, i]
                nyv = nrm[1, j, i]
                ts = -nyv * sx + nxv * sy
                sn = nxv * sx + nyv * sy
                res[0, j, i] = nyv * ts
                res[1, j, i] = -nxv * ts
                kappa[j, i] = max(-sn, 0.0) / g[j, i]
                slip[0, j, i] = sx
                slip[1, j, i] = sy
                a = abs(ts)
                if sn > snmax:
                    snmax = sn
                att = _a_tt(nrm, axx, ayy, j, i)
                b = a * att / (att + kappa[j, i])
                if b > rstop:
                    rstop = b
            if a > rmax:
                rmax = a
            if r == 1 and a > rstop:
                rstop = a
    return rmax, snmax, rstop


@_jit
def conjugate(z, v, gamma):
    """v <- z + gamma v (in place)."""
    ny = z.shape[1]
    nx = z.shape[2]
    for c in range(2):
        for j in range(ny):
            for i in range(nx):
                v[c, j, i] = z[c, j, i] + gamma * v[c, j, i]


@_jit
def curvature_product(nrm, region, kappa, v, av, q, res):
    """q = P (A v) + kappa v (linearised slip-area operator applied to v); returns (v.q, res.v)."""
    ny, nx = region.shape
    vq = 0.0
    rv = 0.0
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r == 0:
                q[0, j, i] = 0.0
                q[1, j, i] = 0.0
                continue
            if r == 1:
                q[0, j, i] = av[0, j, i]
                q[1, j, i] = av[1, j, i]
            else:
                tx = -nrm[1, j, i]
                ty = nrm[0, j, i]
                qt = tx * av[0, j, i] + ty * av[1, j, i] + kappa[j, i] * (tx * v[0, j, i] + ty * v[1, j, i])
                q[0, j, i] = tx * qt
                q[1, j, i] = ty * qt
            vq += v[0, j, i] * q[0, j, i] + v[1, j, i] * q[1, j, i]
            rv += res[0, j, i] * v[0, j, i] + res[1, j, i] * v[1, j, i]
    return vq, rv


@_jit
def dot(a, b):
    s = 0.0
    for c in range(a.shape[0]):
        for j in range(a.shape[1]):
            for i in range(a.shape[2]):
                s += a[c, j, i] * b[c, j, i]
    return s


@_jit
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


@_jit
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