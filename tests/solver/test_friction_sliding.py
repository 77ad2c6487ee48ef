"""Full sliding with a slip-velocity law, and friction memory after a jump of the slip velocity (docs/friction.md,
"Validation"): the seed's Hertz contact (sphere R = 40 mm on rubber, Fn = 21.19 N, dx = 0.4 mm) slid by a
prescribed rigid shift per step, each step solved consistently with the law (solver.friction.transient). In full
sliding at a steady shift every element slips at |dU|/dt, so the force is mu(s) Fn; after a jump of the shift the
coefficient relaxes as mu(s2) + (mu(s1) - mu(s2)) exp(-s2 t / d_c) (the memory equation at constant s)."""
import numpy as np
import pytest

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.friction import FrictionLaw, FrictionMemory, FrictionParams, LocalFriction
from rollcontact.solver.rolling import QuadricProfile, solve_coupled_step

FN, R = 21.19, 40.0
PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
LAW = FrictionLaw("exponential", mu_kin=0.5, mu_1=0.43, s_1=2.0)


@pytest.fixture(scope="module")
def contact():
    grid = Grid.covering(-5.6, 5.6, -5.6, 5.6, 0.4, 0.4)
    return HalfSpaceOperator(grid, PAIR), QuadricProfile(R, R)


def slide(contact, friction, steps):
    """Steps (dU, dt) of prescribed rigid shift dU (mm, along x) over dt (s): the force F_x (N), the mean mu and the
    iterations of each step."""
    op, profile = contact
    X, Y = op.grid.mesh()
    h = profile(X, Y)
    p, tau, mu = None, np.zeros((2,) + op.grid.shape), None
    forces, means, iterations = [], [], []
    for dU, dt in steps:
        def solve(m, last, accuracy, p=p, tau=tau):
            return solve_coupled_step(op, h, FN, None, p, tau, mu=m, shift=(dU, 0.0), **last.warm_start())
        normal, tang, _, state = friction.step(solve, op=op, dt=dt, previous_mu=mu)
        p, tau, mu = normal.pressure, tang.traction, state.mu
        forces.append(tang.force[0])           # on the substrate: dragged along the sphere's shift
        means.append(float(np.sum(mu * p) / np.sum(p)))
        iterations.append(state.iterations)
    return np.array(forces), np.array(means), iterations


@pytest.mark.parametrize("speed_ratio", [0.3, 1.0, 4.0])
def test_full_sliding_carries_mu_of_the_slip_velocity_times_fn(contact, speed_ratio):
    """|F| = mu(s) Fn within 0.5 % (the issue's bound): here within 1e-6, since from the second step on (the traction
    no longer changes) every element slips exactly |dU| over dt. The shift, 50 mm per step, is far beyond U0 =
    0.8 mm: full sliding."""
    s = speed_ratio * LAW.s_1
    friction = LocalFriction(LAW, speed=1.0, params=FrictionParams(tol=1e-9))
    forces, _, _ = slide(contact, friction, [(50.0, 50.0 / s)] * 4)
    assert forces[-1] == pytest.approx(float(LAW.coefficient(s)) * FN, rel=1e-6)
    assert abs(forces[-1] / (float(LAW.coefficient(s)) * FN) - 1) < 5e-3


def test_memory_relaxes_over_the_sliding_distance_after_a_jump_of_the_slip_velocity(contact):
    """From steady sliding at s1 the shift jumps to s2: the force follows Fn (mu(s2) + (mu(s1) - mu(s2))
    exp(-s2 t / d_c)) within 1 % of the jump (the issue's bound). Shifts of 40-200 mm per step (U0 = 0.8 mm): the
    traction's own change after the jump (about U0 dmu/mu) is below 1 % of the slip of a step."""
    d_c = 120.0                              # mm: three steps of the faster sliding
    s1, s2, dU1, dU2 = 0.5, 8.0, 200.0, 40.0
    friction = LocalFriction(LAW, FrictionMemory(distance=d_c), speed=1.0, params=FrictionParams(tol=1e-9))
    before, after = 12, 12
    forces, _, _ = slide(contact, friction, [(dU1, dU1 / s1)] * before + [(dU2, dU2 / s2)] * after)
    mu1, mu2 = float(LAW.coefficient(s1)), float(LAW.coefficient(s2))
    assert forces[before - 1] == pytest.approx(mu1 * FN, rel=1e-4)     # settled at s1 (2400 mm = 20 d_c slid)
    t = dU2 / s2 * np.arange(1, after + 1)
    expected = FN * (mu2 + (forces[before - 1] / FN - mu2) * np.exp(-s2 * t / d_c))
    jump = abs(forces[before - 1] - mu2 * FN)
    assert np.max(np.abs(forces[before:] - expected)) < 0.01 * jump


def test_instantaneous_law_with_memory_distance_zero_is_the_law_at_once(contact):
    plain = LocalFriction(LAW, speed=1.0, params=FrictionParams(tol=1e-9))
    memory0 = LocalFriction(LAW, FrictionMemory(distance=0.0), speed=1.0, params=FrictionParams(tol=1e-9))
    a, _, _ = slide(contact, plain, [(0.5, 0.2)] * 3)
    b, _, _ = slide(contact, memory0, [(0.5, 0.2)] * 3)
    assert np.array_equal(a, b)
