"""Closed-form reference solutions (docs/theory.md §7), used by tests, benchmarks and run summaries.

Units mm, N, MPa. Material constants come from `bem.materials.MaterialPair` (E*, G*).
"""
from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError


@dataclass(frozen=True)
class HertzSphere:
    """Hertz contact of a sphere (radius R, mm) on a flat with contact modulus E* (MPa) under Fn (N)."""

    R: float
    E_star: float
    Fn: float

    @property
    def a(self) -> float:
        """Contact radius (mm): (3 Fn R / (4 E*))^(1/3)."""
        return (3.0 * self.Fn * self.R / (4.0 * self.E_star)) ** (1.0 / 3.0)

    @property
    def approach(self) -> float:
        """Approach d = a^2/R (mm)."""
        return self.a ** 2 / self.R

    @property
    def p0(self) -> float:
        """Peak pressure 3 Fn/(2 pi a^2) (MPa)."""
        return 1.5 * self.Fn / (math.pi * self.a ** 2)

    def pressure(self, r):
        """p(r) = p0 sqrt(1 - r^2/a^2) inside, 0 outside (MPa)."""
        r = np.asarray(r, dtype=float)
        return self.p0 * np.sqrt(np.clip(1.0 - (r / self.a) ** 2, 0.0, None))

    def displacement(self, r):
        """Total normal surface displacement w(r) of both bodies (mm), inside and outside the contact."""
        r = np.asarray(r, dtype=float)
        a, R = self.a, self.R
        out = self.approach - r ** 2 / (2.0 * R)
        rr = np.maximum(r, a)
        outside = ((2 * a ** 2 - rr ** 2) * np.arcsin(a / rr) + a * np.sqrt(rr ** 2 - a ** 2)) / (math.pi * R)
        return np.where(r <= a, out, outside)


@dataclass(frozen=True)
class HertzLine:
    """2-D (plane strain) Hertz line contact of a cylinder of radius R (mm) on a flat, contact modulus E* (MPa),
    load P per unit length (N/mm) (Johnson 1985, §4.3): half-width a = sqrt(4 P R/(pi E*)),
    p0 = 2 P/(pi a) = E* a/(2 R), p(x) = p0 sqrt(1 - x^2/a^2). The approach is not defined in 2-D (it depends on
    where the displacement is measured), so there is none here."""

    R: float
    E_star: float
    P: float

    @property
    def a(self) -> float:
        """Half-width (mm)."""
        return math.sqrt(4.0 * self.P * self.R / (math.pi * self.E_star))

    @property
    def p0(self) -> float:
        """Peak pressure 2 P/(pi a) (MPa)."""
        return 2.0 * self.P / (math.pi * self.a)

    def pressure(self, x):
        """p(x) = p0 sqrt(1 - x^2/a^2) inside, 0 outside (MPa); x across the line, mm."""
        x = np.asarray(x, dtype=float)
        return self.p0 * np.sqrt(np.clip(1.0 - (x / self.a) ** 2, 0.0, None))


def check_ft(f_t):
    if not (0.0 <= f_t <= 1.0):
        raise InputError(f"f_t = Ft/(mu Fn) = {f_t!r}: allowed range is 0 <= f_t <= 1")


