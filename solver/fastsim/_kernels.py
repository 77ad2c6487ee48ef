"""Compiled element loops of the fast models (`solver.fastsim`; docs/creep_fidelity.md, docs/theory.md §12.4).

Fields are (ny, nx) or (2, ny, nx) float64 arrays on a grid whose x axis is the rolling direction: body 1 rolls
in +x, so in contact-fixed coordinates the material enters the contact at its leading edge (largest x) and leaves
at its trailing edge. Kalker's convention: tractions on body 1 (MPa), slip of body 1 relative to body 2.

The rigid slip per unit rolling distance is w = (xi - phi y, eta + phi x); the simplified theory's displacement
is u = L tau, written here with the rates (w_x / L_x, w_y / L_y) = (kx + kxy y, ky + kyx x) in MPa/mm, so that one
flexibility (Kalker's weighted L) and three (L1, L2, L3) share the loops.

The kernels are numba functions compiled once per machine (`rollcontact.bem.compiled`), each called with exactly
its declared signature: float64 arrays C-contiguous, regions int8, scalars Python floats.
"""
import math

import numpy as np

from rollcontact.bem.compiled import internal, kernel

EXTERIOR, STICK, SLIP = 0, 1, 2


@kernel("void(f8[::1], f8, f8[:, ::1], f8[:, ::1], f8[:, ::1])")
def row_edges(x, dx, pressure, lead, trail):
    """For every cell in contact (pressure > 0) the x (mm) of the leading and trailing edges of its run of contact
    cells along the row, into lead and trail ((ny, nx); nan outside the contact).

    An edge lies between the outermost contact cell and the next cell (out of contact); near a smooth contact edge
    p ~ sqrt(distance), so p^2 is extrapolated linearly to zero from the two outermost cells (exact to second order
    in dx for a Hertzian row); a run of one cell, or a pressure not rising inwards, puts the edge half a cell out.
    """
    ny, nx = pressure.shape
    for j in range(ny):
        i = 0
        while i < nx:
            if pressure[j, i] <= 0.0:
                lead[j, i] = np.nan
                trail[j, i] = np.nan
                i += 1
                continue
            start = i
            while i < nx and pressure[j, i] > 0.0:
                i += 1
            end = i - 1                                    # the run start..end (inclusive)
            xl = x[end] + _edge_offset(pressure[j, end], pressure[j, end - 1] if end > start else 0.0, dx)
            xt = x[start] - _edge_offset(pressure[j, start], pressure[j, start + 1] if end > start else 0.0, dx)
            for k in range(start, end + 1):
                lead[j, k] = xl
                trail[j, k] = xt


@internal
def _edge_offset(p_out, p_in, dx):
    """Distance (mm) from the outermost contact cell's centre to the edge: p^2 extrapolated linearly to zero
    through the outermost (p_out) and the next inner cell (p_in), within (0, dx]; dx / 2 without a rise."""
    rise = p_in * p_in - p_out * p_out
    if rise <= 0.0:
        return 0.5 * dx
    return min(max(dx * p_out * p_out / rise, 1e-6 * dx), dx)


@kernel("void(f8[::1], f8[::1], f8[:, ::1], f8[:, ::1], f8, f8, f8, f8, f8, f8, f8[:, :, ::1], f8[:, :, ::1], "
        "i1[:, ::1])")
