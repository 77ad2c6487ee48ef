"""Influence coefficients of steady rolling over viscoelastic bodies, on the contact-fixed grid (docs/theory.md §12.3;
docs/viscoelastic.md, "Steady rolling").

Body 1 rolls in +x at the speed V (mm/s) over body 2; in the contact-fixed frame the material of both bodies streams
in -x, a cell's width dx in dt = dx / V. A material element now at cell I was at cell I + k a time k dt earlier, so
with the exact SLS update of `sls` over each dt (the traction of the element linear in time between cell centres) its
state is q_I = e q_{I+1} + b (t_I - t_{I+1}), i.e. q_I = b t_I - b (1 - e) sum_{k>=1} e^(k-1) t_{I+k}, and the surface
displacement of body i, A_1 (C_r t - (C_r - C_g) q), is a Toeplitz operator on the traction:

    K(d) = C_eff A_1(d) + sum_{k>=1} w e^(k-1) A_h(d + k dx),        w = b (1 - e),

(d the offset target minus source along x; A_h = (C_r - C_g) A_1 the body's history operator, `sls.history_pair`).
The first terms of the bodies make the elastic operator of the effective pair (`sls.effective_pair`); the sums, the
"tails", carry the memory of the material that streamed through the contact and decays behind it: the wake beyond
the grid is in the kernel, none is cut off. This is the transient scheme of `memory` with the contact moving one
cell per step, seen in the contact frame: a transient rolled with step = dx converges to this steady state.

The tail at the grid's offsets is summed exactly over the first columns beyond the grid (a backward recursion
T(d) = w A_h(d + dx) + e T(d + dx)); the far remainder, where A_h is smooth on the scale of its distance, by the
integral of the summand (midpoint rule) with Gauss-Legendre panels no longer than the decay length 1/|ln e| cells,
until e^k < 1e-17. Beyond FAR_FIELD element sizes the influence coefficients are the point-load values (the
rectangle's exact formula loses digits to cancellation there; the point load is within (h/r)^2 / 12 of it).
Units: mm, MPa, s, mm/s; kernels in mm/MPa.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import MaterialPair
from rollcontact.solver.visco.sls import StandardLinearSolid, effective_pair, history_pair

#: Distance (in largest element sizes) beyond which an influence coefficient is the point load's.
FAR_FIELD = 100.0
#: Columns beyond the grid whose tail terms are summed exactly, before the smooth far remainder.
NEAR_COLUMNS = 128
#: Terms of the far remainder summed one by one before it is integrated.
DIRECT_TERMS = 256
#: Gauss-Legendre nodes per panel of the far remainder.
PANEL_NODES = 16
#: Relative size of the last term kept in the exponentially weighted sums.
TAIL_CUTOFF = 1e-17

_ODD_IN_Y = ("xy", "yz")


def influence(X, Y, dx, dy, pair: MaterialPair, components):
    """Influence coefficients (mm/MPa) of `pair` at offsets X, Y (mm, arrays of one shape): the rectangle's closed
    form (bem.influence) within FAR_FIELD element sizes, the point load's beyond."""
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    r = np.hypot(X, Y)
    far = r > FAR_FIELD * max(dx, dy)
    out = {c: np.zeros(X.shape) for c in components}
    near = ~far
    if near.any():
        exact = influence_coefficients(X[near], Y[near], dx, dy, pair.G, pair.nu, pair.K, components=components)
        for c in components:
            out[c][near] = exact[c]
    if far.any():
        x, y, rr = X[far], Y[far], r[far]
        c0 = dx * dy / (math.pi * pair.G)
        nu = pair.nu
        point = {"zz": lambda: c0 * (1.0 - nu) / rr,
                 "xx": lambda: c0 * (x * x + (1.0 - nu) * y * y) / rr ** 3,
                 "yy": lambda: c0 * (y * y + (1.0 - nu) * x * x) / rr ** 3,
                 "xy": lambda: c0 * nu * x * y / rr ** 3,
                 "xz": lambda: c0 * pair.K * x / rr ** 2,
                 "yz": lambda: c0 * pair.K * y / rr ** 2}
        for c in components:
            out[c][far] = point[c]()
    return out


def _far_nodes(decay: float, first: float):
    """Nodes s >= first and weights of the integral of decay^s g(s) ds over [first, inf) (in cells): Gauss-Legendre
    panels doubling in length up to the decay length, then of that length, until decay^s < TAIL_CUTOFF."""
    length = -1.0 / math.log(decay)
    end = first + length * -math.log(TAIL_CUTOFF)
    x, w = np.polynomial.legendre.leggauss(PANEL_NODES)
    nodes, weights = [], []
    a = first
    while a < end:
        b = a + min(max(a, 1.0), length)
        nodes.append(0.5 * (b - a) * x + 0.5 * (a + b))
        weights.append(0.5 * (b - a) * w)
        a = b
    s = np.concatenate(nodes)
    return s, np.concatenate(weights) * decay ** (s - first)


