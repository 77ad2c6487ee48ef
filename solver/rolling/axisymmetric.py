"""Axisymmetric gap profiles h(r) beyond the sphere, with their MDR profiles g(s) (docs/theory.md §8.1, §11.4).

Each profile is a callable profile(X, Y, centre) -> h (mm), like those of `solver.rolling.profiles`, so the
rolling solver takes it as it is; r is the distance from the centre. Each also gives the MDR (method of
dimensionality reduction) profile g(s) = |s| int_0^|s| h'(r)/sqrt(s^2 - r^2) dr of the 1-D spring model, its
slope g'(s) and the integral G(s) = int_0^s g dt, from which `solver.mdr.exact` builds the exact normal and
tangential answers. Lengths in mm, angles in degrees.

    ConeProfile(slope)            h = r tan(slope)                 g = (pi/2) |s| tan(slope)
    PowerProfile(n, R)            h = r^n / (n R^(n-1))            g = kappa_n |s|^n / (n R^(n-1)),
                                  kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2)   (n = 2: sphere)
    RoundedFlatProfile(b, R)      h = 0 for r <= b, (r - b)^2/(2R) beyond (a flat punch of radius b whose edge
                                  is rounded with radius R, to the leading order of the circle, docs/theory.md §11.4)
                                  g = (|s|/R) [sqrt(s^2 - b^2) - b arccos(b/|s|)] for |s| > b, else 0

The rounded flat punch's g follows from int_b^s (r - b)/sqrt(s^2 - r^2) dr = sqrt(s^2 - b^2) - b arccos(b/s);
its slope is g' = (2 sqrt(s^2 - b^2) - b arccos(b/s))/R and its integral
G(s) = [(s^2 - b^2)^(3/2)/3 - b (s^2 arccos(b/s) - b sqrt(s^2 - b^2))/2]/R (b = 0: the sphere's s^3/(3R)).
"""
from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError


class AxisymmetricProfile:
    """Base of the axisymmetric profiles: h(r) (`radial`), g(s), g'(s) and G(s) for s >= 0 (mm)."""

    def __call__(self, X, Y, centre=(0.0, 0.0)):
        return self.radial(np.hypot(X - centre[0], Y - centre[1]))

    def radial(self, r):
        raise NotImplementedError

    def mdr(self, s):
        """The MDR profile g(s) (mm) at s >= 0."""
        raise NotImplementedError

    def mdr_slope(self, s):
        """g'(s) (dimensionless) at s >= 0."""
        raise NotImplementedError

    def mdr_integral(self, s):
        """G(s) = int_0^s g(t) dt (mm^2) at s >= 0."""
        raise NotImplementedError


def _positive(name, value, unit):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"profile {name} = {value!r}{unit}: must be finite and > 0")


@dataclass(frozen=True)
class ConeProfile(AxisymmetricProfile):
    """h = r tan(slope), slope in degrees against the undeformed surface, 0 < slope < 90."""

    slope: float

    def __post_init__(self):
        if not (isinstance(self.slope, (int, float)) and 0.0 < self.slope < 90.0):
            raise InputError(f"cone slope = {self.slope!r} deg: allowed range is (0, 90) deg")

    @property
    def tan(self) -> float:
        return math.tan(math.radians(self.slope))

    def radial(self, r):
        return np.asarray(r, dtype=float) * self.tan

    def mdr(self, s):
        return 0.5 * math.pi * self.tan * np.abs(s)

    def mdr_slope(self, s):
        return np.full_like(np.asarray(s, dtype=float), 0.5 * math.pi * self.tan)

    def mdr_integral(self, s):
        return 0.25 * math.pi * self.tan * np.asarray(s, dtype=float) ** 2


@dataclass(frozen=True)
class PowerProfile(AxisymmetricProfile):
    """h = r^n / (n R^(n-1)), n >= 1 (n = 2 is the sphere of radius R)."""

    n: float
    R: float

    def __post_init__(self):
        if not (isinstance(self.n, (int, float)) and 1.0 <= self.n <= 20.0):
            raise InputError(f"power n = {self.n!r}: allowed range is [1, 20]")
        _positive("R", self.R, " mm")

    @property
    def kappa(self) -> float:
        """kappa_n = sqrt(pi) Gamma(n/2 + 1)/Gamma(n/2 + 1/2) (kappa_2 = 2, kappa_4 = 8/3)."""
        return math.sqrt(math.pi) * math.exp(math.lgamma(self.n / 2 + 1) - math.lgamma(self.n / 2 + 0.5))

    @property
    def coefficient(self) -> float:
        """c of h = c r^n (mm^(1-n))."""
        return 1.0 / (self.n * self.R ** (self.n - 1))

    def radial(self, r):
        return self.coefficient * np.asarray(r, dtype=float) ** self.n

    def mdr(self, s):
        return self.kappa * self.coefficient * np.abs(s) ** self.n

    def mdr_slope(self, s):
        return self.n * self.kappa * self.coefficient * np.abs(s) ** (self.n - 1)

    def mdr_integral(self, s):
        return self.kappa * self.coefficient * np.asarray(s, dtype=float) ** (self.n + 1) / (self.n + 1)


@dataclass(frozen=True)
class RoundedFlatProfile(AxisymmetricProfile):
    """Flat punch of radius b with its edge rounded by radius R: h = 0 for r <= b, (r - b)^2/(2R) beyond."""

    b: float
    R: float

    def __post_init__(self):
        _positive("b", self.b, " mm")
        _positive("R", self.R, " mm")

    def radial(self, r):
        out = np.maximum(np.asarray(r, dtype=float) - self.b, 0.0)
        return out * out / (2.0 * self.R)

    def _parts(self, s):
        s = np.maximum(np.abs(np.asarray(s, dtype=float)), self.b)
        return s, np.sqrt(s * s - self.b * self.b), np.arccos(self.b / s)

    def mdr(self, s):
        s, root, angle = self._parts(s)
        return s * (root - self.b * angle) / self.R

    def mdr_slope(self, s):
        _, root, angle = self._parts(s)
        return (2.0 * root - self.b * angle) / self.R

    def mdr_integral(self, s):
        s, root, angle = self._parts(s)
        return (root ** 3 / 3.0 - 0.5 * self.b * (s * s * angle - self.b * root)) / self.R