def steady_rows(x, y, bound, lead, kx, kxy, ky, kyx, lx, ly, tau, slip, region):
    """Steady FASTSIM (Kalker 1982) on every row, from the leading edge to the trailing edge.

    bound (ny, nx): mu p (MPa, 0 outside the contact); lead: the leading edge of each cell's run (`row_edges`).
    Each cell integrates the rigid slip exactly (it is linear in x) over the stretch of material path it adds,
    [x_i, x_{i+1}], or [x_i, leading edge] for the first cell of a run: the trial traction is the upstream one
    minus that integral of the rates, projected on the disc |tau| <= bound (Coulomb; the implicit step of the
    simplified theory). The slip (per unit rolling distance) is s = L (tau - trial) / h, opposite to tau in slip.
    Writes tau, slip (2, ny, nx) and region (ny, nx) (EXTERIOR, STICK, SLIP).
    """
    ny, nx = bound.shape
    for j in range(ny):
        tx = 0.0
        ty = 0.0
        rate_x = kx + kxy * y[j]
        for i in range(nx - 1, -1, -1):
            g = bound[j, i]
            if g <= 0.0:
                tau[0, j, i] = 0.0
                tau[1, j, i] = 0.0
                slip[0, j, i] = 0.0
                slip[1, j, i] = 0.0
                region[j, i] = EXTERIOR
                tx = 0.0
                ty = 0.0
                continue
            up = x[i + 1] if (i + 1 < nx and bound[j, i + 1] > 0.0) else lead[j, i]
            h = max(up - x[i], 1e-12 * (abs(x[i]) + 1.0))
            mid = 0.5 * (x[i] + up)
            trial_x = tx - h * rate_x
            trial_y = ty - h * (ky + kyx * mid)
            tx, ty, slipping = _project(trial_x, trial_y, g)
            tau[0, j, i] = tx
            tau[1, j, i] = ty
            slip[0, j, i] = lx * (tx - trial_x) / h
            slip[1, j, i] = ly * (ty - trial_y) / h
            region[j, i] = SLIP if slipping else STICK


@kernel("void(f8[::1], f8[::1], f8, f8, f8[:, ::1], f8[:, ::1], b1[:, ::1], f8, f8, f8, f8, f8, f8, "
        "f8[:, :, ::1], f8[:, :, ::1], i1[:, ::1])")
def transient_step(x, y, centre, step, bound, lead, entered, kx, kxy, ky, kyx, lx, ly, tau, slip, region):
    """One step of transient FASTSIM on a world-fixed grid: the contact (centre at x = centre, mm) has moved by
    `step` (mm) since the traction `tau` (2, ny, nx; updated in place) was reached. Each cell in contact keeps the
    traction of its material from the previous step (zero for a cell that `entered`, (ny, nx) bool, the contact
    this step: its path in the contact runs from the leading edge `lead`, not a whole step) minus the rate
    integrated over the path the material travelled relative to the contact, projected on the bound; cells out of
    contact carry nothing. slip: over the step (mm), s = L (tau - trial); region as `steady_rows`.
    """
    ny, nx = bound.shape
    for j in range(ny):
        rate_x = kx + kxy * y[j]
        for i in range(nx):
            g = bound[j, i]
            if g <= 0.0:
                tau[0, j, i] = 0.0
                tau[1, j, i] = 0.0
                slip[0, j, i] = 0.0
                slip[1, j, i] = 0.0
                region[j, i] = EXTERIOR
                continue
            rel = x[i] - centre                          # the material's position relative to the contact now
            if entered[j, i]:
                h = min(step, max(lead[j, i] - x[i], 1e-12 * step))
                t0x = 0.0
                t0y = 0.0
            else:
                h = step
                t0x = tau[0, j, i]
                t0y = tau[1, j, i]
            mid = rel + 0.5 * h
            trial_x = t0x - h * rate_x
            trial_y = t0y - h * (ky + kyx * mid)
            tx, ty, slipping = _project(trial_x, trial_y, g)
            tau[0, j, i] = tx
            tau[1, j, i] = ty
            slip[0, j, i] = lx * (tx - trial_x)
            slip[1, j, i] = ly * (ty - trial_y)
            region[j, i] = SLIP if slipping else STICK


@kernel("void(f8[::1], f8[::1], f8, f8, f8[:, ::1], f8, f8, f8, f8, f8, f8, f8[:, :, ::1], f8[:, :, ::1], i1[:, ::1])")
def at_rest(x, y, centre, step, bound, kx, kxy, ky, kyx, lx, ly, tau, slip, region):
    """The simplified theory at rest under the rigid slip of one step (a Cattaneo shift, with spin a twist about
    the contact centre): tau = projection of -step (rates at the cell), from zero traction."""
    ny, nx = bound.shape
    for j in range(ny):
        for i in range(nx):
            g = bound[j, i]
            if g <= 0.0:
                tau[0, j, i] = 0.0
                tau[1, j, i] = 0.0
                slip[0, j, i] = 0.0
                slip[1, j, i] = 0.0
                region[j, i] = EXTERIOR
                continue
            trial_x = -step * (kx + kxy * y[j])
            trial_y = -step * (ky + kyx * (x[i] - centre))
            tx, ty, slipping = _project(trial_x, trial_y, g)
            tau[0, j, i] = tx
            tau[1, j, i] = ty
            slip[0, j, i] = lx * (tx - trial_x)
            slip[1, j, i] = ly * (ty - trial_y)
            region[j, i] = SLIP if slipping else STICK


