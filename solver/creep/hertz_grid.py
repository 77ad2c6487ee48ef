"""A Hertzian elliptic contact on a contact-fixed grid, for the steady rolling solver (docs/theory.md §7.3, §7.1).

The grid has n elements across each axis of the ellipse (dx = 2a/n along the rolling direction x, dy = 2b/n;
or ny across y),
cell centres on integer multiples of the spacing (n odd puts the ellipse's bounding box exactly on cell edges),
and one free column behind and ahead of the contact (the upwind difference of `steady` needs the cell ahead).
The contact is the set of cells whose centre lies inside the ellipse, with the cell-centre Hertz pressure
p = p0 sqrt(1 - x^2/a^2 - y^2/b^2), p0 = 3 Fn / (2 pi a b). Lengths in mm, pressure in MPa, force in N.
"""
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid


def ellipse_grid(a: float, b: float, n: int, ny: int | None = None) -> Grid:
    """The (n + 2) x ny grid over the ellipse with semi-axes a (x, rolling direction) and b (y), in mm: n
    elements across 2a, ny (default n) across 2b."""
    ny = n if ny is None else ny
    if not (a > 0 and b > 0 and math.isfinite(a) and math.isfinite(b)):
        raise InputError(f"semi-axes a = {a!r}, b = {b!r} mm: must be positive and finite")
    for name, m in (("n", n), ("ny", ny)):
        if int(m) != m or m < 3:
            raise InputError(f"elements across the contact {name} = {m!r}: must be an integer >= 3")
    return Grid(int(n) + 2, int(ny), 2.0 * a / n, 2.0 * b / ny, -(int(n) - 1) // 2 - 1, -(int(ny) - 1) // 2)


def hertz_pressure(grid: Grid, a: float, b: float, normal_force: float) -> np.ndarray:
    """Cell-centre Hertz pressure (MPa) of the ellipse (a, b) carrying normal_force (N), zero outside."""
    X, Y = grid.mesh()
    rho = (X / a) ** 2 + (Y / b) ** 2
    p0 = 3.0 * normal_force / (2.0 * math.pi * a * b)
    return np.where(rho < 1.0, p0 * np.sqrt(np.clip(1.0 - rho, 0.0, None)), 0.0)
