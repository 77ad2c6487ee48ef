"""Steady rolling with creepage and spin (solver/creep/steady.py) against the closed forms of docs/theory.md §7.3, §7.4
and §11.5: Kalker's linear theory (C11, C22, C23), Carter's two-dimensional solution on a slender ellipse, full
sliding, and the solver's own contract (complementarity, warm starts, errors). Kalker's sign convention: forces on
body 1, opposing the creepages. Identical bodies with G = 1 MPa (K = 0), Hertz pressure on the ellipse's cells.
"""
import math

import numpy as np
import pytest

from rollcontact.bem import MaterialPair
from rollcontact.bem.errors import ContactEdgeError, ConvergenceError, InputError
from rollcontact.solver.creep import (SteadyParams, SteadyRolling, ellipse_grid, hertz_pressure,
                                      kalker_coefficients, solve_steady)


def _pair(nu):
    return MaterialPair.from_moduli(2 * (1 + nu), nu, 2 * (1 + nu), nu)  # G1 = G2 = 1 MPa: G = 1, K = 0


def _ellipse(ratio, nu, n, ny=None, normal_force=1.0):
    """c = sqrt(a b) = 1 mm unless ny is given (then a = 1, b = ratio ... see the Carter tests)."""
    a, b = math.sqrt(ratio), 1.0 / math.sqrt(ratio)
    grid = ellipse_grid(a, b, n, ny)
    return SteadyRolling(grid, _pair(nu)), hertz_pressure(grid, a, b, normal_force)


def _linear_coefficients(ratio, nu, n):
    """C11, C22, C23 of the solver: -Fx/(G c^2 xi), -Fy/(G c^2 eta), -Fy/(G c^3 phi) with G = c = 1."""
    problem, pressure = _ellipse(ratio, nu, n)  # default tol 1e-6: forces converged to ~1e-8 (benchmarks/README.md)
    fx = solve_steady(problem, pressure, math.inf, xi=1e-3).force[0]
    fy = solve_steady(problem, pressure, math.inf, eta=1e-3).force[1]
    fs = solve_steady(problem, pressure, math.inf, phi=1e-3).force[1]
    return -fx / 1e-3, -fy / 1e-3, -fs / 1e-3


CASES = [(r, nu) for r in (0.5, 1.0, 2.0) for nu in (0.0, 0.25, 0.5)]


@pytest.mark.parametrize("ratio, nu", CASES)
def test_linear_limit_matches_kalker_c11_c22_c23_within_2_percent_at_41_elements(ratio, nu):
    """Full adhesion (no friction limit) on 41 elements across each axis: the discretisation error of piecewise-
    constant elements (first-order upwind difference, staircase contact area -0.55 %) is within 2 % (the issue's
    bound at ~40 elements; measured: largest |error| 1.2 %, C22 at a/b = 2, nu = 0.5)."""
    got = _linear_coefficients(ratio, nu, 41)
    assert got == pytest.approx(kalker_coefficients(ratio, nu), rel=0.02)


def test_linear_forces_are_linear_and_oppose_the_creepages():
    """Kalker's sign convention: Fx = -G c^2 C11 xi, also for negative xi; doubling xi doubles Fx (no limit)."""
    problem, pressure = _ellipse(1.0, 0.25, 21)
    f1 = solve_steady(problem, pressure, math.inf, xi=1e-3).force
    f2 = solve_steady(problem, pressure, math.inf, xi=-2e-3).force
    assert f1[0] < 0 and f2[0] > 0
    assert f2[0] == pytest.approx(-2 * f1[0], rel=1e-6)
    assert abs(f1[1]) < 1e-6 * abs(f1[0])  # zero by symmetry, to the solver tolerance (1e-6)


