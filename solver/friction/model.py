"""The friction of a run: a law, its memory, the rolling speed and the iteration's tolerances, and what one solve with
it gives besides the contact solution (`FrictionState`). Units: mm, s, mm/s, W, degC."""
from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.friction.iteration import FrictionParams
from rollcontact.solver.friction.laws import FrictionLaw
from rollcontact.solver.friction.memory import FrictionMemory


@dataclass(frozen=True)
class LocalFriction:
    """A friction law with its memory at a rolling speed (mm/s; needed by the velocity laws and memory), the
    iteration's tolerances and, on a run's grid, the contact temperatures (`thermal`, a
    solver.friction.thermal.ContactTemperature: temperatures are computed with every solve; the temperature law needs
    them)."""

    law: FrictionLaw
    memory: FrictionMemory = field(default_factory=FrictionMemory)
    speed: float | None = None
    params: FrictionParams = field(default_factory=FrictionParams)
    thermal: object = None

    def __post_init__(self):
        if self.speed is not None and not (math.isfinite(self.speed) and self.speed > 0):
            raise InputError(f"rolling speed = {self.speed!r} mm/s: must be finite and > 0")
        if (self.law.velocity_dependent or self.memory.active) and self.speed is None:
            raise InputError(f"friction law {self.law.kind!r}" + (" with memory" if self.memory.active else "")
                             + " needs the rolling speed (the slip velocity is the slip over the step's time)")
        if self.memory.active and not self.law.velocity_dependent:
            raise InputError(f"friction memory applies to the slip-velocity laws, not to {self.law.kind!r}")

        if self.law.temperature_dependent and self.thermal is None:
            raise InputError("the temperature law needs the contact temperatures ([thermal])")

    @property
    def mu_static(self) -> float:
        return self.law.mu_static

    def step(self, solve, *, op, dt, previous_mu, moved=(0, 0), previous_residual=None):
        """One step of a stepped run with this law (solver.friction.transient.friction_step) on the grid of `op`
        (bem.HalfSpaceOperator: its self-coefficients are the elements' own feedback): (normal, tangential, outer,
        FrictionState). moved: (rows, cols), the contact's move since the previous step in whole cells.
        previous_residual: the previous step's FrictionState.first_residual (None: unknown)."""
        from rollcontact.solver.friction.transient import friction_step
        a = 0.5 * (op.self_coefficients["xx"] + op.self_coefficients["yy"])
        return friction_step(self, solve, grid=op.grid, dt=dt, previous_mu=previous_mu, self_coefficient=a,
                             thermal=self.thermal, moved=moved, previous_residual=previous_residual)

    @property
    def bounds(self) -> tuple[float, float]:
        """The range of coefficients the law can give (the iteration keeps its iterates in it)."""
        lo, hi = self.law.mu_lowest, self.law.mu_static
        if self.law.temperature_dependent:
            lo, hi = min(lo, hi, self.law.mu_ref + self.law.dmu_heat), max(lo, hi, self.law.mu_ref + self.law.dmu_heat)
        return lo, hi


@dataclass
class FrictionState:
    """With a friction law, a solve also gives: `mu` the local coefficient (ny, nx) that bounds its traction (the
    memory state at its end), `slip_velocity` (mm/s, (ny, nx)), the solves of the slip-velocity iteration
    (`iterations`), the frictional power (W), with temperatures `temperatures` (solver.friction.thermal), and the
    uniqueness indicator `feedback`: max |d mu/d s| of the law times a_self p_max / dt (stepped) or b p_max V (steady),
    the largest feedback J an element can have on its own coefficient (solver.friction.iteration): below 1 every
    element's own relation has one solution; at and above 1 the quasi-static problem may have several (Vollebregt &
    Schuttelaars 2012), and the answer found is one of them (docs/friction.md); memory lowers it."""

    mu: np.ndarray
    slip_velocity: np.ndarray
    iterations: int
    power: float
    temperatures: object | None = None
    feedback: float = 0.0     # the steepest fall of the law times the element's own slip per unit bound, at the
                              # largest pressure: >= 1 where the quasi-static problem may have several solutions
    first_residual: float = 0.0   # the residual of the iteration's first iterate (relative to mu_static): how far the
                                  # step's first coefficient field was from consistent (0: not iterated)
