"""FASTSIM: Kalker's simplified theory of rolling contact on a grid, steady and transient (Kalker 1982, Vehicle
System Dynamics 11:1-13; docs/theory.md §12.4; docs/creep_fidelity.md).

Kalker's convention (solver.creep.kalker): body 1 rolls in +x over body 2, xi, eta (dimensionless) and phi (1/mm)
the rigid slip of body 1 relative to body 2 per unit rolling distance, tractions and forces on body 1. The
simplified theory replaces the half-space by independent springs, u = L tau (flexibilities: solver.fastsim.
flexibility), so that the steady slip s = w - du/dx, w = (xi - phi y, eta + phi x), is integrated strip by strip
from the leading edge: stick where the trial traction stays within the bound mu p, else the traction is the trial
one scaled onto the bound (the implicit step, exact for the spring model). Steady: `solve_fastsim` on a contact-fixed
grid. Transient: `FastsimRolling.step` on a world-fixed grid, one rolling step at a time (Kalker's non-steady
simplified theory; with step = dx it reaches the steady traction once the contact has passed the material).

flexibility = "weighted" (default): Kalker's one flexibility L weighted by the creepages (Flexibilities.weighted),
a consistent elastic model; "three": L1, L2, L3 on the longitudinal, lateral and spin parts of the rigid slip
(the linear range of every combination matches Kalker's, the traction is no longer that of one spring model).
Units: mm, N, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np

from rollcontact.bem.errors import ContactEdgeError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.fastsim import _kernels
from rollcontact.solver.fastsim.flexibility import Flexibilities
from rollcontact.solver.fastsim.strips import strip_edges

#: The flexibility models of `solve_fastsim` (module docstring).
FLEXIBILITY_MODELS = ("weighted", "three")


@dataclass
class FastResult:
    """A fast model's state on its grid (Kalker's convention, module docstring).

    traction (2, ny, nx) MPa on body 1; slip (2, ny, nx): steady, per unit rolling distance (dimensionless);
    transient, over the step (mm); zero outside the contact. region (ny, nx) int8: 0 exterior, 1 stick, 2 slip;
    force (Fx, Fy) N and moment Mz (N mm, about `origin`) on body 1; the creepages (xi, eta, phi); the model
    ("fastsim", "fastrip") and its flexibility (L, or (L1, L2, L3), mm/MPa).
    """
    traction: np.ndarray
    slip: np.ndarray
    region: np.ndarray
    force: tuple
    moment: float
    creepages: tuple
    model: str
    flexibility: object
    origin: tuple = field(default=(0.0, 0.0))

    @property
    def contact(self) -> np.ndarray:
        return self.region > 0

    @property
    def stick(self) -> np.ndarray:
        return self.region == _kernels.STICK


def rates(flex: Flexibilities, xi, eta, phi, flexibility="weighted"):
    """(kx, kxy, ky, kyx, lx, ly): the rates w / L = (kx + kxy y, ky + kyx x) (MPa/mm) and the flexibilities
    (lx, ly) (mm/MPa) that turn a traction change into slip."""
    if flexibility == "weighted":
        L = flex.weighted(xi, eta, phi)
        return xi / L, -phi / L, eta / L, phi / L, L, L
    if flexibility == "three":
        L1, L2, L3 = flex.L1, flex.L2, flex.L3
        return xi / L1, -phi / L3, eta / L2, phi / L3, L1, L2
    raise InputError(f"flexibility = {flexibility!r}: allowed values are {list(FLEXIBILITY_MODELS)}")


def solve_fastsim(grid: Grid, pressure, mu, xi=0.0, eta=0.0, phi=0.0, *, flexibilities: Flexibilities,
                  edges=None, flexibility="weighted") -> FastResult:
    """Steady FASTSIM under `pressure` (MPa, (ny, nx); the contact is where it is > 0 and the bound is mu p) for the
    creepages xi, eta (dimensionless) and spin phi (1/mm), friction coefficient mu > 0. flexibilities: of the
    contact ellipse (`kalker_flexibilities`); edges: (leading, trailing) edge x of each cell's strip (mm, (ny, nx);
    default `strip_edges` of the pressure, `ellipse_edges` for an exact ellipse). ContactEdgeError if the contact
    reaches the grid's first or last column (a strip must start and end inside the grid)."""
    pressure = checked_pressure(grid, pressure, mu, xi, eta, phi)
    lead = strip_edges(grid, pressure)[0] if edges is None else np.ascontiguousarray(edges[0], dtype=float)
    k = rates(flexibilities, xi, eta, phi, flexibility)
    bound = mu * pressure
    tau, slip = np.zeros((2,) + grid.shape), np.zeros((2,) + grid.shape)
    region = np.zeros(grid.shape, dtype=np.int8)
    _kernels.steady_rows(grid.x, grid.y, bound, lead, *k, tau, slip, region)
    return fast_result(grid, tau, slip, region, (xi, eta, phi), "fastsim", _used(flexibilities, k, flexibility))


