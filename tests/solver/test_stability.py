"""Hard regimes on coarse grids (the fast subset of benchmarks/stability.py).

Every case must converge to its stated tolerance with the physics invariants intact (force balance,
|tau| <= mu p (1 + 1e-9), p >= 0, no NaN); all of them do today, so a ConvergenceError here is a regression.
The other side of the contract -- a solve that cannot converge raises ConvergenceError naming the regime, and
a rolling run that fails keeps its steps and says why -- is checked on failures forced by a budget of a few
products (the last two tests). The iteration budgets are finite, so a hang shows up as iterations > max_iter
(asserted) rather than a stuck test.
Units mm, N, MPa.
"""
import math

import numpy as np
import pytest

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import ConvergenceError
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.analytic import CattaneoMindlin, HertzEllipse, HertzSphere
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.normal.normcg import NormalParams, solve_normal
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential

R, FN, MU, TOL, MAX_ITER = 40.0, 21.19, 0.93, 1e-8, 500
SCENE_PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
A = HertzSphere(R, SCENE_PAIR.E_star, FN).a


def assert_invariants(pressure, traction, mu, F, dA, Fn):
    assert np.all(np.isfinite(pressure)) and np.all(np.isfinite(traction)), "NaN/inf in the solution"
    assert pressure.min() >= 0.0, "negative pressure"
    tau = np.hypot(traction[0], traction[1])
    assert np.all(tau <= mu * pressure * (1 + 1e-9)), \
        f"Coulomb bound violated by {float((tau - mu * pressure).max()):.3e} MPa"
    assert pressure.sum() * dA == pytest.approx(Fn, rel=1e-8)
    Fx, Fy = traction[0].sum() * dA, traction[1].sum() * dA
    assert math.hypot(Fx - F[0], Fy - F[1]) <= 1e-8 * max(math.hypot(*F), 1e-300)


def static(pair, rx, ry, Fn, mu, f_t, dx, margin_cells=3, max_iter=MAX_ITER):
    """Static Hertz + Cattaneo in one step; returns (normal, tangential, grid, F, outer iterations)."""
    hz = HertzSphere(rx, pair.E_star, Fn) if rx == ry else HertzEllipse(rx, ry, pair.E_star, Fn)
    sa, sb = (hz.a, hz.a) if rx == ry else (hz.a, hz.b)
    m = margin_cells * dx
    grid = Grid.covering(-sa - m, sa + m, -sb - m, sb + m, dx, dx)
    X, Y = grid.mesh()
    op = HalfSpaceOperator(grid, pair)
    profile = X ** 2 / (2 * rx) + Y ** 2 / (2 * ry)
    nparams, tparams = NormalParams(tol=TOL, max_iter=max_iter), TangentialParams(tol=TOL, max_iter=max_iter)
    F = (f_t * mu * Fn, 0.0)
    zero = np.zeros((2,) + grid.shape)
    outer = 1
    if op.coupled:
        nr, tr, outer = solve_coupled_step(op, profile, Fn, F, None, zero, mu=mu, normal_params=nparams,
                                           tangential_params=tparams)
    else:
        nr = solve_normal(op, profile, force=Fn, params=nparams)
        tr = solve_tangential(op, mu * nr.pressure, zero, force=F, params=tparams)
    return nr, tr, grid, F, outer


def check_static(pair, rx, ry, Fn, mu, f_t, dx):
    """Converged with invariants and iterations within budget (a ConvergenceError fails the test)."""
    nr, tr, grid, F, outer = static(pair, rx, ry, Fn, mu, f_t, dx)
    assert nr.converged and tr.converged
    # a coupled step reports the products of all its outer iterations, each solve within the budget
    assert nr.iterations <= outer * MAX_ITER and tr.iterations <= outer * MAX_ITER
    assert nr.residual <= TOL and tr.residual <= TOL
    assert_invariants(nr.pressure, tr.traction, mu, F, grid.cell_area, Fn)
    return nr, tr, grid


