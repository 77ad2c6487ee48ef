"""Compiled element loops of NormCG (solver.normal; docs/theory.md §4.3): one pass each over the grid.

The per-iteration element work of `solver.normal.solve_normal`, on flat, contiguous float64 arrays of the
(ny, nx) grid: the projected preconditioned residual and search direction (`_direction`), the step with the
truncation of negative pressures (`_step`), the exact influence-column correction of truncated elements
(`_add_columns`), and the deformed gap with the CG residual and the entering elements
(`_residual_and_entries`). Units: p in MPa, u, h, d, e in mm, influence coefficients in mm/MPa.
"""
from rollcontact.bem.compiled import kernel

# --- numba kernels (flat, contiguous float64 arrays; one pass each) ----------------------------------

@kernel("f8(f8[::1], f8[::1], f8[::1], f8[::1], f8, b1[::1], b1)")
def _direction(z, r, r_prev, v, rz_old, active, deflate):
    """The projected preconditioned residual and the new search direction, in place. Returns r.z.

    z <- P_C z (zero off C; zero mean over C if deflate), then v <- P_C (z + beta v) with the
    Polak-Ribiere beta = max(0, (r.z - r_prev.z) / rz_old) (beta = 0, steepest descent, if rz_old = 0).
    """
    n = z.size
    shift = 0.0
    if deflate:
        s = 0.0
        count = 0
        for i in range(n):
            if active[i]:
                s += z[i]
                count += 1
        if count > 0:
            shift = s / count
    rz = 0.0
    rpz = 0.0
    for i in range(n):
        if active[i]:
            zi = z[i] - shift
            z[i] = zi
            rz += r[i] * zi
            rpz += r_prev[i] * zi
        else:
            z[i] = 0.0
    beta = max(0.0, (rz - rpz) / rz_old) if rz_old > 0.0 else 0.0
    s = 0.0
    count = 0
    for i in range(n):
        if active[i]:
            vi = z[i] + beta * v[i]
            v[i] = vi
            s += vi
            count += 1
        else:
            v[i] = 0.0
    if deflate and count > 0 and beta != 0.0:
        shift = s / count
        for i in range(n):
            if active[i]:
                v[i] -= shift
    return rz


@kernel("Tuple((i8, f8, f8, f8))(f8[::1], f8[::1], f8[::1], f8[::1], f8[::1], b1[::1], i8[::1], f8[::1])")
def _step(p, u, v, q, r, active, trunc_index, trunc_value):
    """Step alpha = (r.v)/(v.q) along v (alpha = 0 if v.q <= 0, i.e. v = 0: the residual vanishes on C):
    p <- max(0, p + alpha v) on C, u <- u + alpha q everywhere.

    Elements whose pressure would turn negative leave C; their index and the missing pressure
    (-(p + alpha v) > 0, to be added back to u through A) are stored in trunc_index/trunc_value up to
    their capacity. Returns (number truncated, sum p, sum (p_new - p_old)^2, sum p_new^2).
    """
    rv = 0.0
    vq = 0.0
    for i in range(v.size):
        rv += r[i] * v[i]
        vq += v[i] * q[i]
    alpha = rv / vq if vq > 0.0 else 0.0
    ntrunc = 0
    cap = trunc_index.size
    psum = 0.0
    dp2 = 0.0
    p2 = 0.0
    for i in range(p.size):
        u[i] += alpha * q[i]
        if active[i]:
            old = p[i]
            new = old + alpha * v[i]
            if new < 0.0:
                if ntrunc < cap:
                    trunc_index[ntrunc] = i
                    trunc_value[ntrunc] = -new
                ntrunc += 1
                active[i] = False
                new = 0.0
            p[i] = new
            psum += new
            dp2 += (new - old) * (new - old)
            p2 += new * new
    return ntrunc, psum, dp2, p2


@kernel("void(f8[::1], f8[:, ::1], i8, i8[::1], f8[::1], i8)")
def _add_columns(u, kernel, nx, index, value, count):
    """u[j, i] += sum_t value_t K[(j - j_t) mod Py, (i - i_t) mod Px]: exact A^zz times a sparse field.

    u is the flat (ny*nx) field, kernel the wrapped (Py, Px) influence array of the padded domain.
    Row-major over u (outer loop over rows), so each row of u stays in cache for all columns.
    """
    py, px = kernel.shape
    ny = u.size // nx
    for j in range(ny):
        base = j * nx
        for t in range(count):
            jt = index[t] // nx
            it = index[t] % nx
            val = value[t]
            krow = kernel[(j - jt) % py]
            off = px - it
            for i in range(it):
                u[base + i] += val * krow[off + i]
            for i in range(it, nx):
                u[base + i] += val * krow[i - it]


@kernel("Tuple((f8, i8, f8, f8))(f8[::1], f8[::1], f8, b1[::1], f8[::1], b1, b1)")
def _residual_and_entries(u, h_eff, approach, active, r, deflate, admit):
    """Deformed gap e = u + h_eff - d and the CG residual r = -e on C (after C is updated).

    In force mode (deflate) d = mean_C (u + h_eff) is returned; otherwise d is the given approach.
    If admit, exterior elements with e < 0 enter C (residual -e). Returns (d, number entered,
    max_C |e|, max_C u).
    """
    n = u.size
    d = approach
    if deflate:
        s = 0.0
        count = 0
        for i in range(n):
            if active[i]:
                s += u[i] + h_eff[i]
                count += 1
        if count > 0:
            d = s / count
    entered = 0
    emax = 0.0
    umax = 0.0
    for i in range(n):
        e = u[i] + h_eff[i] - d
        if active[i]:
            r[i] = -e
            if abs(e) > emax:
                emax = abs(e)
            if u[i] > umax:
                umax = u[i]
        elif e < 0.0 and admit:
            active[i] = True
            r[i] = -e
            entered += 1
        else:
            r[i] = 0.0
    return d, entered, emax, umax