def _used(flex, k, flexibility):
    return k[4] if flexibility == "weighted" else (flex.L1, flex.L2, flex.L3)


def checked_pressure(grid, pressure, mu, xi, eta, phi):
    """The pressure as a contiguous float array, after refusing what a fast model cannot take (InputError, or
    ContactEdgeError for a contact touching the grid's first or last column)."""
    pressure = np.ascontiguousarray(pressure, dtype=float)
    if pressure.shape != grid.shape or not np.all(np.isfinite(pressure)) or np.any(pressure < 0):
        raise InputError(f"pressure: must be a finite, non-negative array of the grid's shape {grid.shape}")
    if not (mu > 0 and math.isfinite(mu)):
        raise InputError(f"mu = {mu!r}: must be finite and > 0 (the fast models need a traction bound)")
    for name, v in (("xi", xi), ("eta", eta), ("phi", phi)):
        if not math.isfinite(v):
            raise InputError(f"{name} = {v!r}: must be finite")
    contact = pressure > 0
    if not contact.any():
        raise InputError("pressure: no cell in contact")
    if contact[:, 0].any() or contact[:, -1].any():
        raise ContactEdgeError("the contact reaches the grid's first or last column: each strip needs a free cell "
                               "ahead of and behind it")
    return pressure


def fast_result(grid, tau, slip, region, creepages, model, flexibility, origin=(0.0, 0.0)) -> FastResult:
    """The FastResult of a traction field: forces (sum tau dA) and the moment about `origin`."""
    X, Y = grid.mesh()
    dA = grid.cell_area
    force = (float(tau[0].sum() * dA), float(tau[1].sum() * dA))
    moment = float((((X - origin[0]) * tau[1] - (Y - origin[1]) * tau[0]).sum()) * dA)
    return FastResult(tau, slip, region, force, moment, tuple(float(c) for c in creepages), model, flexibility,
                      origin)


class FastsimRolling:
    """Transient FASTSIM on a world-fixed grid (x the rolling direction): the traction state of the material, moved
    on one rolling step at a time by `step`; module docstring. Start with `at_rest` (the initial state: zero traction,
    or Cattaneo's under the rigid slip of one step) and call `step` for each step of the contact centre."""

    def __init__(self, grid: Grid, mu, xi, eta, phi, *, flexibilities: Flexibilities, flexibility="weighted"):
        if not (mu > 0 and math.isfinite(mu)):
            raise InputError(f"mu = {mu!r}: must be finite and > 0 (the fast models need a traction bound)")
        self.grid, self.mu = grid, float(mu)
        self.creepages = (float(xi), float(eta), float(phi))
        self._k = rates(flexibilities, xi, eta, phi, flexibility)
        self._flexibility = _used(flexibilities, self._k, flexibility)
        self.traction = np.zeros((2,) + grid.shape)
        self._contact = np.zeros(grid.shape, dtype=bool)

    def at_rest(self, pressure, centre=0.0, step=None) -> FastResult:
        """The initial state under `pressure` (MPa) with the contact centre at x = centre (mm): zero traction
        (step None), or the simplified theory's Cattaneo state under the rigid slip of one step (mm)."""
        pressure = checked_pressure(self.grid, pressure, self.mu, *self.creepages)
        tau, slip = np.zeros((2,) + self.grid.shape), np.zeros((2,) + self.grid.shape)
        region = np.where(pressure > 0, _kernels.STICK, _kernels.EXTERIOR).astype(np.int8)
        if step is not None:
            _kernels.at_rest(self.grid.x, self.grid.y, centre, float(step), self.mu * pressure, *self._k, tau, slip,
                             region)
        self.traction, self._contact = tau, pressure > 0
        return fast_result(self.grid, tau.copy(), slip, region, self.creepages, "fastsim", self._flexibility,
                       (centre, 0.0))

    def step(self, pressure, centre, step) -> FastResult:
        """Roll the contact on by `step` (mm) to the centre x = centre (mm) under `pressure` (MPa) and return the
        state; slip over the step (mm)."""
        pressure = checked_pressure(self.grid, pressure, self.mu, *self.creepages)
        contact = pressure > 0
        lead = strip_edges(self.grid, pressure)[0]
        tau, slip = self.traction, np.zeros((2,) + self.grid.shape)
        region = np.zeros(self.grid.shape, dtype=np.int8)
        _kernels.transient_step(self.grid.x, self.grid.y, centre, float(step), self.mu * pressure, lead,
                                contact & ~self._contact, *self._k, tau, slip, region)
        self._contact = contact
        return fast_result(self.grid, tau.copy(), slip, region, self.creepages, "fastsim", self._flexibility,
                       (centre, 0.0))
