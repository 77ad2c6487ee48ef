"""Nested normal/tangential (Panagiotopoulos) loop for coupled materials (docs/theory.md §6.2 step 5).

Steel (E = 210e3 MPa, nu = 0.3) sphere R = 10 mm on aluminium (E = 70e3 MPa, nu = 0.33): Dundurs beta ~ -0.1.
Fn = 100 N gives a ~ 0.24 mm; a 0.03 mm grid keeps the problem at ~20 x 20 elements. Units mm, N, MPa.
"""
import numpy as np
import pytest

from rollcontact.solver.rolling import coupled
from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.analytic import HertzSphere
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.normal.normcg import solve_normal

R, FN, MU = 10.0, 100.0, 0.3


def _setup(materials, coupling="auto"):
    a = HertzSphere(R, materials.E_star, FN).a
    grid = Grid.covering(-a - 0.1, a + 0.1, -a - 0.1, a + 0.1, 0.03, 0.03)
    op = HalfSpaceOperator(grid, materials, coupling=coupling)
    X, Y = grid.mesh()
    return grid, op, (X ** 2 + Y ** 2) / (2 * R)


def test_coupled_loop_converges_and_shifts_the_pressure():
    """With beta ~ -0.1 the tangential load changes the pressure (A^zt tau) measurably; the nested loop
    converges to the coupling tolerance with Coulomb's law and both force balances intact."""
    mats = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)
    assert -0.15 < mats.beta < -0.05
    grid, op, h = _setup(mats)
    assert op.coupled
    zero_t = np.zeros((2,) + grid.shape)
    F = (0.5 * MU * FN, 0.0)
    normal, tang, outer = solve_coupled_step(op, h, FN, F, None, zero_t, mu=MU, coupling_tol=1e-8)
    assert 2 <= outer <= 30
    assert normal.force == pytest.approx(FN, rel=1e-9)
    np.testing.assert_allclose(tang.force, F, atol=1e-9 * MU * FN)
    g = MU * normal.pressure
    assert np.all(np.hypot(*tang.traction) <= g * (1 + 1e-9))
    # the uncoupled normal solve (no A^zt tau) differs by a measurable amount: > 0.1 % of p_max
    plain = solve_normal(op, h, force=FN)
    diff = np.abs(normal.pressure - plain.pressure).max() / plain.pressure.max()
    assert diff > 1e-3, diff
    # consistency of the fixed point: re-solving the normal problem with the final tractions reproduces p
    again = solve_normal(op, h, force=FN, initial=normal.pressure,
                         extra_displacement=op.normal_from_tangential(*tang.traction))
    assert np.abs(again.pressure - normal.pressure).max() < 1e-6 * plain.pressure.max()


def test_uncoupled_materials_cost_exactly_one_normal_solve(monkeypatch):
    """beta = 0 (operator built without coupling): Johnson's process, one normal and one tangential solve."""
    mats = MaterialPair.from_moduli(210e3, 0.3, 210e3, 0.3)
    assert mats.beta == 0
    grid, op, h = _setup(mats)
    assert not op.coupled
    calls = {"normal": 0, "tangential": 0}
    real_n, real_t = coupled.solve_normal, coupled.solve_tangential

    def count_n(*a, **k):
        calls["normal"] += 1
        return real_n(*a, **k)

    def count_t(*a, **k):
        calls["tangential"] += 1
        return real_t(*a, **k)

    monkeypatch.setattr(coupled, "solve_normal", count_n)
    monkeypatch.setattr(coupled, "solve_tangential", count_t)
    normal, tang, outer = solve_coupled_step(op, h, FN, (0.3 * MU * FN, 0.0), None,
                                             np.zeros((2,) + grid.shape), mu=MU)
    assert outer == 1 and calls == {"normal": 1, "tangential": 1}
    assert tang.shift_increment[0] > 0


def test_coupled_step_reports_the_products_of_every_outer_iteration(monkeypatch):
    """The iterations of the returned results are the products of the whole step (all outer iterations), not
    those of the last outer iteration, which starts from the converged fields and needs about one each."""
    mats = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)
    grid, op, h = _setup(mats)
    seen = {"normal": [], "tangential": []}
    real_n, real_t = coupled.solve_normal, coupled.solve_tangential

    def count_n(*a, **k):
        r = real_n(*a, **k)
        seen["normal"].append(r.iterations)
        return r

    def count_t(*a, **k):
        r = real_t(*a, **k)
        seen["tangential"].append(r.iterations)
        return r

    monkeypatch.setattr(coupled, "solve_normal", count_n)
    monkeypatch.setattr(coupled, "solve_tangential", count_t)
    normal, tang, outer = solve_coupled_step(op, h, FN, (0.5 * MU * FN, 0.0), None,
                                             np.zeros((2,) + grid.shape), mu=MU)
    assert outer == len(seen["normal"]) == len(seen["tangential"]) >= 2
    assert normal.iterations == sum(seen["normal"]) > seen["normal"][-1]
    assert tang.iterations == sum(seen["tangential"]) > seen["tangential"][-1]


