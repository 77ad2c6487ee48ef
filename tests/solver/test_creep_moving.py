"""Transient rolling on the grid that moves with the contact (solver/creep/moving.py) against the world-fixed grid
(solver/creep/world.py): the same shift problem per step, the moving grid restricted to the elements near the
contact and carrying the previous step's tractions by the step. Outside the contact the traction is zero on both
grids, so the two must give the same forces at every step up to the solvers' tolerance (tangential tol 1e-8 of the
traction bound: measured <= 2.2e-8 of mu Fn); asserted at 1e-6 mu Fn, a thousand times below the 0.1 % the
formulations are required to agree to. Steel on steel, a sphere R = 40 mm under Fn = 1000 N (Hertz a = 0.641 mm),
mu = 0.3, 21 elements across the contact, rolled 3 contact lengths."""
import numpy as np
import pytest

from rollcontact.bem import HalfSpaceOperator, MaterialPair
from rollcontact.bem.errors import ContactEdgeError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.solver.creep import roll_world
from rollcontact.solver.creep.moving import carried_field, roll_moving, whole_cells
from rollcontact.solver.rolling import QuadricProfile

MATS = MaterialPair.from_moduli(210e3, 0.28, 210e3, 0.28)
R, FN, MU, N = 40.0, 1000.0, 0.3, 21
A = (3 * FN * R * 2 * (1 - 0.28 ** 2) / (4 * 210e3)) ** (1 / 3)
DX = 2 * A / N
M = 2 * DX                       # free cells around the contact
LENGTHS = 3
PROFILE = QuadricProfile(R, R)


def world_op():
    return HalfSpaceOperator(Grid.covering(-A - M, 2 * A * LENGTHS + A + M, -A - M, A + M, DX, DX), MATS)


def moving_op(step):
    return HalfSpaceOperator(Grid.covering(-A - M - step, A + M, -A - M, A + M, DX, DX), MATS)


@pytest.fixture(scope="module")
def world():
    return world_op()


@pytest.mark.parametrize("cells, load", [
    (1, dict(xi=3e-4)),
    (2, dict(xi=2e-4, eta=1e-4, phi=2e-3)),
    (1, dict(forces=(-150.0, 40.0), phi=1e-3)),
    (1, dict(xi=3e-4, initial="cattaneo")),
])
def test_contact_fixed_grid_gives_the_world_fixed_forces_at_every_step(world, cells, load):
    """Creepage, creepage with spin on steps of two elements, prescribed forces with spin (the creepages found per
    step), and Cattaneo's initial state: forces, moment and creepages agree at every step, from the first (mostly
    stick, where the memory matters most) to the steady state."""
    step = cells * DX
    kw = dict(Fn=FN, mu=MU, distance=2 * A * LENGTHS, step=step, **load)
    ref = list(roll_world(world, PROFILE, **kw))
    got = list(roll_moving(moving_op(step), PROFILE, **kw))
    assert [r.step for r in got] == [r.step for r in ref] and len(got) == -(-LENGTHS * N // cells) + 1
    force = np.array([r.force for r in got])
    assert np.abs(force - np.array([r.force for r in ref])).max() <= 1e-6 * MU * FN
    assert np.abs(np.array([r.moment for r in got]) - np.array([r.moment for r in ref])).max() <= 1e-6 * MU * FN * A
    creep = np.array([r.creepages for r in got])
    assert np.abs(creep - np.array([r.creepages for r in ref])).max() <= 1e-6 * max(np.abs(creep).max(), 1e-4)
    assert np.abs(force[-1]).max() > 0.1 * MU * FN          # a real tangential load, not a trivial agreement
    assert np.allclose([r.centre for r in got], [r.centre for r in ref], rtol=0, atol=1e-12)


def test_carried_tractions_move_by_the_step_towards_the_trailing_edge():
    """The element at column i after a step of k elements sat at column i + k before it: the field moves k columns
    towards -x, the entering leading columns are virgin (zero); a nonzero value at the trailing edge cannot be
    carried (the grid would lose the previous contact) and is refused."""
    field = np.zeros((2, 3, 6))
    field[:, :, 2:5] = np.arange(18.0).reshape(2, 3, 3)
    out = carried_field(field, 2, "traction")
    assert np.array_equal(out[..., :3], field[..., 2:5]) and not out[..., 3:].any()
    with pytest.raises(ContactEdgeError, match="traction reaches the last 3 column"):
        carried_field(field, 3, "traction")


def test_moving_grid_refuses_a_step_that_is_not_whole_elements_or_a_short_trailing_margin():
    with pytest.raises(InputError, match=r"step = .* is 1\.5 elements .* set step = k dx or grid = 'world'"):
        whole_cells(1.5 * DX, DX)
    assert whole_cells(3 * DX * (1 + 1e-12), DX) == 3
    with pytest.raises(InputError, match="whole number of elements"):
        next(roll_moving(moving_op(DX), PROFILE, Fn=FN, mu=MU, distance=1.0, step=0.5 * DX, xi=1e-4))
    tight = HalfSpaceOperator(Grid.covering(-A - 0.5 * DX, A + M, -A - M, A + M, DX, DX), MATS)
    with pytest.raises(ContactEdgeError, match="enlarge grid.margin"):
        list(roll_moving(tight, PROFILE, Fn=FN, mu=MU, distance=1.0, step=2 * DX, xi=1e-4))
