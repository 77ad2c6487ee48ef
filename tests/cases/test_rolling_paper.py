"""The seed paper's oscillating-rolling scenes at the paper's resolution (dx = dW-ish 0.2 mm, 10 periods).

Physics checked: shakedown below / ratcheting above the limit in both settings (seed Fig. 4), the perpendicular
setting giving the larger u_sd and du, the three regions of seed Sect. 3.2, the Coulomb bound, and the static limit
w = 0 (Cattaneo-Mindlin).
Regression tests (-m regression; the reference values in tests/reference_data.py): u_sd against seed Eq. 13 with
the kappa the 3-D model converges to (within the paper grid's discretisation error), how that kappa departs from
the seed's rounded fits (a finding), and the periods to shakedown.
Slow (-m slow): a dx = 0.1 mm run of the kind the reference kappa and the discretisation error come from (all six
with ROLLCONTACT_ALL_REFERENCES=1, ~3-5 min).
"""
import os

import numpy as np
import pytest

from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.mdr.limits import KAPPA_PARALLEL, KAPPA_PERPENDICULAR, fit_kappa, u_shakedown

from reference_data import FIG4_PERIODS_TO_SHAKEDOWN, KAPPA_3D

SETTINGS = {"parallel": 0.0, "perpendicular": 90.0}


def paper_run(tmp_path_factory, setting, f_t, *extra):
    scene = default_scene().with_overrides([f"motion.angle={SETTINGS[setting]}", f"load.ft={f_t}", *extra])
    path = tmp_path_factory.mktemp("rolling") / f"{setting}_{f_t}.h5"
    return run_scene(scene, path)


@pytest.fixture(scope="module")
def fig4(tmp_path_factory):
    return {(s, f): paper_run(tmp_path_factory, s, f) for s in SETTINGS for f in (0.46, 0.77)}


def test_fig4_shakedown_at_046_and_ratcheting_at_077_in_both_settings(fig4):
    for setting in SETTINGS:
        low, high = fig4[(setting, 0.46)].summary, fig4[(setting, 0.77)].summary
        assert low["state"] == "shakedown", setting
        assert high["state"] == "ratcheting", setting
        # a clear, settled increment, not a tolerance on du: measured du = 0.1030 / 0.1473 (parallel /
        # perpendicular; dx = 0.4 gives 0.1028 / 0.1466), asserted above half the smaller, 500 x shakedown_tol
        assert high["du"] > 0.05


@pytest.mark.regression
def test_fig4_runs_shake_down_within_two_periods_of_the_reference_count(fig4):
    """A regression cap, not a derived bound: the reference counts (6 parallel / 5 perpendicular, the same at
    dx = dW = 0.4) plus 2, i.e. it fails once the per-period decay of the increments slows by a quarter
    (n ~ 1/|ln q|); the seed's experiments settle after ~10 periods."""
    for setting in SETTINGS:
        assert fig4[(setting, 0.46)].summary["periods_to_shakedown"] <= FIG4_PERIODS_TO_SHAKEDOWN[setting] + 2


def test_fig4_perpendicular_has_larger_shakedown_displacement_and_larger_ratchet(fig4):
    assert fig4[("perpendicular", 0.46)].summary["u_sd"] > fig4[("parallel", 0.46)].summary["u_sd"]
    assert fig4[("perpendicular", 0.77)].summary["du"] > fig4[("parallel", 0.77)].summary["du"]


def test_static_phase_reproduces_cattaneo_mindlin(fig4):
    # after the loading phase (w not yet applied) U = U_stat of seed Eq. 4 within 1 % (docs/theory.md P10: nu = 0.5)
    s = fig4[("parallel", 0.46)].summary
    scene = default_scene()
    pair = scene.material_pair
    cm = CattaneoMindlin(HertzSphere(40.0, pair.E_star, 21.19), 0.93, pair.G_star)
    assert s["U_stat"] == pytest.approx(cm.shift(0.46), rel=0.01)


