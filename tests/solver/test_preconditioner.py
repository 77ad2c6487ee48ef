"""The tangential solver's preconditioner (`solver.tangential._preconditioner`): weights, symmetry, definiteness, deflation.

CG needs a symmetric positive definite preconditioner; these are checked on a random stick/slip division with
curvatures kappa from 1e-3 to 1e3 times the self coefficient (the range met between the stick edge and the
contact edge), for the two-term form and the shifted levels. Units mm, MPa (kappa in mm/MPa).
"""
import numpy as np
import pytest

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.tangential import _preconditioner as PC

MATERIALS = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)


def random_division(grid, seed, p):
    """Operator, random region (probabilities p of exterior, stick, slip), slip directions and curvatures
    (1e-3 ... 1e3 a_self on slip elements, a tenth of them 0: slip elements at the stick edge)."""
    op = HalfSpaceOperator(grid, MATERIALS)
    rng = np.random.default_rng(seed)
    region = rng.choice(np.array([0, 1, 2], np.int8), size=grid.shape, p=p)
    angle = rng.uniform(0, 2 * np.pi, grid.shape)
    nrm = np.array([np.cos(angle), np.sin(angle)])
    a = op.self_coefficients["xx"]
    kappa = np.where(region == 2, a * 10 ** rng.uniform(-3, 3, grid.shape), 0.0)
    kappa[(region == 2) & (rng.random(grid.shape) < 0.1)] = 0.0
    return grid, op, region, nrm, kappa


@pytest.fixture(scope="module")
def division():
    return random_division(Grid(37, 41, 0.1, 0.1, -1.8, -2.0), 7, [0.2, 0.4, 0.4])


def projected(r, region, nrm):
    """P r: unchanged in stick, along the tangent t = (-n_y, n_x) in slip, zero outside."""
    t = np.array([-nrm[1], nrm[0]])
    rt = (t * r).sum(0)
    return np.where(region == 2, t * rt, np.where(region == 1, r, 0.0))


def apply(pre, division, r, deflate=False, gram=(1.0, 0.0, 1.0)):
    grid, op, region, nrm, kappa = division
    z = np.zeros_like(r)
    ax, ay = op.self_coefficients["xx"], op.self_coefficients["yy"]
    pre.apply(nrm, region, kappa, ax, ay, r, z, deflate, gram, np.zeros_like(r))
    return z


def test_level_weights_are_a_partition_of_unity(division):
    """Every slip element's weights sum to one: sum_l W_l^2 + D (a_tt + kappa) = 1 in the shifted form; the
    two-term form has W_0 = a_tt/(a_tt + kappa), D = kappa/(a_tt + kappa)^2; the level inputs carry W_l r in slip,
    r (level 0) or nothing (levels >= 1) in stick, and nothing outside the contact."""
    grid, op, region, nrm, kappa = division
    ax, ay = op.self_coefficients["xx"], op.self_coefficients["yy"]
    n = len(PC.LEVELS)
    slip = np.argwhere(region == 2)
    moderate = 0
    for j, i in slip:
        att = ax * nrm[1, j, i] ** 2 + ay * nrm[0, j, i] ** 2
        k = kappa[j, i]
        w = [PC._slip_weights(nrm, kappa, ax, ay, j, i, PC.SHIFTED, lv) for lv in range(n)]
        total = sum(wl ** 2 for wl, _ in w) + w[0][1] * (att + k)
        assert abs(total - 1.0) < 1e-12
        moderate += 0 < k < 4 * att and w[1][0] > 0
        w0, d = PC._slip_weights(nrm, kappa, ax, ay, j, i, PC.TWO_TERM, 0)
        assert np.isclose(w0, att / (att + k), rtol=1e-14) and np.isclose(d, k / (att + k) ** 2, rtol=1e-14)
    assert moderate > 50  # the shifted level carries the moderate curvatures
    r = np.ones((2,) + grid.shape)
    out = np.empty_like(r)
    for level in range(n):
        PC.inputs(nrm, region, kappa, ax, ay, r, PC.SHIFTED, level, out)
        assert np.all(out[:, region == 1] == (1.0 if level == 0 else 0.0))
        assert np.all(out[:, region == 0] == 0.0)


