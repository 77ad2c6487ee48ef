"""Half-space convolution operator: influence coefficients applied by zero-padded FFT (docs/theory.md §3).

The displacement fields produced by piecewise-constant tractions on a `Grid` are aperiodic 2-D
convolutions with the element influence coefficients (`bem.influence`). They are evaluated exactly by
circular convolution on a padded domain of at least (2*ny - 1) x (2*nx - 1) cells (DC-FFT, Liu, Wang &
Liu 2000). Kernel spectra and pyfftw plans are built once per operator and reused; work buffers are
preallocated, so a product allocates only its output (or nothing, when `out=` is given).

Fields are arrays of shape (ny, nx): pressure p and tractions tau_x, tau_y in MPa, displacements in mm
(docs/theory.md §0 conventions: u_z positive into the bodies, (u_x, u_y) substrate relative to sphere).
"""
import math

import numpy as np
from rollcontact.bem import _spectral, wisdom as _wisdom
from rollcontact.bem._fftw import pyfftw
from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import MaterialPair

#: |beta| below which the normal-tangential coupling is dropped in 'auto' mode. At the seed's
#: steel-on-rubber pair (beta = 7e-6) the coupling displacements are < 1e-5 of the direct ones,
#: far below any accuracy the discretisation offers (docs/theory.md §1).
COUPLING_THRESHOLD = 1e-4

#: Floor on the eigenvalues of the periodic kernel symbols when they are inverted, relative to the self coefficient
#: (the symbols' high-frequency scale: their smallest eigenvalue is 0.28-0.52 of it for cell aspect ratios up to 4,
#: at every grid size). It only guards against non-positive values. A floor relative to the largest eigenvalue
#: would grow with the grid's width (the k = 0 value of a 1/r kernel): 1e-3 of it clips 18 % of the tangential
#: symbol at 511^2 (lambda_min of the preconditioned stick block 0.87 against 0.97) and the normal one from about
#: 520^2 (normal Hertz at 768^2 / 1024^2: 15 / 18 iterations against 13 / 13).
PRECONDITIONER_FLOOR = 0.05

def smooth_length(n: int, even: bool = False) -> int:
    """Smallest 5-smooth integer >= n (only prime factors 2, 3, 5), and even if asked: a fast FFT length.

    Without `even` it equals scipy.fft.next_fast_len(n, real=True) (checked for n < 20000 in tests/bem), which
    the preconditioner's circulant periods were tuned with; it is computed here so that a run does not import
    scipy.fft (0.2 s at start-up).
    """
    m = max(2 if even else 1, int(n))
    while True:
        if not even or m % 2 == 0:
            k = m
            for f in (2, 3, 5):
                while k % f == 0:
                    k //= f
            if k == 1:
                return m
        m += 1


def fft_length(n: int) -> int:
    """Smallest even 5-smooth integer >= n: the FFT length used for a dimension needing n points.

    An odd 5-smooth length (125, 135, 225) is avoided: FFTW's real transforms of odd length are 1.3-4x slower
    than those of the next even 5-smooth one (one padded convolution pair on 125^2 takes 0.13 ms, on 128^2
    0.05 ms; benchmarks/README.md, normal_hertz).
    """
    return smooth_length(n, even=True)


def fft_pairs(ks, shape, threads, planner, rows=None):
    """{k: _FFTPair} for batches of k fields of `shape` (this operator's and bem.toeplitz's), whose fields fill only
    their first `rows` rows (default all). Plans come from the on-disk FFTW wisdom; the wisdom is written back only
    when this process plans a transform for the first time (exporting it costs ms)."""
    rows = shape[0] if rows is None else int(rows)
    with _wisdom.lock:
        _wisdom.load()
        pairs = {k: _FFTPair(k, shape, threads, planner, rows) for k in ks}
        _wisdom.save_if_new({(k, tuple(shape), threads, planner, rows) for k in ks})
    return pairs


