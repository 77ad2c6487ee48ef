"""Surface operators given by their Toeplitz kernels, applied by zero-padded FFT (docs/theory.md §3).

`HalfSpaceOperator` builds the elastic influence coefficients itself and uses their symmetries (even zz, xx, yy; odd
xy: real spectra). `ToeplitzOperator` takes the kernels as arrays instead, with no symmetry assumed: e.g. the
steady-rolling operator of a viscoelastic half-space (solver.visco), whose kernels carry the upstream memory of the
material and are not even in x. It offers the products and the normal preconditioner of `HalfSpaceOperator`
(`normal`, `tangential`, `tangential_from_pressure`, `normal_from_tangential`, `normal_inverse`) on the same FFTW
plans.

Kernels: a dict component -> array of shape (2 ny - 1, 2 nx - 1), entry [oy + ny - 1, ox + nx - 1] the displacement
(mm) at offset (ox dx, oy dy) (target minus source) from a unit traction (1 MPa) on an element; components 'zz', 'xx',
'yy', 'xy' (= 'yx'), and for normal-tangential coupling 'xz', 'yz' (u_x, u_y from p; u_z from tau is zx = -xz,
zy = -yz, as for the elastic kernels, docs/theory.md §2.2). Units: mm, MPa.
"""
import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.operator import PRECONDITIONER_FLOOR, fft_pairs, fft_length, smooth_length

REQUIRED = ("zz", "xx", "yy", "xy")
COUPLING = ("xz", "yz")