@internal
def _project(tx, ty, g):
    """(tx, ty) projected on the disc of radius g: (tau_x, tau_y, outside)."""
    n = math.sqrt(tx * tx + ty * ty)
    if n <= g:
        return tx, ty, False
    f = g / n
    return tx * f, ty * f, True


@kernel("void(f8[::1], f8[::1], f8, f8[:, ::1], f8[:, ::1], f8[:, ::1], f8[:, ::1], f8, f8, f8, f8, f8, f8, f8, "
        "f8[:, :, ::1], f8[:, :, ::1], i1[:, ::1])")
def fastrip_rows(x, y, dx, bound, pressure, lead, trail, mu, cx, cy, cphi, xi, eta, phi, fast, tau, region):
    """FaStrip (Sichani, Enblom & Berg 2016, re-derived in docs/creep_fidelity.md) on every run of contact cells.

    Each run is a strip [trail, lead] of half-length l about m with the pressure P sqrt(l^2 - x'^2), x' = x - m, P
    from the strip's load (P = 2 sum(p dx) / (pi l^2)). Kalker's strip theory with the strip flexibilities
    calibrated on Kalker's coefficients (cx = 1 / K_x, cy = 1 / K_y, cphi = 1 / K_phi, MPa) gives, with
    A = (xi - phi y) / (K_x mu P), B = eta / (K_y mu P) (mm) and Phi = phi / (K_phi mu P), the stick zone
    [2 e - l, l] (the leading part) from A^2 + (B + Phi e)^2 = e^2, and there the traction
        tau_x = -mu P (A / e) (S1 - S2),   tau_y = -mu P [(B / e + Phi) S1 - (B / e) S2],
    S1 = sqrt(l^2 - x'^2), S2 = sqrt((l - e)^2 - (x' - e)^2), averaged over the cell's part of the zone (the
    closed-form integrals; the full-adhesion limit e -> 0 without cancellation). In the slip zone the traction is
    mu p along the FASTSIM traction `fast` (2, ny, nx) of the same cell. Every traction is then kept within the
    bound. Writes tau and region (STICK in the stick zone, SLIP in the slip zone).
    """
    ny, nx = bound.shape
    for j in range(ny):
        i = 0
        while i < nx:
            if bound[j, i] <= 0.0:
                tau[0, j, i] = 0.0
                tau[1, j, i] = 0.0
                region[j, i] = EXTERIOR
                i += 1
                continue
            start = i
            while i < nx and bound[j, i] > 0.0:
                i += 1
            end = i - 1
            xl, xt = lead[j, start], trail[j, start]
            half = 0.5 * (xl - xt)
            m = 0.5 * (xl + xt)
            load = 0.0
            for k in range(start, end + 1):
                load += pressure[j, k] * dx
            P = 2.0 * load / (math.pi * half * half)
            A = (xi - phi * y[j]) * cx / (mu * P)
            B = eta * cy / (mu * P)
            Phi = phi * cphi / (mu * P)
            e = _stick_shift(A, B, Phi, half)
            for k in range(start, end + 1):
                _fastrip_cell(x[k], dx, m, half, e, A, B, Phi, mu * P, bound[j, k], fast[0, j, k],
                              fast[1, j, k], k == start, k == end, tau, region, j, k)