@dataclass(frozen=True)
class CattaneoMindlin:
    """Cattaneo-Mindlin partial slip of a Hertz sphere under a monotonically increasing Ft (docs/theory.md §7.2).

    Exact for nu = 0 and beta = 0; for nu = 0.5 the shift is within a few 0.1 % (docs/theory.md P10).
    """

    hertz: HertzSphere
    mu: float
    G_star: float

    @property
    def U0(self) -> float:
        """Full-slip shift U0 = mu E* d / G* (mm), the normalisation of seed Eq. 9."""
        return self.mu * self.hertz.E_star * self.hertz.approach / self.G_star

    def stick_radius(self, f_t) -> float:
        """c = a (1 - f_t)^(1/3) (mm), seed Eq. 5."""
        check_ft(f_t)
        return self.hertz.a * (1.0 - f_t) ** (1.0 / 3.0)

    def shift(self, f_t) -> float:
        """U_stat = U0 (1 - (1 - f_t)^(2/3)) (mm), seed Eq. 4."""
        check_ft(f_t)
        return self.U0 * (1.0 - (1.0 - f_t) ** (2.0 / 3.0))

    def traction(self, r, f_t):
        """tau(r) along the force (MPa): mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)]."""
        r = np.asarray(r, dtype=float)
        a, c = self.hertz.a, self.stick_radius(f_t)
        mp0 = self.mu * self.hertz.p0
        outer = np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
        inner = (c / a) * np.sqrt(np.clip(1.0 - (r / c) ** 2, 0.0, None)) if c > 0 else 0.0 * r
        return mp0 * (outer - inner)

    def unloading_shift(self, f_t_max, f_t) -> float:
        """Mindlin-Deresiewicz: shift (mm) after loading to f_t_max and unloading to f_t >= -f_t_max.

        U(f) = U_load(f_max) - 2 U_load((f_max - f)/2)   (Johnson 1985, §7.3).
        """
        check_ft(f_t_max)
        if not (-f_t_max <= f_t <= f_t_max):
            raise InputError(f"f_t = {f_t!r}: unloading branch needs -{f_t_max} <= f_t <= {f_t_max}")
        return self.shift(f_t_max) - 2.0 * self.shift(0.5 * (f_t_max - f_t))

    def reloading_shift(self, f_t_max, f_t) -> float:
        """Mindlin-Deresiewicz: shift (mm) on the reloading branch from -f_t_max back to f_t <= f_t_max.

        U(f) = -U_load(f_max) + 2 U_load((f_max + f)/2)   (docs/theory.md §11.2; the unloading branch mirrored).
        """
        return -self.unloading_shift(f_t_max, -f_t)

    def cycle_dissipation(self, f_t_max) -> float:
        """Energy (N mm) dissipated per full cycle between +f_t_max and -f_t_max (the loop area, docs/theory.md §11.2):

        dW = 4 mu Fn U0 [6/5 - x - x (1 - x)^(2/3) - (6/5)(1 - x)^(5/3)],  x = f_t_max (-> 4 mu Fn U0 x^3/27).
        """
        check_ft(f_t_max)
        x = f_t_max
        bracket = 1.2 - x - x * (1.0 - x) ** (2.0 / 3.0) - 1.2 * (1.0 - x) ** (5.0 / 3.0)
        return 4.0 * self.mu * self.hertz.Fn * self.U0 * bracket