def test_full_sliding_traction_is_mu_p_against_the_creepage():
    """Above saturation every contact cell slips with |tau| = mu p. For pure longitudinal creepage at nu = 0 (no
    lateral displacement from a longitudinal traction) every traction is -mu p x, so Fx = -mu Fn (the discrete
    Fn = sum p dA) to round-off. With eta and nu > 0 the slip direction varies by the elastic part of the slip
    (small against the creepage), so |F| = mu Fn only in the limit: |F| <= mu Fn, within 1e-4 at |creepage| 0.54
    (measured 6.5e-5), and F against the rigid slip within a few mrad."""
    mu = 0.3
    problem, pressure = _ellipse(1.0, 0.0, 21)
    fn = pressure.sum() * problem.grid.cell_area
    res = solve_steady(problem, pressure, mu, xi=0.5)
    assert not res.stick.any()
    assert res.force[0] == pytest.approx(-mu * fn, rel=1e-12)
    assert np.allclose(-res.traction[0], mu * pressure, rtol=0, atol=1e-12 * pressure.max())
    problem, pressure = _ellipse(1.0, 0.25, 21)
    res = solve_steady(problem, pressure, mu, xi=0.5, eta=0.2)
    assert not res.stick.any()
    assert np.allclose(np.hypot(*res.traction), mu * pressure, rtol=0, atol=1e-12 * pressure.max())
    magnitude = math.hypot(*res.force)
    assert mu * fn * (1 - 1e-4) < magnitude <= mu * fn * (1 + 1e-12)
    cosine = np.array(res.force) @ np.array([0.5, 0.2]) / (magnitude * math.hypot(0.5, 0.2))
    assert cosine < -1 + 5e-5  # measured 1 - 5.2e-6: 3 mrad off the rigid slip's direction


