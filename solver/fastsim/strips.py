"""The contact seen as strips along the rolling direction, and the traction bounds of the fast models
(docs/creep_fidelity.md; docs/theory.md §7.1, §12.4).

The grid's x axis is the rolling direction; each row's run of cells in contact is a strip from its trailing to its
leading edge. `strip_edges` finds the edges from any pressure on the grid (p^2 extrapolated to zero beyond the
outermost cells, `_kernels.row_edges`), `ellipse_edges` gives them exactly for an ellipse. The bounds:

    semi-ellipsoid (Hertz)   p = p0 sqrt(1 - x^2/a^2 - y^2/b^2),  p0 = 3 Fn / (2 pi a b)
    parabolic (Kalker 1982)  p = p0' (1 - x^2/a^2 - y^2/b^2),     p0' = 2 Fn / (pi a b)

both carrying Fn over the ellipse; the parabolic one is FASTSIM's original bound (it saturates the force more
gradually). Lengths in mm, pressure in MPa, force in N.
"""
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.fastsim import _kernels

#: The traction bounds a Hertzian contact can be given (`ellipse_pressure`).
BOUNDS = ("ellipsoid", "parabolic")


def strip_edges(grid: Grid, pressure) -> tuple[np.ndarray, np.ndarray]:
    """(leading, trailing) edge x (mm) of the run of contact cells each cell belongs to, arrays (ny, nx), nan out of
    contact (pressure > 0 is the contact)."""
    pressure = np.ascontiguousarray(pressure, dtype=float)
    lead, trail = np.empty(grid.shape), np.empty(grid.shape)
    _kernels.row_edges(grid.x, grid.dx, pressure, lead, trail)
    return lead, trail


def ellipse_edges(grid: Grid, a: float, b: float, contact, centre: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The exact edges centre +- a sqrt(1 - y^2/b^2) (mm) of the ellipse centred at (centre, 0), at the cells of
    `contact` (nan elsewhere): (leading, trailing)."""
    half = a * np.sqrt(np.clip(1.0 - (grid.y / b) ** 2, 0.0, None))[:, None] * np.ones(grid.nx)
    half = np.where(contact, half, np.nan)
    return centre + half, centre - half


def equivalent_ellipse(grid: Grid, pressure) -> tuple[float, float]:
    """Semi-axes (a along x, b along y; mm) of the ellipse standing in for a contact of any shape (pressure > 0):
    the contact's area and the ratio of its extents along x and y (Kik & Piotrowski's equivalent ellipse, as
    CONTACT takes it for the flexibilities of a non-Hertzian contact)."""
    contact = np.asarray(pressure) > 0
    if not contact.any():
        raise InputError("pressure: no cell in contact")
    cols, rows = np.nonzero(contact.any(axis=0))[0], np.nonzero(contact.any(axis=1))[0]
    length = (cols[-1] - cols[0] + 1) * grid.dx
    width = (rows[-1] - rows[0] + 1) * grid.dy
    radius = math.sqrt(contact.sum() * grid.cell_area / math.pi)
    return radius * math.sqrt(length / width), radius * math.sqrt(width / length)


def ellipse_pressure(grid: Grid, a: float, b: float, normal_force: float, bound: str = "ellipsoid",
                     centre: float = 0.0) -> np.ndarray:
    """Cell-centre pressure (MPa) of the ellipse (a, b) (mm) centred at (centre, 0) carrying normal_force (N):
    Hertz's semi-ellipsoid or Kalker's parabolic bound (`BOUNDS`), zero outside."""
    if bound not in BOUNDS:
        raise InputError(f"bound = {bound!r}: allowed values are {list(BOUNDS)}")
    if not (a > 0 and b > 0 and normal_force > 0 and math.isfinite(a * b * normal_force)):
        raise InputError(f"a = {a!r}, b = {b!r} mm, Fn = {normal_force!r} N: must be positive and finite")
    X, Y = grid.mesh()
    rest = np.clip(1.0 - ((X - centre) / a) ** 2 - (Y / b) ** 2, 0.0, None)
    if bound == "ellipsoid":
        return 3.0 * normal_force / (2.0 * math.pi * a * b) * np.sqrt(rest)
    return 2.0 * normal_force / (math.pi * a * b) * rest


def strip_grid(a: float, b: float, nx: int, ny: int | None = None) -> Grid:
    """A contact-fixed grid over the ellipse (a, b) (mm) with nx elements across 2 a and ny (default nx) across 2 b,
    cell edges on the ellipse's bounding box, and one free cell ahead and behind (solver.creep.ellipse_grid)."""
    from rollcontact.solver.creep.hertz_grid import ellipse_grid
    return ellipse_grid(a, b, nx, ny)