@dataclass(frozen=True)
class HertzEllipse:
    """Hertz contact of a body with principal radii Rx, Ry (mm) on a flat, contact modulus E* (MPa), load
    Fn (N): profile h = x^2/(2 Rx) + y^2/(2 Ry), elliptic contact with semi-axes a (along x), b (along y).

    Johnson 1985, §4.2 (eqs. 4.36-4.41 in the notation below). With A = 1/(2 Rx) and B = 1/(2 Ry) and,
    for the long axis along x (A <= B, a >= b), the eccentricity e^2 = 1 - b^2/a^2 and the complete
    elliptic integrals K(e), E(e) (scipy's ellipk/ellipe take the parameter m = e^2):

        p(x, y) = p0 sqrt(1 - x^2/a^2 - y^2/b^2),       Fn = (2/3) pi a b p0
        A = p0 b / (E* a^2 e^2) [K - E]
        B = p0 b / (E* a^2 e^2) [(a^2/b^2) E - K]
        d = p0 b K / E*

    e follows from B/A = [(a/b)^2 E - K] / (K - E) (solved with brentq); then
    a^3 = 3 Fn (K - E) / (2 pi A E* e^2), b = a sqrt(1 - e^2), p0 = 3 Fn / (2 pi a b), d = p0 b K / E*.
    For Rx < Ry the roles of x and y are exchanged. Rx = Ry reduces to `HertzSphere` (e = 0).
    """

    Rx: float
    Ry: float
    E_star: float
    Fn: float

    def __post_init__(self):
        for name in ("Rx", "Ry", "E_star", "Fn"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise InputError(f"HertzEllipse.{name} = {value!r}: must be finite and > 0")

    def _solution(self):
        """(a_long, b_short, e, K, E) with the long semi-axis along the axis of the larger radius."""
        from scipy.optimize import brentq
        from scipy.special import ellipe, ellipk

        A, B = 0.5 / max(self.Rx, self.Ry), 0.5 / min(self.Rx, self.Ry)   # A <= B
        ratio = B / A
        if ratio - 1.0 < 1e-12:
            a = (3.0 * self.Fn * (0.5 / A) / (4.0 * self.E_star)) ** (1.0 / 3.0)
            return a, a, 0.0, 0.5 * math.pi, 0.5 * math.pi

        def mismatch(e):
            m = e * e
            K, E = ellipk(m), ellipe(m)
            return (E / (1.0 - m) - K) / (K - E) - ratio

        e = brentq(mismatch, 1e-6, 1.0 - 1e-14, xtol=1e-15, rtol=1e-15, maxiter=200)
        m = e * e
        K, E = float(ellipk(m)), float(ellipe(m))
        a = (3.0 * self.Fn * (K - E) / (2.0 * math.pi * A * self.E_star * m)) ** (1.0 / 3.0)
        return a, a * math.sqrt(1.0 - m), e, K, E

    @property
    def eccentricity(self) -> float:
        """e = sqrt(1 - (short/long)^2) of the contact ellipse."""
        return self._solution()[2]

    @property
    def a(self) -> float:
        """Semi-axis along x (mm)."""
        long, short = self._solution()[:2]
        return long if self.Rx >= self.Ry else short

    @property
    def b(self) -> float:
        """Semi-axis along y (mm)."""
        long, short = self._solution()[:2]
        return short if self.Rx >= self.Ry else long

    @property
    def p0(self) -> float:
        """Peak pressure 3 Fn / (2 pi a b) (MPa)."""
        return 1.5 * self.Fn / (math.pi * self.a * self.b)

    @property
    def approach(self) -> float:
        """Approach d = p0 b_short K(e) / E* (mm)."""
        _, short, _, K, _ = self._solution()
        return self.p0 * short * K / self.E_star

    def pressure(self, x, y):
        """p(x, y) = p0 sqrt(1 - x^2/a^2 - y^2/b^2) inside, 0 outside (MPa); x, y in mm."""
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        return self.p0 * np.sqrt(np.clip(1.0 - (x / self.a) ** 2 - (y / self.b) ** 2, 0.0, None))


def spence_beta_over_mu(c_over_a) -> float:
    """|beta|/mu at which the stick zone of a monotonically loaded Hertz contact has radius c = (c/a) a.

    The closed-form side of the equation solved by `spence_stick_ratio` (see there), with k = c/a in (0, 1):

        |beta|/mu = 2 k K(m = 1 - k^2) / ln((1 + k)/(1 - k)),

    K the complete elliptic integral of the first kind (parameter m, scipy's convention). Decreases
    monotonically from +inf (k -> 0) to 0 (k -> 1).
    """
    from scipy.special import ellipkm1

    k = float(c_over_a)
    if not (0.0 < k < 1.0):
        raise InputError(f"c/a = {c_over_a!r}: allowed range is 0 < c/a < 1")
    return 2.0 * k * float(ellipkm1(k * k)) / (2.0 * math.atanh(k))


def spence_stick_ratio(beta, mu) -> float:
    """Radius ratio c/a of the central stick zone of a Hertz contact of dissimilar materials under a normal
    load increased monotonically from zero, with no tangential force (Spence 1975).

    Parameters: beta, Dundurs' second constant of the pair (`bem.materials.MaterialPair.beta`, sphere =
    body 1, substrate = body 2; -0.5 <= beta <= 0.5); mu > 0, the Coulomb coefficient. Returns c/a in
    [0, 1]: 1 for beta = 0 (no slip: the pressure then displaces both surfaces alike), -> 0 as |beta|/mu
    grows. c/a stays constant during the loading (the problem is self-similar) and depends on |beta|/mu only.

    Background (D. A. Spence, "The Hertz contact problem with finite friction", J. Elasticity 5 (1975)
    297-319; Johnson, Contact Mechanics, 1985, ch. 5). The pressure p displaces the two surfaces radially
    by different amounts (by -(2 beta/E*) (1/r) int_0^r p s ds relative to each other, docs/theory.md §2.2); friction
    resists it with a radial traction that sticks in r < c and slips, |q| = mu p, in the annulus c < r < a.
    Only the first-order coupling is kept: the pressure is Hertz's, unaffected by q (the effect of q on p is
    of order beta mu). Because every field grows self-similarly with a, the load increment is a flat-punch
    pressure dp ~ 1/sqrt(a^2 - r^2). Writing the radial problem with Hankel transforms of order 1 and
    Abel-type representations (Sneddon), the stick condition du = 0 on r < c fixes the Abel density of dq
    there to (beta/pi) ln((a + t)/(a - t)) per unit flat-punch density; the slip condition dq = mu dp
    fixes it to (2 t/(pi a)) mu K(sqrt(1 - t^2/a^2)) on c < t < a. A bounded traction at r = c (and then
    a continuous one) requires the two to meet at t = c:

        |beta|/mu = 2 k K(m = 1 - k^2) / ln((1 + k)/(1 - k)),    k = c/a          (`spence_beta_over_mu`)

    Solved here for k with brentq in the variable L = ln((1 + k)/(1 - k)) (k = tanh(L/2)), which keeps
    both ends representable. Limits: c/a -> 4 exp(-|beta|/mu) for |beta|/mu -> inf (almost full slip) and
    1 - c/a -> 2 exp(-pi mu/|beta|) for |beta|/mu -> 0 (almost full stick); c/a = 0.9, 0.75, 0.5, 0.2 at
    |beta|/mu = 1.0115, 1.3910, 1.9629, 2.9755.

    Signs: in the slip annulus the traction on the substrate is radial, q_r = -sign(beta) mu p: inward for
    beta > 0 (the pressure draws the sphere's surface inward more than the substrate's, (1 - 2 nu1)/G1 >
    (1 - 2 nu2)/G2), outward for beta < 0 (e.g. a rigid sphere on an elastic substrate).

    What it was checked against: the equation above is a derivation made for this module (the 1975 paper
    itself could not be consulted here), so it was checked (i) against its limits (c/a -> 1 as
    |beta|/mu -> 0, -> 0 as |beta|/mu -> inf, monotone in between) and (ii) against the coupled BEM solver
    (tests/solver/test_coupled_spence.py), which solves the full problem independently. Equivalent radius
    of the discrete stick zone, dx = a/80, 400 load steps from 0.15 a: c/a = 0.7630 against 0.7633
    (beta = -0.048, mu = 0.035) and 0.3490 against 0.3493 (beta = +0.048, mu = 0.020); at
    |beta|/mu = 1.668 with beta mu = 2.9e-4 (dx = a/40, 150 steps), 0.6297 against 0.6264; the slip
    traction has the sign above in every case. The neglected effect of q on p lowers the discrete c/a by
    roughly 0.6-0.85 beta mu (at |beta|/mu = 1.668: -0.005 at beta mu = 0.008, the same for either sign of
    beta; -0.07 at beta mu = 0.083, where the contact radius also shrinks by about 1.5 %), so c/a is a
    function of beta/mu alone only while beta mu is small.
    """
    from scipy.optimize import brentq
    from scipy.special import ellipkm1

    beta, mu = float(beta), float(mu)
    if not (math.isfinite(mu) and mu > 0):
        raise InputError(f"mu = {mu!r}: the friction coefficient must be finite and > 0")
    if not (math.isfinite(beta) and abs(beta) <= 0.5):
        raise InputError(f"beta = {beta!r}: Dundurs' beta lies in -0.5 <= beta <= 0.5")
    x = abs(beta) / mu
    if x == 0.0:
        return 1.0
    if x > 300.0:
        # c/a < 1e-130: the asymptote is exact to round-off (relative error O(k^2 ln k)), and k^2 would
        # underflow in the equation beyond x ~ 350
        return 4.0 * math.exp(-x)

    def mismatch(L):
        k = math.tanh(0.5 * L)
        return 2.0 * k * float(ellipkm1(k * k)) / L - x

    # brackets from the two asymptotes: L = 2 exp(-x), i.e. k = exp(-x), a quarter of the small-k root
    # (mismatch about ln 4 > 0 there), and L = 2 pi / x (mismatch about -x/2); both widened for moderate x
    lo, hi = min(2.0 * math.exp(-x), 1e-6), max(2.0 * math.pi / x, 50.0)
    L = brentq(mismatch, lo, hi, xtol=1e-300, rtol=1e-15, maxiter=500)
    return math.tanh(0.5 * L)
