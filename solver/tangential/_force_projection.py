"""Placing a traction field on the Coulomb discs and the force constraint (docs/theory.md §5).

Used by the tangential solver (`solver.tangential`): the start of a step (`start_traction`: the Euclidean
projection `project_on_force`, or `place_on_force` when the previous division is given), and the restoration
of the total force after the renormalisations of the slip tractions (`restore_force`: a uniform shift of the
stick tractions, or, with none left, a turn of the slip tractions along their rims). Fields are (2, ny, nx)
tractions and (ny, nx) bounds g = mu p in MPa; f = F/dA is the prescribed sum of the tractions over the
elements (MPa).
"""
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.bem.compiled import kernel
from rollcontact.solver.tangential._common import _mag
from rollcontact.solver.tangential._division import ON_BOUND
from rollcontact.solver.tangential._moves import restore_force as _kernel_restore_force


_NO_RING = np.zeros((1, 1), np.int8)


def project_discs(tau, g):
    """tau <- radial projection onto |tau_I| <= g_I; zero where g = 0 (in place)."""
    force_projection_eval(tau, g, 0.0, 0.0, tau, _NO_RING)  # element by element, so in place is safe


@kernel("UniTuple(f8, 6)(f8[:, :, ::1], f8[:, ::1], f8, f8, f8[:, :, ::1], i1[:, ::1])")
def force_projection_eval(y, g, lx, ly, tau_out, region):
    """tau_out = proj(y + lambda); returns (sum tau_x, sum tau_y, J_xx, J_xy, J_yy, psi).

    proj is the radial projection onto the disc |tau_I| <= g_I, or, where region (int8, same shape as g;
    a (1, 1) array for none) is 2, onto its rim |tau_I| = g_I (slip elements stay on their bound).
    psi = sum_I h(y_I + lambda) with h(z) = |z|^2/2 - dist(z, disc)^2/2 (disc) or g|z| (rim), convex
    functions whose gradients are the projections, and J = sum of the projection Jacobians (docs/theory.md §5:
    used to put the traction on the force constraint).
    """
    ny, nx = g.shape
    ring = region.shape[0] == ny and region.shape[1] == nx
    sx = 0.0
    sy = 0.0
    jxx = 0.0
    jxy = 0.0
    jyy = 0.0
    psi = 0.0
    for j in range(ny):
        for i in range(nx):
            gi = g[j, i]
            if gi <= 0.0:
                tau_out[0, j, i] = 0.0
                tau_out[1, j, i] = 0.0
                continue
            zx = y[0, j, i] + lx
            zy = y[1, j, i] + ly
            m = _mag(zx, zy)
            on_rim = ring and region[j, i] == 2 and m > 0.0
            if m <= gi and not on_rim:
                tau_out[0, j, i] = zx
                tau_out[1, j, i] = zy
                sx += zx
                sy += zy
                jxx += 1.0
                jyy += 1.0
                psi += 0.5 * m * m
            else:
                nxv = zx / m
                nyv = zy / m
                tau_out[0, j, i] = gi * nxv
                tau_out[1, j, i] = gi * nyv
                sx += gi * nxv
                sy += gi * nyv
                f = gi / m
                jxx += f * (1.0 - nxv * nxv)
                jxy += -f * nxv * nyv
                jyy += f * (1.0 - nyv * nyv)
                psi += gi * m if on_rim else 0.5 * m * m - 0.5 * (m - gi) ** 2
    return sx, sy, jxx, jxy, jyy, psi


def project_on_force(y, g, f, tau_out, region=None):
    """tau_out = Euclidean projection of y onto {|tau_I| <= g_I} intersected with {sum tau = f} (without
    `region`), or onto the same set with the slip elements held on their rims (with it).

    The projection is proj(y + lambda) with lambda (MPa) the root of the monotone 2-D map
    S(lambda) = sum proj(y + lambda) = f (the gradient of a convex dual function), found by a damped
    Newton iteration on |S - f|. f = F/dA in MPa; requires |f| < sum g. With `region` (int8, 2 = slip)
    the slip elements are projected onto their rim |tau_I| = g_I instead of the disc: they stay in slip
    and the force is met by turning them (and shifting the others). Without it a shift that shortens
    the slip tractions moves them all inside their discs, i.e. into stick.
    """
    if region is None:
        region = _NO_RING
    elif region.shape != g.shape:
        raise ValueError(f"project_on_force: region has shape {region.shape}, the bound {g.shape}")
    cap = float(np.sum(g))
    tol = 1e-13 * cap
    fx, fy = f
    n_contact = max(int(np.count_nonzero(g > 0)), 1)
    sy0 = force_projection_eval(y, g, 0.0, 0.0, tau_out, region)
    lx, ly = (fx - sy0[0]) / n_contact, (fy - sy0[1]) / n_contact  # exact if nothing saturates
    sx, sy, jxx, jxy, jyy, _ = force_projection_eval(y, g, lx, ly, tau_out, region)
    err = math.hypot(sx - fx, sy - fy)
    for _ in range(200):
        if err <= tol:
            return
        rx, ry = sx - fx, sy - fy
        reg = 1e-12 * (jxx + jyy) + 1e-300
        a, b, d = jxx + reg, jxy, jyy + reg
        det = a * d - b * b
        dx = -(d * rx - b * ry) / det
        dy = -(-b * rx + a * ry) / det
        t = 1.0
        for _ in range(80):
            nsx, nsy, njxx, njxy, njyy, _ = force_projection_eval(y, g, lx + t * dx, ly + t * dy, tau_out, region)
            nerr = math.hypot(nsx - fx, nsy - fy)
            if nerr < (1.0 - 1e-4 * t) * err:
                break
            t *= 0.5
        else:
            break
        lx, ly = lx + t * dx, ly + t * dy
        sx, sy, jxx, jxy, jyy, err = nsx, nsy, njxx, njxy, njyy, nerr
    sx, sy, *_ = force_projection_eval(y, g, lx, ly, tau_out, region)
    err = math.hypot(sx - fx, sy - fy)
    if err > 1e-10 * cap:
        raise ConvergenceError("could not project the traction onto the discs and the force constraint",
                               solver="tangential/force-projection", residual=err / cap, tol=1e-10)


