"""Exact normal and tangential answers of the MDR for any axisymmetric profile (docs/theory.md §8.1, §11.4).

For an axisymmetric profile with MDR profile g(s) (`solver.rolling.axisymmetric`) pressed by Fn onto an elastic
half-space (contact modulus E*), the MDR is exact (Popov & Hess 2015):

    approach        d(a)  = g(a)
    normal force    Fn(a) = 2 E* int_0^a (d - g(s)) ds = 2 E* (a g(a) - G(a)),   G(s) = int_0^s g
    pressure        p(r)  = (E*/pi) int_r^a g'(s) / sqrt(s^2 - r^2) ds        (r < a)

and, for a tangential force Ft increased monotonically from zero at constant Fn (Cattaneo-type loading), the
traction is the difference of two normal solutions (Jaeger 1995; Ciavarella 1998), so with the stick radius c
given by Fn(c) = (1 - f_t) Fn, f_t = Ft/(mu Fn):

    rigid shift     U = mu (E*/G*) (g(a) - g(c))       (sphere: Cattaneo-Mindlin, U0 (1 - (1 - f_t)^(2/3)))

`MDRContact` and `MDRTangential` have the interface of `solver.analytic.HertzSphere` and `CattaneoMindlin`
(a, approach, p0, pressure; U0, stick_radius, shift). p0 here is the pressure scale 3 Fn/(2 pi a^2), which is
Hertz's peak pressure for the sphere and stays finite for the cone (whose pressure is log-singular at r = 0).
These are exact for uncoupled materials with nu = 0 in the tangential part, like Cattaneo-Mindlin (§7.2).
Units mm, N, MPa.
"""
from dataclasses import dataclass
from functools import cached_property
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.solver.analytic import check_ft


