"""Steady rolling with a slip-velocity law (solver.friction.steady; docs/friction.md, "Validation"): the falling creep
curve of the exponential law on a Hertzian ellipse (steel on steel, a = 6 mm along the rolling direction, b = 4 mm,
Fn = 50 kN, 31 elements across, V = 30 m/s): linear in the creepage with Kalker's coefficient at small creepage, a
peak, then falling to mu_kin Fn in full sliding; Coulomb's law through the same path is solve_steady's answer."""
import math

import numpy as np
import pytest

from rollcontact.bem import MaterialPair
from rollcontact.bem.errors import ConvergenceError
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure, kalker_coefficients,
                                      saturation_creepage, solve_steady)
from rollcontact.solver.friction import (FrictionLaw, FrictionMemory, FrictionParams, LocalFriction,
                                         solve_steady_friction)

A, B, FN, NU, V = 6.0, 4.0, 50e3, 0.28, 30000.0
PAIR = MaterialPair.from_moduli(210e3, NU, 210e3, NU)
LAW = FrictionLaw("exponential", mu_kin=0.15, mu_1=0.15, s_1=100.0)
PARAMS = SteadyParams(tol=1e-8)


@pytest.fixture(scope="module")
def ellipse():
    grid = ellipse_grid(A, B, 31)
    return SteadyRolling(grid, PAIR), hertz_pressure(grid, A, B, FN)


def xi_star():
    """CONTACT's normalising creepage at the static coefficient: mu_static Fn / (G c^2 C11)."""
    c = math.sqrt(A * B)
    return saturation_creepage(PAIR.G, c, kalker_coefficients(A / B, NU)[0], LAW.mu_static, FN)


def test_falling_creep_curve_rises_linearly_peaks_and_falls_to_mu_kin_fn(ellipse):
    problem, p = ellipse
    fn = float(p.sum()) * problem.grid.cell_area
    friction = LocalFriction(LAW, speed=V, params=FrictionParams(tol=1e-8))
    fractions = np.array([0.02, 0.04, 0.5, 1.0, 1.7, 3.0, 12.0, 40.0])
    force, traction, mu = [], None, None
    for f in fractions:
        res = solve_steady_friction(problem, p, friction, f * xi_star(), initial=traction, mu_initial=mu, params=PARAMS)
        traction, mu = res.traction, res.friction.mu
        force.append(-res.force[0])
    force = np.array(force)
    # linear range: the slope of Kalker's linear theory (within the grid's own error at 31 elements, as Coulomb's)
    for f, F in zip(fractions[:2], force[:2]):       # nearly all stick: Coulomb's at mu_static
        assert F == pytest.approx(-solve_steady(problem, p, LAW.mu_static, f * xi_star(), params=PARAMS).force[0],
                                  rel=2e-3)
    linear = PAIR.G * A * B * kalker_coefficients(A / B, NU)[0] * 0.02 * xi_star()
    assert force[0] == pytest.approx(linear, rel=0.03)
    # a peak inside the range, below mu_static Fn and above mu_kin Fn
    k = int(np.argmax(force))
    assert 0 < k < len(force) - 1
    assert LAW.mu_kin * fn < force[k] < LAW.mu_static * fn
    assert np.all(np.diff(force[:k + 1]) > 0) and np.all(np.diff(force[k:]) < 0)
    # full sliding: every element near the slip velocity V xi, the force mu(V xi) Fn, towards mu_kin Fn
    for f, F in zip(fractions[-2:], force[-2:]):
        assert F == pytest.approx(float(LAW.coefficient(V * f * xi_star())) * fn, rel=5e-3)
    assert force[-1] == pytest.approx(LAW.mu_kin * fn, rel=0.01)


def test_coulomb_law_through_the_friction_path_is_solve_steadys_answer(ellipse):
    problem, p = ellipse
    plain = solve_steady(problem, p, 0.3, 0.7 * xi_star(), 0.2 * xi_star(), params=PARAMS)
    law = solve_steady_friction(problem, p, LocalFriction(FrictionLaw("coulomb", mu=0.3)), 0.7 * xi_star(),
                                0.2 * xi_star(), params=PARAMS)
    assert np.array_equal(plain.traction, law.traction)
    assert np.all(law.friction.mu[p > 0] == 0.3)


def test_memory_raises_the_force_of_partial_slip(ellipse):
    """The material entering the slip zone keeps mu_static over the sliding distance d_c: with memory the slip zone
    carries more than with the instantaneous law, and as d_c -> 0 the memory result tends to it."""
    problem, p = ellipse
    xi = 1.0 * xi_star()
    forces = []
    for d_c in (0.0, 1e-4, 0.01, 0.1):        # mm
        friction = LocalFriction(LAW, FrictionMemory(d_c), speed=V, params=FrictionParams(tol=1e-8))
        forces.append(-solve_steady_friction(problem, p, friction, xi, params=PARAMS).force[0])
    assert forces[1] == pytest.approx(forces[0], rel=2e-3)
    assert forces[0] < forces[2] < forces[3]


def test_a_steady_iteration_that_does_not_converge_says_which_law_and_feedback(ellipse):
    problem, p = ellipse
    steep = FrictionLaw("exponential", mu_kin=0.15, mu_1=0.15, s_1=1.0)
    with pytest.raises(ConvergenceError, match=r"friction law.*feedback"):
        solve_steady_friction(problem, p, LocalFriction(steep, speed=V), xi_star(),
                              params=SteadyParams(tol=1e-8, max_sweeps=5))
