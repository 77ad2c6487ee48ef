"""Classification of an oscillating-rolling run: shakedown, ratcheting, undecided (docs/theory.md §6.2, §8.3).

Model-independent: it only sees the rigid displacement U recorded at the same phase of the oscillation at
the end of each period, so the 1-D MDR model (solver.mdr) and the 3-D stepping solver share it.

Input: U_period_end[k] (mm), k = 0 .. P, index 0 = after the loading phase (before the first period),
index k = end of period k; U0 = mu E* d / G* (mm), the normalisation of seed Eq. 9 (docs/theory.md P3).
Increments per period: du_k = (U_k - U_{k-1}) / U0, k = 1 .. P.

Criteria (tolerances are parameters of `classify`):
* 'shakedown'   : the last increment |du_P| < tol (default 1e-4, docs/theory.md §6.2).  periods_to_shakedown =
                  the smallest n such that |du_k| < tol for every k > n (0: no period slipped by tol or more);
                  u_sd = U_P / U0.  A ratcheting run whose increment is below tol cannot be told apart from
                  shakedown at this tol: tol is the resolution of the classification.
* 'ratcheting'  : |du_P| >= tol and the increments have settled: |du_P - du_{P-1}| <= settle_rtol |du_P|
                  (default 2 %) over the last `settle_periods` (default 2) consecutive pairs.  du = du_P.
* 'undecided'   : neither, i.e. increments above tol that still change by more than settle_rtol per period
                  (typically a slow decay near the shakedown limit, docs/theory.md P12), or too few periods to
                  judge.  The message says so, and, for a geometric decay, estimates how many more periods
                  would bring the increment below tol.
* 'cyclic_slip' : by `cyclic_slip`, for a run whose loads vary within the period: 'shakedown' by U, but the
                  frictional work per period does not go to zero (settled, or converging to a limit > 0, above
                  WORK_FLOOR mu Fn U0): the contact slips to and fro every period (fretting, a Mindlin-Deresiewicz
                  cycle) while U returns.
* 'gross_sliding': never produced here; set by the caller when its solver reports that no equilibrium
                  exists (Ft > mu Fn), see `gross_sliding`.
A decay slower than settle_rtol per period is reported as ratcheting: over the periods run it is not
distinguishable from a constant increment.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
import math

import numpy as np

from rollcontact.bem.errors import InputError

STATES = ("shakedown", "ratcheting", "undecided", "gross_sliding", "cyclic_slip")

#: States whose U settled (period-end increments below tol): u_sd is their settled U/U0.
SETTLED_STATES = ("shakedown", "cyclic_slip")

#: Frictional work per period (in mu Fn U0) at or below which a settled run has stopped slipping: the work of a
#: slip at the solvers' relative tolerance 1e-8. The paper scene's runs that shake down under constant loads decay
#: through it geometrically (ratio 0.1-0.2 per period: 7e-10 after 8 periods at f_t = 0.3).
WORK_FLOOR = 1e-8

DEFAULT_TOL = 1e-4
DEFAULT_SETTLE_RTOL = 0.02
DEFAULT_SETTLE_PERIODS = 2


@dataclass(frozen=True)
class Classification:
    """Outcome of a run.

    state: one of STATES.
    periods_to_shakedown: for 'shakedown', the number of periods after which every increment stayed below
        tol (0 if none reached it); None otherwise.
    u_sd: for 'shakedown' and 'cyclic_slip', the final U/U0; None otherwise.
    du: the last per-period increment du_P = (U_P - U_{P-1})/U0 (signed), for every state (None if no
        period was completed).  For 'ratcheting' it is the settled increment per period.
    dU_per_period: the same increment in mm (du * U0), or None.
    increments: all du_k, k = 1 .. P (dimensionless).
    message: one human-readable sentence with the reason (and a suggestion for 'undecided').
    tol, settle_rtol: the tolerances used.
    """

    state: str
    periods_to_shakedown: int | None
    u_sd: float | None
    du: float | None
    dU_per_period: float | None
    increments: np.ndarray = field(repr=False)
    message: str = ""
    tol: float = DEFAULT_TOL
    settle_rtol: float = DEFAULT_SETTLE_RTOL

    def __post_init__(self):
        if self.state not in STATES:
            raise InputError(f"state = {self.state!r}: allowed states are {STATES}")


def _check_positive(name, value):
    if not (isinstance(value, (int, float, np.floating, np.integer)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name} = {value!r}: must be a finite number > 0")


def classify(U_period_end, U0, *, tol=DEFAULT_TOL, settle_rtol=DEFAULT_SETTLE_RTOL,
             settle_periods=DEFAULT_SETTLE_PERIODS) -> Classification:
    """Classify a run from U at the end of each period (mm; index 0 = after loading); see module docstring."""
    _check_positive("U0", U0)
    _check_positive("tol", tol)
    _check_positive("settle_rtol", settle_rtol)
    if not (int(settle_periods) == settle_periods and settle_periods >= 1):
        raise InputError(f"settle_periods = {settle_periods!r}: must be an integer >= 1")
    U = np.asarray(U_period_end, dtype=float).ravel()
    if U.size == 0:
        raise InputError("U_period_end is empty: need at least the value after loading (index 0)")
    if not np.all(np.isfinite(U)):
        raise InputError("U_period_end contains non-finite values (NaN or inf)")
    du = np.diff(U) / U0
    P = du.size
    if P == 0:
        return Classification("undecided", None, None, None, None, du,
                              "no complete period was run: nothing to classify", tol, settle_rtol)
    last = float(du[-1])
    dU_last = last * U0
    small = np.abs(du) < tol
    if small[-1]:
        big = np.flatnonzero(~small)
        n_sd = int(big[-1]) + 1 if big.size else 0
        return Classification(
            "shakedown", n_sd, float(U[-1] / U0), last, dU_last, du,
            f"shakedown: |du| < {tol:g} in every period after period {n_sd} (last du = {last:.3e})",
            tol, settle_rtol)
    # last increment is not small: settled (ratcheting) or still changing (undecided)?
    if P >= settle_periods + 1:
        tail = du[-(settle_periods + 1):]
        change = np.abs(np.diff(tail))
        if np.all(change <= settle_rtol * np.abs(tail[1:])):
            return Classification(
                "ratcheting", None, None, last, dU_last, du,
                f"ratcheting: the increment settled at du = {last:.4e} per period (changes <= "
                f"{settle_rtol:g} relative over the last {settle_periods} periods)", tol, settle_rtol)
    msg = f"undecided after {P} period(s): last du = {last:.3e} >= tol = {tol:g}"
    if P >= 2 and 0.0 < abs(last) < abs(du[-2]):
        q = abs(last) / abs(du[-2])
        more = math.ceil(math.log(tol / abs(last)) / math.log(q))
        msg += (f", still decaying (ratio {q:.3f} per period); about {more} more period(s) would bring it "
                f"below tol if the decay stays geometric - run more periods")
    elif P >= 2:
        msg += f", still changing (previous du = {du[-2]:.3e}) - run more periods"
    else:
        msg += " - run more periods"
    return Classification("undecided", None, None, last, dU_last, du, msg, tol, settle_rtol)


def gross_sliding(U_period_end, U0, message) -> Classification:
    """Classification for a run whose solver reported gross sliding (no equilibrium, Ft > mu Fn).

    U_period_end holds whatever period-end values were recorded before the failure (possibly only some).
    """
    _check_positive("U0", U0)
    U = np.asarray(U_period_end, dtype=float).ravel()
    du = np.diff(U) / U0 if U.size > 1 else np.zeros(0)
    last = float(du[-1]) if du.size else None
    return Classification("gross_sliding", None, None, last, None if last is None else last * U0, du,
                          f"gross sliding: {message}")


@dataclass(frozen=True)
class Decay:
    """The decay of the per-period increments over the last `window` periods (see `geometric_decay`).

    ratio: q, the geometric mean of the last `window` ratios du_k / du_{k-1};
    spread: max - min of those ratios (0 for an exactly geometric decay);
    geometric: all of them in (0, 1) and spread <= spread_tol: the increments fall by a steady factor q;
    periods_to_tol: for a geometric decay, the periods still needed until |du| < tol at that rate, else None;
    remaining: for a geometric decay, the drift still to come, |du_P| q / (1 - q) (in U/U0), else None.
    """

    ratio: float
    spread: float
    geometric: bool
    periods_to_tol: int | None
    remaining: float | None

    def describe(self) -> str:
        if not self.geometric:
            return f"increments not decaying geometrically (ratios {self.ratio:.3f} +- {self.spread:.3f})"
        return (f"geometric decay, ratio {self.ratio:.3f} per period (spread {self.spread:.3f}): about "
                f"{self.periods_to_tol} more period(s) to tol, drift still to come {self.remaining:.2e} U0")


def geometric_decay(increments, *, tol=DEFAULT_TOL, window=4, spread_tol=0.01) -> Decay | None:
    """How the per-period increments du_k (U/U0, k = 1 .. P; Classification.increments) decay at the end: the
    ratio q of consecutive increments over the last `window` periods, whether it is steady (a geometric decay
    towards shakedown), and at that rate the periods still needed to bring |du| below `tol` and the drift still to
    come. None with fewer than window + 1 increments.

    Near the shakedown limit the ratio creeps towards 1 in steps (one element at a time stops slipping), so a
    steady ratio is a forecast, not a proof: use it to decide how long to go on, and judge on the run itself.
    """
    du = np.asarray(increments, dtype=float).ravel()
    if du.size < window + 1 or not np.all(np.isfinite(du)):
        return None
    tail = du[-(window + 1):]
    if np.any(tail == 0.0) or np.any(np.sign(tail) != np.sign(tail[-1])):
        return Decay(float("nan"), float("inf"), False, None, None)
    r = tail[1:] / tail[:-1]
    q = float(np.exp(np.mean(np.log(r))))
    spread = float(r.max() - r.min())
    if not (r.max() < 1.0 and spread <= spread_tol):
        return Decay(q, spread, False, None, None)
    last = abs(float(du[-1]))
    more = 0 if last < tol else math.ceil(math.log(tol / last) / math.log(q))
    return Decay(q, spread, True, more, last * q / (1.0 - q))


def cyclic_slip(cls: Classification, work_per_period, work_scale: float, *,
                settle_periods: int = DEFAULT_SETTLE_PERIODS) -> Classification:
    """`cls` turned 'cyclic_slip' when it is 'shakedown' by U but the frictional work of the completed periods
    (N mm, one value per period) does not go to zero: it has settled above WORK_FLOOR * work_scale (N mm: mu Fn U0;
    changes <= cls.settle_rtol relative over the last settle_periods pairs, the test of ratcheting), or it still
    changes but geometrically towards a limit above half its last value and the floor (Aitken's extrapolation of
    the last three: a decay to zero, W_k = C q^k, extrapolates to 0). A work that decays to zero (shaking down) or
    too few periods to judge keep 'shakedown'."""
    _check_positive("work_scale", work_scale)
    W = np.asarray(work_per_period, dtype=float).ravel()
    floor = WORK_FLOOR * work_scale
    if cls.state != "shakedown" or W.size < max(settle_periods, 2) + 1 or not W[-1] > floor:
        return cls
    tail = W[-(settle_periods + 1):]
    if np.all(np.abs(np.diff(tail)) <= cls.settle_rtol * tail[1:]):
        limit, how = W[-1], f"settled within {cls.settle_rtol:g} over {settle_periods} periods"
    else:
        d1, d2 = W[-2] - W[-3], W[-1] - W[-2]
        q = d2 / d1 if d1 != 0.0 else math.nan
        if not 0.0 < q < 1.0:
            return cls
        limit = W[-1] + d2 * q / (1.0 - q)
        if not (limit > 0.5 * W[-1] and limit > floor):
            return cls
        how = f"changing by a factor {q:.3f} per period towards {limit:.4g} N mm"
    return replace(cls, state="cyclic_slip",
                   message=f"cyclic slip: U settled ({cls.message}), but every period still dissipates "
                           f"{W[-1]:.4g} N mm ({W[-1] / work_scale:.3g} mu Fn U0, {how})")
