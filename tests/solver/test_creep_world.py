"""Transient rolling on the world-fixed grid (solver/creep/world.py) against the steady state (solver/creep/steady.py):
the issue's check that the two formulations agree, forces within 0.5 % after several contact lengths. Steel on
steel, a sphere R = 40 mm under Fn = 1000 N (Hertz a = 0.641 mm), mu = 0.3, 21 elements across the contact, the
profile shifted by one element per step; the steady reference on a contact-fixed grid of the same cells."""
import math

import numpy as np
import pytest

from rollcontact.bem import HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import ContactEdgeError, GrossSlidingError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.creep import SteadyParams, SteadyRolling, roll_world, solve_for_forces, solve_steady
from rollcontact.solver.normal import solve_normal
from rollcontact.solver.rolling import QuadricProfile

MATS = MaterialPair.from_moduli(210e3, 0.28, 210e3, 0.28)
R, FN, MU, N = 40.0, 1000.0, 0.3, 21
A = (3 * FN * R * 2 * (1 - 0.28 ** 2) / (4 * 210e3)) ** (1 / 3)
DX = 2 * A / N
PROFILE = QuadricProfile(R, R)


def world_grid(lengths):
    """The world-fixed grid for `lengths` contact lengths (2a) rolled along +x, two free cells around the contact."""
    m = 2 * DX
    return Grid.covering(-A - m, 2 * A * lengths + A + m, -A - m, A + m, DX, DX)


@pytest.fixture(scope="module")
def world4():
    return HalfSpaceOperator(world_grid(4), MATS)


@pytest.fixture(scope="module")
def steady_problem():
    grid = world_grid(0)
    normal = solve_normal(HalfSpaceOperator(grid, MATS), PROFILE(*grid.mesh()), force=FN)
    return SteadyRolling(grid, MATS), normal.pressure


def roll(op, lengths, **kw):
    return list(roll_world(op, PROFILE, Fn=FN, mu=MU, distance=2 * A * lengths, step=DX, **kw))


@pytest.mark.parametrize("creep", [(1e-3, 0.0, 0.0), (5e-4, 3e-4, 2e-4), (0.0, 0.0, 3e-3)],
                         ids=["xi_partial_slip", "xi_eta_phi", "pure_spin"])
def test_world_fixed_transient_converges_to_the_steady_forces(world4, steady_problem, creep):
    """Rolled 4 contact lengths (84 steps of dx) from rest: Fx, Fy and Mz within 0.5 % (the issue's bound) of the
    steady state, relative to |F| (|Mz| for the moment): measured 0.10 / 0.15 / 0.07 % and 0.05 % for Mz; the
    deficit falls about 6x per contact length (the memory of the start leaves the contact with its material). The
    states are in partial slip (0 < stick < contact) and Fx approaches its steady value monotonically from below."""
    problem, pressure = steady_problem
    steady = solve_steady(problem, pressure, MU, *creep, params=SteadyParams(tol=1e-9))
    steps = roll(world4, 4, xi=creep[0], eta=creep[1], phi=creep[2])
    last = steps[-1]
    scale = math.hypot(*steady.force)
    assert np.abs(last.force - steady.force).max() <= 5e-3 * scale
    assert last.moment == pytest.approx(steady.moment, rel=5e-3, abs=1e-9 * scale * A)
    assert 0 < last.stick_cells < last.normal.contact.sum() and 0 < steady.stick.sum() < steady.contact.sum()
    fx = np.array([s.force[0] for s in steps])
    if creep[0] > 0:
        assert np.all(np.diff(fx) < 1e-9 * scale) and fx[-1] >= steady.force[0] * (1 + 1e-6)


def test_world_fixed_transient_reaches_the_steady_state_itself(steady_problem):
    """With a step of one element the steady state is the fixed point of the world-fixed steps (the same upwind
    discretisation), not only a 0.5 % neighbour: over 8 contact lengths the Fx deficit falls geometrically, each
    contact length by more than 4x (measured 5.6-5.8x: 20, 3.4, 0.59, 0.10, 0.018 % ...), to below 1e-5 of Fx
    (measured 9e-7; the steady and tangential tolerances are 1e-9 and 1e-8)."""
    problem, pressure = steady_problem
    steady = solve_steady(problem, pressure, MU, 1e-3, params=SteadyParams(tol=1e-9))
    steps = roll(HalfSpaceOperator(world_grid(8), MATS), 8, xi=1e-3)
    deficit = np.array([steps[k].force[0] / steady.force[0] - 1.0 for k in range(N, len(steps), N)])
    assert np.all(deficit[1:] / deficit[:-1] > 0) and np.all(np.abs(deficit[1:] / deficit[:-1]) < 0.25)
    assert abs(deficit[-1]) < 1e-5


