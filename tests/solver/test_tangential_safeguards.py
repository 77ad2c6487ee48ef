"""Inside the tangential iteration (`solver.tangential._tangcg.ProjectedTangCG`), driven by hand: the gradient phase of
safeguard 1, the lagged projected steps (one product, u exact, undone when they raise the energy) and the turns
of slip elements whose slip points along their traction (`flip_direction` / `apply_flip`, line search on the
step's energy).

Scene of the seed (Table 1), fixtures `scene` (dx = dy = 0.2 mm) and `fine_scene` (0.1 mm) from conftest.py,
the seed's constants and checks from tangential_helpers.py. Units mm, N, MPa.
"""
import math

import numpy as np
import pytest

from rollcontact.solver.normal.normcg import solve_normal
from rollcontact.solver.tangential.shift import TangentialParams, solve_tangential, traction_capacity
from tangential_helpers import FN, MU, R


def _iteration_at_start(scene, g, previous, f_cells, dU):
    """The iteration object of a step on the bound g (MPa) from the previous traction (MPa), with the prescribed
    force f_cells (MPa x elements) or, when None, the prescribed shift dU (mm): the start as `solve_tangential`
    makes it, u = A tau and u' = A tau' exact."""
    from rollcontact.solver.tangential import _force_projection as FP
    from rollcontact.solver.tangential._tangcg import ProjectedTangCG
    it = ProjectedTangCG(scene.op, g, np.asarray(dU, dtype=float), f_cells, None, TangentialParams(), str)
    ws = it.ws
    FP.start_traction(ws.tau, previous, g, f_cells, None, ws.region, ws.u, 1.0, 1.0)
    it.matvec(ws.tau, ws.u)
    it.matvec(previous, ws.u_prev)
    return it


def _stalled_start(scene, force_mode):
    """The iteration object at the start of the turned-load step of test_tangential_near_bound.py
    (test_warm_start_far_from_a_turned_load_near_the_bound_converges), with the start as its best iterate."""
    capacity = traction_capacity(scene.bound, scene.grid)
    first = scene.cattaneo(0.75)
    dA = scene.grid.cell_area
    f_cells = np.array([math.cos(1.0), math.sin(1.0)]) * 0.99 * capacity / dA if force_mode else None
    it = _iteration_at_start(scene, scene.bound, first.traction, f_cells, [0.0, 0.0] if force_mode else [0.3, 0.4])
    it.tau_best, it.u_best = it.ws.tau.copy(), it.ws.u.copy()
    return it, first.traction


@pytest.mark.parametrize("force_mode", [True, False])
def test_gradient_phase_lowers_the_energy_and_leaves_u_exact(scene, force_mode):
    """Safeguard 1's gradient phase (FISTA with adaptive restart, step 1/L with L = op.tangential_norm): from the
    start of the turned-load step (prescribed force), or a prescribed shift, 20 steps must lower the step's energy
    1/2 (tau - tau') A (tau - tau') (- dU.sum tau for a prescribed shift), keep |tau| <= g and the force to round-off,
    and leave u = A tau exact (its products are tracked by linear combination)."""
    it, previous = _stalled_start(scene, force_mode)
    ws = it.ws

    def energy(tau):
        d = tau - previous
        j = 0.5 * float(np.sum(d * scene.op.tangential(d[0], d[1])))
        return j if force_mode else j - float(it.dU @ tau.sum(axis=(1, 2)))

    before = energy(ws.tau)
    products = it.products
    it.gradient_phase(20)
    assert it.products == products + 20
    assert energy(ws.tau) < before - 1e-3 * abs(before)
    exact = scene.op.tangential(ws.tau[0], ws.tau[1])
    a_self = max(scene.op.self_coefficients.values())
    assert np.abs(ws.u - exact).max() < 1e-10 * a_self * scene.bound.max()
    assert np.all(np.hypot(*ws.tau) <= scene.bound * (1 + 1e-12))
    if force_mode:
        np.testing.assert_allclose(ws.tau.sum(axis=(1, 2)), it.f_cells, rtol=0, atol=1e-10 * scene.bound.sum())


def _moved_contact_start(scene):
    """The iteration object at the start of a profile step: from the state at f_t = 0.5, the contact moved by
    one cell in y at the same force (the warm profile step of benchmarks/tangential_cattaneo.py)."""
    g = MU * solve_normal(scene.op, (scene.X ** 2 + (scene.Y - scene.dx) ** 2) / (2 * R), force=FN).pressure
    f_cells = np.array([0.5 * MU * FN / scene.grid.cell_area, 0.0])
    return _iteration_at_start(scene, g, scene.cattaneo(0.5).traction, f_cells, [0.0, 0.0]), g


