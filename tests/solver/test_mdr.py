"""1-D MDR simulator of oscillating rolling (solver.mdr: step, _kernels, bisection; docs/theory.md §8.2-8.3, seed Eqs. 4-5, 12).

Scene of the seed (Table 1, docs/theory.md P1-P5): R = 40 mm, mu = 0.93, Fn = 21.19 N, steel on rubber.
Runtime: every run below takes 3-150 ms (numba kernel, ~40 us per step at 4001 springs).
"""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.bem.materials import MaterialPair
from rollcontact.solver.mdr import limits as L
from rollcontact.solver.analytic import HertzSphere
from rollcontact.solver.mdr._kernels import _approach_kernel, _rigid_shift_kernel
from rollcontact.solver.mdr.simulate import simulate_mdr
from rollcontact.solver.mdr.bisection import shakedown_limit_ft
from rollcontact.solver.mdr.step import approach_for_force, rigid_shift

from reference_data import RATCHET_RATIO

PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
SCENE = dict(R=40.0, E_star=PAIR.E_star, G_star=PAIR.G_star, Fn=21.19, mu=0.93)
MU_FN = 0.93 * 21.19
A = HertzSphere(40.0, PAIR.E_star, 21.19).a      # 4.786 mm


def run(f_t, w, *, nq=20, periods=10, **kw):
    W = w * A
    return simulate_mdr(**SCENE, Ft=f_t * MU_FN, W=W, dW=W / nq if W else 0.1, periods=periods, **kw)


# ------------------------------------------------------------------------- static (w = 0): Mindlin
@pytest.mark.parametrize("n_springs", [1001, 4001])
@pytest.mark.parametrize("f_t", [0.25, 0.5, 0.75])
def test_without_oscillation_reproduces_mindlin_shift_and_stick_radius(f_t, n_springs):
    """Seed Eqs. 4-5.  Observed: |u_stat error| ~ 0.2-0.5 (ds/a)^2 (9e-7 at ds/a = 2e-3, 6e-8 at 5e-4:
    second order, the spring sum is a midpoint rule of the Hertz integrals); the stick length is a count of
    springs, so its error is at most one spacing per edge: |c_sim - c| <= ds."""
    r = run(f_t, 0.0, periods=2, n_springs=n_springs)
    h = r.ds / r.a
    assert r.state == "shakedown" and r.classification.periods_to_shakedown == 0
    assert abs(r.U_stat / r.U0 - L.u_stat(f_t)) < h ** 2
    assert abs(r.stick_length_static / 2 - r.a * L.stick_ratio_static(f_t)) <= r.ds
    assert abs(r.history["contact_length"][-1] / 2 - r.a) <= r.ds
    assert abs(r.history["approach"][-1] / r.d - 1) < h ** 2      # discrete Hertz: Fn = E* ds sum u_z


def test_monotone_loading_does_not_depend_on_the_ramp():
    # Cattaneo-Mindlin in the MDR is path independent for monotone Ft: ramp or single step agree exactly
    one, ramp = run(0.6, 0.0, periods=0, n_springs=801), run(0.6, 0.0, periods=0, n_springs=801, ramp_steps=7)
    assert ramp.U_stat == pytest.approx(one.U_stat, rel=1e-12)
    assert np.all(np.diff(ramp.history["U"]) > 0)


# ----------------------------------------------------------------- shakedown: seed Eq. 12 (kappa 3/2)
CASES = [(0.1, 0.6), (0.23, 0.46), (0.4, 0.3)]


@pytest.mark.parametrize("w, f_t", CASES)
def test_shakedown_displacement_converges_to_mdr_equilibrium_eq12(w, f_t):
    """Coarse (201 springs, dW = W/5) vs fine (1601 springs, dW = W/40).  Observed errors |u_sd - Eq. 12|:
    3.5e-5 / 5.0e-5 / 7.9e-5 coarse, 0.8e-7 / 1.4e-7 / 3.6e-7 fine.  The error is set by ds (it hardly
    changes with dW: the shaken-down state is fixed by the reversal points, which are hit exactly).
    Asserted: fine error < 1e-5 (docs/theory.md §8.3) and at least 10x below the coarse one: second order in ds would
    give (1600/200)^2 = 64x (measured 440 / 360 / 220x); 10x still demands an order above 1.1."""
    ref = L.u_shakedown(f_t, w, L.KAPPA_MDR)
    errors = []
    for n, nq in ((201, 5), (1601, 40)):
        r = run(f_t, w, nq=nq, periods=15, n_springs=n)
        assert r.state == "shakedown", r.classification.message
        errors.append(abs(r.classification.u_sd - ref))
    coarse, fine = errors
    assert fine < 1e-5
    assert fine < coarse / 10