@dataclass(frozen=True)
class MDRContact:
    """Normal contact of an axisymmetric `profile` (with mdr, mdr_slope, mdr_integral) under Fn (N), E* (MPa)."""

    profile: object
    E_star: float
    Fn: float

    def __post_init__(self):
        for name in ("E_star", "Fn"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise InputError(f"MDRContact.{name} = {value!r}: must be finite and > 0")

    def force_at(self, a) -> float:
        """Fn (N) that gives the contact radius a (mm)."""
        g = self.profile
        return 2.0 * self.E_star * (a * float(g.mdr(a)) - float(g.mdr_integral(a)))

    def radius_at(self, Fn) -> float:
        """Contact radius (mm) under the normal force Fn (N): the root of force_at(a) = Fn (increasing in a)."""
        from scipy.optimize import brentq
        if Fn <= 0:
            return 0.0
        hi = 1.0
        while self.force_at(hi) < Fn:
            hi *= 2.0
            if hi > 1e12:
                raise InputError(f"MDRContact: no contact radius below 1e12 mm carries Fn = {Fn!r} N")
        lo = hi / 2.0
        while lo > 1e-300 and self.force_at(lo) > Fn:
            lo /= 2.0
        return brentq(lambda a: self.force_at(a) - Fn, lo, hi, xtol=1e-15 * hi, rtol=1e-15, maxiter=300)

    @cached_property
    def a(self) -> float:
        """Contact radius (mm)."""
        return self.radius_at(self.Fn)

    @property
    def approach(self) -> float:
        """Approach d = g(a) (mm)."""
        return float(self.profile.mdr(self.a))

    @property
    def p0(self) -> float:
        """Pressure scale 3 Fn/(2 pi a^2) (MPa): Hertz's peak pressure for the sphere, 1.5 x the mean pressure."""
        return 1.5 * self.Fn / (math.pi * self.a ** 2)

    def pressure(self, r):
        """p(r) (MPa) at the radii r (mm): (E*/pi) int_r^a g'(s)/sqrt(s^2 - r^2) ds, 0 for r >= a.

        Evaluated with s = sqrt(r^2 + t^2) (ds/sqrt(s^2 - r^2) = dt/s), which removes the inverse square root,
        by adaptive quadrature split at the profile's kink (s = b of the rounded flat punch) when there is one.
        """
        from scipy.integrate import quad
        a = self.a
        r = np.abs(np.asarray(r, dtype=float))
        out = np.zeros(r.shape)
        kink = getattr(self.profile, "b", None)
        for idx, ri in np.ndenumerate(r):
            if ri >= a:
                continue
            top = math.sqrt(a * a - ri * ri)
            points = None
            if kink is not None and ri < kink < a:
                points = [math.sqrt(kink * kink - ri * ri)]

            def integrand(t, ri=ri):
                s = math.sqrt(ri * ri + t * t)
                return float(self.profile.mdr_slope(s)) / s if s > 0 else math.inf

            val, _ = quad(integrand, 0.0, top, points=points, limit=200, epsabs=0.0, epsrel=1e-10)
            out[idx] = self.E_star / math.pi * val
        return out


@dataclass(frozen=True)
class MDRTangential:
    """Cattaneo-type partial slip of an `MDRContact` under Ft increased monotonically from zero."""

    contact: MDRContact
    mu: float
    G_star: float

    @property
    def U0(self) -> float:
        """Full-slip shift U0 = mu E* d / G* (mm), the normalisation of seed Eq. 9."""
        return self.mu * self.contact.E_star * self.contact.approach / self.G_star

    def stick_radius(self, f_t) -> float:
        """c (mm) with Fn(c) = (1 - f_t) Fn."""
        check_ft(f_t)
        return self.contact.radius_at((1.0 - f_t) * self.contact.Fn)

    def shift(self, f_t) -> float:
        """U = mu (E*/G*) (g(a) - g(c)) (mm)."""
        g = self.contact.profile
        c = self.stick_radius(f_t)
        return self.mu * self.contact.E_star / self.G_star * (float(g.mdr(self.contact.a)) - float(g.mdr(c)))

    # --- oscillating rolling under constant Fn and Ft: the shakedown state of the spring row (docs/theory.md §8.3) ---
    def shakedown_force(self, b, W) -> float:
        """f_t of the MDR shakedown state whose stick band reaches b - W (W <= b <= a; mm): docs/theory.md §8.3 for any
        profile. Springs of the permanently loaded band |s| <= a - W that ever slipped hold their smallest
        bound mu (E*/G*) (d - g(|s| + W)), those of the stick band |s| < c_sd = b - W hold U_sd =
        mu (E*/G*) (d - g(b)), so Ft = 2 E* mu [c_sd (d - g(b)) + int_b^a (d - g(t)) dt] and
        f_t = (2 E*/Fn) [(b - W)(d - g(b)) + (a - b) d - G(a) + G(b)] (sphere: seed Eq. 12, kappa = 3/2)."""
        c = self.contact
        g, a, d = c.profile, c.a, c.approach
        gb = float(g.mdr(b))
        return 2.0 * c.E_star / c.Fn * ((b - W) * (d - gb) + (a - b) * d
                                        - float(g.mdr_integral(a)) + float(g.mdr_integral(b)))

    def shakedown_shift(self, f_t, W):
        """u_sd = U_sd/U0 = 1 - g(b)/d of the MDR shakedown state at f_t and amplitude W (mm), or None when f_t is
        above the limit (`limit`: the spring row ratchets)."""
        from scipy.optimize import brentq
        check_ft(f_t)
        c = self.contact
        a = c.a
        if not (0.0 <= W < a):
            raise InputError(f"W = {W!r} mm: the shakedown state needs 0 <= W < a = {a:.6g} mm")
        if f_t > self.shakedown_force(W, W):
            return None
        if f_t == 0.0:
            return 0.0
        b = brentq(lambda x: self.shakedown_force(x, W) - f_t, W, a, xtol=1e-14 * a, rtol=1e-15)
        return 1.0 - float(c.profile.mdr(b)) / c.approach

    def limit(self, W) -> tuple[float, float]:
        """(f_t,lim, u_lim) of the MDR at amplitude W (mm): the stick band vanishes (b = W), u_lim = 1 - g(W)/d
        (sphere: f_t,lim = 1 - 1.5 w + 0.5 w^3, u_lim = 1 - w^2)."""
        c = self.contact
        return self.shakedown_force(W, W), 1.0 - float(c.profile.mdr(W)) / c.approach