def start_traction(tau, initial, g, f_cells, previous_region, region, u, axx, ayy):
    """tau <- the start of a step: `initial` (MPa) projected onto the discs |tau| <= g and, when f_cells
    (MPa x elements, the prescribed sum of tau; None for a prescribed shift) is given, onto the force. With
    `previous_region` (int8, 2 = slip) its slip elements start on the new bound and the force is met by the
    stick elements alone (`place_on_force`); without it by the Euclidean projection (`project_on_force`).
    region and u are scratch here."""
    tau[...] = np.asarray(initial, dtype=float)
    if not math.isfinite(float(tau.sum())) and not np.all(np.isfinite(tau)):  # the sum is the cheap test
        raise InputError("initial traction must be finite")
    project_discs(tau, g)
    if previous_region is None:
        if f_cells is not None:
            project_on_force(tau.copy(), g, f_cells, tau)
        return
    prev_region = np.asarray(previous_region)
    if prev_region.shape != g.shape:
        raise InputError(f"previous_region has shape {prev_region.shape}, the grid is {g.shape}")
    _keep_slip_on_bound(tau, g, prev_region)
    if f_cells is not None:
        place_on_force(tau, g, f_cells, region, u, axx, ayy)


def restore_force(tau, region, g, f_cells, u, axx, ayy, tol):
    """Put sum tau back on f_cells (MPa x elements) by shifting the stick tractions (`_kernel_restore_force`), or, with
    no stick element left, by turning the slip tractions along their rims; u is updated by the self
    coefficients only (the caller re-synchronises it). Returns (rims turned, stick elements pushed onto their
    rim): either changes the division, and the first is not a local correction of u."""
    n_stick = int(np.count_nonzero(region == 1))
    if restore_force_from_sums(tau, region, g, f_cells, u, axx, ayy, tol, float(tau[0].sum()), float(tau[1].sum()),
                               n_stick):
        return True, False
    return False, int(np.count_nonzero(region == 1)) != n_stick


def restore_force_from_sums(tau, region, g, f_cells, u, axx, ayy, tol, sx, sy, n_stick):
    """`restore_force` with sum tau = (sx, sy) and the stick count already known (a step's kernel returns them,
    which saves the passes). Returns True when the rims were turned (no stick element left)."""
    if _kernel_restore_force(tau, region, g, f_cells[0], f_cells[1], u, axx, ayy, tol, sx, sy, n_stick):
        project_on_force(tau.copy(), g, f_cells, tau, region)
        return True
    return False


def _keep_slip_on_bound(tau, g, prev_region):
    """Elements that slipped in the previous step start on their (new) bound: tau = g tau/|tau|."""
    m = np.hypot(tau[0], tau[1])
    sel = (prev_region == 2) & (g > 0) & (m > 0)
    f = np.where(sel, g / np.where(m > 0, m, 1.0), 1.0)
    tau *= f


def place_on_force(tau, g, f_cells, region, u, axx, ayy):
    """Put the start on the force constraint sum tau = f_cells (MPa x elements) by a uniform shift of the
    elements inside their disc (those pushed out are projected, see `_kernel_restore_force`); the elements on
    the bound stay there. The Euclidean projection onto discs and force (the fallback when no element is
    left inside) would move about half of them inside, into stick, and the solver would have to find them
    again one projection event at a time: from the converged traction perturbed by 1e-6 g in stick, 86
    products against 19 at dx = 0.05 (f_t = 0.5). Writes region (and u by self coefficients, a scratch
    buffer here)."""
    m = np.hypot(tau[0], tau[1])
    region[...] = np.where(g <= 0, 0, np.where(m >= (1 - ON_BOUND) * g, 2, 1))
    n_stick = int(np.count_nonzero(region == 1))
    tol = 1e-15 * float(np.sum(g))
    if _kernel_restore_force(tau, region, g, f_cells[0], f_cells[1], u, axx, ayy, tol, float(tau[0].sum()),
                       float(tau[1].sum()), n_stick):
        project_on_force(tau.copy(), g, f_cells, tau, region)
