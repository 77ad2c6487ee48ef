"""Steady rolling over a Standard Linear Solid (solver.visco.steady, steady_kernels, normal_steady, gmres): the memory
kernels against their defining sums, the elastic limits, the contact conditions of the non-symmetric normal problem,
and the energy balance: the work of the rolling resistance per unit distance is the viscous dissipation computed from
the element states."""
import math

import numpy as np
import pytest

from rollcontact.bem.grid import Grid
from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.creep.steady import SteadyRolling, solve_steady
from rollcontact.solver.normal import solve_normal
from rollcontact.solver.visco.gmres import gmres
from rollcontact.solver.visco.sls import StandardLinearSolid, history_pair
from rollcontact.solver.visco.steady import SteadyVisco, pressure_centroid
from rollcontact.solver.visco.steady_kernels import influence, tail_kernels

R, FN, MU = 20.0, 2.0, 0.5                       # mm, N; E_g / E_r = 10, tau = 1 s
SUBSTRATE = StandardLinearSolid(40.0, 4.0, 1.0, 0.5)
RIGID = Material(math.inf, 0.3)
A_R = (3 * FN * R / (4 * 4.0 / (1 - 0.25))) ** (1 / 3)          # relaxed Hertz radius (mm)


def sphere(n):
    grid = Grid.covering(-1.5 * A_R, 1.5 * A_R, -1.3 * A_R, 1.3 * A_R, A_R / n, A_R / n)
    X, Y = grid.mesh()
    return grid, (X ** 2 + Y ** 2) / (2 * R)


@pytest.mark.parametrize("length", [0.5, 5.0, 120.0])
def test_the_tail_kernels_are_their_exponentially_weighted_sums(length):
    """T(d) = w sum_{k>=1} e^(k-1) A_h(d + k dx) for every offset of a 9 x 7 grid, all six components, against the
    sum taken term by term up to e^k < 1e-20 (relaxation lengths 0.5, 5 and 120 cells): within 1e-6 of the largest
    (the far remainder is integrated, the rest summed exactly)."""
    grid = Grid(9, 7, 0.2, 0.25)
    pair = history_pair(StandardLinearSolid(40.0, 4.0, 0.1, 0.45), 2)
    comps = ("zz", "xx", "yy", "xy", "xz", "yz")
    decay = math.exp(-1.0 / length)
    T = tail_kernels(grid, pair, decay, 0.3, comps)
    ny, nx = grid.shape
    k = np.arange(1, int(46 * length) + 60)
    X = np.broadcast_to((np.arange(-(nx - 1), nx)[None, :, None] + k) * grid.dx, (2 * ny - 1, 2 * nx - 1, k.size))
    Y = np.broadcast_to(np.arange(-(ny - 1), ny)[:, None, None] * grid.dy, X.shape)
    A = influence(X, Y, grid.dx, grid.dy, pair, comps)
    for c in comps:
        brute = 0.3 * (A[c] * decay ** (k - 1)).sum(-1)
        assert np.abs(T[c] - brute).max() <= 1e-6 * np.abs(brute).max()


@pytest.mark.parametrize("speed, E", [(1e-9, 4.0), (1e12, 40.0)])
def test_slow_and_fast_steady_rolling_are_the_relaxed_and_the_glassy_elastic_contact(speed, E):
    """Speed -> 0: the steady viscoelastic state is the elastic one with E_r; speed -> inf with E_g: approach, contact
    area, force, and the creep force at xi = 0.002 within 1e-6 of NormCG and the elastic steady solver."""
    grid, h = sphere(10)
    sv = SteadyVisco(grid, RIGID, SUBSTRATE, speed)
    visco = sv.solve_normal(h, FN)
    pair = MaterialPair(RIGID, Material(E, 0.5))
    op = HalfSpaceOperator(grid, pair)
    elastic = solve_normal(op, h, force=FN)
    assert visco.approach == pytest.approx(elastic.approach, rel=1e-6)
    assert np.array_equal(visco.contact, elastic.contact) and visco.force == pytest.approx(FN, rel=1e-12)
    fv = solve_steady(sv.tangential_problem, visco.pressure, MU, 0.002).force[0]
    fe = solve_steady(SteadyRolling(grid, pair, operator=op), elastic.pressure, MU, 0.002).force[0]
    assert fv == pytest.approx(fe, rel=1e-6)


