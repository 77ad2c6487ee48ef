"""What `solve_tangential` promises beyond the physics: validated inputs and parameters, a ConvergenceError
when the budget is exhausted, a stopping tolerance that bounds the traction error, and its cost counters
(`iterations`: every product; `steps`: the CG search directions).

Scene of the seed (Table 1), fixtures `scene` (dx = dy = 0.2 mm) and `fine_scene` (0.1 mm) from conftest.py,
the seed's constants and checks from tangential_helpers.py. Units mm, N, MPa.
"""
import numpy as np
import pytest

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential
from tangential_helpers import FN, MU


def test_iteration_budget_exhausted_raises_with_regime(scene):
    """A budget that is too small raises ConvergenceError naming f_t and the stick-element count (no silent
    return, no NaN)."""
    with pytest.raises(ConvergenceError, match="f_t = .*stick"):
        scene.cattaneo(0.5, params=TangentialParams(max_iter=3))


def test_inputs_validated(scene):
    with pytest.raises(InputError, match=r"exactly one of force=\(Fx, Fy\) N or shift=\(dUx, dUy\) mm"):
        solve_tangential(scene.op, scene.bound, scene.zero)
    with pytest.raises(InputError, match=r"exactly one of force"):
        solve_tangential(scene.op, scene.bound, scene.zero, force=(1.0, 0.0), shift=(0.0, 0.0))
    with pytest.raises(InputError, match=r"bound has shape \(54, 55\), the grid is \(55, 55\)"):
        solve_tangential(scene.op, scene.bound[:-1], scene.zero, force=(1.0, 0.0))


@pytest.mark.parametrize("kwargs", [dict(tol=0.0), dict(tol=1.5), dict(tol=float("nan")), dict(max_iter=0),
                                    dict(max_iter=2.5)])
def test_tangential_params_are_validated_naming_the_parameter(kwargs):
    name = next(iter(kwargs))
    with pytest.raises(InputError, match=f"TangentialParams.{name}"):
        TangentialParams(**kwargs)


@pytest.mark.parametrize("tol", [1e-4, 1e-6])
def test_stopping_tolerance_bounds_the_traction_error(scene, tol):
    """The stopping residual is the traction change (relative to max g) that each element would need to remove
    its own error (slip elements: resisted by a_tt + kappa). Against a reference at tol 1e-11 the traction error
    of a solve stopped at tol stays below 3 tol max g (measured 0.09-0.57 tol on the 0.2 / 0.1 / 0.05 mm grids for
    tol = 1e-4 ... 1e-8, benchmarks/README.md; the factor 3 allows
    for the coupling between elements that the per-element measure ignores), and the shift is closer still."""
    F = (0.5 * MU * FN, 0.0)
    ref = solve_tangential(scene.op, scene.bound, scene.zero, force=F, params=TangentialParams(tol=1e-11))
    res = solve_tangential(scene.op, scene.bound, scene.zero, force=F, params=TangentialParams(tol=tol))
    assert np.abs(res.traction - ref.traction).max() < 3 * tol * scene.bound.max()
    assert abs(res.shift_increment[0] / ref.shift_increment[0] - 1) < tol


def test_cg_steps_count_the_search_directions(scene):
    """`steps` counts the CG search directions (one product A v each); `iterations` counts every product, so the
    difference is the start product A tau, the exact re-synchronisations of u and the memo misses: at least one
    (the final exact check) and at most half of the products here (measured 22 products, 13 steps)."""
    res = scene.cattaneo(0.5)
    assert 1 <= res.steps < res.iterations
    assert res.iterations - res.steps <= res.iterations // 2
