"""1-D MDR simulator of oscillating rolling under constant Fn and Ft (docs/theory.md §8.1-8.2, seed §2.3).

The 3-D sphere/half-space contact is replaced by a row of independent springs at world-fixed positions s_i
(spacing ds, mm) with normal stiffness k_z = E* ds and tangential stiffness k_x = G* ds (N/mm), indented by
the 1-D equivalent profile g(s) = (s - c_n)^2 / R (a parabola of radius R/2, seed Eq. 8 with the cumulative
shift c_n of the sphere centre, docs/theory.md P4).  The rolling direction does not enter: the MDR cannot tell the
parallel and perpendicular settings apart (seed §2.3), it converges to kappa = 3/2 of seed Eq. 12.

Per step n (centre c_n):
  1. normal, constant Fn: find the approach d_n with E* ds sum_i max(0, d_n - g_i) = Fn (exact: Newton on
     this convex piecewise-linear function terminates when the contact set repeats);
     u_z,i = max(0, d_n - g_i) (mm).
  2. Coulomb bound per spring on the tangential deflection: b_i = mu (E*/G*) u_z,i (mm).
  3. constant Ft: find the rigid displacement U (mm, along Ft) with
        G* ds sum_i clip(U - v_i, -b_i, b_i) = Ft,
     a monotone piecewise-linear function of U; solved exactly by sorting its break points v_i -+ b_i.
  4. deflections u_i = clip(U - v_i, -b_i, b_i); anchors v_i <- U - u_i (the spring's slip memory).
     A spring out of contact has b_i = 0, hence u_i = 0 and v_i = U: it re-attaches unstretched.
The springs' friction capacity G* ds sum b_i = mu E* ds sum u_z,i = mu Fn holds exactly at every step, so
equilibrium exists for every Ft <= mu Fn.  Ft > mu Fn has none: `solver.mdr.step.rigid_shift` raises
GrossSlidingError and `simulate_mdr` records the state 'gross_sliding' (with the history up to the failure)
instead of raising.

Loading phase (period 0): Fn at c = 0 with all springs unstretched, then Ft in `ramp_steps` equal
increments (the MDR result of a monotone ramp does not depend on the number of steps).  Then `periods`
periods of the triangle wave c: 0 -> +W -> 0 -> -W -> 0 in steps of dW_used = W / ceil(W/dW), so the
reversal points are hit exactly (4 ceil(W/dW) steps per period).  U is recorded at c = 0 after loading and
at the end of every period and classified by `solver.rolling.shakedown.classify`.

Units mm, N, MPa.  Normalisations (seed Eq. 9, docs/theory.md P3): f_t = Ft/(mu Fn), u = U/U0 with
U0 = mu E* d/G* (d, a: Hertz values; for a `profile`, its exact MDR values), w = W/a.

Modules: the step is solved exactly by the compiled kernels of `solver.mdr._kernels` (used here) and by
their numpy references in `solver.mdr.step`; `solver.mdr.bisection` finds the simulated shakedown limit.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import NamedTuple

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.analytic import HertzSphere
from rollcontact.solver.rolling.shakedown import DEFAULT_TOL, Classification, classify, gross_sliding
from rollcontact.solver.mdr._kernels import _step_gap_kernel, _step_kernel
from rollcontact.solver.mdr.exact import MDRContact

DEFAULT_N_SPRINGS = 4001


# ------------------------------------------------------------------------------------------- run
@dataclass
class MDRResult:
    """History and summary of one MDR run (units mm, N; see module docstring for the normalisations).

    history: per step (loading steps first): 'step' (0, 1, ...), 'period' (0 = loading phase, k during
        period k), 'W' (centre position c_n along the rolling direction, mm), 'approach' (d_n, mm),
        'U' (rigid displacement along Ft, mm), 'Ft' (applied tangential force, N), 'contact_length' (mm,
        ds times the number of loaded springs; -> 2a), 'stick_length' (mm, ds times the number of loaded
        springs strictly inside their Coulomb bound after the step; after loading -> 2c of seed Eq. 5).
    U_period_end: U (mm) at c = 0 after loading (index 0) and at the end of each completed period.
    U_stat: U after the loading phase (mm; simulated, compare seed Eq. 4).
    U0: mu E* d / G* with the Hertz d (mm).  a, d: Hertz contact radius and approach (mm).
    dW_used: the centre step actually used (mm).  ds: spring spacing (mm); n_springs: number of springs.
    classification: from solver.rolling.shakedown (state 'gross_sliding' if no equilibrium was found).
    """

    history: dict[str, np.ndarray]
    U_period_end: np.ndarray
    U_stat: float
    U0: float
    a: float
    d: float
    dW_used: float
    ds: float
    n_springs: int
    f_t: float
    w: float
    classification: Classification
    stick_length_static: float = field(default=math.nan)

    @property
    def state(self) -> str:
        return self.classification.state

    @property
    def u(self) -> np.ndarray:
        """Normalised history U/U0 per step."""
        return self.history["U"] / self.U0

    @property
    def u_period_end(self) -> np.ndarray:
        return self.U_period_end / self.U0


def _positive(name, value, unit):
    if not (isinstance(value, (int, float, np.integer, np.floating)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} = {value!r} {unit}: must be a finite number > 0")
    return float(value)


def _centre_path(W, dW, periods):
    """Centre positions of the oscillation (after loading at c = 0) and the period index of each step."""
    if W == 0.0:
        nq, dW_used = 1, 0.0  # no oscillation: 4 hold steps per period at c = 0
    else:
        nq = math.ceil(W / dW - 1e-12)
        dW_used = W / nq
    j = np.arange(1, 4 * nq + 1)
    # triangle wave 0 -> +W -> 0 -> -W -> 0 over one period, in units of dW_used
    one = np.where(j <= nq, j, np.where(j <= 3 * nq, 2 * nq - j, j - 4 * nq)).astype(float) * dW_used
    centre = np.tile(one, periods)
    period = np.repeat(np.arange(1, periods + 1), 4 * nq)
    return centre, period, dW_used, nq


class _LoadPath(NamedTuple):
    """Per step (loading steps first): the applied Ft (N), the centre c_n (mm) and the period index (0 during
    loading); n_load loading steps, dW_used the centre step (mm), nq steps per quarter period (0 for a given
    schedule); Fn the normal force per step (N) or None for the constant Fn."""

    Ft: np.ndarray
    centre: np.ndarray
    period: np.ndarray
    n_load: int
    dW_used: float
    nq: int
    Fn: np.ndarray | None = None


class LoadSchedule(NamedTuple):
    """A prescribed load path for `simulate_mdr` (docs/theory.md §11.3): per step the normal force Fn (N, > 0), the
    tangential force Ft (N, signed, along the force direction), the centre c (mm, along the rolling direction)
    and the period index (0 during the loading phase); dW_used the centre step (mm, 0 without rolling)."""

    Fn: np.ndarray
    Ft: np.ndarray
    centre: np.ndarray
    period: np.ndarray
    dW_used: float = 0.0


def simulate_mdr(*, R=None, E_star, G_star, Fn, mu, Ft, W, dW, periods, ramp_steps=1, n_springs=None,
                 ds=None, shakedown_tol=DEFAULT_TOL, profile=None, schedule: LoadSchedule | None = None) -> MDRResult:
    """Run the 1-D MDR model of oscillating rolling (docs/theory.md §8.2); see the module docstring.

    R: sphere radius (mm), or profile: any axisymmetric profile of `solver.rolling.axisymmetric` (cone, power
    law, rounded flat punch), whose MDR profile g(s - c_n) then replaces (s - c_n)^2/R and whose exact MDR
    contact radius and approach (`solver.mdr.exact.MDRContact`) replace Hertz's a and d; E_star, G_star: contact moduli E*, G* (MPa, bem.materials.MaterialPair);
    Fn > 0 (N), mu > 0, 0 <= Ft (N; Ft > mu Fn is recorded as 'gross_sliding'); W >= 0 amplitude of the
    centre (mm; W = 0: no oscillation), dW > 0 requested centre step (mm), periods >= 0.
    Springs: s_i = i ds, |i| <= N, covering [-(a + W) - ds, a + W + ds] at least, so that every spring that
    can ever touch is modelled.  Give either ds (mm) or n_springs (odd total count, rounded up to odd;
    default 4001, then ds = (a + W) / ((n_springs - 1)/2 - 1)).
    shakedown_tol: tolerance on the per-period increment |dU|/U0 passed to solver.rolling.shakedown.classify.
    schedule: a LoadSchedule that replaces the path built from Ft, W, dW, periods and ramp_steps (loads that
    vary within each period, docs/theory.md §11.3); Fn and Ft are then its means (the normalisations use them) and the
    springs reach the contact radius of its largest Fn plus W. Each spring keeps its own slip memory (its
    anchor) whatever Fn does; a spring leaving contact is released and re-attaches unstretched.
    The history's 'dissipation' is the frictional work of each step (N mm): G* ds sum_i u_i (v_i - v_i'), the
    end-of-step spring force times the slip (anchor increment) of the step, as solver.rolling.energy does in 3-D.
    """
    if (R is None) == (profile is None):
        raise InputError("give either R (a sphere) or profile (an axisymmetric profile), not both or neither")
    R, E_star, G_star, Fn, mu, dW, periods, ramp_steps = _checked_inputs(1.0 if R is None else R, E_star, G_star,
                                                                         Fn, mu, Ft, W, dW, periods, ramp_steps)
    hertz = HertzSphere(R, E_star, Fn) if profile is None else MDRContact(profile, E_star, Fn)
    a, d_hertz = hertz.a, hertz.approach
    U0 = mu * E_star * d_hertz / G_star
    if W >= a:
        raise InputError(f"W = {W!r} mm >= a = {a:.6g} mm: the seed's model needs w = W/a < 1 (seed Eq. 10)")
    if schedule is None:
        s, ds = _springs(a + W, ds, n_springs)
        path = _load_path(Ft, float(W), dW, periods, ramp_steps)
    else:
        path = _schedule_path(schedule)
        periods = int(path.period.max())
        Fn_max = float(np.max(path.Fn))
        a_max = (HertzSphere(R, E_star, Fn_max) if profile is None else MDRContact(profile, E_star, Fn_max)).a
        s, ds = _springs(a_max + W, ds, n_springs)
    gap = None if profile is None else profile.mdr
    hist, done, failure = _roll(s, ds, path, R, E_star, G_star, Fn, mu, d_hertz, gap)
    history = {key: val[:done] for key, val in hist.items()}
    history["step"] = np.arange(done)
    history["period"] = path.period[:done]

    n_load = path.n_load
    ends = [int(np.flatnonzero(path.period == k)[-1]) for k in range(periods + 1)]
    U_end = np.array([history["U"][i] for i in ends if i < done])
    if failure is not None:
        cls = gross_sliding(U_end, U0, failure)
    else:
        cls = classify(U_end, U0, tol=shakedown_tol)
    U_stat = float(history["U"][n_load - 1]) if done >= n_load else math.nan
    stick0 = float(history["stick_length"][n_load - 1]) if done >= n_load else math.nan
    return MDRResult(history=history, U_period_end=U_end, U_stat=U_stat, U0=U0, a=a, d=d_hertz,
                     dW_used=path.dW_used, ds=ds, n_springs=s.size, f_t=Ft / (mu * Fn), w=W / a,
                     classification=cls, stick_length_static=stick0)


def _checked_inputs(R, E_star, G_star, Fn, mu, Ft, W, dW, periods, ramp_steps):
    """The scalar inputs of `simulate_mdr` checked (InputError naming the first bad one); returns R, E_star,
    G_star, Fn, mu, dW as floats and periods, ramp_steps as ints."""
    R = _positive("R", R, "mm")
    E_star = _positive("E_star", E_star, "MPa")
    G_star = _positive("G_star", G_star, "MPa")
    Fn = _positive("Fn", Fn, "N")
    mu = _positive("mu", mu, "(friction coefficient)")
    dW = _positive("dW", dW, "mm")
    if not (math.isfinite(Ft) and Ft >= 0):
        raise InputError(f"Ft = {Ft!r} N: must be finite and >= 0 (Ft > mu Fn is reported as gross sliding)")
    if not (math.isfinite(W) and W >= 0):
        raise InputError(f"W = {W!r} mm: the oscillation amplitude must be finite and >= 0")
    if not (int(periods) == periods and periods >= 0):
        raise InputError(f"periods = {periods!r}: must be an integer >= 0")
    if not (int(ramp_steps) == ramp_steps and ramp_steps >= 1):
        raise InputError(f"ramp_steps = {ramp_steps!r}: must be an integer >= 1")
    return R, E_star, G_star, Fn, mu, dW, int(periods), int(ramp_steps)


def _springs(reach, ds, n_springs):
    """Spring positions s (mm, symmetric about 0, reaching beyond `reach` = a + W by at least one spacing) and
    the spacing ds (mm), from the given ds or n_springs (default DEFAULT_N_SPRINGS)."""
    if ds is not None and n_springs is not None:
        raise InputError("give either ds or n_springs, not both")
    if ds is not None:
        ds = _positive("ds", ds, "mm")
        half = math.ceil(reach / ds) + 1
    else:
        n = DEFAULT_N_SPRINGS if n_springs is None else n_springs
        if not (int(n) == n and n >= 7):
            raise InputError(f"n_springs = {n!r}: must be an integer >= 7")
        half = (int(n) - 1 + 1) // 2          # rounds an even count up to the next odd one
        ds = reach / (half - 1)
    return ds * np.arange(-half, half + 1, dtype=float), ds


def _load_path(Ft, W, dW, periods, ramp_steps):
    """The loading phase (Fn at c = 0, then Ft in ramp_steps increments) followed by the oscillation."""
    centre, period, dW_used, nq = _centre_path(W, dW, periods)
    n_load = 1 + ramp_steps                    # normal load, then the Ft ramp
    Ft_path = np.concatenate(([0.0], Ft * np.arange(1, ramp_steps + 1) / ramp_steps,
                              np.full(centre.size, float(Ft))))
    c_path = np.concatenate((np.zeros(n_load), centre))
    period_path = np.concatenate((np.zeros(n_load, dtype=int), period))
    return _LoadPath(Ft_path, c_path, period_path, n_load, dW_used, nq)


def _schedule_path(schedule):
    """The _LoadPath of a LoadSchedule, checked (InputError naming the first bad step)."""
    Fn, Ft = np.asarray(schedule.Fn, float), np.asarray(schedule.Ft, float)
    centre, period = np.asarray(schedule.centre, float), np.asarray(schedule.period, int)
    if not (Fn.shape == Ft.shape == centre.shape == period.shape and Fn.ndim == 1 and Fn.size):
        raise InputError("schedule: Fn, Ft, centre and period must be 1-D arrays of one length")
    if not np.all(Fn > 0):
        raise InputError(f"schedule: Fn = {Fn.min():.6g} N at step {int(np.argmin(Fn))}: must be > 0 at every step")
    if period[0] != 0 or np.any(np.diff(period) < 0) or np.any(np.diff(period) > 1):
        raise InputError("schedule: period must start at 0 (loading) and rise by at most 1 per step")
    return _LoadPath(Ft, centre, period, int(np.count_nonzero(period == 0)), float(schedule.dW_used), 0, Fn)


def _roll(s, ds, path, R, E_star, G_star, Fn, mu, d_hertz, gap=None):
    """Step the spring row along the load path (one `_step_kernel` call per step, anchors updated in place; with
    `gap` (g(s) of an axisymmetric profile) the gaps g(s_i - c_n) are computed here and `_step_gap_kernel` steps).

    Returns the histories (W, approach, U, Ft, contact_length, stick_length; NaN after a failure), the number of
    steps done and the failure message (None, or the step without tangential equilibrium: gross sliding).
    Raises ConvergenceError when the normal problem of a step does not settle.
    """
    n_steps = path.Ft.size
    hist = {key: np.full(n_steps, np.nan) for key in
            ("W", "approach", "U", "Ft", "Fn", "contact_length", "stick_length", "dissipation")}
    anchor = np.zeros_like(s)
    v_buf, b_buf, gap_buf = np.empty_like(s), np.empty_like(s), np.empty_like(s)
    U = 0.0
    ratio = mu * E_star / G_star               # Coulomb bound on the deflection: b = ratio * u_z (mm)
    target_n = Fn / (E_star * ds)
    d_prev = d_hertz
    previous = np.empty_like(s)
    for n in range(n_steps):
        c, Ft = path.centre[n], path.Ft[n]
        if path.Fn is not None:
            Fn = path.Fn[n]
            target_n = Fn / (E_star * ds)
        previous[:] = anchor
        if gap is None:
            d, U_new, n_contact, n_stick, status = _step_kernel(
                s, anchor, c, R, target_n, d_prev, ratio, Ft / (G_star * ds), U, v_buf, b_buf, gap_buf)
        else:
            d, U_new, n_contact, n_stick, status = _step_gap_kernel(
                np.asarray(gap(s - c), dtype=float), anchor, target_n, d_prev, ratio, Ft / (G_star * ds), U,
                v_buf, b_buf)
        if status == 2:
            raise ConvergenceError("MDR normal problem: contact set did not settle", solver="simulate_mdr",
                                   iterations=200, regime=f"step {n}, centre {c:.6g} mm")
        if status == 1:
            return hist, n, (f"no tangential equilibrium at step {n} (period {path.period[n]}): Ft = {Ft:.6g}"
                             f" N exceeds the friction capacity mu Fn = {mu * Fn:.6g} N")
        U, d_prev = U_new, d
        hist["W"][n], hist["approach"][n], hist["U"][n], hist["Ft"][n], hist["Fn"][n] = c, d, U, Ft, Fn
        hist["dissipation"][n] = G_star * ds * float(np.dot(U - anchor, anchor - previous))
        hist["contact_length"][n] = ds * n_contact
        hist["stick_length"][n] = ds * n_stick
    return hist, n_steps, None