def test_coupled_step_reports_the_surface_displacement_so_that_slip_is_its_change():
    """The stored u_x, u_y of coupled runs were A^tt tau + A^tz (p - p'), the solve's internal part, not the
    surface displacement A^tt tau + A^tz p (a review found them 9-100 % off from the second step on). Two steps
    (load, then more load): u = A^tt tau + A^tz p to round-off, and the slip of the second step is
    s = u - u' - dU: zero in stick, the reported slip in slip elements."""
    mats = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)
    grid, op, h = _setup(mats)
    zero_t = np.zeros((2,) + grid.shape)
    n1, t1, _ = solve_coupled_step(op, h, FN, (0.3 * MU * FN, 0.0), None, zero_t, mu=MU, coupling_tol=1e-10)
    n2, t2, _ = solve_coupled_step(op, h, FN, (0.6 * MU * FN, 0.0), n1.pressure, t1.traction, mu=MU,
                                   coupling_tol=1e-10)
    for n, t in ((n1, t1), (n2, t2)):
        u = op.tangential(*t.traction) + op.tangential_from_pressure(n.pressure)
        assert np.abs(t.displacement - u).max() < 1e-12 * np.abs(u).max()
    s = t2.displacement - t1.displacement - t2.shift_increment[:, None, None]
    scale = np.abs(t2.shift_increment).max()
    stick, slip = t2.region == 1, t2.region == 2
    assert stick.sum() > 10 and slip.sum() > 10
    # the solver's residual tolerance (1e-8 of a_self max g) bounds the stick slip: far below 1e-6 dU
    assert np.abs(s[:, stick]).max() < 1e-6 * scale
    assert np.abs(s[:, slip] - t2.slip[:, slip]).max() < 1e-6 * scale


def test_forced_coupling_of_identical_materials_reproduces_the_uncoupled_step():
    """Limiting case beta = 0 (identical materials) with the coupling forced on: the coupling terms A^zt, A^tz vanish,
    so the nested loop must stop at its second pass (the first one that can compare) with the pressure, traction
    and shift of the single uncoupled pass, to the solvers' tolerance (1e-8, relative to p_max and mu p_max)."""
    mats = MaterialPair.from_moduli(70e3, 0.33, 70e3, 0.33)
    assert mats.beta == 0.0
    grid, forced, h = _setup(mats, coupling=True)
    _, plain_op, _ = _setup(mats)
    assert forced.coupled and not plain_op.coupled
    zero_t = np.zeros((2,) + grid.shape)
    F = (0.5 * MU * FN, 0.0)
    n1, t1, outer = solve_coupled_step(forced, h, FN, F, None, zero_t, mu=MU)
    n0, t0, one = solve_coupled_step(plain_op, h, FN, F, None, zero_t, mu=MU)
    assert outer == 2 and one == 1
    pmax = n0.pressure.max()
    assert np.abs(n1.pressure - n0.pressure).max() < 1e-8 * pmax
    assert np.abs(t1.traction - t0.traction).max() < 1e-7 * MU * pmax
    np.testing.assert_allclose(t1.shift_increment, t0.shift_increment, rtol=0, atol=1e-6 * abs(t0.shift_increment[0]))


def test_outer_budget_and_friction_coefficient_are_enforced():
    """max_outer passes without meeting coupling_tol raise ConvergenceError naming the loop, the budget and the
    regime (beta, mu, f_t); mu <= 0 is refused before any solve."""
    from rollcontact.bem.errors import ConvergenceError, InputError
    mats = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)
    grid, op, h = _setup(mats)
    zero_t = np.zeros((2,) + grid.shape)
    F = (0.5 * MU * FN, 0.0)
    with pytest.raises(ConvergenceError, match="Panagiotopoulos") as info:
        solve_coupled_step(op, h, FN, F, None, zero_t, mu=MU, max_outer=2, coupling_tol=1e-15)
    assert info.value.iterations == 2 and "beta = -0.1" in str(info.value) and "f_t = 0.5" in str(info.value)
    for mu in (0.0, -0.3):
        with pytest.raises(InputError, match=r"mu = .*friction coefficient must be > 0"):
            solve_coupled_step(op, h, FN, F, None, zero_t, mu=mu)
