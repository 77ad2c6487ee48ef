"""Classification of a run from its per-period displacements (solver.rolling.shakedown; docs/theory.md §6.2)."""
import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.rolling.shakedown import (STATES, WORK_FLOOR, Classification, classify, cyclic_slip,
                                                 geometric_decay, gross_sliding)

U0 = 0.8   # mm


def _run(increments, U_start=0.3):
    """U at the period ends (mm) from normalised increments du_k."""
    return U_start + U0 * np.concatenate(([0.0], np.cumsum(increments)))


def test_geometric_decay_shakes_down_after_the_right_number_of_periods():
    # du_k = 0.1 * 0.5^(k-1): du_11 = 9.8e-5 is the first below 1e-4, so shakedown after period 10
    du = 0.1 * 0.5 ** np.arange(15)
    U = _run(du)
    c = classify(U, U0)
    assert c.state == "shakedown"
    assert c.periods_to_shakedown == 10
    assert c.u_sd == pytest.approx(U[-1] / U0, abs=1e-15)
    assert c.du == pytest.approx(du[-1], rel=1e-9)
    assert c.dU_per_period == pytest.approx(du[-1] * U0, rel=1e-9)
    np.testing.assert_allclose(c.increments, du, rtol=1e-9, atol=1e-15)


def test_no_slip_at_all_is_shakedown_after_zero_periods():
    c = classify(np.full(6, 0.25), U0)
    assert c.state == "shakedown" and c.periods_to_shakedown == 0 and c.u_sd == pytest.approx(0.25 / U0)


def test_constant_increment_is_ratcheting():
    c = classify(_run(np.full(10, 0.02)), U0)
    assert c.state == "ratcheting"
    assert c.du == pytest.approx(0.02, rel=1e-9) and c.u_sd is None and c.periods_to_shakedown is None


def test_increment_settling_to_a_constant_is_ratcheting():
    du = 0.03 + 0.1 * 0.3 ** np.arange(12)       # transient decays onto a constant increment
    assert classify(_run(du), U0).state == "ratcheting"


def test_slow_decay_above_tol_is_undecided_and_suggests_more_periods():
    du = 0.01 * 0.8 ** np.arange(10)              # still 1.3e-3 after 10 periods, shrinking 20 % per period
    c = classify(_run(du), U0)
    assert c.state == "undecided"
    assert "more period" in c.message and "decaying" in c.message
    assert c.u_sd is None and c.du == pytest.approx(du[-1], rel=1e-9)


def test_too_few_periods_is_undecided():
    assert classify([0.1], U0).state == "undecided"               # loading only
    assert classify(_run([0.05]), U0).state == "undecided"        # one period, one increment: not settled


def test_tolerance_sets_the_resolution():
    du = 0.1 * 0.5 ** np.arange(15)               # last du = 6.1e-6
    assert classify(_run(du), U0, tol=1e-6).state == "undecided"
    assert classify(_run(du), U0, tol=1e-5).state == "shakedown"


def test_gross_sliding_is_an_allowed_state_set_by_the_caller():
    assert set(STATES) == {"shakedown", "ratcheting", "undecided", "gross_sliding", "cyclic_slip"}
    c = gross_sliding([], U0, "Ft > mu Fn")
    assert c.state == "gross_sliding" and "Ft > mu Fn" in c.message and c.du is None
    with pytest.raises(InputError, match="state"):
        Classification("walking", None, None, None, None, np.zeros(0))


@pytest.mark.parametrize("U, U0_, kw, name", [
    ([0.1, np.nan], U0, {}, "non-finite"), ([], U0, {}, "empty"), ([0.1, 0.2], 0.0, {}, "U0"),
    ([0.1, 0.2], U0, {"tol": -1.0}, "tol"), ([0.1, 0.2], U0, {"settle_periods": 0}, "settle_periods"),
])
def test_bad_input_is_refused(U, U0_, kw, name):
    with pytest.raises(InputError, match=name):
        classify(U, U0_, **kw)


