"""The friction laws and the memory equation against their formulas (docs/theory.md §12.1, docs/friction.md)."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.friction import FrictionLaw, FrictionMemory

S = np.array([0.0, 0.3, 1.0, 2.0, 5.0, 17.0, 100.0])


@pytest.mark.parametrize("kind", ["linear", "rational", "exponential"])
def test_velocity_laws_are_their_formulas_with_terms_of_size_mu_i_at_rest(kind):
    law = FrictionLaw(kind, mu_kin=0.2, mu_1=0.3, s_1=2.0, mu_2=0.1, s_2=10.0)
    x1, x2 = S / 2.0, S / 10.0
    expected = {"linear": 0.2 + 0.3 * np.maximum(0, 1 - x1 / 2) + 0.1 * np.maximum(0, 1 - x2 / 2),
                "rational": 0.2 + 0.3 / (1 + x1) + 0.1 / (1 + x2 ** 2),
                "exponential": 0.2 + 0.3 * np.exp(-math.log(2) * x1) + 0.1 * np.exp(-math.log(2) * x2)}[kind]
    assert law.coefficient(S) == pytest.approx(expected, rel=1e-15)
    assert law.mu_static == pytest.approx(0.6) and law.coefficient(0.0) == pytest.approx(0.6)
    assert law.coefficient(1e9) == pytest.approx(0.2, abs=1e-6)      # mu_kin at high slip velocity


def test_terms_are_halved_at_s_i_and_the_linear_ones_end_at_2_s_i():
    for kind in ("rational", "exponential"):
        law = FrictionLaw(kind, mu_kin=0.1, mu_1=0.4, s_1=3.0)
        assert law.coefficient(3.0) == pytest.approx(0.1 + 0.2, rel=1e-14)
    linear = FrictionLaw("linear", mu_kin=0.1, mu_1=0.4, s_1=3.0)
    assert linear.coefficient(3.0) == pytest.approx(0.3) and linear.coefficient([6.0, 9.0]) == pytest.approx([0.1, 0.1])


@pytest.mark.parametrize("kind", ["linear", "rational", "exponential"])
def test_slopes_are_the_derivatives_of_the_laws(kind):
    law = FrictionLaw(kind, mu_kin=0.2, mu_1=0.3, s_1=2.0, mu_2=0.1, s_2=10.0)
    s = np.array([0.1, 0.7, 1.9, 5.0, 13.0, 30.0])       # away from the linear law's kinks at 4 and 20
    h = 1e-6
    numeric = (law.coefficient(s + h) - law.coefficient(s - h)) / (2 * h)
    assert law.slope(s) == pytest.approx(numeric, rel=1e-6, abs=1e-12)
    fine = np.linspace(0, 60, 60001)
    steepest = np.max(np.abs(law.slope(fine)))
    assert steepest * (1 - 1e-9) <= law.steepest_slope() <= 1.05 * steepest       # the sum of the terms' steepest
    one = FrictionLaw(kind, mu_kin=0.2, mu_1=0.3, s_1=2.0)
    assert one.steepest_slope() == pytest.approx(np.max(np.abs(one.slope(fine))), rel=1e-9)


def test_polach_law_is_the_exponential_law_with_one_term():
    """mu_stat ((1 - A) e^(-B s) + A) with mu_kin = A mu_stat, mu_1 = (1 - A) mu_stat, s_1 = ln2 / B."""
    mu_stat, A, B = 0.4, 0.35, 0.6   # B in s/mm
    law = FrictionLaw("exponential", mu_kin=A * mu_stat, mu_1=(1 - A) * mu_stat, s_1=math.log(2) / B)
    assert law.coefficient(S) == pytest.approx(mu_stat * ((1 - A) * np.exp(-B * S) + A), rel=1e-14)


def test_temperature_law_is_piecewise_linear_in_the_surface_temperature():
    law = FrictionLaw("temperature", mu_ref=0.4, T_ref=100.0, dmu_heat=-0.2, dT_heat=300.0)
    T = np.array([-20.0, 100.0, 175.0, 250.0, 400.0, 900.0])
    assert law.of_temperature(T) == pytest.approx([0.4, 0.4, 0.35, 0.3, 0.2, 0.2], rel=1e-14)
    assert law.temperature_slope([50.0, 200.0, 500.0]) == pytest.approx([0.0, -0.2 / 300.0, 0.0])
    assert law.mu_static == 0.4


def test_bad_parameters_are_refused_with_the_key_named():
    with pytest.raises(InputError, match="s_1"):
        FrictionLaw("exponential", mu_kin=0.2, mu_1=0.1)
    with pytest.raises(InputError, match="mu_kin"):
        FrictionLaw("linear", mu_kin=0.0, mu_1=0.1, s_1=1.0)
    with pytest.raises(InputError, match="dmu_heat"):
        FrictionLaw("temperature", mu_ref=0.3, T_ref=0.0, dmu_heat=-0.4, dT_heat=10.0)
    with pytest.raises(InputError, match="distance"):
        FrictionMemory(-1.0)


def test_memory_step_is_the_exact_solution_of_the_relaxation_equation():
    """d mu/dt = -max(s, s0)/d_c (mu - mu_law(s)) at constant s over dt, against a fine Runge-Kutta integration."""
    law = FrictionLaw("exponential", mu_kin=0.2, mu_1=0.3, s_1=2.0)
    memory = FrictionMemory(distance=0.01, s0=0.5)
    mu0, dt = 0.45, 0.004
    for s in (0.0, 0.2, 3.0):
        target, rate = law.coefficient(s), max(s, 0.5) / 0.01
        mu, n = mu0, 4000
        h = dt / n
        f = lambda m: -rate * (m - target)   # noqa: E731
        for _ in range(n):
            k1 = f(mu); k2 = f(mu + h * k1 / 2); k3 = f(mu + h * k2 / 2); k4 = f(mu + h * k3)   # noqa: E702
            mu += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6
        assert memory.step(mu0, target, s, dt) == pytest.approx(mu, rel=1e-12)
    # no memory: the law's value at once
    assert FrictionMemory().step(mu0, 0.33, 5.0, dt) == 0.33


def test_memory_slope_is_the_derivative_of_the_step():
    law = FrictionLaw("rational", mu_kin=0.2, mu_1=0.3, s_1=2.0)
    memory = FrictionMemory(distance=0.02, s0=0.1)
    s, dt, prev, h = np.array([0.5, 2.0, 7.0]), 0.003, 0.47, 1e-6
    step = lambda v: memory.step(prev, law.coefficient(v), v, dt)   # noqa: E731
    numeric = (step(s + h) - step(s - h)) / (2 * h)
    assert memory.step_slope(prev, law.coefficient(s), law.slope(s), s, dt) == pytest.approx(numeric, rel=1e-6)


def test_steady_rows_march_the_memory_along_the_material_path():
    """On the contact-fixed grid the material comes from x + dx: each cell is a step of dx / V from its upstream
    neighbour, starting from mu_static ahead of the grid; at constant slip velocity the coefficient approaches the
    law's over the sliding distance d_c, mu = mu_law + (mu_static - mu_law) exp(-s t / d_c)."""
    law = FrictionLaw("exponential", mu_kin=0.2, mu_1=0.3, s_1=2.0)
    memory = FrictionMemory(distance=0.05)
    nx, dx, V, s = 40, 0.1, 1000.0, 4.0
    vel = np.full((3, nx), s)
    mu, _ = memory.steady_rows(law.coefficient(vel), law.slope(vel), vel, dx, V, law.mu_static)
    travelled = (nx - np.arange(nx)) * dx / V          # time since entering the grid at the leading column
    expected = law.coefficient(s) + (law.mu_static - law.coefficient(s)) * np.exp(-s * travelled / 0.05)
    assert mu[1] == pytest.approx(expected, rel=1e-13)
