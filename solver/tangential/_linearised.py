"""The linearised problem of the tangential solver on a fixed stick/slip division: the projected residual and
stopping measure, the curvature operator P (A v) + kappa v and the vector operations of the CG recurrence
(numba kernels of `solver.tangential._tangcg`; conventions and notation in `solver.tangential._common`).

Tractions MPa, displacements and slips mm, curvature kappa mm/MPa.
"""
from rollcontact.bem.compiled import inline, kernel

from rollcontact.solver.tangential._common import _mag


@inline
def _a_tt(nrm, axx, ayy, j, i):
    """Self coefficient along the slip tangent t = (-n_y, n_x): t^T diag(a_xx, a_yy) t. The same as
    `_preconditioner.a_tt`, kept here because numba's cache is invalidated per file: an inlined function from
    another module would stay stale in these kernels' cache when it changes."""
    return axx * nrm[1, j, i] * nrm[1, j, i] + ayy * nrm[0, j, i] * nrm[0, j, i]


@kernel("UniTuple(f8, 3)(f8[:, :, ::1], f8[:, ::1], i1[:, ::1], f8[:, :, ::1], f8, f8, f8[:, :, ::1], f8[:, "
        "::1], f8[:, :, ::1], f8, f8)")
def residual(nrm, g, region, w, dux, duy, res, kappa, slip, axx, ayy):
    """Projected residual res = -P s (stick: -s; slip: -t (t.s)), curvature kappa = -s.n/g in slip.

    Also writes the slip of the step (s in slip elements, 0 in stick and exterior), and kappa for the
    preconditioner (`solver.tangential._preconditioner`). Returns (max |res_I| over stick
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


@kernel("void(f8[:, :, ::1], f8[:, :, ::1], f8)")
def conjugate(z, v, gamma):
    """v <- z + gamma v (in place)."""
    ny = z.shape[1]
    nx = z.shape[2]
    for c in range(2):
        for j in range(ny):
            for i in range(nx):
                v[c, j, i] = z[c, j, i] + gamma * v[c, j, i]


@kernel("UniTuple(f8, 2)(f8[:, :, ::1], i1[:, ::1], f8[:, ::1], f8[:, :, ::1], f8[:, :, ::1], f8[:, :, ::1], "
        "f8[:, :, ::1])")
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


@kernel("f8(f8[:, :, ::1], f8[:, :, ::1])")
def dot(a, b):
    s = 0.0
    for c in range(a.shape[0]):
        for j in range(a.shape[1]):
            for i in range(a.shape[2]):
                s += a[c, j, i] * b[c, j, i]
    return s