# ------------------------------------------------------------------------------------------ geometric_decay
def test_a_geometric_decay_gives_its_ratio_the_periods_to_tol_and_the_drift_still_to_come():
    """du_k = 0.01 q^(k-1), q = 0.936 (the decay of the paper scene at f_t = 0.66, w = 0.23): the ratio exactly,
    the periods until du < 1e-4 (du_P q^n < 1e-4) and the geometric tail sum du_P q / (1 - q)."""
    q = 0.936
    du = 0.01 * q ** np.arange(20)
    d = geometric_decay(du)
    assert d.geometric and d.ratio == pytest.approx(q, rel=1e-12) and d.spread < 1e-12
    n = d.periods_to_tol
    assert du[-1] * q ** n < 1e-4 <= du[-1] * q ** (n - 1)
    assert d.remaining == pytest.approx(du[-1] * q / (1 - q), rel=1e-9)


def test_increments_settling_to_a_constant_or_rising_ratios_are_not_a_geometric_decay():
    """Ratcheting onto a constant increment (ratios creeping to 1) and a stepwise change of the ratio larger than
    the spread tolerance are not forecast."""
    assert not geometric_decay(0.002 + 0.01 * 0.8 ** np.arange(20)).geometric
    steps = 0.01 * np.cumprod(np.r_[1.0, [0.90] * 8, [0.93] * 2])
    assert not geometric_decay(steps).geometric
    assert not geometric_decay(np.full(8, 0.01)).geometric             # ratio 1: no decay
    assert not geometric_decay(0.01 * (-0.5) ** np.arange(8)).geometric  # alternating sign


def test_too_few_increments_give_no_decay():
    assert geometric_decay(0.01 * 0.5 ** np.arange(4)) is None


def test_cyclic_slip_is_a_settled_u_with_a_settled_frictional_work():
    # U back at the same value every period (shakedown by U) while the work per period stays at a constant > 0:
    # the contact slips to and fro (a Mindlin-Deresiewicz cycle). Measured on the paper scene: the work per period
    # of a run shaking down under constant loads decays by 0.1-0.2 per period; under an oscillating Ft it settles
    # (1.666e-05 mu Fn U0 from the 3rd period at ft_amplitude = 0.05 without rolling).
    settled = classify(_run([0.05, 1e-6, 1e-7, 0.0]), U0)
    assert settled.state == "shakedown"
    scale = 10.0                                             # mu Fn U0, N mm
    work = [0.3, 0.2, 0.2 * (1 + 0.019), 0.2 * (1 + 0.019) ** 2]
    c = cyclic_slip(settled, work, scale)
    assert c.state == "cyclic_slip" and c.u_sd == settled.u_sd and "every period" in c.message
    assert cyclic_slip(settled, [0.3, 0.2, 0.2 * 1.03, 0.2 * 1.03 ** 2], scale).state == "shakedown"  # > 2 %
    assert cyclic_slip(settled, 0.2 * 0.2 ** np.arange(6), scale).state == "shakedown"               # decaying
    floor = WORK_FLOOR * scale
    assert cyclic_slip(settled, [floor] * 4, scale).state == "shakedown"                            # round-off
    assert cyclic_slip(settled, [2 * floor] * 4, scale).state == "cyclic_slip"
    assert cyclic_slip(settled, [0.2, 0.2], scale).state == "shakedown"          # two periods: too few to judge
    # still converging, but to a limit > 0 (Aitken): the last periods of the paper scene (W ∥ Ft, f_t = 0.46 +- 0.1
    # at phase 0, w = 0.23), still 3.4 % apart after 10 periods, extrapolate to 8.1e-4 N mm
    tail = [0.0014014, 0.0010645, 0.00092677, 0.0008638, 0.00083422]
    assert cyclic_slip(settled, tail, 15.74).state == "cyclic_slip"
    assert cyclic_slip(settled, 0.2 * 0.9 ** np.arange(40), scale).state == "shakedown"    # slow decay to zero
    assert cyclic_slip(settled, [0.2, 0.1, 0.15, 0.12], scale).state == "shakedown"       # not monotone
    ratcheting = classify(_run([0.01] * 5), U0)
    assert cyclic_slip(ratcheting, [0.2] * 5, scale) is ratcheting
    with pytest.raises(InputError, match="work_scale"):
        cyclic_slip(settled, work, 0.0)