def test_rest_and_cattaneo_starts_reach_the_same_steady_state(world4, steady_problem):
    """The initial state is forgotten: from rest and from the Cattaneo state (the first step's creep slip applied at
    rest) the forces and moment after 4 contact lengths agree within 0.5 % of |F| with each other and with the
    steady state (measured 0.011 % apart, 0.14 % from the steady Fx: the Cattaneo start is one step ahead), and the
    Cattaneo state itself is a static shift problem: at rest (centre 0), partial slip, a force opposing the creepage."""
    problem, pressure = steady_problem
    creep = (5e-4, 3e-4, 2e-4)
    steady = solve_steady(problem, pressure, MU, *creep, params=SteadyParams(tol=1e-9))
    rest = roll(world4, 4, xi=creep[0], eta=creep[1], phi=creep[2])
    catt = roll(world4, 4, xi=creep[0], eta=creep[1], phi=creep[2], initial="cattaneo")
    assert rest[0].centre == catt[0].centre == 0.0 and np.all(rest[0].force == 0.0)
    assert catt[0].force[0] < 0 and catt[0].force[1] < 0 and 0 < catt[0].stick_cells
    scale = math.hypot(*steady.force)
    for a, b in ((rest[-1], catt[-1]), (catt[-1], steady)):
        assert np.abs(np.asarray(a.force) - np.asarray(b.force)).max() <= 5e-3 * scale
        assert a.moment == pytest.approx(b.moment, rel=5e-3, abs=1e-9 * scale * A)


def test_prescribed_forces_roll_to_the_steady_creepages(world4, steady_problem):
    """Forces (Fx, Fy) on the sphere prescribed at every step (the force-controlled shift problem, the creepages
    (xi, eta) = dU / step): from the Cattaneo state under those forces the step's creepages approach the steady
    creepages of `solve_for_forces` within 0.5 % of |(xi, eta)| after 4 contact lengths (measured 0.0003 %; at rest
    a creepage is not defined, so the Cattaneo state's is its shift over one step length), every step carries the
    prescribed forces to the tangential solver's force balance (1e-9 relative), and |F| >= mu Fn is refused."""
    problem, pressure = steady_problem
    forces = (-60.0, 30.0)
    found = solve_for_forces(problem, pressure, MU, *forces, phi=1e-3, params=SteadyParams(tol=1e-9), tol=1e-9)
    steps = roll(world4, 4, forces=forces, phi=1e-3, initial="cattaneo")
    for s in steps:
        assert s.force == pytest.approx(forces, rel=1e-9, abs=1e-9 * FN)
    xi, eta = steps[-1].creepages[:2]
    assert math.hypot(xi - found.xi, eta - found.eta) <= 5e-3 * math.hypot(found.xi, found.eta)
    assert steps[-1].moment == pytest.approx(found.steady.moment, rel=5e-3)
    with pytest.raises(GrossSlidingError, match="mu Fn"):
        next(roll_world(world4, PROFILE, Fn=FN, mu=MU, distance=1.0, step=DX, forces=(MU * FN, 0.0)))


def test_every_step_keeps_coulombs_bound_and_the_force_balance(world4):
    """Every step from rest with creepage and spin: |tau| <= mu p (round-off), the force and moment on the sphere
    are minus the sums of the substrate traction (1e-12 relative), the stick cells do not slip (below 1e-6 of the
    step's largest rigid creep slip: the solver's tolerance 1e-8 is on the traction) and the slip cells slip
    against their traction (cosine < -0.999; cells whose slip is below 1e-6 of the rigid slip left out)."""
    phi, slipping = 2e-4, 0
    for s in roll(world4, 1, xi=5e-4, eta=3e-4, phi=phi):
        tau, p, dA = s.tangential.traction, s.normal.pressure, world4.grid.cell_area
        X, Y = world4.grid.mesh()
        norm = np.hypot(tau[0], tau[1])
        assert np.all(norm <= MU * p * (1 + 1e-12) + 1e-300)
        assert s.force == pytest.approx(-tau.sum(axis=(1, 2)) * dA, rel=1e-12, abs=1e-12 * FN)
        assert s.moment == pytest.approx(-((X - s.centre) * tau[1] - Y * tau[0]).sum() * dA, rel=1e-12, abs=1e-12)
        if s.step == 0:
            assert np.all(tau == 0.0)
            continue
        region, slip = s.tangential.region, s.tangential.slip
        rigid = DX * (math.hypot(5e-4, 3e-4) + phi * 2 * A)
        assert np.hypot(slip[0], slip[1])[region == 1].max(initial=0.0) < 1e-6 * rigid
        moving = (region == 2) & (np.hypot(slip[0], slip[1]) > 1e-6 * rigid)
        cosine = (tau[0] * slip[0] + tau[1] * slip[1])[moving] / (norm * np.hypot(slip[0], slip[1]))[moving]
        assert np.all(cosine < -0.999)
        slipping += bool(moving.any())
    assert slipping >= N // 2        # a slip zone at the trailing edge in most steps (measured 19 of 21)


def test_world_rolling_refuses_bad_arguments(world4):
    """Step and distance > 0, a known initial state, forces in place of (not with) the creepages: each refused before
    any solve, naming the key; a grid too short for the contact rolled over the distance: refused after the initial
    state, before rolling."""
    go = lambda **kw: next(roll_world(world4, PROFILE, Fn=FN, mu=MU, **{"distance": 1.0, "step": DX, **kw}))
    with pytest.raises(InputError, match=r"\[rolling\] step = 0"):
        go(step=0.0)
    with pytest.raises(InputError, match=r"\[rolling\] distance = -1"):
        go(distance=-1.0)
    with pytest.raises(InputError, match=r"\[rolling\] initial = 'moving'.*'rest', 'cattaneo'"):
        go(initial="moving")
    with pytest.raises(InputError, match="in place of the creepages"):
        go(xi=1e-3, forces=(1.0, 0.0))
    with pytest.raises(ContactEdgeError, match=r"too short for the contact .* rolled [\d.]+ mm \(\[rolling\] distance"):
        go(distance=8 * A + 2 * DX)      # 86 steps: the contact would reach the last column