@pytest.mark.parametrize("case", ["moved contact, force", "turned load, shift"])
def test_lagged_steps_cost_one_product_and_leave_u_exact(scene, case):
    """While the previous CG step clipped elements, the next step is a projected step along the preconditioned
    residual with the lagged step length (`ProjectedTangCG.lagged_step`): one product instead of two. Each such
    step must keep |tau| <= g, put the force back to round-off (prescribed force) and leave u = A tau exact,
    because the residual that decides the next step is computed from u. Driven by hand through evaluate /
    cg_step for 30 steps from the start of a profile step (prescribed force) and of the turned-load step with
    a prescribed shift; both identify the division through chains of projection events."""
    if case.endswith("force"):
        it, g = _moved_contact_start(scene)
    else:
        it, g = _stalled_start(scene, False)[0], scene.bound
    ws = it.ws
    a_self = max(scene.op.self_coefficients.values())
    lagged = 0
    for _ in range(30):
        r = it.evaluate()
        if not it.lag_due(r):
            it.cg_step(r)
            continue
        products = it.products
        it.cg_step(r)
        assert it.lagging  # not undone here (test_a_lagged_step_that_raises_the_energy_is_undone)
        lagged += 1
        assert it.products == products + 1
        exact = scene.op.tangential(ws.tau[0], ws.tau[1])
        assert np.abs(ws.u - exact).max() < 1e-12 * a_self * g.max()
        assert np.all(np.hypot(*ws.tau) <= g * (1 + 1e-12))
        if it.force_mode:
            np.testing.assert_allclose(ws.tau.sum(axis=(1, 2)), it.f_cells, rtol=0, atol=1e-10 * g.sum())
    assert lagged >= 3


def test_a_lagged_step_that_raises_the_energy_is_undone(scene):
    """The lagged step is not monotone: near the bound its fixed length can overshoot. Such a step must be
    undone (traction and u as before it) and end the lagged steps of the solve. Case from the fuzz campaign
    (benchmarks/tangential_fuzz.py, seed 202400244): previous state f_t = 0.7383 at 2.954 rad, bound scaled by
    1.034, load f_t = 0.9872 at 4.569 rad; the third lagged step raised the energy 1/2 (tau - tau') A (tau - tau')
    (without the check near_bound cases of the campaign took up to 72 products instead of 52)."""
    capacity = traction_capacity(scene.bound, scene.grid)
    F = (0.7383 * capacity * math.cos(2.954), 0.7383 * capacity * math.sin(2.954))
    previous = solve_tangential(scene.op, scene.bound, scene.zero, force=F).traction
    g = 1.034 * scene.bound
    f_cells = np.array([math.cos(4.569), math.sin(4.569)]) * 0.9872 * 1.034 * capacity / scene.grid.cell_area
    it = _iteration_at_start(scene, g, previous, f_cells, [0.0, 0.0])
    ws = it.ws

    def energy(tau):
        d = tau - previous
        return 0.5 * float(np.sum(d * scene.op.tangential(d[0], d[1])))

    undone = False
    for _ in range(20):
        r = it.evaluate()
        lagged = it.lag_due(r)
        before, tau_before, u_before, synced = energy(ws.tau), ws.tau.copy(), ws.u.copy(), it.synced
        it.cg_step(r)
        if lagged:
            assert energy(ws.tau) <= before
            if not it.lagging:  # undone: the state before the step, with its u and whether u was exact
                np.testing.assert_array_equal(ws.tau, tau_before)
                np.testing.assert_array_equal(ws.u, u_before)
                assert it.synced == synced
                undone = True
                break
    assert undone, "no lagged step was undone in this case (it was the third one when the case was found)"


