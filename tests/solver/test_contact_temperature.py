"""Contact temperatures (solver.friction.thermal; docs/friction.md, "Temperatures"): the frictional heat split so that
the two surfaces have one temperature in the contact; heat balance against the power of the creep forces; Blok's
high-speed partition; two bodies at different bulk temperatures in perfect thermal contact."""
import math

import numpy as np
import pytest

from rollcontact.bem import MaterialPair
from rollcontact.bem.heat import ThermalBody
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure, kalker_coefficients,
                                      saturation_creepage)
from rollcontact.solver.friction import ContactTemperature, FrictionLaw, LocalFriction, solve_steady_friction

A, B, FN, NU, V, MU = 6.0, 4.0, 50e3, 0.28, 30000.0, 0.3
PAIR = MaterialPair.from_moduli(210e3, NU, 210e3, NU)
STEEL = ThermalBody.from_si(50.0, 7850.0, 450.0)
BRONZE = ThermalBody.from_si(120.0, 8800.0, 380.0)     # about 2.7 times steel's conductivity, 1.6 its effusivity


@pytest.fixture(scope="module")
def ellipse():
    grid = ellipse_grid(A, B, 31)
    return SteadyRolling(grid, PAIR), hertz_pressure(grid, A, B, FN)


def full_sliding(problem, pressure, thermal, factor=6.0):
    c = math.sqrt(A * B)
    xi = factor * saturation_creepage(PAIR.G, c, kalker_coefficients(A / B, NU)[0], MU, FN)
    friction = LocalFriction(FrictionLaw("coulomb", mu=MU), speed=V, thermal=thermal)
    return xi, solve_steady_friction(problem, pressure, friction, xi, params=SteadyParams(tol=1e-9))


def test_dissimilar_bodies_share_one_contact_temperature_and_all_the_heat(ellipse):
    problem, p = ellipse
    thermal = ContactTemperature(problem.grid, STEEL, BRONZE, V, 20.0, 20.0)
    xi, res = full_sliding(problem, p, thermal)
    temps = res.friction.temperatures
    contact = p > 0
    rise = np.max(temps.T1 - 20.0)
    assert np.max(np.abs(temps.T1 - temps.T2)[contact]) < 1e-8 * rise
    dA = problem.grid.cell_area
    heat_in = float((temps.q1 + temps.q2).sum()) * dA
    assert heat_in == pytest.approx(res.friction.power, rel=1e-12)
    assert np.all(temps.q1[~contact] == 0) and np.all(temps.q2[~contact] == 0)


@pytest.mark.parametrize("factor, bound", [(20.0, 5e-3), (6.0, 1.5e-2)])
def test_heat_into_the_bodies_is_the_power_of_the_creep_force(ellipse, factor, bound):
    """Energy: in steady full sliding the heat entering the two bodies is the power of the creep force on the rolling
    body, -V F_x xi (W), within 0.5 % (the issue's bound) at 20 times the saturation creepage. The rest is the upwind
    difference's own dissipation, -V mu^2 p^T A (I - S) p / dx < 0 (S the shift by one cell; first order in dx / the
    creepage): 1.3 % at 6 times, 0.4 % at 20 times (31 elements across)."""
    problem, p = ellipse
    thermal = ContactTemperature(problem.grid, STEEL, BRONZE, V, 20.0, 20.0)
    xi, res = full_sliding(problem, p, thermal, factor)
    temps = res.friction.temperatures
    heat_in = float((temps.q1 + temps.q2).sum()) * problem.grid.cell_area
    assert abs(heat_in / (-V * res.force[0] * xi * 1e-3) - 1) < bound


def test_blok_partition_at_high_speed(ellipse):
    """At Peclet numbers in the thousands heat flows into each body by 1-D conduction in depth, and the share of
    body 1 is e1 / (e1 + e2) (e = sqrt(k rho c_p)) in the contact's interior."""
    problem, p = ellipse
    thermal = ContactTemperature(problem.grid, STEEL, BRONZE, V, 20.0, 20.0)
    _, res = full_sliding(problem, p, thermal)
    temps = res.friction.temperatures
    share = STEEL.effusivity / (STEEL.effusivity + BRONZE.effusivity)
    inner = hertz_pressure(problem.grid, A, B, FN) > 0.6 * p.max()
    assert np.sum(temps.q1[inner]) / np.sum(temps.q1[inner] + temps.q2[inner]) == pytest.approx(share, rel=0.03)


def test_bodies_at_different_bulk_temperatures_meet_at_their_effusivity_weighted_mean(ellipse):
    """Without friction heat still flows from the hotter body to the colder one in the contact: at high speed the
    contact temperature is (e1 T1 + e2 T2) / (e1 + e2), the classical one of two half-spaces put in contact."""
    problem, p = ellipse
    thermal = ContactTemperature(problem.grid, STEEL, BRONZE, V, 0.0, 150.0)
    temps = thermal.solve(np.zeros(problem.grid.shape), p > 0)
    e1, e2 = STEEL.effusivity, BRONZE.effusivity
    inner = p > 0.5 * p.max()
    assert temps.T1[inner] == pytest.approx((e1 * 0.0 + e2 * 150.0) / (e1 + e2), rel=0.03)
    assert np.max(np.abs(temps.T1 - temps.T2)[p > 0]) < 1e-8 * 150.0
    assert temps.power == 0.0 and float(np.sum(temps.q1 + temps.q2)) == pytest.approx(0.0, abs=1e-9)


def test_temperature_law_is_consistent_with_the_contact_temperature_it_heats(ellipse):
    """mu = mu(T) with T the contact temperature of the frictional heat that mu itself produces: in steady full
    sliding the converged coefficient is the law's at the computed temperature everywhere in the contact, and the
    hotter rear of the contact has the lower coefficient."""
    problem, p = ellipse
    thermal = ContactTemperature(problem.grid, STEEL, STEEL, V, 20.0, 20.0)
    law = FrictionLaw("temperature", mu_ref=0.3, T_ref=22.0, dmu_heat=-0.15, dT_heat=80.0)
    c = math.sqrt(A * B)
    xi = 6.0 * saturation_creepage(PAIR.G, c, kalker_coefficients(A / B, NU)[0], 0.3, FN)
    friction = LocalFriction(law, speed=V, thermal=thermal)
    res = solve_steady_friction(problem, p, friction, xi, params=SteadyParams(tol=1e-9))
    temps, mu, contact = res.friction.temperatures, res.friction.mu, p > 0
    assert 22.0 < temps.T1.max() < 102.0                                 # on the law's ramp
    weight = p / p.max()
    assert np.max(np.abs(mu - law.of_temperature(temps.T1)) * weight) < 1e-8 * 0.3
    row = problem.grid.ny // 2
    inside = np.nonzero(contact[row])[0]
    assert mu[row, inside[0]] < mu[row, inside[-1]]                      # trailing (hot) below leading (cold)
    assert not res.stick.any()                                           # full sliding: |F| = sum mu p dA
    assert math.hypot(*res.force) == pytest.approx(float(np.sum(mu * p)) * problem.grid.cell_area, rel=1e-3)