def test_shakedown_state_is_all_stick_with_the_three_regions_of_sect_3_2(fig4):
    d = fig4[("perpendicular", 0.46)]
    mu, U0, p0 = 0.93, d.summary["U0"], d.summary["p0"]
    last_period = d.history["period"][d.field_steps] == d.history["period"].max()
    p, tau = d.fields["p"], np.hypot(d.fields["tau_x"], d.fields["tau_y"])
    # Coulomb bound at every stored step (the solver enforces |tau| <= g to round-off)
    assert np.all(tau <= mu * p * (1 + 1e-9) + 1e-15)
    # no slip during the last period: shakedown means the whole contact sticks. Checked on the displacements, not
    # only on the stored slip (zero in stick by construction): an element in contact at every stored step of the
    # period keeps u - U (the slip of a rolling rigid sphere is the change of u - U), to 1e-5 U0 (measured
    # 5.5e-8; the ratcheting run at f_t = 0.77 moves it by 0.15 U0)
    steps = d.field_steps[last_period]
    held = np.all(p[last_period] > 0, axis=0)
    assert held.sum() > 100
    for comp in ("x", "y"):
        rel = d.fields[f"u_{comp}"][last_period] - d.history[f"U_{comp}"][steps][:, None, None]
        assert np.abs(rel[:, held] - rel[0, held]).max() < 1e-5 * U0, comp
    slip = np.hypot(d.fields["slip_x"], d.fields["slip_y"])[last_period]
    assert slip.max() < 1e-5 * U0
    # the minimum pressure over a cycle is met at the reversal points, which are stored
    p_min = p[last_period].min(axis=0)
    final_p, final_tau, u_x = p[-1], tau[-1], d.fields["u_x"][-1]
    contact = final_p > 0
    U = d.history["U_x"][-1]
    stick = contact & (np.abs(u_x - U) < 1e-3 * U0)                      # (I) u_x = U_sd
    at_min_bound = contact & ~stick & (p_min > 0) & (np.abs(final_tau - mu * p_min) < 0.02 * mu * p0)  # (II)
    released = contact & (p_min == 0)                                      # (III)
    jc, ic = np.argmin(np.abs(np.asarray(d.y))), np.argmin(np.abs(np.asarray(d.x)))
    assert stick[jc, ic], "the stick zone contains the centre"
    assert stick.sum() > 100 and at_min_bound.sum() > 100 and released.sum() > 100
    assert final_tau[released].max() < 1e-3 * mu * p0  # traction vanishes where contact was released
    # spindle: the stick zone is longer across the rolling direction (x) than along it (y)
    X, Y = np.meshgrid(d.x, d.y)
    assert np.ptp(X[stick]) > np.ptp(Y[stick])


