"""One call for the tangential state of a contact patch by a fast model, arrays in and out (docs/theory.md §12.4).

For a caller that has a contact patch rather than a scene (a wheel-rail contact point, a multibody step): either the
semi-axes of a Hertzian ellipse and its normal force (the patch is then discretised on its own strip grid, the
traction bound Hertz's semi-ellipsoid or Kalker's parabola, the strip edges exact), or a grid with a pressure on it
(any shape; the flexibilities from the given semi-axes, else from the contact's equivalent ellipse). Kalker's
convention (solver.creep.kalker): x the rolling direction, forces on body 1. Units: mm, N, MPa; phi in 1/mm.

    patch = fast_patch("fastsim", semi_axes=(6.0, 4.0), normal_force=1e5, creepages=(1e-3, 0.0, 0.0),
                       mu=0.3, G=8.2e4, nu=0.28)
    patch.state.force, patch.state.traction, patch.grid.x
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.fastsim.fastrip import solve_fastrip
from rollcontact.solver.fastsim.fastsim import FastResult, solve_fastsim
from rollcontact.solver.fastsim.flexibility import kalker_flexibilities
from rollcontact.solver.fastsim.strips import ellipse_edges, ellipse_pressure, equivalent_ellipse, strip_grid

_SOLVERS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}


@dataclass
class Patch:
    """The grid (mm) and pressure (MPa) the model ran on, the semi-axes (a, b) of its flexibilities (mm), and the
    state (solver.fastsim.FastResult: traction, slip, region, force, moment)."""
    grid: Grid
    pressure: np.ndarray
    semi_axes: tuple
    state: FastResult


def fast_patch(model: str, *, creepages, mu: float, G: float, nu: float, semi_axes=None, normal_force=None,
               grid: Grid | None = None, pressure=None, elements: int = 40, bound: str = "ellipsoid") -> Patch:
    """The steady state of a contact patch by `model` ("fastsim" or "fastrip").

    creepages: (xi, eta, phi) (phi in 1/mm); mu: friction coefficient; G, nu: Kalker's combined shear modulus (MPa)
    and Poisson ratio. Either semi_axes = (a, b) (mm, a along the rolling direction) and normal_force (N): a strip
    grid of `elements` across each axis and the `bound` ("ellipsoid": Hertz, "parabolic": Kalker 1982, FASTSIM
    only); or grid and pressure (MPa, (ny, nx)), with semi_axes optional (default: the equivalent ellipse).
    """
    if model not in _SOLVERS:
        raise InputError(f"model = {model!r}: allowed values are {list(_SOLVERS)}")
    xi, eta, phi = (float(c) for c in creepages)
    edges = None
    if grid is None:
        if semi_axes is None or normal_force is None or pressure is not None:
            raise InputError("fast_patch: give semi_axes and normal_force, or a grid and a pressure")
        if bound == "parabolic" and model == "fastrip":
            raise InputError("fast_patch: bound = 'parabolic' is FASTSIM's; FaStrip takes the semi-ellipsoid")
        a, b = (float(v) for v in semi_axes)
        grid = strip_grid(a, b, int(elements))
        pressure = ellipse_pressure(grid, a, b, float(normal_force), bound)
        edges = ellipse_edges(grid, a, b, pressure > 0)
    else:
        if pressure is None or normal_force is not None:
            raise InputError("fast_patch: with a grid give its pressure (MPa), not a normal force")
        pressure = np.asarray(pressure, dtype=float)
        a, b = (equivalent_ellipse(grid, pressure) if semi_axes is None else (float(v) for v in semi_axes))
    flex = kalker_flexibilities(a, b, G, nu)
    state = _SOLVERS[model](grid, pressure, mu, xi, eta, phi, flexibilities=flex, edges=edges)
    return Patch(grid, pressure, (a, b), state)