def test_turn_direction_selects_only_large_reversed_slips():
    """`flip_direction` marks a slip element for turning against its slip when the slip points along the traction
    and exceeds big g; smaller reversed slips (left to the release rule) and stick elements get no direction. At
    t = 1 `apply_flip` puts the element on its rim opposite to the slip, u changes by the self coefficients
    times the traction change (exact = False), and at t < 1 the element lies inside its disc, in stick."""
    from rollcontact.solver.tangential import _moves as K
    g = np.array([[1.0, 1.0, 2.0]])
    region = np.array([[2, 2, 1]], np.int8)
    tau0 = np.array([[[1.0, 0.0, 0.5]], [[0.0, 1.0, 0.0]]])
    nrm = tau0 / g
    w = np.array([[[3.0, 0.0, 5.0]], [[0.5, 0.01, 5.0]]])  # element 0: s.n = 3 > 0, |s| = 3.04 > 2 g
    d = np.full_like(w, np.nan)
    n, cx, cy = K.flip_direction(tau0, nrm, g, region, w, 0.0, 0.0, 2.0, d)
    s0 = w[:, 0, 0]
    target = -g[0, 0] * s0 / np.hypot(*s0)
    assert n == 1 and (cx, cy) == tuple(target - tau0[:, 0, 0])
    assert not np.any(d[:, 0, 1:])
    tau, u = tau0.copy(), np.zeros_like(w)
    assert K.apply_flip(tau, d, 1.0, u, np.zeros_like(w), False, g, region.copy(), 0.3, 0.4) == 0
    np.testing.assert_allclose(tau[:, 0, 0], target)
    np.testing.assert_allclose(np.hypot(*tau[:, 0, 0]), g[0, 0])
    np.testing.assert_array_equal(tau[:, 0, 1:], tau0[:, 0, 1:])
    np.testing.assert_allclose(u[:, 0, 0], [0.3 * d[0, 0, 0], 0.4 * d[1, 0, 0]])
    assert not np.any(u[:, 0, 1:])
    reg = region.copy()
    tau = tau0.copy()
    K.apply_flip(tau, d, 0.5, np.zeros_like(w), np.zeros_like(w), False, g, reg, 0.3, 0.4)
    assert reg[0, 0] == 1 and np.hypot(*tau[:, 0, 0]) < g[0, 0]


def _energy(op, tau, tau_prev):
    """The step's energy 1/2 (tau - tau') A (tau - tau') (MPa mm per element; the force term is constant on the
    force constraint)."""
    d = tau - tau_prev
    return 0.5 * float(np.sum(d * op.tangential(d[0], d[1])))


@pytest.mark.parametrize("dense", [False, True])
def test_turns_of_reversed_slips_never_raise_the_energy(scene, dense, monkeypatch):
    """The start of a profile step with previous_region (the contact moved by one cell, the previous slip ring
    put on the new bound) has 67 slip elements whose slip points along their traction and exceeds 2 a_self g.
    Turned whole and all at once they raised the step's energy threefold and the solve cycled; with the line
    search on the energy (docs/theory.md §5.1: the step is a convex program, so a turn that is a descent step must lower
    it) the energy falls, and the force is kept to round-off. Both curvature paths: one product (67^2 > 55^2
    elements) and the dense block of the turned elements (DENSE_TURNS raised to take 67 turns)."""
    from rollcontact.solver.tangential import _force_projection as FP
    from rollcontact.solver.tangential import _tangcg as C
    from rollcontact.solver.tangential import _division as K
    from rollcontact.solver.tangential._tangcg import ProjectedTangCG
    monkeypatch.setattr(C, "DENSE_TURNS", 10.0 if dense else 1.0)
    first = scene.cattaneo(0.5)
    X, Y = scene.X, scene.Y
    g2 = MU * solve_normal(scene.op, (X ** 2 + (Y - scene.dx) ** 2) / (2 * R), force=FN).pressure
    f_cells = np.array([0.5 * MU * FN, 0.0]) / scene.grid.cell_area
    it = ProjectedTangCG(scene.op, g2, np.zeros(2), f_cells, None, TangentialParams(), str)
    ws = it.ws
    FP.start_traction(ws.tau, first.traction, g2, f_cells, first.region, ws.region, ws.u, 1.0, 1.0)
    it.matvec(ws.tau, ws.u)
    it.matvec(first.traction, ws.u_prev)
    it.n_stick, _, *gram = K.classify(ws.tau, g2, ws.region, ws.nrm, ws.u, ws.u_prev, ws.w, False, ws.w)
    it.fit_shift(*gram)
    before = _energy(scene.op, ws.tau, first.traction)
    assert it.turn_reversed() > 50
    assert _energy(scene.op, ws.tau, first.traction) < before
    np.testing.assert_allclose(ws.tau.sum(axis=(1, 2)), f_cells, rtol=0, atol=1e-12 * g2.sum())
    assert np.all(np.hypot(*ws.tau) <= g2 * (1 + 1e-12))