# u_sd against seed Eq. 13 with the kappa of the 3-D model itself, w = 0.23 (setting, f_t as the seed's Fig. 8).
#
# Reference: the kappa that puts Eq. 13 through the converged u_sd, i.e. u_sd of the same scenes at half the
# paper's spacing (dx = dy = dW = 0.1 mm, margin 0.6, 10 periods; 20 at f_t = 0.6, where the increments shrink
# only by a factor 0.6 per period, docs/theory.md P12), kappa = (1 - f_t - (1 - u_sd)^(3/2)) / (w u_sd) = fit_kappa of one point.
# The reference values are regression data (tests/reference_data.py, kappa_3d_fig8: `paper_run(...,
# "grid.dx=0.1", "motion.dW=0.1", f"motion.periods={periods}")`, as test_reference_kappa_is_the_converged_one
# below; 18-34 s per run). u_sd at dx = dW = 0.4 / 0.2 / 0.1 mm:
#   setting        f_t  dx 0.4     dx 0.2     dx 0.1     change 0.2->0.1  kappa (dx 0.1)  Eq. 13, seed kappa
#   parallel       0.2  0.1640171  0.1640507  0.1640705  -2.0e-5          0.946480        0.16584 (kappa 1)
#   parallel       0.4  0.3548177  0.3547999  0.3548408  -4.1e-5          1.002243        0.35465
#   parallel       0.6  0.6112542  0.6118231  0.6119271  -1.04e-4         1.124374        0.58758
#   perpendicular  0.2  0.1700415  0.1700807  0.1701135  -3.3e-5          1.124292        0.16926 (kappa 1.1)
#   perpendicular  0.4  0.3682555  0.3681619  0.3682109  -4.9e-5          1.155073        0.36326
#   perpendicular  0.6  0.6355474  0.6360685  0.6361560  -8.8e-5          1.233845        0.60691
# Truncation: after period 20 at f_t = 0.6 the remaining geometric tail is < 5e-6 (parallel, dx 0.1); at f_t <= 0.4
# periods 10 and 20 agree to 1e-6. The solver tolerance (1e-8) moves u_sd by < 3e-6 (benchmarks/README.md, "Accuracy
# against speed" (c)).
#
# Tolerance: the paper grid's discretisation error. The largest change of u_sd when dx = dW is halved from 0.2
# to 0.1 mm is D = 1.04e-4 (parallel, f_t = 0.6), rounded up: D_MAX = 1.1e-4. For a convergence order p >= 1 the
# error of the 0.2 mm grid against dx -> 0 is at most twice that change (e(0.2) = D / (1 - 2^-p) <= 2 D), and the
# reference (dx 0.1, error <= D) lies within the same 2 D of u_sd(0.2): USD_TOL = 2 D_MAX = 2.2e-4, one value for
# the six points. Checked at dx = dW = 0.05 mm (170-490 s per run): u_sd = 0.1640690 / 0.3548373 /
# 0.6119458 (parallel), 0.1701096 / 0.3682056 / 0.6361649 (perpendicular). At f_t = 0.6 the sequence converges with
# order 2.5 (parallel) / 2.6-3.3 (perpendicular), extrapolating to 0.611950 / 0.636166; at f_t <= 0.4 the changes
# are 1e-5...9e-5 and not monotone (stick-slip boundaries crossing cells), the 0.1 and 0.05 mm values agreeing to
# 5.3e-6. So the paper grid's actual error is <= 1.27e-4 (parallel, f_t = 0.6) and the references' <= 2.3e-5,
# inside 2 D_MAX. Truncation and solver tolerance (< 1e-5) are inside it too. In kappa, USD_TOL is +-0.0067 /
# 0.0026 / 0.0011 (parallel) and +-0.0062 / 0.0024 / 0.0009 (perpendicular) at f_t = 0.2 / 0.4 / 0.6 (dkappa/du_sd
# = 31 / 12 / 4.8 and 28 / 11 / 4.2): the test pins the 3-D kappa to 1e-3...7e-3; the seed's rounded values are
# off by 0.002-0.134.
# test_reference_kappa_is_the_converged_one (slow) re-derives both: the references and D < D_MAX.
#
# Finding (not a tolerance; test_3d_kappa_differs_from_the_seed_fit): the 3-D kappa is not one number per setting.
# At w = 0.23 it rises with f_t, parallel 0.946 / 1.002 / 1.124, perpendicular 1.124 / 1.155 / 1.234 at f_t = 0.2 /
# 0.4 / 0.6 (over the whole Fig. 8 grid, fit_kappa gives 1.028 +- 0.012 and 1.191 +- 0.009: benchmarks/README.md,
# "Sweeps"). The seed's kappa_par = 1 holds at f_t = 0.4 (1.002 +- 0.003), not at 0.2 (8 uncertainties below) or
# 0.6 (118 above); kappa_perp lies above the seed's 1.1 at every f_t, by 0.024 / 0.055 / 0.134 (4 / 23 / 143
# uncertainties). The converged u_sd lies -1.07 / +0.05 / +4.1 % (parallel) and +0.50 / +1.36 / +4.8 %
# (perpendicular) off Eq. 13 with the seed's kappa at f_t = 0.2 / 0.4 / 0.6.
D_MAX = 1.1e-4
USD_TOL = 2 * D_MAX
W_FIG8 = 0.23
FT_FIG8 = (0.2, 0.4, 0.6)


def usd_periods(f_t):
    return 20 if f_t == 0.6 else 10  # near the limit the decay is slow (docs/theory.md P12)


def usd_run(tmp_path_factory, setting, f_t, *extra):
    return paper_run(tmp_path_factory, setting, f_t, f"motion.periods={usd_periods(f_t)}", 'output.fields="none"',
                     *extra).summary