class _FFTPair:
    """Forward r2c and backward c2r transforms of a batch of `k` fields on the (py, px) periodic domain, the fields
    filling its first `rows` rows (the rest zero padding), with their buffers: `forward()` takes real_in (k, rows, px)
    to spec (k, py, px//2 + 1), `backward()` spec to real_out (k, rows, px), the rows wanted. One spectrum buffer
    serves both: a product scales it in place between the two (the backward transform may destroy it).

    Padded fields (rows < py) are transformed a dimension at a time, so that only their rows are: the rows along x
    (r2c, only `rows` of the py rows are not zero), then the columns along y (complex, in place, the rows beyond
    `rows` zeroed first); back, the columns, then only the `rows` rows wanted along x. At the paper's size (65 of 144
    rows) a pair costs about a fifth less than the two-dimensional transforms, which serve full fields (rows = py)."""

    def __init__(self, k, padded, threads, planner, rows):
        py, px = padded
        self.rows = rows
        self.real_in = pyfftw.zeros_aligned((k, rows, px), dtype=np.float64)
        self.spec = pyfftw.zeros_aligned((k, py, px // 2 + 1), dtype=np.complex128)
        self.real_out = pyfftw.empty_aligned((k, rows, px), dtype=np.float64)
        flags = (planner,)
        back = flags + ("FFTW_DESTROY_INPUT",)
        if rows == py:
            self._plans = (pyfftw.FFTW(self.real_in, self.spec, axes=(-2, -1), flags=flags, threads=threads),)
            self._back = (pyfftw.FFTW(self.spec, self.real_out, axes=(-2, -1), direction="FFTW_BACKWARD",
                                      flags=back, threads=threads),)
        else:
            head = self.spec[:, :rows, :]
            self._plans = (pyfftw.FFTW(self.real_in, head, axes=(-1,), flags=flags, threads=threads),
                           pyfftw.FFTW(self.spec, self.spec, axes=(-2,), flags=flags, threads=threads))
            self._back = (pyfftw.FFTW(self.spec, self.spec, axes=(-2,), direction="FFTW_BACKWARD", flags=flags,
                                      threads=threads),
                          pyfftw.FFTW(head, self.real_out, axes=(-1,), direction="FFTW_BACKWARD", flags=back,
                                      threads=threads))
        self.real_in[...] = 0.0  # planning with FFTW_MEASURE may have scribbled on the buffers
        self.spec[...] = 0.0
        self.spec_f = self.spec.view(np.float64)          # (re, im) interleaved view for _spectral

    def forward(self):
        if len(self._plans) == 2:
            self._plans[0].execute()
            self.spec[:, self.rows:, :] = 0.0             # the padding rows (a backward pass wrote over them)
            self._plans[1].execute()
        else:
            self._plans[0].execute()

    def backward(self):
        for plan in self._back:
            plan.execute()


class HalfSpaceOperator:
    """Influence operators of a material pair on a grid, applied by FFT.

    Parameters
    ----------
    grid : Grid
    materials : MaterialPair
    threads : FFTW threads (default 1).
    coupling : 'auto' (on when |beta| > COUPLING_THRESHOLD), True or False.
    planner : FFTW planner flag; plans are cached on disk as FFTW wisdom (ROLLCONTACT_CACHE or
        ~/.cache/rollcontact), so the measuring cost is paid once per grid size and machine.
    """

    def __init__(self, grid: Grid, materials: MaterialPair, *, threads: int = 1, coupling="auto",
                 planner: str = "FFTW_MEASURE"):
        if int(threads) < 1:
            raise InputError(f"solver.threads = {threads!r}: must be an integer >= 1")
        if coupling not in ("auto", True, False):
            raise InputError(f"coupling = {coupling!r}: allowed values are 'auto', True, False")
        self.grid = grid
        self.materials = materials
        self.threads = int(threads)
        self.coupled = (abs(materials.beta) > COUPLING_THRESHOLD) if coupling == "auto" else bool(coupling)
        ny, nx = grid.shape
        self.padded = (fft_length(2 * ny - 1), fft_length(2 * nx - 1))
        comps = ("zz", "xx", "yy", "xy") + (("xz", "yz") if self.coupled else ())
        kernels = self._kernels(comps)
        self.self_coefficients = {c: float(k[0, 0]) for c, k in kernels.items()}
        self._fft = fft_pairs((1, 2), self.padded, self.threads, planner, rows=ny)
        scale = 1.0 / (self.padded[0] * self.padded[1])  # c2r is unnormalised: fold 1/N into spectra
        self.spectra = {c: np.fft.rfft2(kw) * scale for c, kw in kernels.items()}
        self._build_inverses(planner)
        self._blocks = self._coupling_blocks() if self.coupled else {}
        self._tangential_norm = None  # largest eigenvalue of the circulant of A^tt (`tangential_norm`)
        self._tt_kernels = None  # real-space xx, xy, yy kernels (`tangential_block`), on first use
        # zz, xx, yy are even and xy is odd in both offsets, so their spectra are real (imaginary parts are
        # round-off, ~1e-14 of the real ones): the products multiply by real symbols (`_spectral`), a third of
        # the arithmetic and half the memory traffic of complex blocks. xz, yz (odd in one offset) are
        # imaginary and keep the complex path.
        self._real_symbols = {c: np.ascontiguousarray(self.spectra[c].real) for c in ("zz", "xx", "xy", "yy")}

    # --- construction ----------------------------------------------------------------------------
    def _kernels(self, comps):
        """Wrapped kernels on the padded domain: Kw[oy mod Py, ox mod Px] = A(ox dx, oy dy)."""
        g, m = self.grid, self.materials
        ny, nx = g.shape
        py, px = self.padded
        ox = np.arange(-(nx - 1), nx)
        oy = np.arange(-(ny - 1), ny)
        X, Y = np.meshgrid(ox * g.dx, oy * g.dy)
        coeffs = influence_coefficients(X, Y, g.dx, g.dy, m.G, m.nu, m.K, components=comps)
        rows, cols = np.ix_(oy % py, ox % px)
        out = {}
        for c, a in coeffs.items():
            kw = np.zeros((py, px))
            kw[rows, cols] = a
            out[c] = kw
        return out

    def _build_inverses(self, planner):
        """Strang-circulant approximate inverses on the unpadded grid, used as preconditioners.

        The Toeplitz operators of the grid are approximated by circulants of (about) the grid's own size
        whose kernel is the influence coefficient at the nearest periodic offset (Strang's choice); the
        circulant is inverted exactly in Fourier space. Working on the unpadded grid costs a quarter of
        a padded convolution, so a preconditioned CG iteration costs about 1.25 convolution pairs
        (docs/theory.md §4.3, §5.4). Its period is the 5-smooth length of the grid (smooth_length) (an odd length is kept here:
        the circulant's period changes the preconditioner, and the near-bound tangential solves were tuned
        with these periods). The zz, xx, yy kernels are even and xy is odd in X and in Y, so all four
        symbols are real. The symbol's eigenvalues are floored at PRECONDITIONER_FLOOR times the self
        coefficient (a truncated 1/r kernel is not always positive definite at the highest frequencies).
        """
        g, m = self.grid, self.materials
        ny, nx = g.shape
        sy, sx = smooth_length(ny), smooth_length(nx)
        self.small = (sy, sx)
        ox = np.arange(sx) - sx * (np.arange(sx) > sx // 2)
        oy = np.arange(sy) - sy * (np.arange(sy) > sy // 2)
        X, Y = np.meshgrid(ox * g.dx, oy * g.dy)
        k = influence_coefficients(X, Y, g.dx, g.dy, m.G, m.nu, m.K, components=("zz", "xx", "yy", "xy"))
        if sx % 2 == 0:
            k["xy"][:, sx // 2] = 0.0  # odd kernel at the Nyquist offset: no consistent sign
        if sy % 2 == 0:
            k["xy"][sy // 2, :] = 0.0
        s = {c: np.fft.rfft2(v).real for c, v in k.items()}
        zz = np.maximum(s["zz"], PRECONDITIONER_FLOOR * k["zz"][0, 0])
        block = np.stack([np.stack([s["xx"], s["xy"]], -1), np.stack([s["xy"], s["yy"]], -1)], -2)
        lam, vec = np.linalg.eigh(block)
        lam = np.maximum(lam, PRECONDITIONER_FLOOR * min(k["xx"][0, 0], k["yy"][0, 0]))
        self._tt_eigen = (lam, vec)  # for the shifted inverses (`tangential_inverse(shift=...)`)
        self._shifted_inverses = {}
        scale = 1.0 / (sy * sx)  # c2r is unnormalised
        symbols = {"zz": scale / zz, **self._tangential_inverse_symbols(0.0)}
        self.inverse_spectra = {c: np.ascontiguousarray(v, dtype=np.float64) for c, v in symbols.items()}
        self._fft_small = fft_pairs((1, 2), self.small, self.threads, planner)

    def _coupling_blocks(self):
        """The coupling products' (imaginary) spectra stacked as complex (outputs, inputs, Py, Px//2+1) arrays."""
        s = self.spectra
        return {"t_from_p": np.ascontiguousarray(np.array([[s["xz"]], [s["yz"]]])),
                "n_from_t": np.ascontiguousarray(np.array([[-s["xz"], -s["yz"]]]))}

    # --- application -----------------------------------------------------------------------------
    def _apply(self, fields, blocks, out, ffts=None):
        """out[m] = sum_k conv(blocks[m, k], fields[k]); blocks: a stacked (m, k, Py, Px//2+1) spectrum array of the
        coupling products, whose numbers of inputs and outputs differ (the outputs' spectra are formed in the other
        pair's buffer)."""
        ffts = self._fft if ffts is None else ffts
        k, m = len(fields), len(blocks)
        if k == m:
            raise InputError(f"_apply: {k} fields to {m} outputs; equal numbers share a spectrum buffer")
        ny, nx = self.grid.shape
        fin = ffts[k]
        for i, f in enumerate(fields):
            fin.real_in[i, :ny, :nx] = f
        fin.forward()
        fout = ffts[m]
        scratch = None
        for j in range(m):  # spectral products without temporaries
            acc = fout.spec[j]
            np.multiply(blocks[j, 0], fin.spec[0], out=acc)
            for i in range(1, k):
                if scratch is None:
                    scratch = np.empty_like(acc)
                np.multiply(blocks[j, i], fin.spec[i], out=scratch)
                acc += scratch
        fout.backward()
        if out is None:
            out = np.empty((m, ny, nx))
        out[...] = fout.real_out[:m, :ny, :nx]
        return out

    def normal(self, pressure, out=None):
        """u_z (mm) from the pressure field p (MPa): the w = A^zz p product."""
        return self._apply_symbols((pressure,), self._real_symbols, self._fft, None if out is None else out[None])[0]

    def tangential(self, tau_x, tau_y, out=None):
        """(u_x, u_y) (mm), shape (2, ny, nx), from the tractions tau_x, tau_y (MPa)."""
        return self._apply_symbols((tau_x, tau_y), self._real_symbols, self._fft, out)

    def tangential_from_pressure(self, pressure, out=None):
        """Coupling: (u_x, u_y) (mm) caused by the pressure p (MPa); zeros when uncoupled."""
        if not self.coupled:
            res = np.zeros((2,) + self.grid.shape) if out is None else out
            res[...] = 0.0
            return res
        return self._apply((pressure,), self._blocks["t_from_p"], out)

    def normal_from_tangential(self, tau_x, tau_y, out=None):
        """Coupling: u_z (mm) caused by the tractions (MPa): zx = -xz, zy = -yz; zeros when uncoupled."""
        if not self.coupled:
            res = np.zeros(self.grid.shape) if out is None else out
            res[...] = 0.0
            return res
        res = self._apply((tau_x, tau_y), self._blocks["n_from_t"], None if out is None else out[None])
        return res[0]

    def _apply_symbols(self, fields, y, ffts, out):
        """Forward FFT, multiply by the real symbols y (`_spectral`: zz for one field, the symmetric xx, xy, yy
        block for two), inverse FFT; ffts: the padded pairs (products) or the unpadded ones (preconditioners)."""
        k = len(fields)
        ny, nx = self.grid.shape
        f = ffts[k]
        for i, field in enumerate(fields):
            f.real_in[i, :ny, :nx] = field
        f.forward()
        if k == 1:                                   # in place: element by element
            _spectral.scale_1(f.spec_f, y["zz"], f.spec_f)
        else:
            _spectral.scale_2(f.spec_f, y["xx"], y["xy"], y["yy"], f.spec_f)
        f.backward()
        if out is None:
            out = np.empty((k, ny, nx))
        out[...] = f.real_out[:, :ny, :nx]
        return out

    def normal_inverse(self, residual, out=None):
        """Approximate (A^zz)^-1 r by the Strang-circulant inverse (a preconditioner, not an exact solve)."""
        return self._apply_symbols((residual,), self.inverse_spectra, self._fft_small,
                                   None if out is None else out[None])[0]

    def tangential_inverse(self, res_x, res_y, out=None, shift=0.0):
        """Approximate inverse of the 2x2-block tangential operator (preconditioner), shape (2, ny, nx).

        shift (mm/MPa, >= 0): invert A^tt + shift I instead, the Strang circulant with the same symbol plus the
        shift (a local stiffness added to every element, e.g. the curvature of turning slip tractions); the
        symbols of each shift are built once and cached.
        """
        if shift == 0.0:
            symbols = self.inverse_spectra
        else:
            symbols = self._shifted_inverses.get(shift)
            if symbols is None:
                if not (shift > 0.0 and math.isfinite(shift)):
                    raise InputError(f"tangential_inverse: shift = {shift!r} mm/MPa, must be finite and >= 0")
                symbols = self._shifted_inverses[shift] = self._tangential_inverse_symbols(shift)
        return self._apply_symbols((res_x, res_y), symbols, self._fft_small, out)

    def _tangential_inverse_symbols(self, shift):
        """Real symbols xx, xy, yy of (A^tt + shift I)^-1 on the unpadded circulant (1/N of the c2r folded in)."""
        lam, vec = self._tt_eigen
        scale = 1.0 / (self.small[0] * self.small[1])
        inv = np.einsum("...ik,...k,...jk->...ij", vec, 1.0 / (lam + shift), vec) * scale
        return {c: np.ascontiguousarray(inv[..., i, j]) for c, (i, j) in
                (("xx", (0, 0)), ("yy", (1, 1)), ("xy", (0, 1)))}

    def tangential_norm(self):
        """Largest eigenvalue of the padded circulant of A^tt (mm/MPa), an upper bound of the 2-norm of A^tt on the
        grid (A^tt is a principal submatrix of that circulant): the Lipschitz constant of the tangential energy's
        gradient, for gradient steps. Computed once from the symbols."""
        if self._tangential_norm is None:
            n = self.padded[0] * self.padded[1]  # the stored spectra carry the 1/N of the inverse FFT
            xx, xy, yy = (self._real_symbols[c] * n for c in ("xx", "xy", "yy"))
            self._tangential_norm = float(np.max(0.5 * (xx + yy) + np.sqrt((0.5 * (xx - yy)) ** 2 + xy ** 2)))
        return self._tangential_norm

    def tangential_block(self, rows, cols):
        """Dense A^tt among k elements given by their row (y) and column (x) indices: the (k, k) arrays
        (xx, xy, yy) in mm/MPa, entry [a, b] the displacement at element a from a unit traction on element b.
        Looked up in the real-space kernels (recovered from the spectra on the first call and kept: three
        padded real arrays, 24 MB at 511^2), so k^2 lookups: far cheaper than a product for a few elements."""
        if self._tt_kernels is None:
            n = self.padded[0] * self.padded[1]
            self._tt_kernels = tuple(np.fft.irfft2(self.spectra[c] * n, s=self.padded) for c in ("xx", "xy", "yy"))
        rows = np.asarray(rows, dtype=np.intp)
        cols = np.asarray(cols, dtype=np.intp)
        oy = (rows[:, None] - rows[None, :]) % self.padded[0]
        ox = (cols[:, None] - cols[None, :]) % self.padded[1]
        return tuple(k[oy, ox] for k in self._tt_kernels)

    # --- small-grid reference --------------------------------------------------------------------
    def dense(self, component: str) -> np.ndarray:
        """Dense (N x N) matrix of one component, N = nx*ny, row-major over (j, i). For tests only."""
        g, m = self.grid, self.materials
        X, Y = g.mesh()
        dX = X.ravel()[:, None] - X.ravel()[None, :]
        dY = Y.ravel()[:, None] - Y.ravel()[None, :]
        return influence_coefficients(dX, dY, g.dx, g.dy, m.G, m.nu, m.K, components=(component,))[component]