def test_the_non_symmetric_normal_problem_meets_the_contact_conditions():
    """V tau / a = 1: p >= 0, the gap >= 0 outside and 0 inside the contact (1e-8 of the approach), sum p dA = Fn, and
    the pressure leans forward (centroid ahead by a fifth of a_r or more) with the contact shrunk towards the
    glassy one."""
    grid, h = sphere(10)
    sv = SteadyVisco(grid, RIGID, SUBSTRATE, A_R / SUBSTRATE.tau)
    res = sv.solve_normal(h, FN)
    gap = res.gap
    assert np.all(res.pressure >= 0) and res.force == pytest.approx(FN, rel=1e-12)
    assert np.all(gap[~res.contact] >= -1e-8 * res.approach)
    assert np.abs(gap[res.contact]).max() <= 1e-8 * res.approach
    assert pressure_centroid(grid, res.pressure) > 0.2 * A_R


@pytest.mark.parametrize("de", [0.3, 1.0, 3.0])
def test_rolling_resistance_work_per_distance_is_the_viscous_dissipation(de):
    """Energy in steady rolling: the rolling resistance Fn x_c / R of a rigid sphere (the work per unit distance
    rolled) equals the viscous power of the element states (wake behind the grid included) over the speed, within
    1 % at a_r/dx = 12 (measured 0.2-0.5 %; the difference falls with dx)."""
    grid, h = sphere(12)
    speed = de * A_R / SUBSTRATE.tau
    sv = SteadyVisco(grid, RIGID, SUBSTRATE, speed)
    res = sv.solve_normal(h, FN)
    traction = np.concatenate([res.pressure[None], np.zeros((2,) + grid.shape)])
    dissipated_per_mm = sv.viscous_power(traction) * 1e3 / speed          # W -> N mm/s, per mm/s
    assert dissipated_per_mm == pytest.approx(FN * pressure_centroid(grid, res.pressure) / R, rel=0.01)


def test_gmres_solves_a_non_symmetric_system_to_its_tolerance():
    rng = np.random.default_rng(7)
    n = 60
    A = np.eye(n) * 4 + rng.random((n, n)) - 0.5 + np.tril(rng.random((n, n)), -1)
    b = rng.random(n)
    x, products, res = gmres(lambda v: A @ v, lambda v: v / 4.0, b, tol=1e-10, restart=20, max_products=400)
    assert res <= 1e-10 and np.linalg.norm(A @ x - b) <= 1.01e-10 * np.linalg.norm(b) and products < 400


def test_the_steady_tangential_problem_with_memory_converges_where_kalkers_order_does_not():
    """E_g/E_r = 10 at V tau/a = 0.3: the rows swept with the flow converge (under 60 sweeps); Kalker's order, from
    the trailing edge, cycles on this operator (docs/viscoelastic.md): the reason the memory's problem starts with
    the flow."""
    from rollcontact.bem.errors import ConvergenceError
    from rollcontact.solver.creep.steady import SteadyParams
    grid, h = sphere(12)
    sv = SteadyVisco(grid, RIGID, SUBSTRATE, 0.3 * A_R / SUBSTRATE.tau)
    p = sv.solve_normal(h, FN).pressure
    assert solve_steady(sv.tangential_problem, p, MU, 0.002).sweeps < 60
    sv.tangential_problem.with_flow = False
    with pytest.raises(ConvergenceError):
        solve_steady(sv.tangential_problem, p, MU, 0.002, params=SteadyParams(max_sweeps=300))