def test_partial_slip_satisfies_coulomb_complementarity():
    """At a creepage halfway to saturation, from a fresh product of the final traction: |s| < 1e-5 of the rigid
    slip in stick (tol 1e-8 on the traction), |tau| = mu p in slip with tau antiparallel to s (cosine -1 to 1e-6),
    and the stick zone at the leading edge of the middle row (Carter)."""
    problem, pressure = _ellipse(1.0, 0.25, 31)
    mu = 0.3
    res = solve_steady(problem, pressure, mu, xi=0.02, eta=0.005, phi=0.01, params=SteadyParams(tol=1e-8))
    assert res.stick_slip < 1e-5
    slipping = res.contact & ~res.stick
    assert slipping.any() and res.stick.any()
    tau, s = res.traction[:, slipping], res.slip[:, slipping]
    assert np.allclose(np.hypot(*tau), mu * pressure[slipping], rtol=1e-9)
    cosine = (tau * s).sum(0) / (np.hypot(*tau) * np.hypot(*s))
    assert cosine.max() < -1 + 1e-6
    row = res.stick[problem.grid.shape[0] // 2]
    cells = np.nonzero(res.contact[problem.grid.shape[0] // 2])[0]
    assert row[cells[-1]] and not row[cells[0]]


def test_warm_start_reaches_the_same_state_in_fewer_sweeps():
    problem, pressure = _ellipse(1.0, 0.25, 31)
    cold = solve_steady(problem, pressure, 0.3, xi=0.021)
    warm_from = solve_steady(problem, pressure, 0.3, xi=0.02)
    warm = solve_steady(problem, pressure, 0.3, xi=0.021, initial=warm_from.traction)
    assert warm.sweeps < cold.sweeps
    assert warm.force[0] == pytest.approx(cold.force[0], rel=1e-6)


def test_contact_at_the_leading_column_and_bad_input_are_refused():
    problem, pressure = _ellipse(1.0, 0.25, 11)
    edge = pressure.copy()
    edge[5, -1] = 1.0
    with pytest.raises(ContactEdgeError, match="leading|last column"):
        solve_steady(problem, edge, 0.3, xi=0.01)
    with pytest.raises(InputError, match="mu"):
        solve_steady(problem, pressure, 0.0, xi=0.01)
    with pytest.raises(InputError, match="xi"):
        solve_steady(problem, pressure, 0.3, xi=math.nan)
    with pytest.raises(InputError, match="pressure"):
        solve_steady(problem, -pressure, 0.3, xi=0.01)


def test_sweep_budget_exhausted_raises_convergence_error():
    problem, pressure = _ellipse(1.0, 0.25, 21)
    with pytest.raises(ConvergenceError, match="solve_steady"):
        solve_steady(problem, pressure, 0.3, xi=0.01, params=SteadyParams(max_sweeps=2))


def _carter_traction(x, a, s, mu_p0):
    """Carter's |tau_x|(x) (docs/theory.md §7.4) for creepage s = R|xi|/(mu a): stick zone of half-width c = a(1 - s)
    at the leading edge x = a."""
    c = a * (1.0 - s)
    tau = mu_p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    return tau - mu_p0 * (c / a) * np.sqrt(np.clip(1 - ((x - (a - c)) / c) ** 2, 0, None))


@pytest.fixture(scope="module")
def slender():
    """The ellipse a = 1 (rolling direction), b = 10 mm, nu = 0.25, mu = 0.3, 81 x 41 elements, solved at
    Carter's s = 0.2, 0.5, 0.8 at mid-length (s = xi E*/(2 mu p0), plane-strain E* = G/(1 - nu)), warm-started."""
    a, b, nu, mu = 1.0, 10.0, 0.25, 0.3
    grid = ellipse_grid(a, b, 81, 41)
    problem = SteadyRolling(grid, _pair(nu))
    pressure = hertz_pressure(grid, a, b, 1.0)
    p0 = 3.0 / (2 * math.pi * a * b)
    e_star = problem.materials.G / (1 - nu)
    out, previous = {}, None
    for s in (0.2, 0.5, 0.8):
        res = solve_steady(problem, pressure, mu, xi=s * 2 * mu * p0 / e_star, initial=previous)
        out[s], previous = res, res.traction
    return problem, pressure, mu, p0, out


@pytest.mark.parametrize("s", [0.2, 0.5, 0.8])
def test_carter_traction_and_stick_zone_at_mid_length(slender, s):
    """Mid-length row of the slender ellipse against Carter's 2-D traction: rms difference within 1.1 % of mu p0, as
    docs/creep_rolling.md states (measured 0.48 / 0.65 / 1.095 % at s = 0.2 / 0.5 / 0.8; the pointwise difference
    peaks at the stick/slip kink, 2.5-6.6 % in one cell), the stick zone one block at the leading edge with width 2c = 2a(1 - s) within 1.5 cells (measured
    within 0.5 cells), and the row's force ratio sum tau / (mu sum p) within 2 % of Carter's 1 - (1 - s)^2
    (measured +0.9 / +0.8 / +0.6 %)."""
    problem, pressure, mu, p0, results = slender
    res = results[s]
    j0 = problem.grid.index_of(0.0, 0.0)[0]
    x = problem.grid.x
    inside = pressure[j0] > 0
    tau = -res.traction[0, j0]
    carter = _carter_traction(x, 1.0, s, mu * p0)
    assert np.sqrt(np.mean((tau - carter)[inside] ** 2)) < 0.011 * mu * p0
    stick = np.nonzero(res.stick[j0])[0]
    assert stick[-1] == np.nonzero(inside)[0][-1] and np.all(np.diff(stick) == 1)
    assert abs(stick.size * problem.grid.dx - 2 * (1 - s)) <= 1.5 * problem.grid.dx
    ratio = tau.sum() / (mu * pressure[j0].sum())
    assert ratio == pytest.approx(1 - (1 - s) ** 2, rel=0.02)


def test_carter_total_force_follows_strip_theory(slender):
    """The whole slender ellipse: Fx/(mu Fn) against Carter applied strip by strip (each strip y has its own
    s(y) = s / sqrt(1 - y^2/b^2), saturated where s(y) >= 1), within 3 %: the three-dimensional excess of a b/a = 10
    ellipse (Kalker's C11 at a/b = 0.1 is 0.6 % above the plane-strain limit at nu = 0.25) plus the grid's
    (measured +1.3 / +0.9 / +0.3 % at s = 0.2 / 0.5 / 0.8)."""
    problem, pressure, mu, p0, results = slender
    fn = pressure.sum() * problem.grid.cell_area
    y = np.linspace(-10.0, 10.0, 40001)[1:-1]
    q = np.sqrt(1 - (y / 10.0) ** 2)
    for s, res in results.items():
        strip = np.minimum(s / q, 1.0)
        load = math.pi * 1.0 * q * p0 * q / 2  # strip load per unit length, half-width a q, peak p0 q
        expected = np.trapezoid(load * (1 - (1 - strip) ** 2), y) / np.trapezoid(load, y)
        assert -res.force[0] / (mu * fn) == pytest.approx(expected, rel=0.03)


@pytest.mark.slow
@pytest.mark.parametrize("ratio, nu", [(0.5, 0.0), (1.0, 0.25), (2.0, 0.5)])
def test_linear_limit_error_falls_with_refinement_to_1_percent_at_81_elements(ratio, nu):
    """From 41 to 81 elements across, with the staircase area error divided out (c^2 -> N_contact dA / pi; it is
    -0.55 % at 41, +0.31 % at 81 and not monotone in n), the error of C11, C22 against the table falls and is
    within 1 % at 81 (the issue's bound at ~80). Measured (benchmarks/creep_linear.py), area-corrected (C11, C22, C23)
    at 81: (+0.40, +0.40, +0.05), (+0.19, +0.39, -0.02), (+0.28, +0.97, +0.68) %; 21 -> 41 -> 81 falls at first order.
    Raw (not corrected): largest +1.38 % (C11 at a/b = 0.5, nu = 0.5, not tested here: area-corrected +1.07 %, and
    +0.92 % at n = 161, converging to +0.76 %: the table's entry 4.83 sits below its neighbours 4.82 and 4.91 at
    a/b = 0.4 and 0.6, docs/creep_rolling.md)."""
    table = kalker_coefficients(ratio, nu)
    errors = {}
    for n in (41, 81):
        problem, pressure = _ellipse(ratio, nu, n)
        area = (pressure > 0).sum() * problem.grid.cell_area / math.pi
        got = _linear_coefficients(ratio, nu, n)
        errors[n] = [got[0] / area / table[0] - 1, got[1] / area / table[1] - 1, got[2] / area ** 1.5 / table[2] - 1]
    for k in (0, 1):
        assert abs(errors[81][k]) < abs(errors[41][k])
    assert max(abs(e) for e in errors[81]) < 0.01


def test_displacements_match_the_direct_sum_and_the_coupling_of_the_bem_layer():
    """SteadyRolling's products (to 1e-12 of the largest value): the FFT product of the whole field (the operator's
    plans) equals the direct Toeplitz sum with the dense kernels the element sweeps use, and u1 - u2 from the
    pressure is minus the operator's substrate-convention coupling displacement (Kalker's K of a steel / aluminium
    pair, beta = 0.07)."""
    from scipy.signal import convolve2d
    from rollcontact.bem import HalfSpaceOperator
    grid = ellipse_grid(1.0, 0.7, 15)
    mats = MaterialPair.from_moduli(210e3, 0.28, 70e3, 0.33)
    problem = SteadyRolling(grid, mats)
    op = HalfSpaceOperator(grid, mats, coupling=True)
    rng = np.random.default_rng(3)
    tau = rng.standard_normal((2,) + grid.shape)
    ny, nx = grid.shape
    kxx, kxy, kyy = problem.kernels
    direct = [convolve2d(tau[0], ka) + convolve2d(tau[1], kb) for ka, kb in ((kxx, kxy), (kxy, kyy))]
    want = np.stack([d[ny - 1:2 * ny - 1, nx - 1:2 * nx - 1] for d in direct])
    assert np.abs(problem.displacement(tau) - want).max() < 1e-12 * np.abs(want).max()
    pressure = hertz_pressure(grid, 1.0, 0.7, 100.0)
    want = -op.tangential_from_pressure(pressure)
    assert np.abs(problem.pressure_displacement(pressure) - want).max() < 1e-12 * np.abs(want).max()
