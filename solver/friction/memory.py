"""Friction memory: the local coefficient relaxes towards the law's value over a sliding distance (docs/theory.md §12.1;
docs/friction.md, "Friction memory"; Vollebregt & Schuttelaars 2012; the CONTACT user guide's "Friction memory").

    d mu / dt = -max(s, s_0) / d_c (mu - mu_law(s))

with s the slip velocity (mm/s), d_c the memory distance (mm) and s_0 (mm/s) the smallest rate at which the
coefficient still relaxes where nothing slips (s = 0: towards mu_static). Over a step of duration dt with s and
mu_law(s) constant (the step's slip velocity; the coefficient at the end of the step is the one that bounds its
traction, as the slip of the step is the one that ends it) the solution is exact:

    mu_n = mu_law(s) + (mu_(n-1) - mu_law(s)) E,      E = exp(-max(s, s_0) dt / d_c).

d_c = 0 is the instantaneous law, mu = mu_law(s). Where the surfaces are out of contact s = 0. In steady rolling the
time derivative follows the material through the contact-fixed grid, d/dt = -V d/dx: the same step from the cell
upstream (x + dx) to the cell, dt = dx / V, starting from mu_static ahead of the contact (the material there has
rested). Units: mm, s, mm/s.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError


@dataclass(frozen=True)
class FrictionMemory:
    """d_c = `distance` (mm, >= 0; 0: no memory) and s_0 = `s0` (mm/s, >= 0)."""

    distance: float = 0.0
    s0: float = 0.0

    def __post_init__(self):
        for name, unit in (("distance", "mm"), ("s0", "mm/s")):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"friction memory {name} = {v!r} {unit}: must be finite and >= 0")

    @property
    def active(self) -> bool:
        return self.distance > 0.0

    def decay(self, s, dt) -> np.ndarray:
        """E = exp(-max(s, s_0) dt / d_c) for slip velocities s (mm/s) over dt (s); 0 without memory."""
        s = np.asarray(s, dtype=float)
        if not self.active:
            return np.zeros(s.shape)
        return np.exp(-np.maximum(s, self.s0) * dt / self.distance)

    def step(self, previous, law_value, s, dt) -> np.ndarray:
        """mu at the end of a step of dt (s) from `previous` with the law's value `law_value` at slip velocity s
        (module docstring)."""
        if not self.active:
            return np.asarray(law_value, dtype=float)
        E = self.decay(s, dt)
        return law_value + (np.asarray(previous, dtype=float) - law_value) * E

    def step_slope(self, previous, law_value, law_slope, s, dt) -> np.ndarray:
        """d mu_n / d s of `step` (1/(mm/s)): the law's slope weighted by 1 - E, plus the faster decay of the
        difference where s > s_0."""
        s = np.asarray(s, dtype=float)
        E = self.decay(s, dt)
        if not self.active:
            return np.asarray(law_slope, dtype=float) * np.ones(s.shape)
        faster = np.where(s > self.s0, -dt / self.distance * E, 0.0)
        return law_slope * (1.0 - E) + (np.asarray(previous, dtype=float) - law_value) * faster

    def steady_rows(self, law_value, law_slope, s, dx, speed, entering):
        """The steady coefficient on a contact-fixed grid (ny, nx) whose material flows from x + dx to x (the cell
        upstream is [:, i + 1]), each cell a step of dt = dx / speed (s) at its own slip velocity s (mm/s), from
        `entering` ahead of the grid. Returns (mu, d mu / d s of each cell with its upstream value held)."""
        law_value, law_slope, s = (np.asarray(a, dtype=float) for a in (law_value, law_slope, s))
        dt = dx / speed
        mu = np.empty_like(law_value)
        slope = np.empty_like(law_value)
        upstream = np.full(law_value.shape[0], float(entering))
        for i in range(law_value.shape[1] - 1, -1, -1):
            mu[:, i] = self.step(upstream, law_value[:, i], s[:, i], dt)
            slope[:, i] = self.step_slope(upstream, law_value[:, i], law_slope[:, i], s[:, i], dt)
            upstream = mu[:, i]
        return mu, slope
