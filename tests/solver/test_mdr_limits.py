"""Closed forms of the MDR shakedown theory (seed Eqs. 4-5, 12-21; docs/theory.md §8.3-8.5)."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.mdr import limits as L

W_VALUES = (0.05, 0.1, 0.23, 0.4, 0.7)
KAPPAS = (L.KAPPA_PARALLEL, L.KAPPA_PERPENDICULAR, 1.3, L.KAPPA_MDR)


def test_static_shift_and_stick_radius_are_mindlin():
    # seed Eqs. 4-5: u_stat = 1 - (1 - f_t)^(2/3), c/a = (1 - f_t)^(1/3); hence u_stat = 1 - (c/a)^2
    f = np.linspace(0.0, 1.0, 11)
    assert np.allclose(L.u_stat(f), 1.0 - L.stick_ratio_static(f) ** 2, atol=1e-15)
    assert L.u_stat(0.0) == 0.0 and L.u_stat(1.0) == 1.0
    assert L.stick_ratio_static(0.5) == pytest.approx(0.5 ** (1 / 3), abs=1e-15)


@pytest.mark.parametrize("kappa", KAPPAS)
@pytest.mark.parametrize("w", W_VALUES)
def test_shakedown_displacement_round_trip_u_to_ft_to_u(w, kappa):
    # Eq. 13 is strictly increasing in u on [0, 1 - w^2] for kappa <= 3/2: the inverse is unique.
    # Points kept 5 % away from u_lim, where the slope (3/2 - kappa) w is not small for kappa = 3/2.
    for u in np.linspace(0.0, 0.95 * L.u_lim(w), 9):
        f = L.f_t_equilibrium(u, w, kappa)
        assert L.u_shakedown(f, w, kappa) == pytest.approx(u, abs=1e-10)


@pytest.mark.parametrize("kappa", KAPPAS)
def test_limit_round_trip_w_lim_and_ft_lim(kappa):
    for w in np.linspace(0.0, 1.0, 21):
        assert L.w_lim(L.f_t_lim(w, kappa), kappa) == pytest.approx(w, abs=1e-10)
    for f in np.linspace(0.0, 1.0, 21):
        assert L.f_t_lim(L.w_lim(f, kappa), kappa) == pytest.approx(f, abs=1e-10)


@pytest.mark.parametrize("kappa", KAPPAS)
@pytest.mark.parametrize("w", W_VALUES)
def test_limit_is_equilibrium_at_vanishing_stick_band(w, kappa):
    # f_t,lim(w) = Eq. 13 evaluated at u_lim = 1 - w^2 (seed Eq. 17), and u_sd(f_t,lim) = u_lim
    assert L.f_t_lim(w, kappa) == pytest.approx(L.f_t_equilibrium(L.u_lim(w), w, kappa), abs=1e-14)
    assert L.u_shakedown(L.f_t_lim(w, kappa), w, kappa) == pytest.approx(L.u_lim(w), abs=1e-12)


def test_parallel_kappa_gives_seed_eq18_exactly():
    for w in np.linspace(0.0, 1.0, 11):
        assert L.f_t_lim(w, L.KAPPA_PARALLEL) == 1.0 - w      # exact: (kappa - 1) w^3 = 0
    for f in np.linspace(0.0, 1.0, 11):
        assert L.w_lim(f, L.KAPPA_PARALLEL) == pytest.approx(1.0 - f, abs=1e-12)


def test_perpendicular_kappa_gives_seed_eq19():
    for w in np.linspace(0.0, 1.0, 11):
        assert L.f_t_lim(w, L.KAPPA_PERPENDICULAR) == pytest.approx(1.0 - 1.1 * w + 0.1 * w ** 3, abs=1e-15)


def test_pure_mdr_kappa_is_seed_eq12():
    assert L.KAPPA_MDR == 1.5
    w, u = 0.23, 0.5
    assert L.f_t_equilibrium(u, w) == pytest.approx(1 - 1.5 * w * u - (1 - u) ** 1.5, abs=1e-15)


def test_without_oscillation_shakedown_is_static_mindlin():
    for f in (0.1, 0.46, 0.9):
        for k in KAPPAS:
            assert L.u_shakedown(f, 0.0, k) == pytest.approx(L.u_stat(f), abs=1e-12)


def test_oscillation_raises_the_displacement_and_perpendicular_exceeds_parallel():
    # seed Fig. 8: u_sd > u_stat, and larger for kappa_perp = 1.1 than for kappa_par = 1
    f, w = 0.46, 0.23
    u_par, u_perp, u_mdr = (L.u_shakedown(f, w, k) for k in (1.0, 1.1, 1.5))
    assert L.u_stat(f) < u_par < u_perp < u_mdr < L.u_lim(w)


def test_beyond_the_limit_no_shakedown_error_names_parameters():
    with pytest.raises(L.NoShakedownError, match=r"f_t, w.*beyond the shakedown limit.*kappa"):
        L.u_shakedown(0.8, 0.23, L.KAPPA_PARALLEL)   # f_t,lim = 0.77
    assert issubclass(L.NoShakedownError, InputError)


@pytest.mark.parametrize("call, name", [
    (lambda: L.u_stat(1.2), "f_t"), (lambda: L.u_stat(-0.1), "f_t"), (lambda: L.u_stat(math.nan), "f_t"),
    (lambda: L.u_lim(1.5), "w"), (lambda: L.f_t_lim(-0.2), "w"), (lambda: L.w_lim(2.0), "f_t"),
    (lambda: L.f_t_lim(0.2, kappa=0.0), "kappa"), (lambda: L.f_t_lim(0.2, kappa=-1.0), "kappa"),
    (lambda: L.f_t_lim(0.2, kappa=1.6), "kappa"), (lambda: L.u_shakedown(0.5, 0.2, math.inf), "kappa"),
    (lambda: L.f_t_equilibrium(1.1, 0.2), "u_sd"), (lambda: L.f_t_equilibrium(0.99, 0.2), "u_sd"),
    (lambda: L.kappa_for_angle(200.0), "angle"), (lambda: L.ratcheting_increment(0.5, 0.5, "diagonal"), "setting"),
])
def test_out_of_range_input_is_refused_with_the_parameter_named(call, name):
    with pytest.raises(InputError, match=rf"{name} = .*(allowed|must|applies)"):
        call()


def test_kappa_for_angle_interpolates_in_sin_squared():
    assert L.kappa_for_angle(0.0) == L.KAPPA_PARALLEL
    assert L.kappa_for_angle(90.0) == pytest.approx(L.KAPPA_PERPENDICULAR, abs=1e-15)
    assert L.kappa_for_angle(180.0) == pytest.approx(L.KAPPA_PARALLEL, abs=1e-15)
    assert L.kappa_for_angle(45.0) == pytest.approx(1.05, abs=1e-15)


def test_fit_kappa_recovers_kappa_from_exact_points():
    f = np.array([0.2, 0.4, 0.3, 0.5])
    w = np.array([0.1, 0.23, 0.3, 0.2])
    u = np.array([L.u_shakedown(fi, wi, 1.1) for fi, wi in zip(f, w)])
    fit = L.fit_kappa(f, w, u)
    assert fit.kappa == pytest.approx(1.1, abs=1e-10) and fit.n == 4 and fit.stderr < 1e-9


def test_fit_kappa_uncertainty_reflects_noise():
    rng = np.random.default_rng(1)
    f = np.linspace(0.2, 0.6, 12)
    w = np.full(12, 0.23)
    u = np.array([L.u_shakedown(fi, 0.23, 1.1) for fi in f]) + rng.normal(0, 2e-3, 12)
    fit = L.fit_kappa(f, w, u)
    assert 1e-3 < fit.stderr < 0.1
    assert abs(fit.kappa - 1.1) < 4 * fit.stderr
    single = L.fit_kappa(0.46, 0.23, L.u_shakedown(0.46, 0.23, 1.0))
    assert single.kappa == pytest.approx(1.0, abs=1e-10) and single.stderr is None
    with pytest.raises(InputError, match="w \\* u_sd = 0"):
        L.fit_kappa([0.3], [0.0], [0.2])


def test_seed_ratcheting_regression_grows_with_load_and_amplitude():
    # seed Eqs. 20-21 (empirical fits, docs/theory.md §8.5): qualitative checks only
    assert L.ratcheting_increment(0.3, 0.5, "parallel") == 0.0          # w_lim(0.3) = 0.7 (Eq. 18)
    f, w = 0.77, 0.35
    par, perp = L.ratcheting_increment(f, w, "parallel"), L.ratcheting_increment(f, w, "perpendicular")
    assert 0.0 < par < perp
    assert perp == pytest.approx(math.sqrt(5 * L.u_stat(f)) * (w - L.w_lim(f, 1.1)), rel=1e-12)
    assert L.ratcheting_increment(0.8, w, "perpendicular") > perp
    assert L.ratcheting_increment(f, 0.45, "perpendicular") > perp
