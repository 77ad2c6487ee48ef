"""The slip-velocity iteration: the local coefficient of friction consistent with the solution it bounds
(docs/friction.md, "Solving with a friction law"; the CONTACT user guide's "Solution processes", process 2).

A friction law makes the traction bound g = mu p depend on the solution (its slip velocity, or the surface temperature
that its frictional power raises). Each iterate solves the contact problem with a given coefficient field mu (a convex
Coulomb problem: `solve`), reads off the coefficient the law gives for that solution (`target`, with friction memory
the coefficient at the end of the step) and moves mu towards it. The update is Newton's on each element's own
relation, mu <- mu + omega (T - mu) / (1 - J), with J = dT/dmu the element's feedback through its own slip: a
slipping element whose bound rises by p dmu slips less by a_self p dmu (its self-influence), so J = -T'(s) a_self p /
dt >= 0 for falling friction (per unit rolled distance and V in steady rolling). J -> 1 is where the element's
quasi-static problem stops having a unique solution (Vollebregt & Schuttelaars 2012): the gain 1/(1 - J) is capped at
`max_gain`, and omega is halved whenever the residual grows (a safeguard against the coupling between elements,
which the diagonal leaves out). Stops when max |T - mu| <= tol mu_static; ConvergenceError after max_iter iterates,
naming the law, the largest feedback and the number of elements with J >= 1.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError, GrossSlidingError, InputError


@dataclass(frozen=True)
class FrictionParams:
    """tol: on max |T - mu| / mu_static (the law's coefficient of the solution against the one used);
    max_iter: solves per step (or per steady state) before ConvergenceError; max_gain: largest factor 1/(1 - J)."""

    tol: float = 1e-8
    max_iter: int = 200
    max_gain: float = 4.0

    def __post_init__(self):
        if not (0.0 < self.tol < 1.0):
            raise InputError(f"FrictionParams.tol = {self.tol!r}: allowed range 0 < tol < 1")
        if int(self.max_iter) != self.max_iter or self.max_iter < 1:
            raise InputError(f"FrictionParams.max_iter = {self.max_iter!r}: must be an integer >= 1")
        if not self.max_gain >= 1.0:
            raise InputError(f"FrictionParams.max_gain = {self.max_gain!r}: must be >= 1")


@dataclass
class Consistent:
    """The outcome: the coefficient field used by the last solve (consistent with the law within tol), that solve's
    solution, the solves done, the last residual (relative to mu_static) and each element's feedback J."""

    mu: np.ndarray
    solution: object
    iterations: int
    residual: float
    feedback: np.ndarray


class CoefficientUpdate:
    """The safeguarded update of the coefficient field towards the law's (module docstring): `step(mu, T, J)` returns
    the next iterate and keeps the relaxation omega (halved when the residual grew, raised by a quarter back towards 1
    when it fell); `residual` is the last max |T - mu| / mu_static."""

    def __init__(self, mu_static, bounds, params: FrictionParams):
        self.mu_static, self.bounds, self.params = mu_static, bounds, params
        self.cap = 1.0 - 1.0 / params.max_gain
        self.omega, self.residual = 1.0, math.inf

    def converged(self, mu, T) -> bool:
        """Records the residual of T against mu; True when it is within tol."""
        previous, self.residual = self.residual, float(np.max(np.abs(T - mu))) / self.mu_static
        if self.residual > previous:
            self.omega = max(self.omega / 2.0, 1.0 / 16.0)
        else:
            self.omega = min(1.0, 1.25 * self.omega)
        return self.residual <= self.params.tol

    def step(self, mu, T, J) -> np.ndarray:
        """The next coefficient field: mu + omega (T - mu) / (1 - J), J clipped to [0, 1 - 1/max_gain], kept within
        the law's bounds."""
        return np.clip(mu + self.omega * (T - mu) / (1.0 - np.clip(J, 0.0, self.cap)), *self.bounds)

    def back_off(self):
        self.omega = max(self.omega / 2.0, 1.0 / 16.0)


#: Iterates kept by the Anderson acceleration of `consistent_coefficient`.
ANDERSON_DEPTH = 5
#: The solve after an iterate with residual r (relative to mu_static) asks for the relative accuracy INEXACT r (never
#: beyond its own tolerance): no iterate is solved much more accurately than its coefficient is known.
INEXACT = 1e-2


def consistent_coefficient(solve, target, mu0, *, mu_static, bounds, params: FrictionParams, regime) -> Consistent:
    """Iterate mu until the law's coefficient of the solution is mu (module docstring).

    solve(mu) -> solution; target(solution, mu) -> (T, J) arrays of mu's shape; mu0 the first coefficient field;
    bounds = (lowest, highest) coefficient the law can give (iterates are kept inside); regime(J) -> str for the
    error message. The element-wise Newton steps are combined by Anderson's acceleration over the last
    ANDERSON_DEPTH iterates (Walker & Ni 2011: the coupling between neighbouring slipping elements, which the
    element-wise steps leave out, otherwise converges linearly at rates of 0.8-0.9); when the residual grows, the
    history is dropped and the plain step is damped (CoefficientUpdate). A solve that finds the force beyond the
    capacity of the current coefficients (GrossSlidingError) is retried from halfway back to the last coefficients
    that carried it; if the law's own coefficients cannot carry it either, that GrossSlidingError is raised."""
    update = CoefficientUpdate(mu_static, bounds, params)
    mu = np.clip(np.array(mu0, dtype=float), *bounds)
    carried, failures = None, 0
    J = np.zeros_like(mu)
    history = []          # (g, f) of earlier iterates: the Newton step's result g and its change f = g - mu
    for k in range(1, params.max_iter + 1):
        # inexact solves while the coefficient is far from consistent: the solve's tolerance follows the residual
        accuracy = None if not math.isfinite(update.residual) else INEXACT * update.residual
        try:
            solution = solve(mu, accuracy)
        except GrossSlidingError:
            failures += 1
            if carried is None or failures > 30:
                raise
            mu = 0.5 * (mu + carried)
            update.back_off()
            history.clear()
            continue
        carried = mu.copy()
        T, J = target(solution, mu)
        previous = update.residual
        if update.converged(mu, T):
            if accuracy is not None and accuracy > params.tol:
                update.residual = accuracy       # confirm with a solve to the full tolerance
                continue
            return Consistent(mu, solution, k, update.residual, J)
        if update.residual > previous:
            history.clear()
            mu = update.step(mu, T, J)
            continue
        g = np.clip(mu + (T - mu) / (1.0 - np.clip(J, 0.0, update.cap)), *bounds)
        history.append((g, g - mu))
        del history[:-(ANDERSON_DEPTH + 1)]
        mu = g
        if len(history) > 1:
            dG = np.stack([b[0] - a[0] for a, b in zip(history[:-1], history[1:])], axis=-1).reshape(-1, len(history) - 1)
            dF = np.stack([b[1] - a[1] for a, b in zip(history[:-1], history[1:])], axis=-1).reshape(-1, len(history) - 1)
            gamma = np.linalg.lstsq(dF, history[-1][1].ravel(), rcond=None)[0]
            mu = np.clip(g - (dG @ gamma).reshape(g.shape), *bounds)
    raise ConvergenceError("slip-velocity iteration (friction law) did not converge", solver="friction",
                           iterations=params.max_iter, residual=update.residual, tol=params.tol, regime=regime(J))


def feedback_regime(law, J, where: str) -> str:
    """The regime of a failed iteration for its message: the law, the largest feedback and the unstable elements."""
    unstable = int(np.count_nonzero(J >= 1.0))
    text = f"{law.describe()}, {where}, largest feedback J = {float(np.max(J, initial=0.0)):.3g}"
    if unstable:
        text += (f"; J >= 1 at {unstable} element(s): falling friction steeper than the elements' own elastic "
                 "stiffness, where the quasi-static problem can have several solutions (use friction memory, "
                 "[friction] memory_distance, or a flatter law, or roll the transient)")
    return text
