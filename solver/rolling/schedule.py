"""Loads that oscillate within each period: the load schedule of a path (docs/theory.md §11.2-11.3).

A period is the rolling period when the sphere rolls (4 ceil(W/dW) steps, solver.rolling.stepping), or
`steps_per_period` steps at rest when it does not. At step k = 1..N of a period the rolling phase is
theta_k = 2 pi k / N, and the loads are

    Fn_k = Fn + normal_amplitude sin(m theta_k + phase)            (N)
    F_k  = F  + force_amplitude  sin(m theta_k + phase)            (N, vector along the force direction)

with m = cycles_per_period load cycles per period. The centre's triangle wave 0 -> +W -> 0 -> -W -> 0 has the
phase of sin theta, so phase = 0 puts the load maximum at c = +W (for m = 1), phase = 90 deg at c = 0 on the way
out, 180 deg at -W. The loading phase (Fn alone, then the ramp of the tangential force) goes to the schedule's
value at theta = 0: Fn_0 = Fn + normal_amplitude sin(phase), F_0 = F + force_amplitude sin(phase), so the
schedule is continuous at the start of the first period.

Units: N, degrees.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError

#: steps of one period when the sphere does not roll (motion.steps_per_period)
DEFAULT_STEPS_PER_PERIOD = 24


@dataclass(frozen=True)
class LoadOscillation:
    """Oscillation of the loads around their means within each period (see the module docstring).

    force_amplitude: (2,) N, amplitude of the tangential force vector; normal_amplitude: N, amplitude of Fn;
    phase: degrees, relative to the rolling (sin theta); cycles_per_period: load cycles per period (m >= 1);
    steps_per_period: steps of a period without rolling (N >= 4).
    """

    force_amplitude: tuple = (0.0, 0.0)
    normal_amplitude: float = 0.0
    phase: float = 0.0
    cycles_per_period: int = 1
    steps_per_period: int = DEFAULT_STEPS_PER_PERIOD

    def __post_init__(self):
        if int(self.cycles_per_period) != self.cycles_per_period or self.cycles_per_period < 1:
            raise InputError(f"load.cycles_per_period = {self.cycles_per_period}: must be an integer >= 1")
        if int(self.steps_per_period) != self.steps_per_period or self.steps_per_period < 4:
            raise InputError(f"motion.steps_per_period = {self.steps_per_period}: must be an integer >= 4")
        if not (math.isfinite(self.normal_amplitude) and self.normal_amplitude >= 0):
            raise InputError(f"load.fn_amplitude: normal force amplitude {self.normal_amplitude} N must be >= 0")

    @property
    def active(self) -> bool:
        """True when any load oscillates (otherwise the path is today's constant-load path)."""
        return bool(np.any(np.asarray(self.force_amplitude, dtype=float) != 0) or self.normal_amplitude != 0)

    def factor(self, k, n_per_period) -> np.ndarray:
        """sin(m theta_k + phase) at steps k (1..N) of a period of N steps; k = 0 gives the start value."""
        theta = 2.0 * math.pi * np.asarray(k, dtype=float) / n_per_period
        return np.sin(self.cycles_per_period * theta + math.radians(self.phase))

    def loads(self, Fn, force, k, n_per_period) -> tuple[np.ndarray, np.ndarray]:
        """(normal forces (len(k),) N, tangential forces (len(k), 2) N) at steps k of a period of N steps."""
        s = self.factor(k, n_per_period)
        normal = Fn + self.normal_amplitude * s
        forces = np.asarray(force, float)[None, :] + s[:, None] * np.asarray(self.force_amplitude, float)[None, :]
        return normal, forces

    def reversals(self, n_per_period) -> np.ndarray:
        """(N,) bool: steps 1..N of a period after which the load turns back (a discrete extremum of the
        schedule), and the period's last step."""
        k = np.arange(0, n_per_period + 2)
        v = self.factor(k, n_per_period)
        before, after = np.diff(v)[:-1], np.diff(v)[1:]
        turn = np.sign(before) * np.sign(after) < 0
        turn[-1] = True
        return turn


def check_schedule(normal_forces, forces, mu):
    """InputError naming the key if a step would lift the sphere off (Fn <= 0) or ask for |F| >= mu Fn."""
    normal_forces = np.asarray(normal_forces, dtype=float)
    if np.any(~(normal_forces > 0)):
        k = int(np.argmin(normal_forces))
        raise InputError(f"load.fn_amplitude: the normal force reaches {normal_forces[k]:.6g} N <= 0 at step {k} "
                         "(the sphere would lift off); allowed: Fn (1 - fn_amplitude) > 0")
    use = np.hypot(*np.asarray(forces, dtype=float).T) / (mu * normal_forces)
    if np.any(use >= 1.0):
        k = int(np.argmax(use))
        raise InputError(f"load.ft_amplitude: |Ft| reaches {use[k]:.6g} mu Fn at step {k} (gross sliding); "
                         "allowed: |Ft| < mu Fn at every step")
