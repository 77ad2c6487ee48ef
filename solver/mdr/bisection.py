"""Shakedown limit of the 1-D MDR model by bisection in f_t = Ft/(mu Fn) (docs/theory.md §8.2-8.3, seed Eq. 12).

Each probe is a full `solver.mdr.simulate_mdr` run; the result brackets the limit between a shakedown and a
ratcheting f_t.  Units mm, N, MPa (R, W, dW in mm; E*, G* in MPa; Fn in N); f_t is dimensionless.
Compare with the closed form `solver.mdr.limits.f_t_lim`.
"""
from __future__ import annotations

from dataclasses import dataclass

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.mdr.simulate import simulate_mdr


@dataclass(frozen=True)
class LimitBracket:
    """Shakedown limit in f_t found by bisection: f_t_shakedown < limit <= f_t_ratcheting.

    runs: number of simulations; undecided_retries: runs repeated with doubled periods because the first
    classification was 'undecided' (slow decay close to the limit, docs/theory.md P12).
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

    Each probe is a full `simulate_mdr` run classified by solver.rolling.shakedown.classify: 'shakedown' moves the
    lower end up, 'ratcheting' the upper end down.  An 'undecided' probe is rerun with twice the periods
    (at most `max_period_doublings` times), then ConvergenceError.  f_t_lo must shake down and f_t_hi must
    ratchet (checked).  Stops when the bracket is narrower than f_t_tol.  Compare with
    solver.mdr.limits.f_t_lim(W/a, KAPPA_MDR) (seed Eq. 12 at the limit).
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
