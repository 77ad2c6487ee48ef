"""The bracketing and bisection of the shakedown-limit search (cases.sweep.limit_search._LimitSearch) on a state whose
limit is known exactly: the probe's run is replaced by a threshold rule, so that the 'ok', 'widened' and 'failed'
outcomes and the continuation of undecided probes are checked at their edges, which real runs reach only by
chance (the real probes are tested in test_sweep.py). f_t, w dimensionless (seed Eq. 9)."""
import pytest

from rollcontact.bem.errors import RollcontactError
from rollcontact.cases.sweep.limit_search import _LimitSearch
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.rolling.shakedown import Decay

LIMIT = 0.437


class ThresholdSearch(_LimitSearch):
    """Shakedown below LIMIT, ratcheting above; 'undecided' within `band` of it unless the run has at least
    `decide_at` periods. Records every probe (x, periods, the run it continues); `decay`: what the undecided
    probes' increments look like (None: not enough periods to tell)."""

    def __init__(self, tol, band=0.0, decide_at=None, always=None, decay=None):
        super().__init__(default_scene(), ["motion.periods=10"], {}, "load.ft", tol, None, None, False)
        self.band, self.decide_at, self.always, self.calls, self.model_decay = band, decide_at, always, [], decay

    def run(self, x, periods, extend_from=None):
        self.calls.append((x, periods, extend_from))
        self.probes += 1
        path = f"run x={x} periods={periods}"
        if self.always:
            return self.always, path
        if abs(x - LIMIT) < self.band and (self.decide_at is None or periods < self.decide_at):
            return "undecided", path
        return ("shakedown" if x < LIMIT else "ratcheting"), path

    def decay(self, path):
        return self.model_decay


@pytest.mark.parametrize("guess", [(0.3, 0.6), (0.5, 0.55), (0.1, 0.2)])
def test_bisection_brackets_the_limit_to_the_tolerance_from_any_guess(guess):
    """Guesses around, above and below the limit: the bracket grows outwards until both sides are decided, then
    halves to width <= tol with lower < LIMIT <= upper."""
    s = ThresholdSearch(tol=0.01)
    lo, hi = s.bracket(*guess)
    lo, hi, status = s.bisect(lo, hi)
    assert status == "ok" and lo < LIMIT <= hi and hi - lo <= 0.01 * (1 + 1e-9)
    assert all(p == 10 for _, p, _ in s.calls)


def test_an_undecided_probe_without_a_steady_decay_is_continued_with_as_many_periods_again():
    """Undecided at 10 and 20 periods, decided at 40, increments not (yet) decaying geometrically: the probe is
    continued from its own run file to 20, then 40 periods, and classified; nothing is widened."""
    s = ThresholdSearch(tol=0.01, band=0.02, decide_at=40)
    lo, hi, status = s.bisect(*s.bracket(0.3, 0.6))
    assert status == "ok" and lo < LIMIT <= hi and not s.undecided
    near = [(x, p, src) for x, p, src in s.calls if abs(x - LIMIT) < 0.02]
    assert near and [p for _, p, _ in near[:3]] == [10, 20, 40]
    x = near[0][0]
    assert [src for _, _, src in near[:3]] == [None, f"run x={x} periods=10", f"run x={x} periods=20"]


def test_an_undecided_probe_with_a_geometric_decay_is_continued_for_the_periods_it_needs():
    """A steady decay that needs 35 more periods to reach the shakedown tolerance: the probe is continued to
    10 + 35 + 2 periods in one go (2 periods of margin, for the ratio creeping up near the limit)."""
    decay = Decay(ratio=0.936, spread=0.002, geometric=True, periods_to_tol=35, remaining=1.5e-3)
    s = ThresholdSearch(tol=0.01, band=0.02, decide_at=47, decay=decay)
    lo, hi, status = s.bisect(*s.bracket(0.3, 0.6))
    assert status == "ok" and lo < LIMIT <= hi and not s.undecided
    near = [p for x, p, _ in s.calls if abs(x - LIMIT) < 0.02]
    assert near[:2] == [10, 47]


def test_a_probe_undecided_after_the_retries_widens_the_bracket_around_it():
    """Undecided within 0.03 of the limit at any length (continued up to 16 x 10 periods): bisection stops at the first such midpoint and steps
    outwards by tol/2, tol, 2 tol, ... until each side is decided: 'widened', with the undecided value recorded and
    the bracket still containing the limit and the whole undecided band."""
    s = ThresholdSearch(tol=0.01, band=0.03)
    lo, hi, status = s.bisect(*s.bracket(0.3, 0.6))
    assert status == "widened"
    assert lo <= LIMIT - 0.03 and hi >= LIMIT + 0.03 and s.undecided
    assert all(abs(x - LIMIT) < 0.03 for x in s.undecided)
    assert max(p for _, p, _ in s.calls) == 160


@pytest.mark.parametrize("state, message", [("ratcheting", "still no shakedown at the lower end"),
                                            ("shakedown", "still no ratcheting at the upper end")])
def test_a_limit_outside_the_search_range_fails_naming_the_end(state, message):
    s = ThresholdSearch(tol=0.01, always=state)
    with pytest.raises(RollcontactError, match=message):
        s.bracket(0.3, 0.6)