@pytest.mark.parametrize("w, f_t", [(0.1, 0.6), (0.23, 0.6), (0.4, 0.3)])
def test_theory_claim_4001_springs_ten_periods_within_1e5(w, f_t):
    # docs/theory.md §8.3: 4001 springs reach Eq. 12 to 1e-5 within 5-10 periods (w = 0.23, f_t = 0.6 is the
    # slowest: still du = 8e-6 after period 10, error 4e-6). Both bounds are the theory's claim, not fitted
    # (periods_to_shakedown 3 / 7 / 6 and errors 2e-8 / 4.2e-6 / 7.7e-7).
    r = run(f_t, w, nq=50, periods=10, n_springs=4001)
    assert r.state == "shakedown" and r.classification.periods_to_shakedown <= 10
    assert abs(r.classification.u_sd - L.u_shakedown(f_t, w)) < 1e-5


def test_rigid_displacement_never_decreases_and_exceeds_static():
    # docs/theory.md §8.3: U is non-decreasing during the transient (every slip increases the anchors)
    r = run(0.46, 0.23, n_springs=801)
    assert np.all(np.diff(r.history["U"]) >= -1e-12 * r.U0)
    # rolling adds u_sd - u_stat = 0.1439 (Eq. 12 minus Eq. 4); simulated to within the spring spacing's
    # second-order error h^2 = (ds/a)^2 = 9.5e-6 of the static test above (measured 2.3e-7)
    h = r.ds / r.a
    gain = L.u_shakedown(0.46, 0.23, L.KAPPA_MDR) - L.u_stat(0.46)
    assert abs(r.classification.u_sd - r.U_stat / r.U0 - gain) < h ** 2


@pytest.mark.parametrize("w", [0.23, 0.4])
def test_shakedown_limit_by_bisection_matches_mdr_closed_form(w):
    """Bisection in f_t (801 springs, dW = W/20, 40 periods, bracket 1e-3).  Observed: the closed form
    f_t,lim = 1 - 1.5 w + 0.5 w^3 lies inside the simulated bracket even at 2e-4 width, for 401-3201
    springs.  Asserted: inside the bracket widened by 2e-4 (allowance for ds and for the classification
    tolerance 1e-4 close to the limit, where increments decay slowly, docs/theory.md P12)."""
    b = shakedown_limit_ft(**SCENE, W=w * A, dW=w * A / 20, periods=40, f_t_lo=0.2, f_t_hi=0.95,
                           f_t_tol=1e-3, n_springs=801)
    ref = L.f_t_lim(w, L.KAPPA_MDR)
    assert b.f_t_ratcheting - b.f_t_shakedown <= 1e-3
    assert b.f_t_shakedown - 2e-4 <= ref <= b.f_t_ratcheting + 2e-4


# ------------------------------------------------------------------------------------- ratcheting
# Pure-MDR ratcheting increment per period, as du / (sqrt(u_stat) (w - w_lim,MDR)) (docs/theory.md §8.5). No closed form is
# known to us, so the reference is the program's own converged value (regression data, tests/reference_data.py,
# mdr_ratchet_ratio): 16001 springs, nq = W/dW = 400 and 1600, extrapolated to dW -> 0 with order 1 (the
# extrapolation from nq = 100/400 agrees to 1e-5). Ratios:
#   (w, f_t)     nq 25 (1001 springs)  nq 100    nq 400    nq 1600   dW -> 0   du / seed Eq. 21 (perpendicular)
#   (0.3, 0.7)   4.58710               4.59888   4.60186   4.60261   4.60286   7.88
#   (0.5, 0.5)   4.51402               4.53236   4.53701   4.53817   4.53856   8.52
#   (0.7, 0.3)   4.34580               4.36955   4.37559   4.37711   4.37761   9.95
# The error is first order in dW (it shrinks 3.94-3.96 times per 4 times finer dW) and hardly depends on the springs
# (1001 vs 16001 at nq = 100: <= 2.5e-5). The test runs 1001 springs at nq = 25 and 100 and extrapolates the same way;
# that misses the reference by the second-order remainder, measured -7.3e-5 / -8.8e-5 / -1.0e-4 (it falls 9-18x per
# 4x finer dW: about second order), plus the spring effect <= 2.5e-5 and the reference's own 1e-5: 1.35e-4,
# rounded up to RATIO_TOL = 2e-4 (4e-5 relative). Extrapolating a first-order error as if it were second order
# would be off by 3e-3 ... 6e-3, and the single nq = 25 run is off by 0.016-0.032: both fail it.
RATIO_TOL = 2e-4


