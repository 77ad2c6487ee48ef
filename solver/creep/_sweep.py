"""Compiled element loops of the steady rolling Gauss-Seidel solver (`solver.creep.steady`; docs/theory.md §11.5, §5.3).

Fields are (2, ny, nx) float64 arrays on the contact-fixed grid, index [k, j, i] the component k (x, y) at the
cell (x_i, y_j); body 1 rolls in +x, so the cell upstream of (j, i) is (j, i + 1). Kernels are the dense
Toeplitz influence arrays kxx, kxy, kyy of shape (2 ny - 1, 2 nx - 1): entry [oy + ny - 1, ox + nx - 1] is the
displacement (mm) at offset (ox dx, oy dy) from a unit traction (1 MPa) on an element.

The unknowns of the sweep are, as in Kalker's SteadyGS, the traction differences along the rolling direction
dp_I = p_I - p_{I+1}: with a Toeplitz A the upwind displacement difference is u_I - u_{I+1} = (A dp)_I, so the
slip is s = w + A dp / dx with the symmetric positive definite A (the traction itself would meet the
non-symmetric, non-diagonally-dominant operator (I - shift) A, on which an element sweep diverges). Changing
the traction of element I by delta changes dp at I by +delta; downstream, elements in stick keep their dp (the
change is carried down the row with their traction), elements in slip keep their traction (their dp absorbs
it), and the first cell out of contact takes the rest.
"""
import numpy as np

from rollcontact.bem.compiled import internal, kernel

EXTERIOR, STICK, SLIP = 0, 1, 2


@internal
def local_solve(rx, ry, bx, by, bound):
    """The element's 2x2 problem s = b tau + r (b diagonal, > 0) with Coulomb's law |tau| <= bound.

    Stick if the traction that zeroes s lies inside the disc; otherwise slip, s = -lam tau with lam >= 0 and
    |tau| = bound, i.e. tau_k = -r_k / (b_k + lam): lam is the root of sum_k r_k^2/(b_k + lam)^2 = bound^2,
    found by Newton from below (the function is convex and decreasing, so the iterates rise monotonically).
    Returns (tau_x, tau_y, in_slip).
    """
    tx = -rx / bx
    ty = -ry / by
    if tx * tx + ty * ty <= bound * bound:
        return tx, ty, False
    if bound <= 0.0:
        return 0.0, 0.0, True
    rn = np.sqrt(rx * rx + ry * ry)
    lam = max(0.0, rn / bound - max(bx, by))
    for _ in range(100):
        dx = bx + lam
        dy = by + lam
        f = (rx / dx) ** 2 + (ry / dy) ** 2 - bound * bound
        df = -2.0 * (rx * rx / dx ** 3 + ry * ry / dy ** 3)
        step = -f / df
        lam += step
        if step <= 1e-14 * (lam + bx):
            break
    return -rx / (bx + lam), -ry / (by + lam), True


@internal
def _carry_down(j, i, tau, dp, status, bound, lo):
    """After element (j, i) changed: update the row downstream (x < x_i) as the module docstring says."""
    for ii in range(i - 1, lo - 1, -1):
        st = status[j, ii]
        if st == STICK:
            for k in range(2):
                tau[k, j, ii] = tau[k, j, ii + 1] + dp[k, j, ii]
            norm = np.sqrt(tau[0, j, ii] ** 2 + tau[1, j, ii] ** 2)
            if norm > bound[j, ii]:
                f = bound[j, ii] / norm
                for k in range(2):
                    tau[k, j, ii] *= f
                    dp[k, j, ii] = tau[k, j, ii] - tau[k, j, ii + 1]
        else:  # slip keeps its traction; a cell out of contact keeps tau = 0
            for k in range(2):
                dp[k, j, ii] = tau[k, j, ii] - tau[k, j, ii + 1]


@kernel("f8(i8, f8[:, :, ::1], f8[:, :, ::1], f8[:, :, ::1], i1[:, ::1], f8[:, ::1], f8[:, :, ::1], f8[::1], "
        "f8[::1], f8, i8, i8, f8[:, ::1], f8, b1)")
def row_sweep(j, rigid, tau, dp, status, bound, disp, row_xx, row_yy, inv_dx, lo, hi, dp_start, omega,
              with_flow):
    """Gauss-Seidel over the contact cells of row j, from the trailing edge (lo) to the leading edge (hi - 1), or with
    the material's flow, from the leading edge to the trailing one (`with_flow`: an operator with memory, whose
    displacement at a cell depends most on the traction upstream, is then swept as a forward substitution).

    rigid: the rigid slip (2, ny, nx); tau, dp: traction (MPa) and its difference to the upstream cell, kept
    consistent; status: EXTERIOR / STICK / SLIP per cell (int8), updated; bound: mu p (MPa, inf for no limit);
    disp: A dp (mm) as it was when the row started; row_xx, row_yy: the in-row kernels A^xx(ox dx, 0),
    A^yy(ox dx, 0) at index ox + nx - 1, ox the target minus the source column (any Toeplitz kernel, also one not
    even in x, e.g. steady viscoelastic rolling; A^xy vanishes on a row); dp_start: dp of the row when it started.
    omega: over-relaxation factor of the stick elements (1 = plain Gauss-Seidel).
    The row's own changes are added to disp exactly, element by element; the caller carries them to the
    other rows afterwards. Returns the largest change of a traction (MPa) in the row.
    """
    nx = tau.shape[2]
    c0x = row_xx[nx - 1]
    c0y = row_yy[nx - 1]
    change = 0.0
    for k in range(hi - lo):
        i = hi - 1 - k if with_flow else lo + k
        if status[j, i] == EXTERIOR:
            continue
        jx = i - 1
        while jx > lo and status[j, jx] == STICK:
            jx -= 1
        bx = (c0x - row_xx[nx - 1 + i - jx]) * inv_dx
        by = (c0y - row_yy[nx - 1 + i - jx]) * inv_dx
        ux = disp[0, j, i]
        uy = disp[1, j, i]
        for ii in range(lo, hi):
            m = i - ii + nx - 1
            ux += row_xx[m] * (dp[0, j, ii] - dp_start[0, ii])
            uy += row_yy[m] * (dp[1, j, ii] - dp_start[1, ii])
        tx = tau[0, j, i]
        ty = tau[1, j, i]
        rx = rigid[0, j, i] + ux * inv_dx - bx * tx
        ry = rigid[1, j, i] + uy * inv_dx - by * ty
        nx_, ny_, slipping = local_solve(rx, ry, bx, by, bound[j, i])
        status[j, i] = SLIP if slipping else STICK
        if not slipping and omega != 1.0:  # over-relaxation in stick, kept inside the Coulomb disc
            nx_ = tx + omega * (nx_ - tx)
            ny_ = ty + omega * (ny_ - ty)
            norm = np.sqrt(nx_ * nx_ + ny_ * ny_)
            if norm > bound[j, i]:
                nx_ *= bound[j, i] / norm
                ny_ *= bound[j, i] / norm
        dtx = nx_ - tx
        dty = ny_ - ty
        tau[0, j, i] = nx_
        tau[1, j, i] = ny_
        dp[0, j, i] += dtx
        dp[1, j, i] += dty
        _carry_down(j, i, tau, dp, status, bound, lo)
        d = np.sqrt(dtx * dtx + dty * dty)
        if d > change:
            change = d
    return change
