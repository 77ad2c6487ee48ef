"""A rigid cylinder rolling steadily on a Standard Linear Solid half-space, frictionless, in plane strain: the closed
form of Hunter (1961, "The rolling contact of a rigid cylinder with a viscoelastic half space", J. Appl. Mech.
28:611-617), derived anew in docs/viscoelastic.md, "Hunter's cylinder".

The cylinder (radius R, mm) rolls in +x at V (mm/s) under the load P per unit length (N/mm); the half-space has the
creep compliance C(t) = C_g + (C_r - C_g)(1 - exp(-t/tau)) and Poisson ratio nu (plane strain: k = 2 (1 - nu^2)/pi).
With ell = V tau (the relaxation length), lam = ell C_g / C_r, f = C_r/C_g - 1 and the contact [c - w, c + w],
x = c + w t:

    p(t) = sqrt(1 - t^2) / (pi k R C_r) [w - (c + lam - ell) Q(kappa, t) / I0(kappa)],      kappa = w / lam,
    P    = w / (k R C_r) [w/2 - (c + lam - ell) I1(kappa)/I0(kappa)],
    M    = int x p dx = c P - w^2 (c + lam - ell) I2(kappa) / (2 k R C_r I0(kappa)),

Q(kappa, t) = (1/pi) PV int_{-1}^{1} exp(kappa s) / (sqrt(1 - s^2) (s - t)) ds (an entire function of t, evaluated by
Gauss-Chebyshev quadrature of the regular integrand (exp(kappa s) - exp(kappa t))/(s - t)), I_n the modified Bessel
functions. The centre c and half-width w solve P = the load and the continuity at the leading edge of the material's
memory (its exponentially averaged surface slope): inside the contact it is A exp(x/lam) - (x + lam)/(R C_r) with
f A exp(c/lam) = -(c + lam - ell)/(R C_r I0(kappa)), ahead of it the average of the free surface's slope, which the
exponential integral E1 gives in closed form. ell -> 0 is Hertz's line contact with C_r, ell -> inf with C_g.
The rolling resistance is M / R (N/mm) and its coefficient M / (P R). Units: mm, N, MPa, s.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError


def _exp_e1(z: float) -> float:
    """exp(z) E1(z) for z > 0, by its asymptotic series where exp(z) would overflow the product's factors."""
    from scipy.special import exp1
    if z < 50.0:
        return math.exp(z) * float(exp1(z))
    total, term = 0.0, 1.0 / z
    for n in range(1, 30):
        total += term
        term *= -n / z
    return total


def _q_scaled(kappa: float, t):
    """Q(kappa, t) exp(-kappa) for an array t in [-1, 1] by Gauss-Chebyshev quadrature: the trapezoidal rule in
    s = cos(theta), whose error falls as the Fourier coefficients I_n(kappa)/I_0(kappa) ~ exp(-n^2 / (2 kappa)) of
    exp(kappa cos(theta)): 10 sqrt(kappa) + 96 nodes reach round-off (checked against 2 kappa + 96 up to kappa = 1e5)."""
    n = int(10.0 * math.sqrt(kappa)) + 96
    s = np.cos((2.0 * np.arange(1, n + 1) - 1.0) * math.pi / (2.0 * n))
    t = np.atleast_1d(np.asarray(t, dtype=float))
    es = np.exp(kappa * (s - 1.0))
    et = np.exp(kappa * (t - 1.0))
    diff = s[None, :] - t[:, None]
    close = np.abs(diff) < 1e-12
    ratio = np.where(close, kappa * et[:, None], (es[None, :] - et[:, None]) / np.where(close, 1.0, diff))
    return ratio.mean(axis=1)


@dataclass(frozen=True)
class HunterCylinder:
    """The solution for load P (N/mm), radius R (mm), moduli E_g > E_r (MPa), nu, relaxation length ell = V tau (mm):
    centre c and half-width w of the contact (mm), the rolling moment M (N mm/mm) about the lowest point."""
    P: float
    R: float
    E_glassy: float
    E_relaxed: float
    nu: float
    ell: float
    c: float
    w: float

    @property
    def k(self) -> float:
        return 2.0 * (1.0 - self.nu ** 2) / math.pi

    @property
    def lam(self) -> float:
        return self.ell * self.E_relaxed / self.E_glassy

    @property
    def kappa(self) -> float:
        return self.w / self.lam

    def _ratios(self):
        from scipy.special import ive
        i0, i1, i2 = (float(ive(n, self.kappa)) for n in (0, 1, 2))
        return i1 / i0, i2 / i0, i0

    def pressure(self, x):
        """p (MPa) at x (mm), zero outside the contact."""
        x = np.asarray(x, dtype=float)
        t = (x - self.c) / self.w
        inside = np.abs(t) < 1.0
        out = np.zeros(x.shape)
        if inside.any():
            _, _, i0 = self._ratios()
            ts = t[inside]
            phi = self.w - (self.c + self.lam - self.ell) * _q_scaled(self.kappa, ts) / i0
            out[inside] = np.sqrt(1.0 - ts * ts) * phi / (math.pi * self.k * self.R / self.E_relaxed)
        return out

    @property
    def moment(self) -> float:
        """M = int x p dx (N mm per mm of length) about the lowest point of the cylinder."""
        _, r2, _ = self._ratios()
        return self.c * self.P - self.w ** 2 * (self.c + self.lam - self.ell) * r2 / (
            2.0 * self.k * self.R / self.E_relaxed)

    @property
    def centroid(self) -> float:
        """The pressure centroid M / P (mm) ahead of the lowest point."""
        return self.moment / self.P

    @property
    def resistance_coefficient(self) -> float:
        """Rolling resistance / load = M / (P R)."""
        return self.moment / (self.P * self.R)