def tail_kernels(grid, pair: MaterialPair, decay: float, weight: float, components):
    """T_c(ox, oy) = weight sum_{k>=1} decay^(k-1) A_c((ox + k) dx, oy dy) for the offsets of `grid`, as arrays of
    shape (2 ny - 1, 2 nx - 1) (module docstring), A the influence coefficients of `pair` (mm/MPa)."""
    ny, nx = grid.shape
    dx, dy = grid.dx, grid.dy
    if weight == 0.0 or not decay < 1.0:               # no memory at all (dt/tau below round-off)
        return {c: np.zeros((2 * ny - 1, 2 * nx - 1)) for c in components}
    oy = np.arange(ny) * dy                            # oy >= 0; mirrored below
    first = nx + NEAR_COLUMNS                          # first column of the far remainder
    cols = np.arange(-(nx - 2), first) * dx            # columns d + 1 for d = -(nx - 1) .. first - 2
    X, Y = np.meshgrid(cols, oy)
    F = influence(X, Y, dx, dy, pair, components)      # (ny, columns)
    # the far remainder S = sum_{n>=0} decay^n A(first + n): direct terms, then the integral of the summand
    n_direct = DIRECT_TERMS
    if decay ** n_direct < TAIL_CUTOFF:
        n_direct = max(1, math.ceil(math.log(TAIL_CUTOFF) / math.log(decay))) if decay > 0.0 else 1
    xs = (first + np.arange(n_direct)) * dx
    Xd, Yd = np.meshgrid(xs, oy)
    Fd = influence(Xd, Yd, dx, dy, pair, components)
    wd = decay ** np.arange(n_direct)
    S = {c: np.einsum("jn,n->j", Fd[c], wd) for c in components}      # numpy's loop: BLAS threads contend
    if decay ** n_direct >= TAIL_CUTOFF:
        s, ws = _far_nodes(decay, n_direct - 0.5)      # midpoint rule: sum_{n >= N} g(n) ~ int_{N - 1/2} g
        Xf, Yf = np.meshgrid((first + s) * dx, oy)
        Ff = influence(Xf, Yf, dx, dy, pair, components)
        scale = decay ** (n_direct - 0.5)
        for c in components:
            S[c] += scale * np.einsum("jn,n->j", Ff[c], ws)
    out = {}
    for c in components:
        T = np.empty((ny, 2 * nx - 1))
        t = weight * S[c]                              # T(first - 1)
        for d in range(first - 2, -nx, -1):            # T(d) = w A(d + 1) + e T(d + 1)
            t = weight * F[c][:, d + 1 + (nx - 2)] + decay * t
            if d <= nx - 1:
                T[:, d + nx - 1] = t
        full = np.empty((2 * ny - 1, 2 * nx - 1))
        full[ny - 1:] = T
        full[:ny - 1] = (-1.0 if c in _ODD_IN_Y else 1.0) * T[:0:-1]
        out[c] = full
    return out


def steady_kernels(grid, body1, body2, speed: float, *, coupled: bool):
    """(kernels, effective pair): the Toeplitz kernels (dict component -> (2 ny - 1, 2 nx - 1) array, mm/MPa; 'zz',
    'xx', 'yy', 'xy', and 'xz', 'yz' when `coupled`) of steady rolling at `speed` (mm/s, body 1 rolling in +x) over
    bodies that are a bem Material or a StandardLinearSolid each, and the effective elastic pair of the time dx / V
    a material element takes to cross a cell (module docstring)."""
    if not (speed > 0 and math.isfinite(speed)):
        raise InputError(f"rolling speed = {speed!r} mm/s: must be finite and > 0 for viscoelastic steady rolling")
    dt = grid.dx / speed
    pair = effective_pair(body1, body2, dt)
    comps = ("zz", "xx", "yy", "xy") + (("xz", "yz") if coupled else ())
    ny, nx = grid.shape
    X, Y = np.meshgrid(np.arange(-(nx - 1), nx) * grid.dx, np.arange(-(ny - 1), ny) * grid.dy)
    kernels = influence_coefficients(X, Y, grid.dx, grid.dy, pair.G, pair.nu, pair.K, components=comps)
    for index, body in ((1, body1), (2, body2)):
        if isinstance(body, StandardLinearSolid):
            st = body.step(dt)
            tails = tail_kernels(grid, history_pair(body, index), st.decay, st.ramp * (1.0 - st.decay), comps)
            for c in comps:
                kernels[c] = kernels[c] + tails[c]
    return kernels, pair
