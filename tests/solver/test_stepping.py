"""Time stepping of oscillating rolling (docs/theory.md §6): the load path, memory, restarts, grid edge."""
import numpy as np
import pytest

from rollcontact.bem import ContactEdgeError, Grid, HalfSpaceOperator, InputError, MaterialPair
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.normal.normcg import solve_normal
from rollcontact.solver.rolling.profiles import ArrayProfile, FunctionProfile, QuadricProfile
from rollcontact.solver.rolling.stepping import build_path, run_path
from rollcontact.solver.tangential.shift import solve_tangential

PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
FN, MU, R = 21.19, 0.93, 40.0
HERTZ = HertzSphere(R, PAIR.E_star, FN)


def test_path_hits_reversal_points_exactly_and_returns_to_the_origin():
    W = 1.1007  # w = 0.23 on the paper scene: not a multiple of 0.2
    path = build_path(force=(9.0, 0.0), ramp_steps=3, rolling_direction=(0.0, 1.0), amplitude=W,
                      max_step=0.2, periods=2)
    nq = 6  # ceil(1.1007 / 0.2)
    assert path.dW == pytest.approx(W / nq) and path.dW <= 0.2
    assert path.n_steps == 1 + 3 + 2 * 4 * nq  # Fn alone, ramp, two periods
    s = path.centres[:, 1]
    assert np.all(path.centres[:, 0] == 0)
    assert s.max() == pytest.approx(W, abs=1e-14) and s.min() == pytest.approx(-W, abs=1e-14)
    assert np.all(np.abs(np.diff(s)) <= path.dW * (1 + 1e-12))
    ends = path.period_ends()
    assert list(ends) == [3, 3 + 4 * nq, 3 + 8 * nq] and np.all(s[ends] == pytest.approx(0, abs=1e-14))
    assert np.allclose(path.forces[:4, 0], [0, 3, 6, 9]) and np.all(path.forces[4:, 0] == 9.0)
    assert path.reversal.sum() == 2 * 3


def test_levels_unload_and_reverse_the_force():
    path = build_path(force=(4.0, 0.0), ramp_steps=2, levels=[(0.0, 0.0), (-4.0, 0.0)])
    assert np.allclose(path.forces[:, 0], [0, 2, 4, 2, 0, -2, -4])


@pytest.mark.parametrize("kwargs, key", [(dict(ramp_steps=0), "ramp_steps"),
                                         (dict(amplitude=1.0, max_step=0.0, periods=1), "dW"),
                                         (dict(amplitude=1.0, periods=-1), "periods"),
                                         (dict(amplitude=-1.0), "motion.W")])
def test_ill_posed_paths_are_refused(kwargs, key):
    with pytest.raises(InputError, match=key):
        build_path(force=(1.0, 0.0), **kwargs)


@pytest.fixture(scope="module")
def op():
    a = HERTZ.a
    grid = Grid.covering(-a - 0.8, a + 0.8, -a - 0.8, a + 0.8, 0.4, 0.4)
    return HalfSpaceOperator(grid, PAIR)


def test_without_motion_the_stepper_reproduces_the_static_cattaneo_solve(op):
    # w = 0: the stepper's last state must equal a direct normal + tangential solve (same equations,
    # same tolerance): U agrees to the solver tolerance, and both lie within 1 % of Mindlin (docs/theory.md P10).
    f_t = 0.5
    F = np.array([f_t * MU * FN, 0.0])
    recs = list(run_path(op, QuadricProfile(R, R), build_path(force=F), Fn=FN, mu=MU))
    X, Y = op.grid.mesh()
    nr = solve_normal(op, (X ** 2 + Y ** 2) / (2 * R), force=FN)
    tr = solve_tangential(op, MU * nr.pressure, np.zeros((2,) + op.grid.shape), force=F)
    U = recs[-1].state.rigid_shift
    assert U[0] == pytest.approx(tr.shift_increment[0], rel=1e-6)
    cm = CattaneoMindlin(HERTZ, MU, PAIR.G_star)
    assert U[0] == pytest.approx(cm.shift(f_t), rel=0.01)
    assert abs(U[1]) < 1e-9 * U[0]


def rolling_path(periods=2):
    return build_path(force=(0.4 * MU * FN, 0.0), rolling_direction=(0.0, 1.0), amplitude=0.8,
                      max_step=0.4, periods=periods)


