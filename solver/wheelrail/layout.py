"""Where a wheel's patches go and their grids (docs/wheelrail.md, §4): a Hertz estimate of the wheel's lowering, the
coarse passes that find the load centre and load-weighted angle of each patch, and the grid over a patch's
interpenetration region. Units: mm, N, MPa, rad.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.wheelrail.balance import PatchState, vertical
from rollcontact.solver.wheelrail.patch import patch_gap, rail_distance
from rollcontact.solver.wheelrail.search import ContactSearch, PatchFrame


def hertz_estimate(search: ContactSearch, radius: float, E_star: float, Fz: float) -> float:
    """The approach (mm) of a Hertz contact with the wheel's radius along x and the gap's curvature across it at the
    first touch (limited to 1/50 of the wheel's radius: a flat tread), carrying Fz: the search's starting guess."""
    from rollcontact.solver.analytic import HertzEllipse
    k = max(search.curvature_estimate(), 1.0 / (50.0 * radius))
    return HertzEllipse(radius, 1.0 / k, E_star, Fz).approach


def coarse_pass(search, materials, Fz, dz, params, rows=None):
    """dz (mm) carrying Fz on coarse grids over the patches at `dz` (module docstring, step 2), centred by the row
    loads `rows` of an earlier pass if given, and the load of their rows (`row_loads`)."""
    frames = search.patches(dz, params.combine)
    if rows is not None:
        frames = centred(search, frames, rows)
    if not frames:
        raise InputError("the contact search found no interpenetration")
    patches = []
    for f in frames:
        sx, ss = extent(search, f, dz)
        h = max(min(2 * sx, 2 * ss) / params.coarse_cells, 1e-6)
        patches.append(PatchState(search, f, patch_grid(search, f, dz, h, h), materials, params))
    found, _ = vertical(search, patches, [math.cos(p.frame.angle) for p in patches], Fz, 0.5 * dz, params)
    rows = [row_loads(search, p) for p in patches if p.loaded]
    return found, tuple(np.concatenate([r[k] for r in rows]) for k in range(4))


def row_loads(search: ContactSearch, patch) -> tuple:
    """Per row of a solved patch's grid: its normal load (N), the lateral position y of the rail point below it and
    the rail's surface angle there, and its load's mean x (side frame; mm, rad)."""
    frame, grid, p = patch.frame, patch.grid, patch.normal.pressure
    load = p.sum(axis=1) * grid.cell_area
    c, s = math.cos(frame.angle), math.sin(frame.angle)
    y = frame.origin[1] + grid.y * c - patch.rail_t * s
    x = frame.origin[0] + (p * grid.x[None, :]).sum(axis=1) / np.where(load > 0, p.sum(axis=1), 1.0)
    keep = load > 0
    return load[keep], y[keep], np.arctan(search.rail.surface.slope(y[keep])), x[keep]


def centred(search: ContactSearch, frames: list, rows) -> list:
    """The frames moved to their load centres: each coarse row's load goes to the frame whose lateral extent is
    nearest to the row's y; a frame's reference becomes the load-weighted mean x, y of its rows and its contact angle
    the load-weighted mean of the rail's surface angle (the load centre, weighted angle). A frame without load keeps
    the search's reference."""
    load, y, angle, x = rows
    if not frames or load.size == 0:
        return frames
    lo = np.array([f.y_lo for f in frames])
    hi = np.array([f.y_hi for f in frames])
    distance = np.maximum(lo[None, :] - y[:, None], 0.0) + np.maximum(y[:, None] - hi[None, :], 0.0)
    owner = np.argmin(distance, axis=1)
    out = []
    for k, f in enumerate(frames):
        w = load[owner == k]
        if w.sum() <= 0:
            out.append(f)
            continue
        yk = float(np.dot(w, y[owner == k]) / w.sum())
        xk = float(np.dot(w, x[owner == k]) / w.sum())
        ak = float(np.dot(w, angle[owner == k]) / w.sum())
        out.append(PatchFrame(np.array([xk, yk, float(search.rail.surface(yk))]), ak, f.y_lo, f.y_hi))
    return out


def extent(search: ContactSearch, frame: PatchFrame, dz: float) -> tuple[float, float]:
    """Estimated half-extents (mm) along x and s of a patch's interpenetration region at dz: along s from its
    lateral interval, along x from the wheel's radius and the depth (and the spread of the contact locus)."""
    c = math.cos(frame.angle)
    half_s = 0.5 * (frame.y_hi - frame.y_lo) / max(c, 0.2) + 2 * search.step
    depth = search.depth(frame, dz)
    half_x = math.sqrt(2.0 * search.wheel_placement.radius * max(depth, 0.0) / max(c, 0.2))
    return 1.2 * half_x + search.locus_spread(frame), 1.2 * half_s


def patch_grid(search: ContactSearch, frame: PatchFrame, dz: float, dx: float, dy: float) -> Grid:
    """The grid of cells dx x dy over the interpenetration region h < 0 of the patch at dz, plus one cell on every
    side (the steady solver needs a free cell ahead of and behind the contact)."""
    half_x, half_s = extent(search, frame, dz)
    half_x, half_s = max(half_x, 2 * dx), max(half_s, 2 * dy)
    wheel = search.wheel(dz)
    for _ in range(8):
        grid = Grid.covering(-half_x, half_x, -half_s, half_s, dx, dy)
        rail_t = rail_distance(search.rail, frame, grid.y)
        gap, _ = patch_gap(rail_t, wheel, frame, grid.x, grid.y)
        inside = np.nan_to_num(gap, nan=1.0) < 0
        if not inside.any():
            raise InputError(f"patch at y = {frame.origin[1]:.4g} mm: no interpenetration on its plane at dz = "
                             f"{dz:.3g} mm")
        grow_x = inside[:, 0].any() or inside[:, -1].any()
        grow_s = inside[0].any() or inside[-1].any()
        if not (grow_x or grow_s):
            break
        half_x *= 1.5 if grow_x else 1.0
        half_s *= 1.5 if grow_s else 1.0
    else:
        raise InputError(f"patch at y = {frame.origin[1]:.4g} mm: its interpenetration region does not close "
                         "within 20 times its estimated size (a conformal or flat contact the planar patch cannot "
                         "hold)")
    cols, rows = np.flatnonzero(inside.any(axis=0)), np.flatnonzero(inside.any(axis=1))
    x, s = grid.x, grid.y
    return Grid.covering(x[cols[0]] - dx, x[cols[-1]] + dx, s[rows[0]] - dy, s[rows[-1]] + dy, dx, dy)
