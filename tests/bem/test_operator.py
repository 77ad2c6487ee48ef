"""FFT convolution operator (docs/theory.md §3): exact against the dense matrix product."""
import numpy as np
import pytest
from scipy.fft import next_fast_len

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.analytic import HertzSphere

COUPLED = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)   # steel on aluminium, beta ~ -0.1
SCENE = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)       # beta ~ 7e-6


def rel(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.fixture(scope="module")
def small():
    grid = Grid(13, 9, 0.2, 0.3, -6, -4)  # odd, non-square, rectangular cells: catches transposes
    return grid, HalfSpaceOperator(grid, COUPLED)


def test_fft_products_equal_dense_matrix_products(small):
    grid, op = small
    rng = np.random.default_rng(1)
    p, tx, ty = rng.standard_normal((3,) + grid.shape)
    D = {c: op.dense(c) for c in ("zz", "xx", "yy", "xy", "xz", "yz")}
    flat = lambda v: v.reshape(grid.shape)
    assert rel(op.normal(p), flat(D["zz"] @ p.ravel())) < 1e-12
    u = op.tangential(tx, ty)
    assert rel(u[0], flat(D["xx"] @ tx.ravel() + D["xy"] @ ty.ravel())) < 1e-12
    assert rel(u[1], flat(D["xy"] @ tx.ravel() + D["yy"] @ ty.ravel())) < 1e-12
    c = op.tangential_from_pressure(p)
    assert rel(c[0], flat(D["xz"] @ p.ravel())) < 1e-12
    assert rel(c[1], flat(D["yz"] @ p.ravel())) < 1e-12
    w = op.normal_from_tangential(tx, ty)  # Betti: zx = -xz, zy = -yz
    assert rel(w, flat(-D["xz"] @ tx.ravel() - D["yz"] @ ty.ravel())) < 1e-12


def test_multithreaded_products_equal_the_dense_matrix_products(small):
    """threads = 2 (solver.threads): FFTW plans of their own, the same products as the dense matrices to 1e-12."""
    grid, _ = small
    op2 = HalfSpaceOperator(grid, COUPLED, threads=2)
    rng = np.random.default_rng(2)
    p, tx, ty = rng.standard_normal((3,) + grid.shape)
    flat = lambda v: v.reshape(grid.shape)
    assert rel(op2.normal(p), flat(op2.dense("zz") @ p.ravel())) < 1e-12
    u = op2.tangential(tx, ty)
    assert rel(u[0], flat(op2.dense("xx") @ tx.ravel() + op2.dense("xy") @ ty.ravel())) < 1e-12
    assert rel(u[1], flat(op2.dense("xy") @ tx.ravel() + op2.dense("yy") @ ty.ravel())) < 1e-12
    assert rel(op2.tangential_from_pressure(p)[0], flat(op2.dense("xz") @ p.ravel())) < 1e-12


def test_tangential_block_is_the_fft_product_restricted_to_the_elements(small):
    """op.tangential_block (dense A^tt among a few elements, for the solver's turn line search) against the FFT
    product of a field supported on those elements, read at the same elements."""
    grid, op = small
    rng = np.random.default_rng(3)
    rows = np.array([0, 4, 4, 8, 2, 7])
    cols = np.array([0, 3, 12, 5, 11, 1])
    d = rng.standard_normal((2, rows.size))
    field = np.zeros((2,) + grid.shape)
    field[:, rows, cols] = d
    u = op.tangential(field[0], field[1])[:, rows, cols]
    xx, xy, yy = op.tangential_block(rows, cols)
    assert rel(u[0], xx @ d[0] + xy @ d[1]) < 1e-12
    assert rel(u[1], xy @ d[0] + yy @ d[1]) < 1e-12


def test_tangential_norm_bounds_the_largest_eigenvalue(small):
    """op.tangential_norm (largest eigenvalue of the padded circulant, the gradient phase's Lipschitz constant) must
    bound the largest eigenvalue of the dense A^tt from above; the circulant embedding is about twice it here."""
    grid, op = small
    D = np.block([[op.dense("xx"), op.dense("xy")], [op.dense("xy"), op.dense("yy")]])
    lam = np.linalg.eigvalsh(0.5 * (D + D.T)).max()
    L = op.tangential_norm()
    assert lam <= L * (1 + 1e-12)
    assert L < 4 * lam


def test_out_argument_is_filled_and_buffers_do_not_leak_between_calls(small):
    grid, op = small
    rng = np.random.default_rng(2)
    a, b = rng.standard_normal((2,) + grid.shape)
    ref = op.normal(a)
    op.tangential(b, a)  # use the other buffers in between
    out = np.empty(grid.shape)
    op.normal(a, out=out)
    np.testing.assert_array_equal(out, ref)


def test_coupling_is_off_for_the_seed_materials_and_costs_nothing():
    grid = Grid(8, 8, 0.2, 0.2)
    op = HalfSpaceOperator(grid, SCENE)
    assert not op.coupled and "xz" not in op.spectra
    assert np.all(op.tangential_from_pressure(np.ones(grid.shape)) == 0)


def test_hertz_pressure_gives_hertz_displacement():
    # docs/theory.md §2.2: the cell-sampled Hertz pressure of the scene gives w within ~0.1 % of d everywhere
    # (inside w = d - r^2/2R, outside the closed form). Sampling at centres (not cell averages) adds
    # an O(dx^2/a^2) error: the bound 3e-3 d covers both.
    hz = HertzSphere(40.0, SCENE.E_star, 21.19)
    grid = Grid.covering(-6.4, 6.4, -6.4, 6.4, 0.2, 0.2)
    op = HalfSpaceOperator(grid, SCENE)
    X, Y = grid.mesh()
    w = op.normal(hz.pressure(np.hypot(X, Y)))
    assert np.abs(w - hz.displacement(np.hypot(X, Y))).max() < 3e-3 * hz.approach


def test_preconditioners_approximate_the_inverse_in_the_interior():
    grid = Grid.covering(-5, 5, -6, 6, 0.2, 0.2)
    op = HalfSpaceOperator(grid, SCENE)
    rng = np.random.default_rng(3)
    p, tx, ty = rng.standard_normal((3,) + grid.shape)
    inner = (slice(4, -4), slice(4, -4))
    # Strang circulant: exact up to the wrap-around of the kernel tail, a few % at this size
    assert rel(op.normal_inverse(op.normal(p))[inner], p[inner]) < 0.05
    z = op.tangential_inverse(*op.tangential(tx, ty))
    assert rel(z[0][inner], tx[inner]) < 0.1 and rel(z[1][inner], ty[inner]) < 0.1


def test_preconditioners_are_the_circulants_of_their_real_symbols_and_symmetric(small):
    # the compiled multiply stage (bem._spectral) against a plain numpy circulant on the unpadded period
    grid, op = small
    ny, nx = grid.shape
    sy, sx = op.small
    rng = np.random.default_rng(4)
    p, tx, ty, a, b = rng.standard_normal((5,) + grid.shape)

    def circulant(fields, symbols):
        spec = [np.fft.rfft2(f, s=(sy, sx)) for f in fields]
        out = [sum(sym * s_ for sym, s_ in zip(row, spec)) for row in symbols]
        return np.array([np.fft.irfft2(o, s=(sy, sx))[:ny, :nx] * (sy * sx) for o in out])

    s = op.inverse_spectra
    assert all(v.dtype == np.float64 for v in s.values())
    assert rel(op.normal_inverse(p), circulant([p], [[s["zz"]]])[0]) < 1e-12
    ref = circulant([tx, ty], [[s["xx"], s["xy"]], [s["xy"], s["yy"]]])
    assert rel(op.tangential_inverse(tx, ty), ref) < 1e-12
    # CG needs a symmetric preconditioner: <a, M b> = <M a, b>
    assert np.isclose(np.vdot(a, op.normal_inverse(b)), np.vdot(op.normal_inverse(a), b), rtol=1e-12)
    ab, ba = op.tangential_inverse(a, b), op.tangential_inverse(b, a)   # u = (a, b), w = (b, a)
    assert np.isclose(np.vdot(a, ba[0]) + np.vdot(b, ba[1]), np.vdot(ab[0], b) + np.vdot(ab[1], a), rtol=1e-12)


def test_shifted_tangential_inverse_inverts_the_shifted_circulant():
    """tangential_inverse(shift=s) is the inverse of the Strang circulant C plus s I (the solver's curvature
    levels): on a grid whose circulant period equals the grid (64 = next_fast_len(64): no truncation),
    M_0 x - M_s x = s M_0 M_s x to round-off (the resolvent identity), and a bad shift is refused."""
    grid = Grid(64, 64, 0.02, 0.02, -0.63, -0.63)
    op = HalfSpaceOperator(grid, MaterialPair.from_moduli(206e3, 0.3, 70e3, 0.33))
    assert op.small == grid.shape
    a = op.self_coefficients["xx"]
    x = np.random.default_rng(5).standard_normal((2,) + grid.shape)
    for s in (0.5 * a, 4 * a, 60 * a):
        ms = op.tangential_inverse(*x, shift=s)
        lhs = op.tangential_inverse(*x) - ms
        rhs = s * op.tangential_inverse(*ms)
        assert rel(lhs, rhs) < 1e-10
    assert op.tangential_inverse(*x, shift=4 * a) is not None and len(op._shifted_inverses) == 3
    with pytest.raises(InputError, match="shift"):
        op.tangential_inverse(*x, shift=-a)


def test_preconditioners_invert_the_circulant_exactly_on_a_large_grid():
    """The circulant's symbols are floored only to guard against non-positive values. A floor relative to the largest
    eigenvalue would grow with the grid (the k = 0 value of a 1/r kernel grows like its width): 1e-3 of it clips the
    tangential symbol's high frequencies at 576^2 (18 % of them at 511^2), and the preconditioner would not invert
    its own circulant there. Strang circulant C (kernel at the nearest periodic offset, the odd xy kernel
    zero at the Nyquist offset) on a grid equal to its period: M C x = x to round-off."""
    n = 576
    assert n == next_fast_len(n, real=True)
    grid = Grid(n, n, 0.01, 0.01, -n // 2, -n // 2)
    op = HalfSpaceOperator(grid, SCENE)
    assert op.small == grid.shape
    off = (np.arange(n) - n * (np.arange(n) > n // 2)) * grid.dx
    X, Y = np.meshgrid(off, off)
    m = op.materials
    k = influence_coefficients(X, Y, grid.dx, grid.dy, m.G, m.nu, m.K, components=("zz", "xx", "yy", "xy"))
    k["xy"][:, n // 2] = k["xy"][n // 2, :] = 0.0
    K = {c: np.fft.rfft2(v) for c, v in k.items()}
    conv = lambda f, c: np.fft.irfft2(np.fft.rfft2(f) * K[c], s=(n, n))
    rng = np.random.default_rng(6)
    p, tx, ty = rng.standard_normal((3, n, n))
    assert rel(op.normal_inverse(conv(p, "zz")), p) < 1e-9
    z = op.tangential_inverse(conv(tx, "xx") + conv(ty, "xy"), conv(tx, "xy") + conv(ty, "yy"))
    assert rel(z, np.array([tx, ty])) < 1e-9


def test_smooth_length_is_scipys_next_fast_len_for_real_transforms():
    # the preconditioner's circulant periods were measured with scipy.fft.next_fast_len(n, real=True); the
    # operator computes the same 5-smooth lengths itself so that a run does not import scipy.fft
    from rollcontact.bem.operator import fft_length, smooth_length
    n = np.arange(1, 20000)
    assert [smooth_length(int(k)) for k in n] == [next_fast_len(int(k), real=True) for k in n]
    assert all(fft_length(int(k)) % 2 == 0 and fft_length(int(k)) >= k for k in n[:3000])