@pytest.mark.parametrize("f_t", [0.9, 0.99, 0.999])
@pytest.mark.parametrize("a_over_dx", [12, 24])
def test_cattaneo_near_traction_bound_converges(f_t, a_over_dx):
    nr, tr, grid = check_static(SCENE_PAIR, R, R, FN, MU, f_t, A / a_over_dx)
    cm = CattaneoMindlin(HertzSphere(R, SCENE_PAIR.E_star, FN), MU, SCENE_PAIR.G_star)
    assert tr.shift_increment[0] == pytest.approx(cm.shift(f_t), rel=0.01)   # docs/theory.md P10, P12: within 1 %


@pytest.mark.parametrize("mu", [0.05, 2.0])
def test_normalised_cattaneo_shift_independent_of_friction_coefficient(mu):
    nr, tr, grid = check_static(SCENE_PAIR, R, R, FN, mu, 0.5, A / 12)
    ref = check_static(SCENE_PAIR, R, R, FN, MU, 0.5, A / 12)[1]
    assert tr.shift_increment[0] / mu == pytest.approx(ref.shift_increment[0] / MU, rel=1e-6)


@pytest.mark.parametrize("a_over_dx", [3, 6])
def test_very_coarse_grid_still_converges_with_invariants(a_over_dx):
    check_static(SCENE_PAIR, R, R, FN, MU, 0.5, A / a_over_dx)


@pytest.mark.parametrize("aspect", [5, 10])
def test_elongated_ellipse_matches_hertz_and_keeps_invariants(aspect):
    rx, ry = R * math.sqrt(aspect), R / math.sqrt(aspect)
    hz = HertzEllipse(rx, ry, SCENE_PAIR.E_star, FN)
    nr, tr, grid = check_static(SCENE_PAIR, rx, ry, FN, MU, 0.5, hz.b / 8)
    assert nr.approach == pytest.approx(hz.approach, rel=2e-3)


@pytest.mark.parametrize("E2,nu2", [(70e3, 0.3), (70e3, 0.0)])
def test_coupled_materials_converge_with_invariants(E2, nu2):
    pair = MaterialPair.from_moduli(210e3, 0.3, E2, nu2)
    assert abs(pair.beta) > 0.1
    a = HertzSphere(R, pair.E_star, FN).a
    check_static(pair, R, R, FN, MU, 0.5, a / 10)


@pytest.mark.parametrize("eps", [1e-3, 1e-6])
def test_tiny_pressures_at_contact_edge_respect_coulomb_bound(eps):
    out = check_static(SCENE_PAIR, R, R, FN, MU, 0.5, A * (1 - eps) / 12)   # element centre at r = a(1 - eps)
    nr = out[0]
    assert nr.pressure[nr.pressure > 0].min() < 0.05 * nr.pressure.max()


def test_tiny_load_converges_with_invariants():
    a = HertzSphere(R, SCENE_PAIR.E_star, 1e-4).a
    check_static(SCENE_PAIR, R, R, 1e-4, MU, 0.99, a / 12)


def rolling(overrides, tmp_path):
    overrides = list(overrides)
    dx = [o.split("=")[1] for o in overrides if o.startswith("grid.dx=")]
    scene = default_scene().with_overrides(overrides + [f"grid.dy={dx[0]}" if dx else "grid.dy=0.4",
                                                        "output.fields=reversals", f"solver.max_iter={MAX_ITER}"])
    out = run_scene(scene, tmp_path / "run.h5")
    d, h = out, out.history
    assert len(h["step"]) > 0
    assert np.all(np.asarray(h["normal_iterations"]) <= MAX_ITER)
    assert np.all(np.asarray(h["tangential_iterations"]) <= MAX_ITER)
    assert d.status == "complete", d.error
    assert np.all(np.asarray(h["residual"]) <= TOL * (1 + 1e-12))
    dA = (d.x[1] - d.x[0]) * (d.y[1] - d.y[0])
    F = (scene.Ft * scene.load_direction[0], scene.Ft * scene.load_direction[1])
    for i in range(len(d.field_steps)):
        assert_invariants(d.fields["p"][i], np.stack([d.fields["tau_x"][i], d.fields["tau_y"][i]]),
                          scene.load.mu, F, dA, scene.load.Fn)
    return d


