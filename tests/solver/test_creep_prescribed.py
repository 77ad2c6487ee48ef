"""Prescribed creep forces (solver/creep/prescribed.py): the creepages that give forces (Fx, Fy) on the rolling
body are those of the forward steady solve, from the linear range to near saturation; |F| >= mu Fn is refused.
Steel on steel, ellipse a = 1.2, b = 1 mm, Fn = 1000 N, mu = 0.3, 31 elements across."""
import math

import numpy as np
import pytest

from rollcontact.bem import MaterialPair
from rollcontact.bem.errors import GrossSlidingError
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure, solve_for_forces,
                                      solve_steady)

PARAMS = SteadyParams(tol=1e-9)


@pytest.fixture(scope="module")
def setup():
    mats = MaterialPair.from_moduli(210e3, 0.28, 210e3, 0.28)
    grid = ellipse_grid(1.2, 1.0, 31)
    pressure = hertz_pressure(grid, 1.2, 1.0, 1000.0)
    return SteadyRolling(grid, mats), pressure, 0.3 * pressure.sum() * grid.cell_area


@pytest.mark.parametrize("creep, rel", [((1e-4, 0.0, 0.0), 1e-6), ((5e-4, 3e-4, 2e-4), 1e-6),
                                        ((2e-3, 1e-3, 0.0), 1e-3)])
def test_the_creepages_of_a_forward_solve_are_recovered_from_its_forces(setup, creep, rel):
    """Forces of the forward solve at |F|/(mu Fn) = 0.14, 0.69 and 0.9996 (near saturation, where dF/dxi -> 0 and a
    force error of 1e-6 mu Fn leaves 6e-5 of the creepage: measured) give back its creepages: within 1e-6 relative
    (1e-3 near saturation), the forces within the tolerance 1e-6 mu Fn."""
    problem, pressure, capacity = setup
    forward = solve_steady(problem, pressure, 0.3, *creep, params=PARAMS)
    found = solve_for_forces(problem, pressure, 0.3, *forward.force, creep[2], params=PARAMS)
    scale = math.hypot(creep[0], creep[1])
    assert abs(found.xi - creep[0]) <= rel * scale and abs(found.eta - creep[1]) <= rel * scale
    assert np.hypot(*(np.array(found.steady.force) - forward.force)) <= 1e-6 * capacity


def test_a_force_beyond_mu_fn_is_gross_sliding(setup):
    problem, pressure, capacity = setup
    with pytest.raises(GrossSlidingError, match="mu Fn"):
        solve_for_forces(problem, pressure, 0.3, -0.8 * capacity, -0.7 * capacity)