class ToeplitzOperator:
    """Products with given Toeplitz kernels on `grid` (module docstring); `materials` (optional) is carried for the
    solvers that read constants from it (a cold start's E*). coupled: True when the 'xz', 'yz' kernels are given."""

    def __init__(self, grid: Grid, kernels: dict, *, materials=None, threads: int = 1,
                 planner: str = "FFTW_MEASURE"):
        ny, nx = grid.shape
        missing = [c for c in REQUIRED if c not in kernels]
        if missing:
            raise InputError(f"ToeplitzOperator: kernels {missing} missing; need {list(REQUIRED)} (+ {list(COUPLING)})")
        self.coupled = all(c in kernels for c in COUPLING)
        for c, k in kernels.items():
            if np.shape(k) != (2 * ny - 1, 2 * nx - 1) or not np.all(np.isfinite(k)):
                raise InputError(f"ToeplitzOperator: kernel {c!r} must be a finite array of shape "
                                 f"{(2 * ny - 1, 2 * nx - 1)} for the grid {grid.shape}, got {np.shape(k)}")
        self.grid, self.materials, self.threads = grid, materials, int(threads)
        self.kernels = {c: np.asarray(k, dtype=float) for c, k in kernels.items()}
        self.self_coefficients = {c: float(k[ny - 1, nx - 1]) for c, k in self.kernels.items()}
        self.padded = (fft_length(2 * ny - 1), fft_length(2 * nx - 1))
        self._fft = fft_pairs((1, 2, 3), self.padded, self.threads, planner)
        py, px = self.padded
        self._products = np.empty((3, py, px // 2 + 1), dtype=np.complex128)   # two outputs at most, and a term
        rows, cols = np.ix_(np.arange(-(ny - 1), ny) % py, np.arange(-(nx - 1), nx) % px)
        f1 = self._fft[1]
        spectra = {}
        for c, k in self.kernels.items():
            f1.real_in[0] = 0.0
            f1.real_in[0][rows, cols] = k
            f1.forward()
            spectra[c] = f1.spec[0] / (py * px)            # c2r is unnormalised
        f1.real_in[...] = 0.0
        self._blocks = {"zz": np.array([[spectra["zz"]]]),
                        "tt": np.array([[spectra["xx"], spectra["xy"]], [spectra["xy"], spectra["yy"]]])}
        if self.coupled:
            self._blocks["t_from_p"] = np.array([[spectra["xz"]], [spectra["yz"]]])
            self._blocks["n_from_t"] = np.array([[-spectra["xz"], -spectra["yz"]]])
        self._build_inverse(planner)

    def _build_inverse(self, planner):
        """The Strang circulant of the zz kernel on the 5-smooth period of the grid, inverted in Fourier space (a
        preconditioner): its symbol is complex when the kernel is not even; its real part is floored at
        PRECONDITIONER_FLOOR times the self coefficient."""
        ny, nx = self.grid.shape
        sy, sx = smooth_length(ny), smooth_length(nx)
        self.small = (sy, sx)
        ox = np.arange(sx) - sx * (np.arange(sx) > sx // 2)
        oy = np.arange(sy) - sy * (np.arange(sy) > sy // 2)
        ox, oy = np.clip(ox, -(nx - 1), nx - 1), np.clip(oy, -(ny - 1), ny - 1)
        circ = self.kernels["zz"][np.ix_(oy + ny - 1, ox + nx - 1)]
        s = np.fft.rfft2(circ)
        floor = PRECONDITIONER_FLOOR * self.self_coefficients["zz"]
        s = np.maximum(s.real, floor) + 1j * s.imag
        self._inverse = np.array([[1.0 / (s * (sy * sx))]])
        self._fft_small = fft_pairs((1,), self.small, self.threads, planner)

    def _apply(self, fields, blocks, out, ffts=None):
        """out[m] = sum_k conv(blocks[m, k], fields[k]) (complex spectra; formed in `_products`, then handed to the
        output batch's spectrum, which may be the input's)."""
        ffts = self._fft if ffts is None else ffts
        k, m = len(fields), len(blocks)
        ny, nx = self.grid.shape
        fin = ffts[k]
        for i, f in enumerate(fields):
            fin.real_in[i, :ny, :nx] = f
        fin.forward()
        fout = ffts[m]
        acc, scratch = self._products[:m], self._products[-1]
        for j in range(m):
            np.multiply(blocks[j, 0], fin.spec[0], out=acc[j])
            for i in range(1, k):
                np.multiply(blocks[j, i], fin.spec[i], out=scratch)
                acc[j] += scratch
        fout.spec[...] = acc
        fout.backward()
        if out is None:
            out = np.empty((m, ny, nx))
        out[...] = fout.real_out[:m, :ny, :nx]
        return out

    def normal(self, pressure, out=None):
        """u_z (mm) from the pressure p (MPa)."""
        return self._apply((pressure,), self._blocks["zz"], None if out is None else out[None])[0]

    def tangential(self, tau_x, tau_y, out=None):
        """(u_x, u_y) (mm), shape (2, ny, nx), from the tractions (MPa)."""
        return self._apply((tau_x, tau_y), self._blocks["tt"], out)

    def tangential_from_pressure(self, pressure, out=None):
        """Coupling: (u_x, u_y) (mm) from the pressure (MPa); zeros when uncoupled."""
        if not self.coupled:
            res = np.zeros((2,) + self.grid.shape) if out is None else out
            res[...] = 0.0
            return res
        return self._apply((pressure,), self._blocks["t_from_p"], out)

    def normal_from_tangential(self, tau_x, tau_y, out=None):
        """Coupling: u_z (mm) from the tractions (MPa); zeros when uncoupled."""
        if not self.coupled:
            res = np.zeros(self.grid.shape) if out is None else out
            res[...] = 0.0
            return res
        return self._apply((tau_x, tau_y), self._blocks["n_from_t"], None if out is None else out[None])[0]

    def normal_inverse(self, residual, out=None):
        """Approximate inverse of the zz operator (the Strang circulant's; a preconditioner, not a solve)."""
        ny, nx = self.grid.shape
        sy, sx = self.small
        f = self._fft_small[1]
        f.real_in[0] = 0.0
        f.real_in[0, :ny, :nx] = residual
        f.forward()
        np.multiply(self._inverse[0, 0], f.spec[0], out=f.spec[0])
        f.backward()
        if out is None:
            out = np.empty((ny, nx))
        out[...] = f.real_out[0, :ny, :nx]
        return out

    def dense(self, component: str) -> np.ndarray:
        """Dense (N x N) matrix of one component, N = nx*ny, row-major over (j, i). For tests only."""
        ny, nx = self.grid.shape
        j, i = np.divmod(np.arange(ny * nx), nx)
        k = self.kernels[component]
        return k[(j[:, None] - j[None, :]) + ny - 1, (i[:, None] - i[None, :]) + nx - 1]

