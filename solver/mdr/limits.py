"""Closed forms of the MDR shakedown theory for oscillating rolling (seed Eqs. 4-5, 12-21; docs/theory.md §8).

Everything here is dimensionless (seed Eq. 9 with the correction of docs/theory.md P3):

    f_t = Ft / (mu Fn)                tangential load ratio,          0 <= f_t <= 1
    u   = U / U0,  U0 = mu E* d / G*  rigid displacement (mm / mm),    U0 = full-slip shift of Mindlin
    w   = W / a                       oscillation amplitude of the sphere centre over the Hertz radius

Mapping parameter kappa (seed Eq. 13, docs/theory.md §8.4):

    f_t = 1 - kappa w u_sd - (1 - u_sd)^(3/2)          equilibrium of the shaken-down state

* ``KAPPA_MDR = 1.5`` is what the pure 1-D MDR derivation gives (seed Eq. 12, docs/theory.md §8.3): in 1-D a spring
  that re-enters contact is unloaded and stays so while U is constant, so only the band of permanent contact
  |s| <= a - W carries force.  `solver.mdr.simulate_mdr` converges to this value.
* ``KAPPA_PARALLEL = 1.0`` and ``KAPPA_PERPENDICULAR = 1.1`` are the seed's fits to CONTACT runs and
  experiments (seed Eq. 14) for rolling parallel / perpendicular to Ft.  They are smaller than 3/2 because
  in 3-D a point re-entering contact keeps a non-zero elastic displacement and can carry traction induced
  by its stuck neighbours, so the capacity loss is smaller than in 1-D, and it depends on the rolling
  direction (the spindle-shaped stick zone).  They are rounded empirical values (docs/theory.md §8.4: the seed's own
  Fig. 4b shows ratcheting of the parallel case at f_t = 0.77, w = 0.23, exactly on the kappa = 1 limit),
  so keep a margin around f_t,lim when using them as oracles.

Allowed kappa: 0 < kappa <= 3/2.  For kappa > 3/2 the limit curve f_t,lim(w) = 1 - kappa w + (kappa - 1) w^3
is no longer monotone and becomes negative near w = 1, and the equilibrium relation is no longer monotone in
u_sd; 3/2 is also the upper bound given by the 1-D (lens) argument of docs/theory.md §8.4.  Such values are refused.

Out-of-range inputs raise `InputError` naming the parameter and the allowed range (never NaN);
`NoShakedownError` (a subclass) is raised when a shakedown state is asked for beyond the shakedown limit.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import brentq

from rollcontact.bem.errors import InputError

KAPPA_PARALLEL = 1.0        # seed Eq. 14, fitted (CONTACT + experiment), rolling direction parallel to Ft
KAPPA_PERPENDICULAR = 1.1   # seed Eq. 14, fitted (CONTACT + experiment), rolling direction perpendicular to Ft
KAPPA_MDR = 1.5             # seed Eq. 12, pure 1-D MDR derivation (docs/theory.md §8.3)
KAPPA_MAX = 1.5             # upper end of the allowed range (see module docstring)

# Seed Eqs. 20-21: regression constants C of du ~ sqrt(C u_stat(f_t)) (w - w_lim(f_t)) (docs/theory.md §8.5, P13).
RATCHET_C = {"parallel": 2.0, "perpendicular": 5.0}
SETTING_KAPPA = {"parallel": KAPPA_PARALLEL, "perpendicular": KAPPA_PERPENDICULAR}

_ROOT_XTOL = 1e-15
_ROOT_RTOL = 4 * np.finfo(float).eps


class NoShakedownError(InputError):
    """(f_t, w) lies beyond the shakedown limit: the run ratchets, there is no shakedown displacement."""


# --------------------------------------------------------------------------------------------- checks
def _check_range(name, value, lo, hi, what):
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr < lo) or np.any(arr > hi):
        raise InputError(f"{name} = {value!r}: {what}; allowed range is {lo} <= {name} <= {hi}")
    return arr


def check_ft(f_t):
    return _check_range("f_t", f_t, 0.0, 1.0, "f_t = Ft/(mu Fn) is the tangential load ratio")


def check_w(w):
    return _check_range("w", w, 0.0, 1.0, "w = W/a is the oscillation amplitude over the contact radius")


def _check_u(u, name="u_sd"):
    return _check_range(name, u, 0.0, 1.0, f"{name} = U/U0 is the rigid displacement over the full-slip shift")


def check_kappa(kappa):
    k = float(kappa)
    if not (math.isfinite(k) and 0.0 < k <= KAPPA_MAX):
        raise InputError(
            f"kappa = {kappa!r}: the mapping parameter of seed Eq. 13 must satisfy 0 < kappa <= {KAPPA_MAX} "
            f"(1 parallel, 1.1 perpendicular, 1.5 pure MDR; above 1.5 the limit curve is not monotone)")
    return k


def _out(arr):
    """Return a Python float for 0-d input, an array otherwise."""
    return float(arr) if np.ndim(arr) == 0 else arr


# ------------------------------------------------------------------------------------ static (Mindlin)
def u_stat(f_t):
    """Static shift u_stat = U_stat/U0 = 1 - (1 - f_t)^(2/3) (seed Eq. 4, Cattaneo-Mindlin; docs/theory.md §7.2)."""
    f = check_ft(f_t)
    return _out(1.0 - (1.0 - f) ** (2.0 / 3.0))


def stick_ratio_static(f_t):
    """Static stick radius over contact radius c/a = (1 - f_t)^(1/3) (seed Eq. 5)."""
    f = check_ft(f_t)
    return _out((1.0 - f) ** (1.0 / 3.0))


# ------------------------------------------------------------------------------ shakedown equilibrium
def u_lim(w):
    """Largest shakedown displacement u_lim = 1 - w^2 (seed Eq. 17): the stick band c_sd has vanished."""
    ww = check_w(w)
    return _out(1.0 - ww ** 2)


def f_t_equilibrium(u_sd, w, kappa=KAPPA_MDR):
    """Tangential load ratio in equilibrium with a shaken-down displacement (seed Eq. 13; Eq. 12 for 3/2).

    f_t = 1 - kappa w u_sd - (1 - u_sd)^(3/2), valid while the stick band exists: sqrt(1 - u_sd) >= w,
    i.e. u_sd <= u_lim(w) = 1 - w^2.  Beyond that the relation has no meaning and InputError is raised.
    """
    u, ww, k = _check_u(u_sd), check_w(w), check_kappa(kappa)
    if np.any(u > 1.0 - ww ** 2 + 1e-15):
        raise InputError(f"u_sd = {u_sd!r} > u_lim = 1 - w^2 for w = {w!r}: no stick band left, "
                         f"seed Eq. 13 applies only for u_sd <= 1 - w^2")
    return _out(1.0 - k * ww * u - (1.0 - u) ** 1.5)


def f_t_lim(w, kappa=KAPPA_MDR):
    """Shakedown limit of the load ratio f_t,lim(w) = 1 - kappa w + (kappa - 1) w^3 (seed Eqs. 18-19).

    Equals f_t_equilibrium(u_lim(w), w, kappa).  kappa = 1: 1 - w (Eq. 18); kappa = 1.1: 1 - 1.1 w + 0.1 w^3
    (Eq. 19); kappa = 3/2: pure MDR (docs/theory.md §8.3).  Monotonically decreasing from 1 (w = 0) to 0 (w = 1).
    """
    ww, k = check_w(w), check_kappa(kappa)
    return _out(1.0 - k * ww + (k - 1.0) * ww ** 3)


def w_lim(f_t, kappa=KAPPA_MDR):
    """Inverse of f_t_lim: the largest amplitude w_lim with shakedown at load ratio f_t (scalar).

    f_t,lim(w) is strictly decreasing on [0, 1] for 0 < kappa <= 3/2, so the root is unique (Brent, to
    ~1e-15).  f_t = 1 gives 0, f_t = 0 gives 1.
    """
    f, k = float(check_ft(f_t)), check_kappa(kappa)
    if f >= 1.0:
        return 0.0
    if f <= 0.0:
        return 1.0
    return float(brentq(lambda w: 1.0 - k * w + (k - 1.0) * w ** 3 - f, 0.0, 1.0,
                        xtol=_ROOT_XTOL, rtol=_ROOT_RTOL))


def u_shakedown(f_t, w, kappa=KAPPA_MDR):
    """Shakedown displacement u_sd solving f_t = 1 - kappa w u - (1 - u)^(3/2) (seed Eq. 13; scalar).

    The right-hand side F(u) is 0 at u = 0 and f_t,lim(w) at u = u_lim(w) = 1 - w^2, and strictly
    increasing in between for kappa <= 3/2 (dF/du = 3/2 sqrt(1-u) - kappa w >= (3/2 - kappa) w), so the root
    in [0, u_lim] is unique.  w = 0 gives the static Mindlin value u_stat(f_t).
    Raises NoShakedownError (an InputError) naming f_t, w, kappa if f_t > f_t,lim(w): ratcheting, no u_sd.
    """
    f, ww, k = float(check_ft(f_t)), float(check_w(w)), check_kappa(kappa)
    limit = f_t_lim(ww, k)
    if f > limit * (1.0 + 1e-14) + 1e-15:
        raise NoShakedownError(
            f"(f_t, w) = ({f!r}, {ww!r}) is beyond the shakedown limit f_t,lim(w) = {limit:.6g} for kappa = {k}"
            f" (w_lim(f_t) = {w_lim(f, k):.6g}): ratcheting, no shakedown displacement")
    ul = 1.0 - ww ** 2
    if f >= limit:
        return ul
    if f <= 0.0:
        return 0.0
    return float(brentq(lambda u: 1.0 - k * ww * u - (1.0 - u) ** 1.5 - f, 0.0, ul,
                        xtol=_ROOT_XTOL, rtol=_ROOT_RTOL))


# ----------------------------------------------------------------------------------- kappa helpers
def kappa_for_angle(angle_deg):
    """Mapping parameter for a rolling direction at angle_deg to Ft (0 parallel, 90 perpendicular).

    ASSUMPTION (not in the seed, which only treats 0 and 90 deg; its conclusion asks for this as future
    work): interpolation in sin^2(angle),
        kappa = KAPPA_PARALLEL + (KAPPA_PERPENDICULAR - KAPPA_PARALLEL) sin^2(angle),
    the lowest-order form that is even in the angle and periodic over 180 deg (rolling back and forth along
    e_r is the same motion as along -e_r).  Allowed range 0 <= angle_deg <= 180.
    """
    a = float(_check_range("angle", angle_deg, 0.0, 180.0,
                           "angle (deg) between the rolling direction and Ft"))
    return KAPPA_PARALLEL + (KAPPA_PERPENDICULAR - KAPPA_PARALLEL) * math.sin(math.radians(a)) ** 2


@dataclass(frozen=True)
class KappaFit:
    """Least-squares kappa of seed Eq. 13 from shaken-down points.

    kappa: estimate; stderr: standard error from the residual scatter (None for a single point, where the
    fit is exact and carries no scatter information); n: number of points; residual_rms: rms of the
    residuals of Eq. 13 in f_t units.
    """

    kappa: float
    stderr: float | None
    n: int
    residual_rms: float


def fit_kappa(f_t, w, u_sd) -> KappaFit:
    """Solve seed Eq. 13 for kappa in the least-squares sense from simulated (f_t, w, u_sd) points.

    Eq. 13 is linear in kappa: kappa x = y with x = w u_sd, y = 1 - f_t - (1 - u_sd)^(3/2), so
    kappa = sum(x y) / sum(x^2); stderr = sqrt(sum r^2 / (n - 1) / sum x^2) with r = y - kappa x
    (ordinary least squares, errors treated as residuals of Eq. 13 in f_t units).  Points with w u_sd = 0
    carry no information on kappa; at least one informative point is required.  The result is not
    range-checked against 0 < kappa <= 3/2 (a fit may land outside).
    """
    f = np.atleast_1d(check_ft(f_t)).astype(float)
    ww = np.atleast_1d(check_w(w)).astype(float)
    u = np.atleast_1d(_check_u(u_sd)).astype(float)
    try:
        f, ww, u = np.broadcast_arrays(f, ww, u)
    except ValueError as exc:
        raise InputError(f"fit_kappa: f_t, w, u_sd must have matching lengths ({exc})") from None
    x = ww * u
    y = 1.0 - f - (1.0 - u) ** 1.5
    sxx = float(np.sum(x * x))
    if not sxx > 0.0:
        raise InputError("fit_kappa: every point has w * u_sd = 0; kappa is undetermined (need w > 0)")
    kappa = float(np.sum(x * y) / sxx)
    r = y - kappa * x
    n = int(x.size)
    stderr = float(math.sqrt(np.sum(r * r) / (n - 1) / sxx)) if n > 1 else None
    return KappaFit(kappa=kappa, stderr=stderr, n=n, residual_rms=float(math.sqrt(np.mean(r * r))))


# ------------------------------------------------------------------------------------ ratcheting
def ratcheting_increment(f_t, w, setting="perpendicular"):
    """Seed's regression for the increment per period beyond the limit (seed Eqs. 20-21, docs/theory.md §8.5).

    du ~ sqrt(C u_stat(f_t)) (w - w_lim(f_t)), C = 2 (parallel, w_lim from Eq. 18, kappa = 1) or
    C = 5 (perpendicular, w_lim from Eq. 19, kappa = 1.1); 0 for w <= w_lim (shakedown).
    These are the seed's empirical regression fits with u_stat as regressor (its ref. [15]), dimensionally
    loose and NOT an MDR result: the pure MDR (solver.mdr) gives increments several times larger
    (docs/theory.md §8.5, P13).  Use for qualitative checks only.  "Per period" is presumed.
    """
    if setting not in RATCHET_C:
        raise InputError(f"setting = {setting!r}: allowed values are {sorted(RATCHET_C)}")
    f, ww = float(check_ft(f_t)), float(check_w(w))
    wl = w_lim(f, SETTING_KAPPA[setting])
    if ww <= wl:
        return 0.0
    return math.sqrt(RATCHET_C[setting] * u_stat(f)) * (ww - wl)
