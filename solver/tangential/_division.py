"""The stick/slip division of the tangential solver and the least-squares fit of the rigid shift (numba kernels
of `solver.tangential._tangcg`; conventions and notation in `solver.tangential._common`).

`classify` divides the contact by the current traction (stick |tau| < g, slip |tau| on the bound) and sums the
shift fit in the same pass; `gram_and_fit` recomputes the fit after `release` returned slip elements whose
slip points along their traction to stick. Tractions and bounds MPa, displacements and slips mm.
"""
from rollcontact.bem.compiled import inline, kernel

from rollcontact.solver.tangential._common import _mag


#: |tau| >= (1 - ON_BOUND) g counts as "on the bound" (slip). Renormalised and clipped elements sit
#: exactly on the bound, so this only absorbs round-off.
ON_BOUND = 1e-12


@inline
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


@inline
def _add_gram_terms(sums, slip, nxv, nyv, wx, wy):
    """sums (Gxx, Gxy, Gyy, bx, by) plus one element's terms (`_gram_terms`)."""
    a, b, c, d, e = _gram_terms(slip, nxv, nyv, wx, wy)
    return sums[0] + a, sums[1] + b, sums[2] + c, sums[3] + d, sums[4] + e


#: the empty sums of the shift fit (Gxx, Gxy, Gyy, bx, by)
_NO_TERMS = (0.0, 0.0, 0.0, 0.0, 0.0)


@kernel("Tuple((i8, i8, f8, f8, f8, f8, f8))(f8[:, :, ::1], f8[:, ::1], i1[:, ::1], f8[:, :, ::1], f8[:, :, "
        "::1], f8[:, :, ::1], f8[:, :, ::1], b1, f8[:, :, ::1])")
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
    sums = _NO_TERMS
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
            sums = _add_gram_terms(sums, slip, nxv, nyv, wx, wy)
    gxx, gxy, gyy, bx, by = sums
    return n_stick, n_slip, gxx, gxy, gyy, bx, by


@kernel("UniTuple(f8, 5)(f8[:, :, ::1], i1[:, ::1], f8[:, :, ::1])")
def gram_and_fit(nrm, region, w):
    """Least-squares shift fit: returns (Gxx, Gxy, Gyy, bx, by).

    G = sum_stick I + sum_slip t t^T is the Gram matrix of the force-constraint vectors restricted to
    the free directions; b = sum_stick w + sum_slip t (t.w). dU = G^-1 b makes the stick slip and the
    tangential slip component orthogonal to the constraint (the multiplier of sum tau = F/dA).
    `classify` returns the same sums; this kernel recomputes them after a release changed the division.
    """
    ny, nx = region.shape
    sums = _NO_TERMS
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r != 0:
                sums = _add_gram_terms(sums, r == 2, nrm[0, j, i], nrm[1, j, i], w[0, j, i], w[1, j, i])
    return sums


@kernel("i8(f8[:, :, ::1], i1[:, ::1], f8[:, :, ::1], f8, f8, f8)")
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
