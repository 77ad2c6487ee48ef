"""1-D MDR simulator of oscillating rolling under constant Fn and Ft (theory.md §8.1-8.2, seed §2.3).

The 3-D sphere/half-space contact is replaced by a row of independent springs at world-fixed positions s_i
(spacing ds, mm) with normal stiffness k_z = E* ds and tangential stiffness k_x = G* ds (N/mm), indented by
the 1-D equivalent profile g(s) = (s - c_n)^2 / R (a parabola of radius R/2, seed Eq. 8 with the cumulative
shift c_n of the sphere centre, pitfall P4).  The rolling direction does not enter: the MDR cannot tell the
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
equilibrium exists for every Ft <= mu Fn.  Ft > mu Fn has none: `rigid_shift` raises GrossSlidingError and
`simulate_mdr` records the state 'gross_sliding' (with the history up to the failure) instead of raising.

Loading phase (period 0): Fn at c = 0 with all springs unstretched, then Ft in `ramp_steps` equal
increments (the MDR result of a monotone ramp does not depend on the number of steps).  Then `periods`
periods of the triangle wave c: 0 -> +W -> 0 -> -W -> 0 in steps of dW_used = W / ceil(W/dW), so the
reversal points are hit exactly (4 ceil(W/dW) steps per period).  U is recorded at c = 0 after loading and
at the end of every period and classified by `solver.shakedown.classify`.

Units mm, N, MPa.  Normalisations (seed Eq. 9, pitfall P3): f_t = Ft/(mu Fn), u = U/U0 with
U0 = mu E* d/G* (d, a: Hertz values), w = W/a.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np
from numba import njit

from bem.errors import ConvergenceError, GrossSlidingError, InputError
from .analytic import HertzSphere
from .shakedown import DEFAULT_TOL, Classification, classify, gross_sliding

DEFAULT_N_SPRINGS = 4001


# --------------------------------------------------------------------------------------- one step
def approach_for_force(gap, Fn, E_star, ds):
    """Approach d (mm) with E* ds sum_i max(0, d - gap_i) = Fn, exact for the discrete springs.

    gap: undeformed gaps g_i (mm).  Newton on the convex piecewise-linear force-approach function
    (equivalently the fixed point d = (Fn/(E* ds) + sum_C g_i)/|C| over the contact set C); it converges
    monotonically after the first step and stops when C repeats, so the result is exact to round-off.
    """
    target = Fn / (E_star * ds)
    d = float(np.min(gap)) + target  # one spring carrying everything: an upper bound of d
    count = -1
    for _ in range(200):
        in_contact = gap < d
        n = int(np.count_nonzero(in_contact))
        if n == count:
            return d
        count = n
        d = (target + float(np.sum(gap[in_contact]))) / n
    raise ConvergenceError("MDR normal problem: contact set did not settle", solver="approach_for_force",
                           iterations=200)


def rigid_shift(anchor, bound, target):
    """Rigid displacement U (mm) with sum_i clip(U - anchor_i, -bound_i, bound_i) = target (mm).

    target = Ft/(G* ds).  The left side is non-decreasing and piecewise linear in U with break points
    anchor_i -+ bound_i; sorting them gives the exact root (the smallest one if the function is flat
    there, which only happens at target = sum bound, i.e. Ft = mu Fn).  Springs with bound_i = 0 carry no
    force and are skipped.  Raises GrossSlidingError if |target| > sum bound (no equilibrium).
    """
    loaded = bound > 0.0
    v = anchor[loaded]
    b = bound[loaded]
    capacity = float(np.sum(b))
    if abs(target) > capacity * (1.0 + 1e-12):
        raise GrossSlidingError(
            f"no tangential equilibrium: |Ft|/(G* ds) = {abs(target):.6g} mm exceeds the friction capacity "
            f"sum mu (E*/G*) u_z = {capacity:.6g} mm (f_t = {abs(target) / capacity if capacity else math.inf:.6g}"
            f" > 1)")
    x = np.concatenate((v - b, v + b))
    order = np.argsort(x, kind="stable")
    xs = x[order]
    kinks = np.concatenate((np.ones(v.size), -np.ones(v.size)))[order]
    slope = np.cumsum(kinks)                      # slope on [xs[k], xs[k+1]]
    force = np.empty_like(xs)                     # function value at xs[k]
    force[0] = -capacity
    np.cumsum(slope[:-1] * np.diff(xs), out=force[1:])
    force[1:] -= capacity
    k = int(np.searchsorted(force, target, side="left"))
    if k == 0:
        return float(xs[0])
    if k >= xs.size:
        return float(xs[-1])
    U = xs[k - 1] + (target - force[k - 1]) / slope[k - 1]
    return float(min(U, xs[k]))


# ------------------------------------------------------------------- compiled step (numba, cached)
@njit(cache=True)
def _approach_kernel(s, centre, R, target, d_guess):
    """Numba twin of `approach_for_force` for the gap (s - centre)^2/R; returns (d, n_contact) or (nan, -1).

    Starts from d_guess (the previous step's approach): from the left, the first Newton step of the convex
    force-approach function lands right of the root; from there the iterates decrease monotonically.
    """
    gmin = np.inf
    for i in range(s.size):
        g = (s[i] - centre) ** 2 / R
        if g < gmin:
            gmin = g
    d = d_guess if d_guess > gmin else gmin + target
    count = -1
    for _ in range(200):
        n = 0
        acc = 0.0
        for i in range(s.size):
            g = (s[i] - centre) ** 2 / R
            if g < d:
                n += 1
                acc += g
        if n == count:
            return d, n
        count = n
        d = (target + acc) / n
    return np.nan, -1


@njit(cache=True)
def _rigid_shift_kernel(v, b, target, U_guess):
    """Numba root of sum clip(U - v_i, -b_i, b_i) = target (all b_i > 0); returns (U, status).

    status 0: solved; 1: |target| > sum b (gross sliding).  A few Newton steps from the previous U shrink a
    bracket (usually they already land on the exact linear piece); the break points left inside the
    bracket are then sorted and walked, which makes the result exact like `rigid_shift`.
    """
    m = v.size
    cap = 0.0
    xmin = np.inf
    xmax = -np.inf
    for i in range(m):
        cap += b[i]
        xmin = min(xmin, v[i] - b[i])
        xmax = max(xmax, v[i] + b[i])
    if abs(target) > cap * (1.0 + 1e-12):
        return np.nan, 1
    if m == 0 or target <= -cap:
        return (xmin if m else U_guess), 0
    if target >= cap:
        return xmax, 0
    lo, flo, hi = xmin, -cap, xmax
    U = min(max(U_guess, xmin), xmax)
    for _ in range(6):
        F = 0.0
        k_right = 0
        k_left = 0
        for i in range(m):
            x = U - v[i]
            if x >= b[i]:
                F += b[i]
            elif x <= -b[i]:
                F -= b[i]
            else:
                F += x
            if -b[i] <= x < b[i]:
                k_right += 1
            if -b[i] < x <= b[i]:
                k_left += 1
        if abs(F - target) <= 1e-14 * cap:
            return U, 0
        if F < target:
            if U > lo:
                lo, flo = U, F
            slope = k_right
        else:
            hi = min(hi, U)
            slope = k_left
        if slope == 0:
            break
        Un = U + (target - F) / slope
        if not (lo < Un < hi):
            break
        U = Un
    # exact walk over the break points inside (lo, hi), starting from F(lo) = flo < target
    xs = np.empty(2 * m)
    ks = np.empty(2 * m)
    n = 0
    slope = 0.0
    for i in range(m):
        if v[i] - b[i] <= lo < v[i] + b[i]:
            slope += 1.0
        for x, kink in ((v[i] - b[i], 1.0), (v[i] + b[i], -1.0)):
            if lo < x < hi:
                xs[n] = x
                ks[n] = kink
                n += 1
    order = np.argsort(xs[:n])
    x_prev = lo
    F = flo
    for j in range(n):
        x = xs[order[j]]
        F_next = F + slope * (x - x_prev)
        if F_next >= target:
            return x_prev + (target - F) / slope, 0
        F = F_next
        slope += ks[order[j]]
        x_prev = x
    if slope > 0.0:
        return min(x_prev + (target - F) / slope, hi), 0
    return hi, 0


@njit(cache=True)
def _step_kernel(s, anchor, centre, R, target_n, d_guess, ratio, target_t, U_guess, v_buf, b_buf):
    """One MDR step in place on `anchor`; returns (d, U, n_contact, n_stick, status).

    status 0 ok, 1 gross sliding (anchor untouched), 2 normal problem did not settle.
    """
    d, n_contact = _approach_kernel(s, centre, R, target_n, d_guess)
    if n_contact < 0:
        return np.nan, np.nan, 0, 0, 2
    m = 0
    for i in range(s.size):
        uz = d - (s[i] - centre) ** 2 / R
        if uz > 0.0:
            v_buf[m] = anchor[i]
            b_buf[m] = ratio * uz
            m += 1
    U, status = _rigid_shift_kernel(v_buf[:m], b_buf[:m], target_t, U_guess)
    if status != 0:
        return d, np.nan, n_contact, 0, status
    n_stick = 0
    for i in range(s.size):
        uz = d - (s[i] - centre) ** 2 / R
        bound = ratio * uz if uz > 0.0 else 0.0
        defl = min(max(U - anchor[i], -bound), bound)
        anchor[i] = U - defl
        if uz > 0.0 and abs(defl) < bound * (1.0 - 1e-12):
            n_stick += 1
    return d, U, n_contact, n_stick, 0


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
    classification: from solver.shakedown (state 'gross_sliding' if no equilibrium was found).
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


def simulate_mdr(*, R, E_star, G_star, Fn, mu, Ft, W, dW, periods, ramp_steps=1, n_springs=None,
                 ds=None, shakedown_tol=DEFAULT_TOL) -> MDRResult:
    """Run the 1-D MDR model of oscillating rolling (theory §8.2); see the module docstring.

    R: sphere radius (mm); E_star, G_star: contact moduli E*, G* (MPa, bem.materials.MaterialPair);
    Fn > 0 (N), mu > 0, 0 <= Ft (N; Ft > mu Fn is recorded as 'gross_sliding'); W >= 0 amplitude of the
    centre (mm; W = 0: no oscillation), dW > 0 requested centre step (mm), periods >= 0.
    Springs: s_i = i ds, |i| <= N, covering [-(a + W) - ds, a + W + ds] at least, so that every spring that
    can ever touch is modelled.  Give either ds (mm) or n_springs (odd total count, rounded up to odd;
    default 4001, then ds = (a + W) / ((n_springs - 1)/2 - 1)).
    shakedown_tol: tolerance on the per-period increment |dU|/U0 passed to solver.shakedown.classify.
    """
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
    periods, ramp_steps = int(periods), int(ramp_steps)

    hertz = HertzSphere(R, E_star, Fn)
    a, d_hertz = hertz.a, hertz.approach
    U0 = mu * E_star * d_hertz / G_star
    if W >= a:
        raise InputError(f"W = {W!r} mm >= a = {a:.6g} mm: the seed's model needs w = W/a < 1 (seed Eq. 10)")
    reach = a + W
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
    s = ds * np.arange(-half, half + 1, dtype=float)

    centre, period, dW_used, nq = _centre_path(float(W), dW, periods)
    n_load = 1 + ramp_steps                    # normal load, then the Ft ramp
    n_steps = n_load + centre.size
    Ft_path = np.concatenate(([0.0], Ft * np.arange(1, ramp_steps + 1) / ramp_steps,
                              np.full(centre.size, float(Ft))))
    c_path = np.concatenate((np.zeros(n_load), centre))
    period_path = np.concatenate((np.zeros(n_load, dtype=int), period))

    hist = {key: np.full(n_steps, np.nan) for key in
            ("W", "approach", "U", "Ft", "contact_length", "stick_length")}
    anchor = np.zeros_like(s)
    v_buf, b_buf = np.empty_like(s), np.empty_like(s)
    U = 0.0
    ratio = mu * E_star / G_star               # Coulomb bound on the deflection: b = ratio * u_z (mm)
    target_n = Fn / (E_star * ds)
    d_prev = d_hertz
    done, failure = 0, None
    for n in range(n_steps):
        target_t = Ft_path[n] / (G_star * ds)
        d, U_new, n_contact, n_stick, status = _step_kernel(
            s, anchor, c_path[n], R, target_n, d_prev, ratio, target_t, U, v_buf, b_buf)
        if status == 2:
            raise ConvergenceError("MDR normal problem: contact set did not settle", solver="simulate_mdr",
                                   iterations=200, regime=f"step {n}, centre {c_path[n]:.6g} mm")
        if status == 1:
            failure = (f"no tangential equilibrium at step {n} (period {period_path[n]}): Ft = {Ft_path[n]:.6g}"
                       f" N exceeds the friction capacity mu Fn = {mu * Fn:.6g} N")
            break
        U, d_prev = U_new, d
        hist["W"][n], hist["approach"][n], hist["U"][n], hist["Ft"][n] = c_path[n], d, U, Ft_path[n]
        hist["contact_length"][n] = ds * n_contact
        hist["stick_length"][n] = ds * n_stick
        done = n + 1
    history = {key: val[:done] for key, val in hist.items()}
    history["step"] = np.arange(done)
    history["period"] = period_path[:done]

    ends = [n_load - 1 + k * 4 * nq for k in range(periods + 1)]
    U_end = np.array([history["U"][i] for i in ends if i < done])
    if failure is not None:
        cls = gross_sliding(U_end, U0, failure)
    else:
        cls = classify(U_end, U0, tol=shakedown_tol)
    U_stat = float(history["U"][n_load - 1]) if done >= n_load else math.nan
    stick0 = float(history["stick_length"][n_load - 1]) if done >= n_load else math.nan
    return MDRResult(history=history, U_period_end=U_end, U_stat=U_stat, U0=U0, a=a, d=d_hertz,
                     dW_used=dW_used, ds=ds, n_springs=s.size, f_t=Ft / (mu * Fn), w=W / a,
                     classification=cls, stick_length_static=stick0)


@dataclass(frozen=True)
class LimitBracket:
    """Shakedown limit in f_t found by bisection: f_t_shakedown < limit <= f_t_ratcheting.

    runs: number of simulations; undecided_retries: runs repeated with doubled periods because the first
    classification was 'undecided' (slow decay close to the limit, pitfall P12).
    """

    f_t_shakedown: float
    f_t_ratcheting: float
    runs: int
    undecided_retries: int

    @property
    def estimate(self) -> float:
        return 0.5 * (self.f_t_shakedown + self.f_t_ratcheting)


def shakedown_limit_ft(*, R, E_star, G_star, Fn, mu, W, dW, periods, f_t_lo=0.0, f_t_hi=1.0,
                       f_t_tol=1e-3, n_springs=None, ds=None, max_period_doublings=2) -> LimitBracket:
    """Bisection in f_t = Ft/(mu Fn) for the shakedown/ratcheting limit of the MDR model at amplitude W (mm).

    Each probe is a full `simulate_mdr` run classified by solver.shakedown.classify: 'shakedown' moves the
    lower end up, 'ratcheting' the upper end down.  An 'undecided' probe is rerun with twice the periods
    (at most `max_period_doublings` times), then ConvergenceError.  f_t_lo must shake down and f_t_hi must
    ratchet (checked).  Stops when the bracket is narrower than f_t_tol.  Compare with
    mdr_limits.f_t_lim(W/a, KAPPA_MDR) (seed Eq. 12 at the limit).
    """
    common = dict(R=R, E_star=E_star, G_star=G_star, Fn=Fn, mu=mu, W=W, dW=dW, n_springs=n_springs, ds=ds)
    runs = retries = 0

    def state_at(f_t):
        nonlocal runs, retries
        p = periods
        for _ in range(max_period_doublings + 1):
            runs += 1
            state = simulate_mdr(**common, Ft=f_t * mu * Fn, periods=p).state
            if state != "undecided":
                return state
            retries += 1
            p *= 2
        raise ConvergenceError(f"shakedown_limit_ft: run at f_t = {f_t:.6g} still undecided after {p // 2} "
                               f"periods", solver="shakedown_limit_ft", iterations=runs)

    if not (0.0 <= f_t_lo < f_t_hi <= 1.0):
        raise InputError(f"f_t_lo = {f_t_lo!r}, f_t_hi = {f_t_hi!r}: need 0 <= f_t_lo < f_t_hi <= 1")
    if state_at(f_t_lo) != "shakedown":
        raise InputError(f"f_t_lo = {f_t_lo!r} does not shake down: lower it")
    if state_at(f_t_hi) != "ratcheting":
        raise InputError(f"f_t_hi = {f_t_hi!r} does not ratchet: raise it")
    lo, hi = f_t_lo, f_t_hi
    while hi - lo > f_t_tol:
        mid = 0.5 * (lo + hi)
        if state_at(mid) == "shakedown":
            lo = mid
        else:
            hi = mid
    return LimitBracket(lo, hi, runs, retries)
