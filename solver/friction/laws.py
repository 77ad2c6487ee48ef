"""Friction laws: the local coefficient of friction as a function of the slip velocity or of the surface temperature
(docs/theory.md §12.1; docs/friction.md, "Friction laws"; the CONTACT user guide's "Friction description").

With s >= 0 the magnitude of the local slip velocity (mm/s):

    coulomb       mu(s) = mu
    linear        mu(s) = mu_kin + mu_1 max(0, 1 - s/(2 s_1)) + mu_2 max(0, 1 - s/(2 s_2))
    rational      mu(s) = mu_kin + mu_1 / (1 + s/s_1) + mu_2 / (1 + (s/s_2)^2)
    exponential   mu(s) = mu_kin + mu_1 exp(-ln2 s/s_1) + mu_2 exp(-ln2 s/s_2)      (Polach 2005 with one term)

each velocity term of size mu_i at s = 0, so mu_static = mu(0) = mu_kin + mu_1 + mu_2; s_i is where a term is halved
(linear: where it ends). With T the surface temperature (degC):

    temperature   mu(T) = mu_ref for T <= T_ref, linear to mu_ref + dmu_heat over [T_ref, T_ref + dT_heat],
                  constant above

Polach's mu_stat ((1 - A) e^(-B s) + A) is the exponential law with mu_kin = A mu_stat, mu_1 = (1 - A) mu_stat,
s_1 = ln 2 / B (B in s/mm). Evaluations take and return numpy arrays; `slope` is d mu / d s (1/(mm/s)), zero where a
linear term has ended, `temperature_slope` d mu / d T (1/degC).
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError

KINDS = ("coulomb", "linear", "rational", "exponential", "temperature")
VELOCITY_KINDS = ("linear", "rational", "exponential")
LN2 = math.log(2.0)


@dataclass(frozen=True)
class FrictionLaw:
    """One friction law (module docstring). `kind` names it; the parameters that do not belong to it stay 0.

    Velocity laws: mu_kin > 0 and mu_1, mu_2 >= 0; s_1, s_2 (mm/s) > 0 for a term of non-zero size. Coulomb: mu > 0.
    Temperature: mu_ref > 0, T_ref (degC), dmu_heat with mu_ref + dmu_heat > 0, dT_heat (degC) > 0."""

    kind: str
    mu: float = 0.0
    mu_kin: float = 0.0
    mu_1: float = 0.0
    mu_2: float = 0.0
    s_1: float = 0.0
    s_2: float = 0.0
    mu_ref: float = 0.0
    T_ref: float = 0.0
    dmu_heat: float = 0.0
    dT_heat: float = 0.0

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"friction law {self.kind!r}: allowed values are {list(KINDS)}")
        for name in ("mu", "mu_kin", "mu_1", "mu_2", "s_1", "s_2", "mu_ref", "T_ref", "dmu_heat", "dT_heat"):
            if not math.isfinite(getattr(self, name)):
                raise InputError(f"friction.{name} = {getattr(self, name)!r}: must be finite")
        if self.kind == "coulomb" and not self.mu > 0:
            raise InputError(f"friction.mu = {self.mu!r}: must be > 0")
        if self.kind in VELOCITY_KINDS:
            if not self.mu_kin > 0 or self.mu_1 < 0 or self.mu_2 < 0:
                raise InputError(f"friction.mu_kin = {self.mu_kin!r}, mu_1 = {self.mu_1!r}, mu_2 = {self.mu_2!r}: "
                                 "allowed mu_kin > 0, mu_1 >= 0, mu_2 >= 0")
            for size, speed in (("mu_1", "s_1"), ("mu_2", "s_2")):
                if getattr(self, size) > 0 and not getattr(self, speed) > 0:
                    raise InputError(f"friction.{speed} = {getattr(self, speed)!r} mm/s: must be > 0 with "
                                     f"{size} = {getattr(self, size)!r}")
        if self.kind == "temperature":
            if not (self.mu_ref > 0 and self.mu_ref + self.dmu_heat > 0 and self.dT_heat > 0):
                raise InputError(f"friction.mu_ref = {self.mu_ref!r}, dmu_heat = {self.dmu_heat!r}, dT_heat = "
                                 f"{self.dT_heat!r}: allowed mu_ref > 0, mu_ref + dmu_heat > 0, dT_heat > 0 degC")

    @property
    def velocity_dependent(self) -> bool:
        return self.kind in VELOCITY_KINDS

    @property
    def temperature_dependent(self) -> bool:
        return self.kind == "temperature"

    @property
    def mu_static(self) -> float:
        """mu at rest: mu(0) of a velocity law, mu_ref at a temperature at or below T_ref, mu of Coulomb's."""
        if self.kind == "coulomb":
            return self.mu
        if self.kind == "temperature":
            return self.mu_ref
        return self.mu_kin + self.mu_1 + self.mu_2

    @property
    def mu_lowest(self) -> float:
        """The smallest coefficient the law gives: mu_kin of a velocity law (reached as s -> inf)."""
        if self.kind == "temperature":
            return min(self.mu_ref, self.mu_ref + self.dmu_heat)
        return self.mu if self.kind == "coulomb" else self.mu_kin

    def coefficient(self, s) -> np.ndarray:
        """mu(s) at slip velocities s (mm/s, >= 0); for the temperature law use `of_temperature`."""
        s = np.abs(np.asarray(s, dtype=float))
        if self.kind == "coulomb":
            return np.full(s.shape, self.mu)
        if self.kind == "temperature":
            raise InputError("the temperature law depends on the surface temperature, not on the slip velocity")
        return self.mu_kin + self._term(self.mu_1, self.s_1, s, 1) + self._term(self.mu_2, self.s_2, s, 2)

    def slope(self, s) -> np.ndarray:
        """d mu / d s (1/(mm/s)) at s (mm/s, >= 0): <= 0 for these laws (falling friction)."""
        s = np.abs(np.asarray(s, dtype=float))
        if not self.velocity_dependent:
            return np.zeros(s.shape)
        return self._dterm(self.mu_1, self.s_1, s, 1) + self._dterm(self.mu_2, self.s_2, s, 2)

    def steepest_slope(self) -> float:
        """The steepest fall |d mu / d s| (1/(mm/s)): the sum of each term's (at s = 0 for the linear, exponential and
        first rational terms, at s = s_2/sqrt(3) for the second rational term), exact for one term and an upper bound
        for two; 0 for Coulomb and the temperature law."""
        if not self.velocity_dependent:
            return 0.0
        terms = []
        for size, scale, which in ((self.mu_1, self.s_1, 1), (self.mu_2, self.s_2, 2)):
            if size > 0:
                x = 1.0 / math.sqrt(3.0) if (self.kind == "rational" and which == 2) else 0.0
                terms.append(abs(float(self._dterm(size, scale, np.array(x * scale), which))))
        return sum(terms)

    def _term(self, size, scale, s, which):
        if size == 0.0:
            return 0.0
        x = s / scale
        if self.kind == "linear":
            return size * np.maximum(0.0, 1.0 - 0.5 * x)
        if self.kind == "rational":
            return size / (1.0 + x) if which == 1 else size / (1.0 + x * x)
        return size * np.exp(-LN2 * x)

    def _dterm(self, size, scale, s, which):
        if size == 0.0:
            return 0.0
        x = s / scale
        if self.kind == "linear":
            return np.where(x < 2.0, -0.5 * size / scale, 0.0)
        if self.kind == "rational":
            return -size / (scale * (1.0 + x) ** 2) if which == 1 else -2.0 * size * x / (scale * (1.0 + x * x) ** 2)
        return -LN2 * size / scale * np.exp(-LN2 * x)

    def of_temperature(self, T) -> np.ndarray:
        """mu(T) of the temperature law at surface temperatures T (degC)."""
        T = np.asarray(T, dtype=float)
        ramp = np.clip((T - self.T_ref) / self.dT_heat, 0.0, 1.0)
        return self.mu_ref + self.dmu_heat * ramp

    def temperature_slope(self, T) -> np.ndarray:
        """d mu / d T (1/degC) of the temperature law."""
        T = np.asarray(T, dtype=float)
        inside = (T > self.T_ref) & (T < self.T_ref + self.dT_heat)
        return np.where(inside, self.dmu_heat / self.dT_heat, 0.0)

    def describe(self) -> str:
        """The law in one line, for summaries and messages."""
        if self.kind == "coulomb":
            return f"coulomb mu = {self.mu:.6g}"
        if self.kind == "temperature":
            return (f"temperature mu_ref = {self.mu_ref:.6g} below T_ref = {self.T_ref:.6g} degC, "
                    f"{self.mu_ref + self.dmu_heat:.6g} above {self.T_ref + self.dT_heat:.6g} degC")
        terms = [f"mu_{i} = {m:.6g} (s_{i} = {s:.6g} mm/s)" for i, (m, s) in
                 enumerate(((self.mu_1, self.s_1), (self.mu_2, self.s_2)), start=1) if m > 0]
        return f"{self.kind} mu_kin = {self.mu_kin:.6g}" + ("" if not terms else ", " + ", ".join(terms))
