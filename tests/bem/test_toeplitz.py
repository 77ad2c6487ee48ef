"""bem.toeplitz.ToeplitzOperator: given kernels applied by padded FFT, checked against the elastic operator (with the
elastic kernels) and against dense matrix products (kernels not even in x)."""
import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.bem.toeplitz import ToeplitzOperator

GRID = Grid(11, 8, 0.2, 0.25, -5, -3)
PAIR = MaterialPair.from_moduli(50.0, 0.2, 20.0, 0.45)


def elastic_kernels():
    ny, nx = GRID.shape
    X, Y = np.meshgrid(np.arange(-(nx - 1), nx) * GRID.dx, np.arange(-(ny - 1), ny) * GRID.dy)
    return influence_coefficients(X, Y, GRID.dx, GRID.dy, PAIR.G, PAIR.nu, PAIR.K)


def test_with_the_elastic_kernels_it_is_the_half_space_operator():
    """Products (normal, tangential, both couplings) to 1e-13 of their size, the preconditioner to 1e-12."""
    op = HalfSpaceOperator(GRID, PAIR, coupling=True)
    to = ToeplitzOperator(GRID, elastic_kernels(), materials=PAIR)
    p, tx, ty = np.random.default_rng(1).random((3,) + GRID.shape)
    for a, b in ((to.normal(p), op.normal(p)), (to.tangential(tx, ty), op.tangential(tx, ty)),
                 (to.tangential_from_pressure(p), op.tangential_from_pressure(p)),
                 (to.normal_from_tangential(tx, ty), op.normal_from_tangential(tx, ty))):
        assert np.abs(a - b).max() <= 1e-13 * np.abs(b).max()
    assert np.abs(to.normal_inverse(p) - op.normal_inverse(p)).max() <= 1e-12 * np.abs(op.normal_inverse(p)).max()


def test_kernels_not_even_in_x_are_applied_as_their_dense_matrices():
    """Kernels with a one-sided exponential added along x (as steady viscoelastic rolling has): the FFT products equal
    the dense Toeplitz matrices (u_z from tau through zx = -xz), to 1e-13."""
    k = elastic_kernels()
    ny, nx = GRID.shape
    ramp = np.exp(-np.abs(np.arange(-(nx - 1), nx)) / 3.0) * (np.arange(-(nx - 1), nx) < 0)
    k = {c: v + 0.3 * v.max() * ramp[None, :] for c, v in k.items()}
    to = ToeplitzOperator(GRID, k)
    p, tx, ty = np.random.default_rng(2).random((3,) + GRID.shape)
    D = {c: to.dense(c) for c in k}
    assert np.abs(D["zz"] - D["zz"].T).max() > 0.1 * np.abs(D["zz"]).max()
    flat = [v.ravel() for v in (p, tx, ty)]
    assert np.allclose(to.normal(p).ravel(), D["zz"] @ flat[0], rtol=0, atol=1e-13 * np.abs(D["zz"]).sum(1).max())
    ut = to.tangential(tx, ty)
    assert np.allclose(ut[0].ravel(), D["xx"] @ flat[1] + D["xy"] @ flat[2], atol=1e-13 * ut.max())
    assert np.allclose(ut[1].ravel(), D["xy"] @ flat[1] + D["yy"] @ flat[2], atol=1e-13 * ut.max())
    assert np.allclose(to.normal_from_tangential(tx, ty).ravel(), -(D["xz"] @ flat[1] + D["yz"] @ flat[2]),
                       atol=1e-13 * np.abs(D["xz"]).sum(1).max())


def test_kernels_of_the_wrong_shape_or_missing_are_refused():
    k = elastic_kernels()
    with pytest.raises(InputError, match="missing"):
        ToeplitzOperator(GRID, {c: k[c] for c in ("zz", "xx")})
    with pytest.raises(InputError, match="shape"):
        ToeplitzOperator(GRID, {**k, "zz": k["zz"][:-1]})