@pytest.mark.parametrize("f_t", [0.99, 0.999])
@pytest.mark.parametrize("angle", [90, 0])
def test_rolling_near_traction_bound_ratchets(f_t, angle, tmp_path):
    d = rolling([f"load.ft={f_t}", f"motion.angle={angle}", "grid.dx=0.4", "motion.dW=0.4", "motion.periods=2"],
                tmp_path)
    assert d.summary["state"] in ("ratcheting", "undecided")
    assert d.summary["du"] > 1e-3       # far beyond f_t,lim(0.23) = 0.75-0.77: the contact walks


@pytest.mark.parametrize("factor,state", [(0.5, "shakedown"), (1.2, "ratcheting")])
def test_rolling_well_below_and_above_shakedown_limit(factor, state, tmp_path):
    # factor of w_lim(f_t = 0.46; seed kappa 1.1) = 0.50. Not closer: rollcontact already ratchets at
    # 0.9 w_lim (benchmarks/stability.py, group w_limit), i.e. its limit lies below the seed's fit there.
    from rollcontact.solver.mdr import limits as lim
    w = factor * lim.w_lim(0.46, lim.KAPPA_PERPENDICULAR)
    d = rolling([f"motion.w={w}", "grid.dx=0.4", "motion.dW=0.4", "motion.periods=6"], tmp_path)
    assert d.status == "complete"
    assert d.summary["state"] == state or (state == "ratcheting" and d.summary["state"] == "undecided"
                                           and d.summary["du"] > 1e-4)


@pytest.mark.parametrize("dW_over_dx", [0.25, 3.0])
def test_rolling_step_much_smaller_or_larger_than_element(dW_over_dx, tmp_path):
    d = rolling(["grid.dx=0.4", f"motion.dW={0.4 * dW_over_dx}", "motion.periods=2"], tmp_path)
    assert d.status == "complete"


def test_coupled_rolling_converges_with_invariants(tmp_path):
    pair = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.3)
    a = HertzSphere(R, pair.E_star, FN).a
    dx = a / 8
    d = rolling(["materials.E1=210e3", "materials.nu1=0.3", "materials.E2=70e3", "materials.nu2=0.3",
                 f"grid.dx={dx}", f"motion.dW={dx}", f"grid.margin={4 * dx}", "motion.periods=1"], tmp_path)
    assert d.status == "complete"


@pytest.mark.parametrize("coupled", [False, True])
def test_a_solve_that_cannot_converge_names_its_regime(coupled):
    """A budget of 3 products cannot reach tol 1e-8 (near the bound, f_t = 0.99): ConvergenceError with the
    budget, the residual above the tolerance and the regime (loads and the stick/slip or contact counts)."""
    pair = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.3) if coupled else SCENE_PAIR
    a = HertzSphere(R, pair.E_star, FN).a
    with pytest.raises(ConvergenceError) as info:
        static(pair, R, R, FN, MU, 0.99, a / 12, max_iter=3)
    exc = info.value
    assert exc.iterations is not None and exc.iterations <= 3 + 1
    assert exc.regime and "regime" in str(exc) and str(exc.regime) in str(exc)


def test_a_rolling_run_that_cannot_converge_keeps_its_steps_and_names_the_regime(tmp_path):
    """The near-bound rolling case with a budget of 3 products per solve: the run ends as 'failed' with the
    ConvergenceError's regime in its error text (docs/theory.md §6.2 step 4 cannot finish)."""
    scene = default_scene().with_overrides(["load.ft=0.99", "grid.dx=0.4", "grid.dy=0.4", "motion.dW=0.4",
                                            "motion.periods=1", "solver.max_iter=3"])
    d = run_scene(scene, tmp_path / "run.h5")
    assert d.status == "failed"
    assert d.error.startswith("ConvergenceError") and "regime" in d.error, d.error
