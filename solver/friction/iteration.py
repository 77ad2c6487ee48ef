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
`max_gain`. The coupling between elements, which the diagonal leaves out, is taken up by Anderson's acceleration
(stepped solves, `consistent_coefficient`) or by the Gauss-Seidel sweeps themselves (steady rolling,
solver.friction.steady), and safeguarded by a relaxation omega per element (`CoefficientUpdate`). Stops when
max |T - mu| p / p_max <= tol mu_static (the bound's inconsistency relative to the largest bound);
ConvergenceError after max_iter iterates, naming the law, the largest feedback and the
number of elements with J >= 1.
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
    solution, the solves done, the last residual (relative to mu_static), each element's feedback J and the residual
    of the first iterate (how far the first coefficient field was from consistent; relative to mu_static)."""

    mu: np.ndarray
    solution: object
    iterations: int
    residual: float
    feedback: np.ndarray
    first_residual: float = 0.0


class CoefficientUpdate:
    """The safeguarded update of the coefficient field towards the law's (module docstring).

    `observe(mu, T)` records the residual T - mu of an iterate and adapts a relaxation omega per element: halved when
    the element's residual changed sign since the last iterate (its iterates oscillate about its consistent value),
    raised by a quarter up to OMEGA_MAX while the sign holds (they approach, or are chased by, that value from one
    side). `step(mu, T, J)` is then mu + omega (T - mu) / (1 - J). `residual` is the last max |T - mu| / mu_static."""

    def __init__(self, mu_static, bounds, params: FrictionParams):
        self.mu_static, self.bounds, self.params = mu_static, bounds, params
        self.cap = 1.0 - 1.0 / params.max_gain
        self.residual = math.inf
        self.omega = None
        self._sign = None

    def observe(self, mu, T, weight=None) -> bool:
        """Records the residual of T against mu, max |T - mu| weight / mu_static (weight: p / p_max, so that the
        residual is the inconsistency of the traction bound relative to the largest, as the contact solvers measure
        theirs; None: 1); True when it is within tol."""
        change = T - mu
        self.residual = float(np.max(np.abs(change if weight is None else change * weight))) / self.mu_static
        sign = np.sign(change)
        if self.omega is None:
            self.omega = np.ones_like(mu)
        else:
            flip, hold = sign * self._sign < 0, sign * self._sign > 0
            self.omega = np.where(flip, np.maximum(OMEGA_MIN, 0.5 * self.omega),
                                  np.where(hold, np.minimum(OMEGA_MAX, 1.25 * self.omega), self.omega))
        self._sign = sign
        return self.residual <= self.params.tol

    def settled(self, mu, T, weight) -> bool:
        """True when every element with a residual above a tenth of the largest is relaxed by 1 or more again (none
        of them is still being damped after swapping sides)."""
        change = np.abs(T - mu) * weight
        significant = change > 0.1 * change.max()
        return bool(np.all(self.omega[significant] >= 1.0))

    def newton(self, mu, T, J) -> np.ndarray:
        """mu + (T - mu) / (1 - J), J clipped to [0, 1 - 1/max_gain], within the law's bounds."""
        return np.clip(mu + (T - mu) / (1.0 - np.clip(J, 0.0, self.cap)), *self.bounds)

    def step(self, mu, T, J) -> np.ndarray:
        """The relaxed Newton step mu + omega (T - mu) / (1 - J) (class docstring), within the law's bounds."""
        return np.clip(mu + self.omega * (T - mu) / (1.0 - np.clip(J, 0.0, self.cap)), *self.bounds)

    def back_off(self):
        if self.omega is not None:
            self.omega = np.maximum(OMEGA_MIN, 0.5 * self.omega)


#: Range of the relaxation of an element's step (CoefficientUpdate).
OMEGA_MIN, OMEGA_MAX = 1.0 / 1024.0, 1.5
#: Iterates kept by the Anderson acceleration of `consistent_coefficient`, the iterates whose residual grew after
#: which it stops...
ANDERSON_DEPTH = 5
ACCELERATION_TROUBLES = 2
#: ... and the relaxed iterates with falling residual after which it resumes.
RESUME_AFTER = 4
#: The solve after an iterate with residual r (relative to mu_static) asks for the relative accuracy INEXACT r: no
#: iterate is solved much more accurately than its coefficient is known, and near the iteration's tolerance the solves
#: go below theirs (down to a tenth, StepParams.loosened), so that their noise does not hold the residual above it.
INEXACT = 1e-2
#: An iterate whose residual times the expected ratio of the next residual to it is within the tolerance is solved to
#: the full tolerance at once (its solution is then final when it converges, without a confirming solve). The ratio
#: expected is the last one observed; before the iteration has shown one (and after a residual that grew) the largest
#: feedback J of the iterate (the coupling between elements that the element-wise Newton step leaves out is of its
#: order), at least RATE_FLOOR.
RATE_FLOOR = 1e-3


def consistent_coefficient(solve, target, mu0, *, mu_static, bounds, params: FrictionParams, regime,
                           expected_residual=None) -> Consistent:
    """Iterate mu until the law's coefficient of the solution is mu (module docstring).

    solve(mu, accuracy) -> solution (accuracy: a relative tolerance the solve may stop at, looser than its own, or
    None); target(solution, mu) -> (T, J, weight) arrays of mu's shape (weight: p / p_max, CoefficientUpdate.observe);
    mu0 the first coefficient field; bounds = (lowest, highest) coefficient the law can give (iterates are kept inside);
    regime(J) -> str for the error message. expected_residual: the residual mu0 is expected to have (relative to
    mu_static; e.g. the first residual of the previous step's iteration, where the coefficient field changes little
    from step to step), None or <= tol when mu0 is expected to be consistent.

    While the residual falls, the element-wise Newton steps are combined by Anderson's acceleration over the last
    ANDERSON_DEPTH iterates (Walker & Ni 2011: the coupling between neighbouring slipping elements, which the
    element-wise steps leave out, otherwise converges linearly at rates of 0.8-0.9); after an iterate whose residual
    grew, and after ACCELERATION_TROUBLES of them until RESUME_AFTER relaxed iterates in a row have lowered it and the
    elements that matter are no longer damped (CoefficientUpdate.settled), the step is the relaxed one of
    CoefficientUpdate (elements at the stick/slip boundary that swap between stick and slip
    are damped until they settle). The early solves are inexact, the last ones below the solver's tolerance (INEXACT):
    the first asks for the expected residual of mu0 (its answer is off by about that much through its coefficients
    anyway), the one whose iterate is expected to converge (RATE_FLOOR) for the
    full tolerance; an iterate that converges after a looser solve is confirmed by a solve to the full tolerance. A
    solve that finds the force beyond the capacity of the current coefficients (GrossSlidingError) is retried from
    halfway back to the last coefficients that carried it; if the law's own coefficients cannot carry it either,
    that GrossSlidingError is raised."""
    update = CoefficientUpdate(mu_static, bounds, params)
    mu = np.clip(np.array(mu0, dtype=float), *bounds)
    carried, failures = None, 0
    J = np.zeros_like(mu)
    history = []          # (g, f) of earlier iterates: the Newton step's result g and its change f = g - mu
    troubles, falling = (0 if ANDERSON_DEPTH > 0 else ACCELERATION_TROUBLES), 0
    rate, first = 1.0, None     # the expected ratio of the next residual to the last; the first residual
    for k in range(1, params.max_iter + 1):
        if math.isfinite(update.residual):
            accuracy = INEXACT * update.residual
            if update.residual * rate <= params.tol:
                accuracy = min(accuracy, params.tol)          # expected to be the last solve
        else:
            accuracy = expected_residual if expected_residual is not None and expected_residual > params.tol \
                else None
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
        T, J, weight = target(solution, mu)
        previous = update.residual
        converged = update.observe(mu, T, weight)
        first = update.residual if first is None else first
        if converged:
            if accuracy is not None and accuracy > params.tol:
                update.residual = params.tol / INEXACT     # confirm with a solve to the full tolerance
                continue
            # where nothing presses (weight 0) the coefficient bounds nothing: it is the law's (the memory state)
            return Consistent(np.where(weight > 0, mu, T), solution, k, update.residual, J, first)
        grew = update.residual >= previous
        rate = (update.residual / previous if math.isfinite(previous) and not grew
                else max(float(np.max(J, initial=0.0)), RATE_FLOOR))
        troubles, falling = (troubles + 1, 0) if grew else (troubles, falling + 1)
        if troubles >= ACCELERATION_TROUBLES and falling >= RESUME_AFTER and update.settled(mu, T, weight):
            troubles = 0             # the relaxed steps have settled the swapping elements: accelerate again
        if grew or troubles >= ACCELERATION_TROUBLES:
            history.clear()
            mu = update.step(mu, T, J)
            continue
        g = update.newton(mu, T, J)
        history.append((g, g - mu))
        del history[:-(ANDERSON_DEPTH + 1)]
        mu = g
        if len(history) > 1:
            n = len(history) - 1
            dG = np.stack([b[0] - a[0] for a, b in zip(history[:-1], history[1:])], axis=-1).reshape(-1, n)
            dF = np.stack([b[1] - a[1] for a, b in zip(history[:-1], history[1:])], axis=-1).reshape(-1, n)
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