@internal
def _stick_shift(A, B, Phi, half):
    """The shift e (mm) of the strip's stick zone from A^2 + (B + Phi e)^2 = e^2, i.e. (1 - Phi^2) e^2 - 2 B Phi e -
    (A^2 + B^2) = 0: for |Phi| < 1 the non-negative root (0 without creepage); for |Phi| > 1 the smaller positive
    root, which exists only when the lateral creepage opposes the spin (B Phi < 0) strongly enough; else inf, a strip
    that slides entirely. At |Phi| > 1 the degenerate root e = 0 of A = B = 0 (the strip through the spin pole) is
    the limit of sliding strips on either side and slides too; A and B below 1e-12 of the strip's half-length `half`
    (rounding in the creepages) count as zero, so that the branch does not depend on them."""
    if abs(A) <= 1e-12 * half:
        A = 0.0
    if abs(B) <= 1e-12 * half:
        B = 0.0
    q = 1.0 - Phi * Phi
    disc = B * B + q * A * A
    if disc < 0.0:
        return np.inf
    if abs(q) < 1e-12:                      # |Phi| = 1: 2 B Phi e + A^2 + B^2 = 0
        if B * Phi < 0.0:
            return -(A * A + B * B) / (2.0 * B * Phi)
        return np.inf
    if q < 0.0 and not B * Phi < 0.0:
        return np.inf
    e = (B * Phi + math.sqrt(disc)) / q
    if not (e >= 0.0) or not math.isfinite(e):
        return np.inf
    return e


@internal
def _fastrip_cell(xc, dx, m, half, e, A, B, Phi, muP, g, fx, fy, first, last, tau, region, j, k):
    """The FaStrip traction of one cell (see `fastrip_rows`). A cell whose centre lies in the slip zone slips: mu p
    along the FASTSIM traction. A cell whose centre lies in the stick zone sticks: the strip traction integrated
    over the cell's part of the stick zone, plus the strip's mu P sqrt(l^2 - x'^2) along the FASTSIM traction over
    its part of the slip zone, divided by dx (so that sum(tau) dx is the strip's force, the trailing edge's integrable singularity included)."""
    xs = xc - m
    lo_zone = 2.0 * e - half
    dirx, diry = _slip_direction(xs, A, B, Phi, fx, fy)
    if not (e < half and xs >= lo_zone):
        tau[0, j, k] = g * dirx
        tau[1, j, k] = g * diry
        region[j, k] = SLIP
        return
    lo = -half if first else max(xs - 0.5 * dx, -half)
    hi = half if last else min(xs + 0.5 * dx, half)
    lo_stick = max(lo, lo_zone)
    i1 = _semi_ellipse_integral(hi, half) - _semi_ellipse_integral(lo_stick, half)
    if e > 1e-6 * half:                          # (below: the limit, O(e / l) off, avoids the cancellation)
        c = half - e
        i2 = _semi_ellipse_integral(hi - e, c) - _semi_ellipse_integral(lo_stick - e, c)
        diff = (i1 - i2) / e
    else:                                        # (S1 - S2) / e -> sqrt((l - x') / (l + x')): its integral
        diff = _adhesion_integral(hi, half) - _adhesion_integral(lo_stick, half)
    sliding = muP * (_semi_ellipse_integral(lo_stick, half) - _semi_ellipse_integral(lo, half))
    tx = (-muP * A * diff + sliding * dirx) / dx
    ty = (-muP * (B * diff + Phi * i1) + sliding * diry) / dx
    n = math.sqrt(tx * tx + ty * ty)
    if n > g:
        tx *= g / n
        ty *= g / n
    tau[0, j, k] = tx
    tau[1, j, k] = ty
    region[j, k] = STICK


@internal
def _slip_direction(xs, A, B, Phi, fx, fy):
    """Unit direction of the slip zone's traction: FASTSIM's traction (fx, fy), or without it (no creepage there)
    against the strip's rigid slip (A, B + Phi x')."""
    n = math.sqrt(fx * fx + fy * fy)
    if n > 0.0:
        return fx / n, fy / n
    wy = B + Phi * xs
    d = math.sqrt(A * A + wy * wy)
    if d > 0.0:
        return -A / d, -wy / d
    return 0.0, 0.0


@internal
def _semi_ellipse_integral(s, r):
    """Antiderivative of sqrt(r^2 - s^2) in s, clipped to [-r, r]."""
    if r <= 0.0:
        return 0.0
    s = min(max(s, -r), r)
    return 0.5 * (s * math.sqrt(max(r * r - s * s, 0.0)) + r * r * math.asin(s / r))


@internal
def _adhesion_integral(s, r):
    """Antiderivative of sqrt((r - s) / (r + s)) in s, clipped to [-r, r]: sqrt(r^2 - s^2) + r asin(s / r)."""
    s = min(max(s, -r), r)
    return math.sqrt(max(r * r - s * s, 0.0)) + r * math.asin(s / r)