def test_continuing_from_a_stored_step_gives_the_uninterrupted_history():
    a = HERTZ.a
    grid = Grid.covering(-a - 0.8, a + 0.8, -a - 1.6, a + 1.6, 0.4, 0.4)
    op = HalfSpaceOperator(grid, PAIR)
    path = rolling_path()
    prof = QuadricProfile(R, R)
    full = list(run_path(op, prof, path, Fn=FN, mu=MU))
    k = 5
    resumed = list(run_path(op, prof, path, Fn=FN, mu=MU, state=full[k].state))
    assert [r.step for r in resumed] == list(range(k + 1, path.n_steps))
    U_full = np.array([r.state.rigid_shift for r in full[k + 1:]])
    U_res = np.array([r.state.rigid_shift for r in resumed])
    # the warm starts differ (the resumed run starts from the stored fields), so agreement is to the
    # solver tolerance (1e-8 relative on tractions), not bitwise: 1e-6 U0 is a safe margin.
    U0 = CattaneoMindlin(HERTZ, MU, PAIR.G_star).U0
    assert np.abs(U_full - U_res).max() < 1e-6 * U0


def test_uncoupled_normal_problems_are_solved_once_per_gap_and_force():
    """For uncoupled materials the normal problem of a step is the frictionless contact of its gap under Fn,
    whatever the tractions: along an oscillating path (2 periods) each distinct centre is solved once and a step that
    comes back to it takes that solution (no normal iterations, the same pressure bit for bit), while a fresh solve
    at the same centre from the warm start of that step agrees with it to the solver tolerance (1e-8 of p0: measured
    1.8e-9) and carries Fn."""
    a = HERTZ.a
    grid = Grid.covering(-a - 0.8, a + 0.8, -a - 1.6, a + 1.6, 0.4, 0.4)
    op = HalfSpaceOperator(grid, PAIR)
    path = rolling_path()
    prof = QuadricProfile(R, R)
    recs = list(run_path(op, prof, path, Fn=FN, mu=MU))
    first = {}
    for rec in recs:
        key = tuple(rec.centre)
        if key in first:
            assert rec.normal.iterations == 0
            assert np.array_equal(rec.normal.pressure, first[key].normal.pressure)
        else:
            assert rec.normal.iterations > 0 or rec.step == 0
            first[key] = rec
    assert len(first) < len(recs) / 2
    X, Y = grid.mesh()
    last = recs[-1]
    fresh = solve_normal(op, prof(X, Y, last.centre), force=FN, initial=recs[-2].normal.pressure)
    assert np.abs(fresh.pressure - last.normal.pressure).max() <= 1e-8 * HERTZ.p0
    assert last.normal.pressure.sum() * grid.cell_area == pytest.approx(FN, rel=1e-12)


def test_contact_reaching_the_grid_edge_stops_the_run_with_a_clear_error():
    a = HERTZ.a
    grid = Grid.covering(-a - 0.4, a + 0.4, -a - 0.4, a + 0.4, 0.4, 0.4)  # no room to roll 0.8 mm
    op = HalfSpaceOperator(grid, PAIR)
    with pytest.raises(ContactEdgeError, match="edge of the grid"):
        list(run_path(op, QuadricProfile(R, R), rolling_path(), Fn=FN, mu=MU))


def test_function_and_array_profiles_give_the_quadric_solution(op):
    X, Y = op.grid.mesh()
    centre = (0.0, 0.4)
    ref = QuadricProfile(R, R)(X, Y, centre)
    f = FunctionProfile(lambda x, y: (x * x + y * y) / (2 * R))(X, Y, centre)
    np.testing.assert_allclose(f, ref, rtol=1e-15)
    xs = np.linspace(-8, 8, 161)
    arr = ArrayProfile(xs, xs, (xs[None, :] ** 2 + xs[:, None] ** 2) / (2 * R))(X, Y, centre)
    # scipy's cubic grid interpolation is not exact for a quadric (measured 1e-6 mm at 0.1 mm spacing);
    # 1e-5 mm is < 2e-5 of the approach d = 0.57 mm, far below the discretisation error of the contact.
    np.testing.assert_allclose(arr, ref, atol=1e-5)


def test_bad_loads_are_refused(op):
    with pytest.raises(InputError, match="Fn"):
        next(run_path(op, QuadricProfile(R, R), rolling_path(), Fn=0.0, mu=MU))
    with pytest.raises(InputError, match="mu"):
        next(run_path(op, QuadricProfile(R, R), rolling_path(), Fn=FN, mu=0.0))


def test_shifted_field_translates_by_whole_cells_with_zero_fill():
    from rollcontact.solver.rolling.stepping import shifted_field
    f = np.arange(20.0).reshape(4, 5)
    assert shifted_field(f, 0, 0) is None
    down_right = shifted_field(f, 1, 2)
    assert np.array_equal(down_right[1:, 2:], f[:-1, :-2])
    assert not down_right[0].any() and not down_right[:, :2].any()
    up_left = shifted_field(f, -1, -1)
    assert np.array_equal(up_left[:-1, :-1], f[1:, 1:]) and not up_left[-1].any() and not up_left[:, -1].any()
    assert not shifted_field(f, 4, 0).any()