def _residuals(c, w, P, R, Eg, Er, nu, ell):
    """(force equation, leading-edge continuity), both relative (module docstring)."""
    from scipy import integrate, special
    k = 2.0 * (1.0 - nu * nu) / math.pi
    Cr = 1.0 / Er
    f = Eg / Er - 1.0
    lam = ell / (1.0 + f)
    kappa = w / lam
    i0, i1 = special.ive(0, kappa), special.ive(1, kappa)
    b = c + lam - ell
    force = w / (k * R * Cr) * (w / 2.0 - b * i1 / i0) / P - 1.0

    def phi(t):
        return w - b * _q_scaled(kappa, t)[0] / i0

    # y ahead of the leading edge: (w / (pi ell)) int sqrt(1 - t^2) phi(t) e^z E1(z) dt, z = w (1 - t) / ell, in
    # units R C_r; near t = 1 the log of E1 is split off (weight 'alg-logb'), elsewhere e^z E1(z) is smooth
    split = max(-1.0, 1.0 - ell / w)
    total = 0.0
    if split > -1.0:
        def far(t):
            z = w * (1.0 - t) / ell
            return math.sqrt(1.0 - t) * phi(t) * _exp_e1(z)
        total += integrate.quad(far, -1.0, split, weight="alg", wvar=(0.5, 0.0), limit=200)[0]

    def smooth(t):                     # e^z (E1(z) + ln(1 - t)) = e^z (Ein(z) - gamma - ln(w/ell))
        z = w * (1.0 - t) / ell
        ein = special.exp1(z) + math.log(z) + np.euler_gamma if z > 0 else 0.0
        return math.sqrt(1.0 + t) * phi(t) * math.exp(z) * (ein - np.euler_gamma - math.log(w / ell))

    def logpart(t):
        z = w * (1.0 - t) / ell
        return -math.sqrt(1.0 + t) * phi(t) * math.exp(z)

    total += integrate.quad(smooth, split, 1.0, weight="alg", wvar=(0.0, 0.5), limit=200)[0]
    total += integrate.quad(logpart, split, 1.0, weight="alg-logb", wvar=(0.0, 0.5), limit=200)[0]
    ahead = w / (math.pi * ell) * total
    inside = b / (f * i0) + c + w + lam              # b e^kappa / (f I0(kappa)); i0 = I0(kappa) e^-kappa
    return force, (ahead - inside) / w


def hunter_cylinder(P, R, E_glassy, E_relaxed, nu, ell, guess=None) -> HunterCylinder:
    """Hunter's solution for load P (N/mm), radius R (mm), SLS moduli E_glassy > E_relaxed (MPa), Poisson ratio nu and
    relaxation length ell = V tau (mm, > 0); guess: (c, w) to start from (default: between the relaxed and glassy
    Hertz half-widths, centred). ConvergenceError if the two conditions are not met to 1e-10."""
    from scipy import optimize
    if not (P > 0 and R > 0 and 0 < E_relaxed < E_glassy and ell > 0 and -1 < nu <= 0.5):
        raise InputError(f"hunter_cylinder: need P, R, ell > 0, 0 < E_r < E_g, -1 < nu <= 0.5; got P = {P!r}, "
                         f"R = {R!r}, E_g = {E_glassy!r}, E_r = {E_relaxed!r}, nu = {nu!r}, ell = {ell!r}")
    k = 2.0 * (1.0 - nu * nu) / math.pi
    w_r = math.sqrt(2.0 * k * R * P / E_relaxed)
    w_g = math.sqrt(2.0 * k * R * P / E_glassy)
    c0, w0 = guess if guess is not None else (0.1 * w_r, 0.5 * (w_r + w_g))

    def equations(v):
        return _residuals(v[0] * w_r, v[1] * w_r, P, R, E_glassy, E_relaxed, nu, ell)

    sol, info, _, msg = optimize.fsolve(equations, [c0 / w_r, w0 / w_r], full_output=True, xtol=1e-13)
    residual = max(abs(r) for r in equations(sol))
    # the two conditions decide: at a root fsolve may still report no progress (its step test cannot be met
    # within the quadratures' round-off), which is not a failure when both residuals are below 1e-10
    if not (residual <= 1e-10 and sol[1] > 0):
        raise ConvergenceError(f"Hunter's cylinder: the contact conditions were not met ({msg.strip()})",
                               solver="hunter_cylinder", iterations=int(info["nfev"]), residual=residual, tol=1e-10,
                               regime=f"ell / a_r = {ell / w_r:.4g}, E_g / E_r = {E_glassy / E_relaxed:.4g}")
    return HunterCylinder(P, R, E_glassy, E_relaxed, nu, ell, sol[0] * w_r, sol[1] * w_r)