def kappa_of(f_t, u_sd):
    """The kappa of seed Eq. 13 through one shaken-down point (w = 0.23), and its uncertainty for USD_TOL in u_sd."""
    kappa = fit_kappa(f_t, W_FIG8, u_sd).kappa
    slope = (1.5 * (1 - u_sd) ** 0.5 - kappa * W_FIG8) / (W_FIG8 * u_sd)      # dkappa / du_sd along Eq. 13
    return kappa, USD_TOL * slope


@pytest.fixture(scope="module")
def fig8(tmp_path_factory):
    """The six paper-grid runs (dx = dW = 0.2 mm), ~15 s together."""
    return {(s, f): usd_run(tmp_path_factory, s, f) for s in SETTINGS for f in FT_FIG8}


@pytest.mark.regression
@pytest.mark.parametrize("setting", list(SETTINGS))
@pytest.mark.parametrize("f_t", FT_FIG8)
def test_shakedown_displacement_follows_eq_13_with_the_converged_3d_kappa(fig8, setting, f_t):
    s = fig8[(setting, f_t)]
    assert s["state"] == "shakedown"
    expected = u_shakedown(f_t, W_FIG8, KAPPA_3D[(setting, f_t)])      # = u_sd at dx = 0.1 mm, to 1.1e-7
    assert abs(s["u_sd"] - expected) < USD_TOL, (s["u_sd"], expected, fit_kappa(f_t, W_FIG8, s["u_sd"]).kappa)
    assert s["u_sd"] > s["u_stat"]  # rolling always adds displacement (seed Fig. 8)


@pytest.mark.regression
def test_3d_kappa_differs_from_the_seed_fit(fig8):
    """The finding stated above, each part by more than the kappa uncertainty USD_TOL implies at that point."""
    k = {key: kappa_of(key[1], s["u_sd"]) for key, s in fig8.items()}
    for setting in SETTINGS:
        for lo, hi in zip(FT_FIG8, FT_FIG8[1:]):                       # kappa rises with f_t
            (k_lo, e_lo), (k_hi, e_hi) = k[(setting, lo)], k[(setting, hi)]
            assert k_hi - k_lo > e_lo + e_hi, (setting, lo, hi, k_lo, k_hi)
    for f_t in FT_FIG8:
        kp, ep = k[("perpendicular", f_t)]
        kq, eq = k[("parallel", f_t)]
        assert kp - KAPPA_PERPENDICULAR > ep, (f_t, kp)                  # above the seed's 1.1 everywhere
        assert kp - kq > ep + eq, (f_t, kp, kq)                           # perpendicular above parallel
    (k2, e2), (k6, e6) = k[("parallel", 0.2)], k[("parallel", 0.6)]
    assert k2 < KAPPA_PARALLEL - e2 and k6 > KAPPA_PARALLEL + e6        # the seed's 1 only in between


#: the references re-derived by the suite: the cheapest point (10 s); ROLLCONTACT_ALL_REFERENCES=1 derives all six
#: (another 2-4 min), as tests/reference_data.py does
REFERENCE_POINTS = ([(f, s) for f in FT_FIG8 for s in SETTINGS] if os.environ.get("ROLLCONTACT_ALL_REFERENCES")
                    else [(0.2, "perpendicular")])


@pytest.mark.slow
@pytest.mark.regression
@pytest.mark.parametrize("f_t, setting", REFERENCE_POINTS)
def test_reference_kappa_is_the_converged_one(fig8, tmp_path_factory, setting, f_t):
    """Where KAPPA_3D and D_MAX come from: the scenes at dx = dy = dW = 0.1 mm (10-30 s each). u_sd reproduces the
    reference to 1e-5 (the solver tolerance moves u_sd by < 3e-6, rounding kappa to 6 digits by < 1.1e-7), and
    differs from the paper grid's by less than D_MAX (measured <= 1.04e-4), the premise of USD_TOL."""
    s = usd_run(tmp_path_factory, setting, f_t, "grid.dx=0.1", "motion.dW=0.1")
    assert s["state"] == "shakedown"
    assert abs(s["u_sd"] - u_shakedown(f_t, W_FIG8, KAPPA_3D[(setting, f_t)])) < 1e-5, s["u_sd"]
    assert abs(s["u_sd"] - fig8[(setting, f_t)]["u_sd"]) < D_MAX, (s["u_sd"], fig8[(setting, f_t)]["u_sd"])