@pytest.mark.parametrize("n_contact", [0, 10 ** 6], ids=["two-term", "shifted levels"])
def test_preconditioner_is_symmetric_and_stays_in_the_free_directions(division, n_contact):
    """<r1, z(r2)> = <r2, z(r1)> to round-off for residuals on the free directions (P r) on a 37 x 41 division,
    and z lies in the free directions (zero outside, along t in slip); definiteness: the dense test below."""
    grid, op, region, nrm, kappa = division
    pre = PC.Preconditioner(op, grid.shape, n_contact)
    assert pre.shifted == (n_contact >= PC.MIN_CONTACT_ELEMENTS)
    rng = np.random.default_rng(8)
    r1, r2 = (projected(rng.standard_normal((2,) + grid.shape), region, nrm) for _ in range(2))
    z1, z2 = apply(pre, division, r1), apply(pre, division, r2)
    assert np.isclose(np.vdot(r1, z2), np.vdot(r2, z1), rtol=1e-10)
    np.testing.assert_allclose(projected(z1, region, nrm), z1, atol=1e-12 * np.abs(z1).max())


def test_deflation_keeps_the_force(division):
    """With a prescribed force the preconditioned residual must not change sum tau: with the Gram matrix of
    the constraint vectors C = [P e_x, P e_y], sum over the free directions of z is zero to round-off."""
    grid, op, region, nrm, kappa = division
    t = np.array([-nrm[1], nrm[0]])
    cx = np.where(region == 2, t * t[0], np.where(region == 1, np.array([1.0, 0.0])[:, None, None], 0.0))
    cy = np.where(region == 2, t * t[1], np.where(region == 1, np.array([0.0, 1.0])[:, None, None], 0.0))
    gram = (float((cx * cx).sum()), float((cx * cy).sum()), float((cy * cy).sum()))
    r = projected(np.random.default_rng(9).standard_normal((2,) + grid.shape), region, nrm)
    for n_contact in (0, 10 ** 6):
        z = apply(PC.Preconditioner(op, grid.shape, n_contact), division, r, deflate=True, gram=gram)
        scale = np.abs(z).sum()
        assert abs((cx * z).sum()) < 1e-12 * scale and abs((cy * z).sum()) < 1e-12 * scale


@pytest.mark.parametrize("n_contact", [0, 10 ** 6], ids=["two-term", "shifted levels"])
def test_dense_preconditioner_has_positive_eigenvalues_on_the_free_directions(n_contact):
    """The preconditioner as a dense matrix on the free directions (e_x, e_y in stick, t in slip) of a small
    random division with curvatures 1e-3 ... 1e3 a_self: symmetric to round-off and every eigenvalue positive
    (a sign error of D on the high-curvature elements, or a one-sided weight, makes it fail)."""
    division = random_division(Grid(12, 13, 0.1, 0.1, -0.6, -0.6), 11, [0.1, 0.4, 0.5])
    grid, op, region, nrm, kappa = division
    basis = []
    for j, i in np.argwhere(region == 1):
        for c in range(2):
            b = np.zeros((2,) + grid.shape)
            b[c, j, i] = 1.0
            basis.append(b)
    for j, i in np.argwhere(region == 2):
        b = np.zeros((2,) + grid.shape)
        b[:, j, i] = (-nrm[1, j, i], nrm[0, j, i])
        basis.append(b)
    pre = PC.Preconditioner(op, grid.shape, n_contact)
    Z = np.array([[np.vdot(bi, apply(pre, division, bj)) for bj in basis] for bi in basis])
    np.testing.assert_allclose(Z, Z.T, rtol=0, atol=1e-12 * np.abs(Z).max())
    assert np.linalg.eigvalsh(0.5 * (Z + Z.T)).min() > 0
