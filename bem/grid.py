"""World-fixed rectangular grid of piecewise-constant elements (docs/theory.md §0, §6.1).

Cell centres sit on integer multiples of the spacing: x_i = i*dx for i = i0 .. i0+nx-1 (same in y), so the
origin (the sphere's initial centre) is a cell centre and the centre lines x = 0, y = 0 are rows of
cells. Fields on the grid are arrays of shape (ny, nx): index [j, i] is the cell at (x_i, y_j).
Lengths in mm.
"""
from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError

#: Largest grid the operator will build by default: a memory guard. The operator (kernel spectra, FFT
#: buffers and plans) takes about 740 bytes per element (measured at 512^2), about 3.1 GB at this size.
MAX_ELEMENTS = 2048 * 2048


@dataclass(frozen=True)
class Grid:
    """nx x ny cells of size dx x dy (mm); the first cell centre is at (i0*dx, j0*dy)."""

    nx: int
    ny: int
    dx: float
    dy: float
    i0: int = 0
    j0: int = 0

    def __post_init__(self):
        for name, n in (("nx", self.nx), ("ny", self.ny)):
            if int(n) != n or n < 1:
                raise InputError(f"grid.{name} = {n!r}: must be a positive integer")
        for name, h in (("dx", self.dx), ("dy", self.dy)):
            if not (h > 0 and math.isfinite(h)):
                raise InputError(f"grid.{name} = {h!r} mm: must be a positive finite length")

    @classmethod
    def covering(cls, xmin, xmax, ymin, ymax, dx, dy, max_elements=MAX_ELEMENTS) -> "Grid":
        """Smallest grid whose cells cover the box [xmin, xmax] x [ymin, ymax] (mm).

        Raises InputError if it would need more than `max_elements` cells.
        """
        if not (xmax > xmin and ymax > ymin):
            raise InputError(f"grid box [{xmin}, {xmax}] x [{ymin}, {ymax}] mm is empty")
        if not (dx > 0 and dy > 0):
            raise InputError(f"grid.dx = {dx!r}, grid.dy = {dy!r} mm: must be > 0")
        i0, i1 = math.floor(xmin / dx + 0.5), math.ceil(xmax / dx - 0.5)
        j0, j1 = math.floor(ymin / dy + 0.5), math.ceil(ymax / dy - 0.5)
        nx, ny = i1 - i0 + 1, j1 - j0 + 1
        if nx * ny > max_elements:
            raise InputError(
                f"grid of {nx} x {ny} = {nx * ny} elements (dx = {dx}, dy = {dy} mm over "
                f"[{xmin:.3g}, {xmax:.3g}] x [{ymin:.3g}, {ymax:.3g}] mm) exceeds the limit of "
                f"{max_elements} elements; use a coarser grid or a smaller amplitude")
        return cls(nx, ny, float(dx), float(dy), i0, j0)

    @property
    def x(self) -> np.ndarray:
        """Cell-centre x coordinates (mm), shape (nx,)."""
        return (self.i0 + np.arange(self.nx)) * self.dx

    @property
    def y(self) -> np.ndarray:
        """Cell-centre y coordinates (mm), shape (ny,)."""
        return (self.j0 + np.arange(self.ny)) * self.dy

    @property
    def shape(self) -> tuple[int, int]:
        return (self.ny, self.nx)

    @property
    def size(self) -> int:
        return self.nx * self.ny

    @property
    def cell_area(self) -> float:
        """dA = dx*dy (mm^2)."""
        return self.dx * self.dy

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """Cell-centre coordinates X, Y (mm), each of shape (ny, nx)."""
        return np.meshgrid(self.x, self.y)

    def index_of(self, x: float, y: float) -> tuple[int, int]:
        """(j, i) of the cell containing the point (x, y) in mm, or raise if it lies outside."""
        i = round(x / self.dx) - self.i0
        j = round(y / self.dy) - self.j0
        if not (0 <= i < self.nx and 0 <= j < self.ny):
            raise InputError(f"point ({x}, {y}) mm lies outside the grid")
        return j, i


def contact_box(semi_x, semi_y, centres, margin):
    """Box (xmin, xmax, ymin, ymax) in mm that every contact ellipse can reach, plus a margin.

    semi_x, semi_y: semi-axes of the largest expected contact ellipse (mm); centres: array (n, 2) of
    the sphere-centre positions the run visits (mm); margin: extra width on every side (mm).
    """
    c = np.atleast_2d(np.asarray(centres, dtype=float))
    return (c[:, 0].min() - semi_x - margin, c[:, 0].max() + semi_x + margin,
            c[:, 1].min() - semi_y - margin, c[:, 1].max() + semi_y + margin)