@pytest.mark.regression
@pytest.mark.parametrize("w, f_t", list(RATCHET_RATIO))
def test_ratcheting_increment_is_the_pure_mdr_one_not_the_seed_regression(w, f_t):
    """docs/theory.md §8.5: pure-MDR increments ~ 4.4-4.6 sqrt(u_stat) (w - w_lim,MDR) per period, far above the seed's
    regression fit (Eq. 21). The first is checked against the converged reference above, to RATIO_TOL."""
    scale = math.sqrt(L.u_stat(f_t)) * (w - L.w_lim(f_t, L.KAPPA_MDR))
    ratio = {}
    for nq in (25, 100):
        r = run(f_t, w, nq=nq, n_springs=1001)
        assert r.state == "ratcheting"
        ratio[nq] = r.classification.du / scale
    extrapolated = ratio[100] + (ratio[100] - ratio[25]) / 3            # first order in dW, 4x refinement
    assert abs(extrapolated - RATCHET_RATIO[(w, f_t)]) < RATIO_TOL, (ratio, extrapolated)
    # the finding, not a tolerance: the converged increment is 7.9-9.9 times the seed's regression (perpendicular,
    # the larger of its two); asserted with the factor rounded down to one digit
    assert extrapolated * scale > 7 * L.ratcheting_increment(f_t, w, "perpendicular")


def test_gross_sliding_is_recorded_not_raised():
    r = run(1.01, 0.2, n_springs=401)
    assert r.state == "gross_sliding" and "mu Fn" in r.classification.message
    # at exactly f_t = 1 the springs' capacity mu Fn is reached, not exceeded: everything slides, U walks
    assert run(1.0, 0.2, n_springs=401).state == "ratcheting"


# ------------------------------------------------------------------------------------ bookkeeping
def test_triangle_wave_hits_the_reversal_points_exactly():
    W = 1.0
    r = simulate_mdr(**SCENE, Ft=0.3 * MU_FN, W=W, dW=0.3, periods=2, n_springs=401, ramp_steps=3)
    nq = math.ceil(W / 0.3)
    assert r.dW_used == pytest.approx(W / nq, rel=1e-15)
    h = r.history
    assert len(h["U"]) == 1 + 3 + 2 * 4 * nq
    assert np.array_equal(h["period"], np.r_[np.zeros(4, int), np.repeat([1, 2], 4 * nq)])
    centre = h["W"][4:4 * nq + 4]
    assert centre.max() == pytest.approx(W, abs=1e-15) and centre.min() == pytest.approx(-W, abs=1e-15)
    assert centre[-1] == 0.0 and h["W"][-1] == 0.0
    assert np.allclose(h["Ft"][1:4], 0.3 * MU_FN * np.array([1, 2, 3]) / 3)
    assert np.allclose(r.U_period_end, h["U"][[3, 3 + 4 * nq, 3 + 8 * nq]])


def test_compiled_kernels_agree_with_the_numpy_reference():
    rng = np.random.default_rng(7)
    for _ in range(200):
        m = int(rng.integers(1, 60))
        v = rng.normal(0, 1, m)
        b = rng.uniform(0.01, 1, m)
        target = rng.uniform(-0.99, 0.99) * b.sum()
        U_ref = rigid_shift(v, b, target)
        U_nb, status = _rigid_shift_kernel(v, b, target, rng.normal())
        assert status == 0 and U_nb == pytest.approx(U_ref, abs=1e-12)
        assert np.clip(U_nb - v, -b, b).sum() == pytest.approx(target, abs=1e-12)
    s = np.linspace(-6, 6, 2001)
    for centre in (0.0, 0.37, -1.1):
        gap = (s - centre) ** 2 / 40.0
        d_ref = approach_for_force(gap, 21.19, PAIR.E_star, s[1] - s[0])
        d_nb, _ = _approach_kernel(gap, 21.19 / (PAIR.E_star * (s[1] - s[0])), 0.5)
        assert d_nb == pytest.approx(d_ref, rel=1e-13)


@pytest.mark.parametrize("kw, name", [
    (dict(W=5.0), "W"), (dict(Ft=-1.0), "Ft"), (dict(dW=0.0), "dW"), (dict(periods=1.5), "periods"),
    (dict(mu=0.0), "mu"), (dict(ds=0.01, n_springs=101), "either ds or n_springs"),
])
def test_bad_input_is_refused_with_the_parameter_named(kw, name):
    args = dict(SCENE, Ft=1.0, W=0.5, dW=0.1, periods=1, n_springs=101)
    args.update(kw)
    with pytest.raises(InputError, match=name):
        simulate_mdr(**args)
