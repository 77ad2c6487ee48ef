"""Warm starts of the tangential solver: from the previous traction, displacement (or the product memo) and
division (previous_region), the start placed on the force constraint, and the shifted preconditioner level on a
warm step; each must change the cost, not the answer (the step is a strictly convex program).

Scene of the seed (Table 1), fixtures `scene` (dx = dy = 0.2 mm) and `fine_scene` (0.1 mm) from conftest.py,
the seed's constants and checks from tangential_helpers.py. Units mm, N, MPa.
"""
import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.normal.normcg import solve_normal
from rollcontact.solver.tangential.shift import solve_tangential
from tangential_helpers import FN, MINDLIN, MU, R, check_invariants


def test_warm_start_after_small_load_change_is_cheap(scene):
    """f_t 0.5 -> 0.52 from the previous traction: the increment is small, so the warm-started solve costs far
    fewer products than the cold one (iterations count every op.tangential call)."""
    cold = scene.cattaneo(0.5)
    warm = solve_tangential(scene.op, scene.bound, cold.traction, force=(0.52 * MU * FN, 0.0))
    check_invariants(warm, scene.bound, scene.op, cold.traction, force=(0.52 * MU * FN, 0.0))
    assert warm.iterations < cold.iterations
    total = cold.shift_increment[0] + warm.shift_increment[0]
    assert abs(total / MINDLIN.shift(0.52) - 1) < 0.01


def test_displacement_is_exact_outside_the_contact_and_the_next_step_uses_it(scene):
    """A small unloading (f_t 0.5 -> 0.49) ends with every element in stick. The returned displacement must be
    A tau on the whole grid, outside the contact too: it is handed to the next step (memo, previous_displacement),
    whose contact may cover those elements. Before the fix the exterior kept the start's product (error 4e-2
    a_self max g) and the next step on the contact moved by one cell converged to a traction off by 4e-2 max g.
    Checked against the FFT product to round-off, and the next step against one with the memo cleared."""
    from rollcontact.solver.tangential import shift as T
    first = scene.cattaneo(0.5)
    F = (0.49 * MU * FN, 0.0)
    unload = solve_tangential(scene.op, scene.bound, first.traction, force=F)
    assert not np.any(unload.region == 2)
    exact = scene.op.tangential(unload.traction[0], unload.traction[1])
    a_self = max(scene.op.self_coefficients.values())
    assert np.abs(unload.displacement - exact).max() < 1e-12 * a_self * scene.bound.max()
    X, Y = scene.X, scene.Y
    g2 = MU * solve_normal(scene.op, (X ** 2 + (Y - scene.dx) ** 2) / (2 * R), force=FN).pressure
    nxt = solve_tangential(scene.op, g2, unload.traction, force=F)
    T._memo.clear()
    clean = solve_tangential(scene.op, g2, unload.traction, force=F)
    np.testing.assert_allclose(nxt.traction, clean.traction, rtol=0, atol=1e-7 * g2.max())


def test_previous_displacement_and_memo_give_the_same_step(scene):
    first = scene.cattaneo(0.5)
    g = scene.bound
    F = (0.52 * MU * FN, 0.0)
    given = solve_tangential(scene.op, g, first.traction, force=F, previous_displacement=first.displacement)
    computed = solve_tangential(scene.op, g, first.traction.copy() + 0.0, force=F,
                                previous_displacement=scene.op.tangential(*first.traction))
    np.testing.assert_allclose(given.shift_increment, computed.shift_increment, rtol=1e-7)
    np.testing.assert_allclose(given.traction, computed.traction, atol=1e-7 * g.max())


def test_start_placement_keeps_elements_on_the_bound_and_meets_the_force(scene):
    """The start is put on the force constraint by shifting only the elements inside their disc: elements on
    the bound stay on it (same traction), |tau| <= g everywhere and sum tau dA = F to round-off."""
    from rollcontact.solver.tangential import _division as K
    from rollcontact.solver.tangential._force_projection import place_on_force
    res = scene.cattaneo(0.5)
    g, dA = scene.bound, scene.grid.cell_area
    tau = res.traction.copy()
    on_bound = np.hypot(*tau) >= (1 - K.ON_BOUND) * g
    on_bound &= g > 0
    assert on_bound.sum() > 100  # the Cattaneo slip ring
    target = np.array([0.53 * MU * FN, 0.02 * MU * FN]) / dA  # a force the previous traction does not carry
    region = np.zeros(g.shape, np.int8)
    place_on_force(tau, g, target, region, np.zeros_like(tau), 1.0, 1.0)
    np.testing.assert_array_equal(tau[:, on_bound], res.traction[:, on_bound])
    np.testing.assert_allclose(tau.sum(axis=(1, 2)), target, rtol=0, atol=1e-12 * g.sum())
    assert np.all(np.hypot(*tau) <= g * (1 + 1e-12))


