"""bem/rows.py: the tangential influence of one row's change on other rows by 1-D FFTs equals the dense product
of the influence coefficients (bem.operator.HalfSpaceOperator.dense) to round-off (1e-12 of the largest
displacement), for square and non-square cells and any target rows."""
import numpy as np
import pytest

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.rows import RowInfluence


@pytest.mark.parametrize("nx, ny, dx, dy", [(13, 9, 0.2, 0.2), (20, 7, 0.1, 0.35)])
def test_row_change_reaches_the_other_rows_as_the_dense_product(nx, ny, dx, dy):
    grid = Grid(nx, ny, dx, dy, -nx // 2, -ny // 2)
    mats = MaterialPair.from_moduli(210e3, 0.28, 70e3, 0.33)
    X, Y = np.meshgrid(np.arange(-(nx - 1), nx) * dx, np.arange(-(ny - 1), ny) * dy)
    k = influence_coefficients(X, Y, dx, dy, mats.G, mats.nu, mats.K, components=("xx", "xy", "yy"))
    rows = RowInfluence(k["xx"], k["xy"], k["yy"])
    op = HalfSpaceOperator(grid, mats, coupling=False)
    dense = {c: op.dense(c) for c in ("xx", "xy", "yy")}
    rng = np.random.default_rng(1)
    j = ny // 3
    change = rng.standard_normal((2, nx))
    disp = np.zeros((2, ny, nx))
    targets = slice(1, ny - 1)
    rows.add(disp, j, change, targets)
    field = np.zeros((2, ny, nx))
    field[:, j] = change
    fx, fy = field[0].ravel(), field[1].ravel()
    want = np.stack([(dense["xx"] @ fx + dense["xy"] @ fy).reshape(ny, nx),
                     (dense["xy"] @ fx + dense["yy"] @ fy).reshape(ny, nx)])
    scale = np.abs(want).max()
    assert np.abs(disp[:, targets] - want[:, targets]).max() < 1e-12 * scale
    assert not disp[:, 0].any() and not disp[:, -1].any()          # rows outside `targets` untouched
