"""FaStrip: Kalker's strip theory amended with his creep coefficients, with FASTSIM's traction directions in the slip
zone (Sichani, Enblom & Berg 2016, "An alternative to FASTSIM for tangential solution of the wheel-rail contact",
Vehicle System Dynamics 54:748-764; re-derived in docs/creep_fidelity.md; docs/theory.md §12.4).

Each row's run of contact cells is a strip of half-length l with an elliptical pressure P sqrt(l^2 - x'^2) (P from
the strip's own load, so any pressure on the grid can be used). Kalker's strip theory (1967) solves each strip as
Carter's two-dimensional rolling contact with lateral creepage and a lateral creepage linear in x (the spin): a stick
zone at the leading edge shifted by e, the traction there the difference of two semi-ellipses; its flexibilities are
calibrated so that full adhesion gives Kalker's C11, C22, C23 over the ellipse (solver.fastsim.flexibility). In the
trailing slip zone the traction is mu p along the FASTSIM traction of the same cell (the strip theory does not keep
the slip direction along the strip). Steady rolling only (the strip theory is a steady theory); the slip reported in
the slip zone is FASTSIM's, zero in the stick zone. Kalker's convention (solver.creep.kalker). Units: mm, N, MPa.

Compared with FASTSIM it keeps the half-space's traction shape in the stick zone (no parabolic bound is needed to get
the forces right) and the elliptical bound. A strip whose spin parameter |Phi| exceeds 1 slides entirely unless its
lateral creepage opposes the spin enough to leave a stick zone (`_kernels._stick_shift`).
"""
from __future__ import annotations

import numpy as np

from rollcontact.bem.grid import Grid
from rollcontact.solver.fastsim import _kernels
from rollcontact.solver.fastsim.fastsim import FastResult, checked_pressure, fast_result, solve_fastsim
from rollcontact.solver.fastsim.flexibility import Flexibilities
from rollcontact.solver.fastsim.strips import strip_edges


def solve_fastrip(grid: Grid, pressure, mu, xi=0.0, eta=0.0, phi=0.0, *, flexibilities: Flexibilities,
                  edges=None, flexibility="weighted") -> FastResult:
    """Steady FaStrip under `pressure` (MPa, (ny, nx): contact where > 0, bound mu p) for the creepages xi, eta
    and spin phi (1/mm); arguments as `solver.fastsim.solve_fastsim` (edges: (leading, trailing) x of each cell's
    strip, mm; flexibility: of the FASTSIM pass that gives the slip zone's traction directions)."""
    pressure = checked_pressure(grid, pressure, mu, xi, eta, phi)
    lead, trail = strip_edges(grid, pressure) if edges is None else (
        np.ascontiguousarray(edges[0], dtype=float), np.ascontiguousarray(edges[1], dtype=float))
    fast = solve_fastsim(grid, pressure, mu, xi, eta, phi, flexibilities=flexibilities, edges=(lead, trail),
                         flexibility=flexibility)
    cx, cy, cphi = flexibilities.strip_stiffnesses()
    tau = np.zeros((2,) + grid.shape)
    region = np.zeros(grid.shape, dtype=np.int8)
    _kernels.fastrip_rows(grid.x, grid.y, grid.dx, mu * pressure, pressure, lead, trail, float(mu), cx, cy, cphi,
                          float(xi), float(eta), float(phi), fast.traction, tau, region)
    slip = np.where(region == _kernels.SLIP, fast.slip, 0.0)
    return fast_result(grid, tau, slip, region, (xi, eta, phi), "fastrip", fast.flexibility)