def test_previous_region_changes_the_start_not_the_solution(scene):
    """A step whose bound grew under the slip ring (pressure x 1.01, the force kept): with previous_region the
    slip elements start on the new bound instead of inside it. The step is a strictly convex program (A is
    positive definite), so both starts must reach the same traction and shift to the solver tolerance (1e-8
    of a_self max g, i.e. ~1e-7 relative after the conditioning of A), with Coulomb's law intact."""
    first = scene.cattaneo(0.5)
    g = 1.01 * scene.bound
    F = (0.5 * MU * FN, 0.0)
    plain = solve_tangential(scene.op, g, scene.zero, force=F, initial=first.traction)
    kept = solve_tangential(scene.op, g, scene.zero, force=F, initial=first.traction,
                            previous_region=first.region)
    check_invariants(kept, g, scene.op, scene.zero, force=F)
    assert kept.iterations < plain.iterations  # the point of it (measured 13 against 20 products)
    np.testing.assert_allclose(kept.traction, plain.traction, rtol=0, atol=1e-6 * g.max())
    np.testing.assert_allclose(kept.shift_increment, plain.shift_increment, rtol=0,
                               atol=1e-6 * abs(plain.shift_increment[0]))
    with pytest.raises(InputError, match="previous_region"):
        solve_tangential(scene.op, g, scene.zero, force=F, previous_region=first.region[:-1])


def test_force_projection_on_rims_keeps_slip_elements_on_their_bound(scene):
    """project_on_force with the region turns the slip tractions along their rims |tau| = g instead of pulling
    them inside (where they would count as stick): every slip element stays on its bound to round-off, the
    others stay in their discs, and the sum meets the force to the projection's tolerance (1e-10 sum g)."""
    from rollcontact.solver.tangential import _force_projection as FP
    res = scene.cattaneo(0.9)
    g, region = scene.bound, res.region
    assert (region == 2).sum() > 3 * (region == 1).sum()  # f_t = 0.9: a wide slip ring
    target = res.traction.sum(axis=(1, 2)) * np.array([0.97, 1.0]) + np.array([0.0, 0.05 * g.sum()])
    out = np.empty_like(res.traction)
    FP.project_on_force(res.traction, g, target, out, region)
    slip = region == 2
    np.testing.assert_allclose(np.hypot(*out)[slip], g[slip], rtol=1e-12)
    assert np.all(np.hypot(*out) <= g * (1 + 1e-12))
    np.testing.assert_allclose(out.sum(axis=(1, 2)), target, rtol=0, atol=1e-10 * g.sum())
    plain = np.empty_like(out)
    FP.project_on_force(res.traction, g, target, plain)  # the Euclidean projection pulls the ring inside
    assert np.count_nonzero(np.hypot(*plain)[slip] < g[slip] * (1 - 1e-9)) > 0.5 * slip.sum()


def test_profile_step_with_previous_region_converges_to_the_plain_solution(scene):
    """The contact moved by one cell with the previous division given (previous_region): before the turn line
    search this cycled for 500 products at 55^2 and 109^2 (305 products at 511^2). The step is a strictly convex
    program, so it must reach the solution of the plain start, with Coulomb's law and the force intact and a
    cost of the order of the plain start's (measured 21 against 19 products)."""
    first = scene.cattaneo(0.5)
    X, Y = scene.X, scene.Y
    g2 = MU * solve_normal(scene.op, (X ** 2 + (Y - scene.dx) ** 2) / (2 * R), force=FN).pressure
    F = (0.5 * MU * FN, 0.0)
    plain = solve_tangential(scene.op, g2, first.traction, force=F)
    kept = solve_tangential(scene.op, g2, first.traction, force=F, previous_region=first.region)
    check_invariants(kept, g2, scene.op, first.traction, force=F)
    assert kept.iterations <= 2 * plain.iterations
    np.testing.assert_allclose(kept.traction, plain.traction, rtol=0, atol=1e-6 * g2.max())
    np.testing.assert_allclose(kept.shift_increment, plain.shift_increment, rtol=0,
                               atol=1e-6 * abs(first.shift_increment[0]))


def test_shifted_preconditioner_levels_speed_up_the_warm_step_not_its_answer(fine_scene, monkeypatch):
    """The shifted preconditioner level (the circulant inverse of A + 4 a I for slip elements with moderate
    curvature, `solver.tangential._preconditioner`; by default only on contacts of 16000 elements and more, where it also
    saves time) switched on for the 109^2 grid (7221 contact elements). Same warm load step (f_t 0.5 -> 0.52)
    with it and with the two-term form alone: the same traction and shift to the solver tolerance (1e-8 of
    a_self max g: 1e-6 max g and 1e-6 relative leave room for the conditioning of A), Coulomb's law intact
    in both, and fewer products with the level (measured 17 against 22)."""
    from rollcontact.solver.tangential import _preconditioner as PC
    scene = fine_scene
    assert np.count_nonzero(scene.bound) < PC.MIN_CONTACT_ELEMENTS  # the default: two-term form here
    first = scene.cattaneo(0.5)
    F = (0.52 * MU * FN, 0.0)
    two_term = solve_tangential(scene.op, scene.bound, first.traction, force=F)
    monkeypatch.setattr(PC, "MIN_CONTACT_ELEMENTS", 0)
    shifted = solve_tangential(scene.op, scene.bound, first.traction, force=F)
    for res in (shifted, two_term):
        check_invariants(res, scene.bound, scene.op, first.traction, force=F)
    g = scene.bound.max()
    np.testing.assert_allclose(shifted.traction, two_term.traction, rtol=0, atol=1e-6 * g)
    np.testing.assert_allclose(shifted.shift_increment, two_term.shift_increment, rtol=0,
                               atol=1e-6 * abs(two_term.shift_increment[0]))
    assert shifted.iterations < two_term.iterations
