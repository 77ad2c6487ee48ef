"""The fast models of solver/fastsim against what they are built on: Kalker's creep coefficients in the linear range
(docs/theory.md §7.3), Coulomb's bound and full sliding at mu Fn, Carter's two-dimensional solution for FaStrip's strips
(docs/theory.md §7.4), the steady state as the limit of transient rolling, and the exact theory where the literature says
FaStrip is the closer model (docs/creep_fidelity.md). Kalker's convention: forces on body 1, opposing the creepages.
Identical bodies with G = 1 MPa, Hertz pressure on the ellipse's cells (solver.creep.ellipse_grid), c = sqrt(ab) = 1.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from rollcontact.bem import MaterialPair
from rollcontact.bem.errors import ContactEdgeError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.creep import SteadyRolling, ellipse_grid, hertz_pressure, kalker_coefficients, solve_steady
from rollcontact.solver.fastsim import (FastsimRolling, ellipse_edges, ellipse_pressure, fast_patch,
                                        kalker_flexibilities, solve_fastrip, solve_fastsim, strip_edges)

SOLVERS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}


def _ellipse(ratio, n=61, normal_force=1.0):
    a, b = math.sqrt(ratio), 1.0 / math.sqrt(ratio)
    grid = ellipse_grid(a, b, n)
    return grid, hertz_pressure(grid, a, b, normal_force), a, b


@pytest.mark.parametrize("model", ["fastsim", "fastrip"])
@pytest.mark.parametrize("ratio", [0.2, 0.5, 1.0, 2.0, 5.0])
@pytest.mark.parametrize("nu", [0.0, 0.28, 0.5])
def test_linear_range_equals_kalker_coefficients_to_half_a_percent(model, ratio, nu):
    """Both models are calibrated on C11, C22, C23 (FASTSIM's L1, L2, L3; FaStrip's strip stiffnesses): with a bound
    that never binds, -Fx/(G c^2 xi), -Fy/(G c^2 eta) and -Fy/(G c^3 phi) equal the table to 0.5 % at 61 elements
    across the ellipse (measured: FASTSIM +0.33 / +0.33 / +0.16 %, FaStrip +0.14 / +0.14 / +0.13 %, the strips'
    edges extrapolated from the cell pressures; the error falls with the grid: FASTSIM's xi +1.45 % at 23, +0.11 % at
    121)."""
    grid, pressure, a, b = _ellipse(ratio)
    flex = kalker_flexibilities(a, b, 1.0, nu)
    solve = SOLVERS[model]
    got = []
    for creep, comp in (((1e-3, 0, 0), 0), ((0, 1e-3, 0), 1), ((0, 0, 1e-3), 1)):
        res = solve(grid, pressure, 1e6, *creep, flexibilities=flex)
        assert not (res.region == 2).any()                      # the bound never binds: the linear range
        got.append(-res.force[comp] / 1e-3)
    assert got == pytest.approx(kalker_coefficients(ratio, nu), rel=0.005)


@pytest.mark.parametrize("model", ["fastsim", "fastrip"])
@pytest.mark.parametrize("creep", [(1, 0, 0), (0, 1, 0), (0.6, -0.8, 0), (-0.3, 0.9, 0)])
def test_full_sliding_saturates_at_mu_fn_within_a_tenth_of_a_percent(model, creep):
    """At 50 times the saturation creepage (xi* = mu Fn / (G c^2 C11), and C22 for eta) the whole contact slides:
    |F| = mu Fn (Fn = sum p dA) within 0.1 % (measured: to rounding, every cell on its bound), opposite to
    the rigid slip."""
    grid, pressure, a, b = _ellipse(2.0, 41)
    mu, fn = 0.3, pressure.sum() * grid.cell_area
    c11, c22, c23 = kalker_coefficients(2.0, 0.28)
    scale = 50 * mu * fn
    xi, eta, phi = creep[0] * scale / c11, creep[1] * scale / c22, creep[2] * scale / c23
    res = SOLVERS[model](grid, pressure, mu, xi, eta, phi, flexibilities=kalker_flexibilities(a, b, 1.0, 0.28))
    assert math.hypot(*res.force) == pytest.approx(mu * fn, rel=1e-3)
    assert np.dot(res.force, (xi, eta)) == pytest.approx(-math.hypot(*res.force) * math.hypot(xi, eta), rel=1e-9)


@pytest.mark.parametrize("model", ["fastsim", "fastrip"])
def test_full_sliding_with_spin_is_mu_p_against_the_rigid_slip(model):
    """With spin the slip direction turns over the contact: in full sliding the traction is mu p against
    w = (xi - phi y, eta + phi x) everywhere once the rigid slip of one cell's path far exceeds the bound's
    spring displacement (5000 times the saturation creepage; spin pole outside the contact). FASTSIM takes w at the
    middle of the material's path into each cell, half a cell upstream of its centre: with w there the forces equal
    mu p against w summed over the cells within 0.1 % of mu Fn (measured 0.02 %; with w at the centres 1 %, the
    spin turning w by a few degrees per cell), below mu Fn."""
    grid, pressure, a, b = _ellipse(2.0, 41)
    mu, fn = 0.3, pressure.sum() * grid.cell_area
    c11, c22, c23 = kalker_coefficients(2.0, 0.28)
    xi, eta, phi = (5000 * mu * fn * f for f in (0.5 / c11, 0.5 / c22, 0.2 / c23))
    res = SOLVERS[model](grid, pressure, mu, xi, eta, phi, flexibilities=kalker_flexibilities(a, b, 1.0, 0.28))
    X, Y = grid.mesh()
    w = np.stack([xi - phi * Y, eta + phi * (X + 0.5 * grid.dx)])
    expected = (-mu * pressure * w / np.hypot(*w)).sum(axis=(1, 2)) * grid.cell_area
    assert not (res.region == 1).any()
    assert np.abs(np.subtract(res.force, expected)).max() < 1e-3 * mu * fn
    assert math.hypot(*res.force) < 0.995 * mu * fn


@settings(max_examples=40, deadline=None)
@given(ratio=st.floats(0.2, 5.0), mu=st.floats(0.05, 2.0), xi=st.floats(-3, 3), eta=st.floats(-3, 3),
       phi=st.floats(-3, 3), model=st.sampled_from(["fastsim", "fastrip"]))
def test_traction_never_exceeds_its_bound(ratio, mu, xi, eta, phi, model):
    """Coulomb: |tau| <= mu p in every cell (to rounding), for creepages from the linear range to full sliding
    (given in saturation units) and any ellipse; zero traction and slip outside the contact."""
    grid, pressure, a, b = _ellipse(ratio, 21)
    c11, c22, c23 = kalker_coefficients(ratio, 0.28)
    fn = pressure.sum() * grid.cell_area
    res = SOLVERS[model](grid, pressure, mu, xi * mu * fn / c11, eta * mu * fn / c22, phi * mu * fn / c23,
                         flexibilities=kalker_flexibilities(a, b, 1.0, 0.28))
    assert np.all(np.hypot(*res.traction) <= mu * pressure * (1 + 1e-12))
    outside = pressure <= 0
    assert not res.traction[:, outside].any() and not res.slip[:, outside].any()
    assert np.all(np.isfinite(res.traction)) and np.all(np.isfinite(res.slip))


def test_fastsim_slip_vanishes_in_stick_and_opposes_the_traction_in_slip():
    """The simplified theory's Coulomb conditions: s = 0 where |tau| < mu p; |tau| = mu p and tau = -mu p s/|s| where
    it slips (the implicit step projects the trial traction on the bound)."""
    grid, pressure, a, b = _ellipse(1.0, 41)
    res = solve_fastsim(grid, pressure, 0.3, 0.02, 0.01, 0.05, flexibilities=kalker_flexibilities(a, b, 1.0, 0.28))
    stick, slip = res.region == 1, res.region == 2
    assert stick.any() and slip.any()
    assert not res.slip[:, stick].any()
    tau, s = res.traction[:, slip], res.slip[:, slip]
    assert np.allclose(np.hypot(*tau), 0.3 * pressure[slip], rtol=1e-12)
    cosine = (tau * s).sum(axis=0) / (np.hypot(*tau) * np.hypot(*s))
    assert np.allclose(cosine, -1.0, atol=1e-9)


@pytest.mark.parametrize("step_cells", [1, 2])
def test_transient_fastsim_rolls_into_the_steady_state(step_cells):
    """Rolled on a world-fixed grid from rest in steps of one (two) elements, the traction of each material point is
    the steady recursion's once the contact has passed over it: after 1.5 contact lengths the transient traction
    equals steady FASTSIM on the same cells to rounding (step = dx), and for step = 2 dx within 2 % of mu p0 (the
    same integral taken over twice the path per step: the rate is linear in x, so the steps sum it exactly; only the
    leading cells' first step differs)."""
    a = b = 1.0
    n = 31
    dx = 2 * a / n
    rolled = step_cells * dx * math.ceil(3.0 * a / (step_cells * dx))
    world = Grid.covering(-a - 2 * dx, rolled + a + 2 * dx, -b - dx, b + dx, dx, dx)
    flex = kalker_flexibilities(a, b, 1.0, 0.28)
    mu, creep = 0.3, (2e-3, 1e-3, 4e-3)
    X, Y = world.mesh()

    def pressure(centre):
        return np.where((X - centre) ** 2 + Y ** 2 < 1, 3 / (2 * math.pi) * np.sqrt(
            np.clip(1 - (X - centre) ** 2 - Y ** 2, 0, None)), 0.0)

    rolling = FastsimRolling(world, mu, *creep, flexibilities=flex)
    rolling.at_rest(pressure(0.0))
    steps = round(rolled / (step_cells * dx))
    for k in range(1, steps + 1):
        state = rolling.step(pressure(k * step_cells * dx), k * step_cells * dx, step_cells * dx)
    centre = steps * step_cells * dx
    # the steady model on the cells of the contact-fixed grid at the final centre
    fixed = Grid(world.nx, world.ny, dx, dx, world.i0 - round(centre / dx), world.j0)
    steady = solve_fastsim(fixed, pressure(centre), mu, *creep, flexibilities=flex)
    tol = 1e-12 if step_cells == 1 else 0.02 * mu * 3 / (2 * math.pi)
    assert np.abs(state.traction - steady.traction).max() <= tol
    assert state.force == pytest.approx(steady.force, rel=1e-9 if step_cells == 1 else 0.02)


def test_fastsim_transient_at_rest_is_the_simplified_cattaneo_state():
    """At rest under the rigid slip of one step the simplified theory's springs each take -step w / L, cut at mu p:
    a uniform traction in the linear range (Cattaneo's shape in the simplified theory), total -A step xi / L."""
    grid, pressure, a, b = _ellipse(1.0, 31)
    flex = kalker_flexibilities(a, b, 1.0, 0.28)
    rolling = FastsimRolling(grid, 1e6, 1e-3, 0.0, 0.0, flexibilities=flex)
    state = rolling.at_rest(pressure, 0.0, step=0.1)
    contact = pressure > 0
    assert np.allclose(state.traction[0][contact], -0.1 * 1e-3 / flex.L1, rtol=1e-12)
    assert state.force[0] == pytest.approx(-0.1 * 1e-3 / flex.L1 * contact.sum() * grid.cell_area, rel=1e-12)


def _carter_traction(x, a, s, mu_p0):
    """Carter's |tau_x|(x) (docs/theory.md §7.4): stick zone of half-width c = a (1 - s) at the leading edge x = a."""
    c = a * (1.0 - s)
    tau = mu_p0 * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    return tau - mu_p0 * (c / a) * np.sqrt(np.clip(1 - ((x - (a - c)) / c) ** 2, 0, None))


@pytest.mark.parametrize("s", [0.2, 0.5, 0.8])
def test_fastrip_strip_is_carters_two_dimensional_solution(s):
    """On a slender ellipse (a = 1, b = 10 mm, nu = 0.25) FaStrip's mid-length strip is Carter's rolling cylinder
    with the plane-strain creep coefficient (C11 at a/b = 0.1 is 0.6 % above it, pi^2 / (4 (1 - nu))): rms traction
    within 1 % of mu p0 (the cells' averages against Carter's point values), the stick zone at the leading edge of
    width 2 a (1 - s) within one cell, the row's force ratio within 1 % of 1 - (1 - s)^2, where the exact solver is
    allowed 2 % (tests/solver/test_creep_steady.py)."""
    a, b, nu, mu = 1.0, 10.0, 0.25, 0.3
    grid = ellipse_grid(a, b, 81, 41)
    pressure = hertz_pressure(grid, a, b, 1.0)
    p0 = 3.0 / (2 * math.pi * a * b)
    G = 1.0
    xi = s * 2 * mu * p0 * (1 - nu) / G
    res = solve_fastrip(grid, pressure, mu, xi, flexibilities=kalker_flexibilities(a, b, G, nu))
    j0 = grid.index_of(0.0, 0.0)[0]
    inside = pressure[j0] > 0
    tau = -res.traction[0, j0]
    carter = _carter_traction(grid.x, a, s, mu * p0)
    assert np.sqrt(np.mean((tau - carter)[inside] ** 2)) < 0.01 * mu * p0
    stick = np.nonzero(res.region[j0] == 1)[0]
    assert stick[-1] == np.nonzero(inside)[0][-1] and np.all(np.diff(stick) == 1)
    assert abs(stick.size * grid.dx - 2 * a * (1 - s)) <= grid.dx
    assert tau.sum() / (mu * pressure[j0].sum()) == pytest.approx(1 - (1 - s) ** 2, rel=0.01)


_CURVES = {}


def _curve_errors(ratio, case):
    """nu = 0.28, mu = 0.3, 31 elements across the ellipse a/b = ratio: the exact steady solver and both fast models
    over fractions 0.1 ... 2 of the saturation creepage, for pure xi, pure eta, and eta with spin adding to it
    (phi / phi* = eta / eta* / 2); the force error |F - F_exact| / |F_exact| of each model per point (cached)."""
    if (ratio, case) in _CURVES:
        return _CURVES[ratio, case]
    nu, mu = 0.28, 0.3
    grid, pressure, a, b = _ellipse(ratio, 31)
    pair = MaterialPair.from_moduli(2 * (1 + nu), nu, 2 * (1 + nu), nu)
    problem, flex = SteadyRolling(grid, pair), kalker_flexibilities(a, b, 1.0, nu)
    c11, c22, c23 = kalker_coefficients(ratio, nu)
    mu_fn = mu * pressure.sum() * grid.cell_area
    unit = {"xi": (1 / c11, 0, 0), "eta": (0, 1 / c22, 0), "eta+phi": (0, 1 / c22, 0.5 / c23)}[case]
    rows = {"fastsim": [], "fastrip": []}
    previous = None
    for f in (0.1, 0.3, 0.6, 1.0, 2.0):
        creep = [f * mu_fn * u for u in unit]
        exact = solve_steady(problem, pressure, mu, *creep, initial=previous)
        previous = exact.traction
        for model, solve in SOLVERS.items():
            got = solve(grid, pressure, mu, *creep, flexibilities=flex)
            rows[model].append(np.hypot(*np.subtract(got.force, exact.force)) / np.hypot(*exact.force))
    _CURVES[ratio, case] = rows
    return rows


@pytest.mark.parametrize("ratio, case", [(0.2, "xi"), (1.0, "xi"), (5.0, "xi"), (0.2, "eta"), (1.0, "eta"),
                                         (5.0, "eta"), (0.5, "eta+phi"), (1.0, "eta+phi"), (5.0, "eta+phi")])
def test_fastrip_is_closer_to_the_exact_theory_than_fastsim(ratio, case):
    """Sichani, Enblom & Berg (2016) report FaStrip's creep forces closer to the exact theory than FASTSIM's, the
    largest gain with lateral creepage and spin together: the largest error over the curve is smaller for FaStrip in
    pure xi and eta at a/b = 0.2, 1, 5 and with spin adding to eta at a/b = 0.5, 1, 5 (measured on the circle: xi FASTSIM
    5.8 %, FaStrip 0.8 %; eta + phi 22 % and 1.9 %). Not where FaStrip's strips meet spin across a wide contact:
    a/b = 0.2 with eta + phi FASTSIM is the closer (docs/creep_fidelity.md). FASTSIM's error stays in the 5-25 % the
    literature quotes for it without spin."""
    errors = _curve_errors(ratio, case)
    assert max(errors["fastrip"]) < max(errors["fastsim"])
    if case != "eta+phi":
        assert 0.02 < max(errors["fastsim"]) < 0.25


def test_fast_patch_from_semi_axes_equals_the_grid_call():
    """The patch entry point with semi-axes builds the strip grid, Hertz's pressure and the exact strip edges: the
    same state as the grid call with those arrays; and a grid with a pressure takes the equivalent ellipse."""
    kw = dict(creepages=(1e-3, -2e-3, 0.01), mu=0.3, G=8e4, nu=0.28)
    patch = fast_patch("fastrip", semi_axes=(6.0, 4.0), normal_force=1e5, elements=30, **kw)
    grid = ellipse_grid(6.0, 4.0, 30)
    pressure = ellipse_pressure(grid, 6.0, 4.0, 1e5)
    direct = solve_fastrip(grid, pressure, 0.3, 1e-3, -2e-3, 0.01, flexibilities=kalker_flexibilities(6, 4, 8e4, 0.28),
                           edges=ellipse_edges(grid, 6.0, 4.0, pressure > 0))
    assert np.array_equal(patch.state.traction, direct.traction) and patch.grid == grid
    again = fast_patch("fastrip", grid=grid, pressure=pressure, **kw)
    assert again.semi_axes == pytest.approx((6.0, 4.0), rel=0.05)
    assert again.state.force == pytest.approx(direct.force, rel=0.05)


def test_bad_input_is_refused():
    """Refused before any work: a contact touching the grid's first or last column, no contact, mu <= 0 or infinite,
    a non-finite creepage, a pressure of the wrong shape, an unknown model or flexibility, FaStrip on the parabola."""
    grid, pressure, a, b = _ellipse(1.0, 21)
    flex = kalker_flexibilities(a, b, 1.0, 0.28)
    with pytest.raises(ContactEdgeError):
        solve_fastsim(grid, np.ones(grid.shape), 0.3, 1e-3, flexibilities=flex)
    for kwargs, match in ((dict(pressure=np.zeros(grid.shape)), "no cell"), (dict(mu=0.0), "mu"),
                          (dict(mu=math.inf), "mu"), (dict(xi=math.nan), "xi"),
                          (dict(pressure=np.ones((3, 3))), "shape")):
        args = dict(pressure=pressure, mu=0.3, xi=1e-3) | kwargs
        with pytest.raises(InputError, match=match):
            solve_fastsim(grid, args["pressure"], args["mu"], args["xi"], flexibilities=flex)
    with pytest.raises(InputError, match="flexibility"):
        solve_fastsim(grid, pressure, 0.3, 1e-3, flexibilities=flex, flexibility="two")
    with pytest.raises(InputError, match="model"):
        fast_patch("polach", semi_axes=(1, 1), normal_force=1, creepages=(0, 0, 0), mu=0.3, G=1, nu=0.3)
    with pytest.raises(InputError, match="parabolic"):
        fast_patch("fastrip", semi_axes=(1, 1), normal_force=1, creepages=(0, 0, 0), mu=0.3, G=1, nu=0.3,
                   bound="parabolic")
    with pytest.raises(InputError, match="semi-axes"):
        kalker_flexibilities(-1.0, 1.0, 1.0, 0.3)


def test_strip_edges_of_a_hertz_pressure_are_second_order_accurate():
    """p^2 of a Hertzian row is quadratic in x; extrapolating it linearly to zero from the two outermost cells puts
    each edge within dx^2 / l of the ellipse's (l the row's half-length; measured 0.87-0.92 dx^2 / l on 21, 41 and
    81 elements across a circle, rows of at least 3 cells)."""
    for n in (21, 41, 81):
        grid, pressure, a, b = _ellipse(1.0, n)
        lead, trail = strip_edges(grid, pressure)
        exact_lead, exact_trail = ellipse_edges(grid, a, b, pressure > 0)
        rows = (pressure > 0).sum(axis=1) >= 3
        half = np.nanmax(exact_lead, axis=1)[rows]
        for got, exact in ((lead, exact_lead), (trail, exact_trail)):
            error = np.nanmax(np.abs(got - exact), axis=1)[rows]
            assert np.all(error <= grid.dx ** 2 / half)
