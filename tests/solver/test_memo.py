"""The product memo shared by the solvers (solver/memo.py): exact matching, reuse limit, capacity."""
import numpy as np

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.memo import ProductMemo, same

PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)


def Op():
    return HalfSpaceOperator(Grid(3, 2, 0.2, 0.2), PAIR)


def test_same_compares_shape_and_every_value():
    a = np.arange(12.0).reshape(3, 4)
    assert same(a, a.copy())
    b = a.copy()
    b[-1, -1] = np.nextafter(b[-1, -1], np.inf)  # the last element, one ulp apart
    assert not same(a, b)
    assert not same(a, a.reshape(4, 3))
    c = a.copy()
    c[0, 0] = np.nan
    assert not same(c, c.copy())  # a NaN field never matches: its product is always recomputed


def test_lookup_returns_the_stored_product_until_the_reuse_limit():
    memo, op = ProductMemo(size=1, max_reuses=3), Op()
    field, product = np.ones((2, 3)), np.full((2, 3), 7.0)
    assert memo.lookup(op, field) == (None, 0)
    memo.store(op, field, product, 0)
    field[0, 0] = 5.0                       # the memo keeps copies
    got, reuses = memo.lookup(op, np.ones((2, 3)))
    np.testing.assert_array_equal(got, product)
    assert reuses == 1
    memo.store(op, np.ones((2, 3)), product, 3)
    assert memo.lookup(op, np.ones((2, 3))) == (None, 0)   # reused 3 times: recompute by FFT
    assert memo.lookup(Op(), np.ones((2, 3))) == (None, 0)  # entries belong to their operator


def test_capacity_keeps_the_newest_distinct_fields():
    memo, op = ProductMemo(size=2), Op()
    fields = [np.full(4, float(k)) for k in range(3)]
    for k, f in enumerate(fields):
        memo.store(op, f, 10.0 * f, 0)
    assert memo.lookup(op, fields[0])[0] is None
    assert memo.lookup(op, fields[1])[0][0] == 10.0 and memo.lookup(op, fields[2])[0][0] == 20.0
    memo.store(op, fields[2], 30.0 * fields[2], 5)      # an equal field replaces its entry
    assert memo.lookup(op, fields[1])[0] is not None
    assert memo.lookup(op, fields[2])[1] == 6
