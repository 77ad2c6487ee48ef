"""Transient rolling from rest (solver/creep/transient.py) converges to the steady state (solver/creep/steady.py):
the issue's check that the two formulations agree, forces within 0.5 % after several contact lengths. Steel on
steel, a circle a = 1 mm under Fn = 1000 N, mu = 0.3, 21 elements across."""
import math

import numpy as np
import pytest

from rollcontact.bem import HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import InputError
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure, roll_transient,
                                      solve_steady)


@pytest.fixture(scope="module")
def setup():
    mats = MaterialPair.from_moduli(210e3, 0.28, 210e3, 0.28)
    grid = ellipse_grid(1.0, 1.0, 21)
    return HalfSpaceOperator(grid, mats), SteadyRolling(grid, mats), hertz_pressure(grid, 1.0, 1.0, 1000.0)


@pytest.mark.parametrize("creep", [(1e-3, 0.0, 0.0), (5e-4, 3e-4, 2e-4)])
def test_transient_rolling_converges_to_the_steady_state(setup, creep):
    """Rolling 4 contact lengths (84 steps of dx) from zero traction: forces and moment within 0.5 % of the steady
    solution (measured 0.007 % and 0.07 %; after 1 / 2 / 3 lengths 9-16 / 0.8-2.4 / 0.07-0.4 %); the force
    approaches it monotonically from below (the stick zone fills the contact from the leading edge)."""
    op, problem, pressure = setup
    steady = solve_steady(problem, pressure, 0.3, *creep, params=SteadyParams(tol=1e-9))
    rolled = roll_transient(op, problem, pressure, 0.3, *creep, steps=84)
    assert rolled.force[-1] == pytest.approx(steady.force, rel=5e-3, abs=1e-9 * abs(steady.force[0]))
    assert rolled.moment[-1] == pytest.approx(steady.moment, rel=5e-3, abs=1e-9 * abs(steady.force[0]))
    fx = -rolled.force[:, 0]
    assert np.all(np.diff(fx) > -1e-9 * fx[-1]) and fx[-1] <= -steady.force[0] * (1 + 1e-6)


def test_transient_rolling_refuses_a_contact_at_the_grid_edge(setup):
    op, problem, pressure = setup
    edge = pressure.copy()
    edge[10, -1] = 1.0
    with pytest.raises(InputError, match="free column"):
        roll_transient(op, problem, edge, 0.3, 1e-3, steps=2)
