"""The tangential influence of a change on one grid row on the other rows, by 1-D FFTs along x (docs/theory.md §3).

A row-by-row Gauss-Seidel sweep (the steady rolling solver, `solver.creep`) changes the tractions of one row of
the (ny, nx) grid at a time; before the next row starts, the displacements of every other row must include that
change. Row j' receives the 1-D aperiodic convolution along x of the change with the kernel row of offset
j' - j: with the kernel rows' spectra computed once, that is one forward transform of the change (two fields)
and one batch of inverse transforms (two fields times the target rows), O(ny L log L) per row instead of the
O(ny nx^2) of direct sums. The convolution is circular with period L >= 2 nx - 1 (the kernel row's support):
the nx outputs read back are not reached by the wrap-around. Plans are pyfftw objects with FFTW_ESTIMATE (1-D transforms of a few hundred points:
measuring them costs more than it saves). Units: kernels in mm/MPa, changes in MPa, displacements in mm.
"""
import numpy as np

from rollcontact.bem._fftw import pyfftw
from rollcontact.bem.compiled import kernel
from rollcontact.bem.operator import fft_length


@kernel("void(f8[:, :, ::1], i8, f8[:, :, ::1], i8)")
def _accumulate(disp, first, result, nx):
    """disp[k, first + r, i] += result[k, r, i] for i < nx."""
    for k in range(2):
        for r in range(result.shape[1]):
            for i in range(nx):
                disp[k, first + r, i] += result[k, r, i]


@kernel("void(c16[:, ::1], c16[:, ::1], c16[:, ::1], i8, c16[:, ::1], c16[:, :, ::1])")
def _row_products(sxx, sxy, syy, first, spec, out):
    """out[k, r] = sum_l S_kl[first + r] spec[l] for the symmetric 2x2 block of row spectra (complex)."""
    rows = out.shape[1]
    nf = out.shape[2]
    for r in range(rows):
        o = first + r
        for f in range(nf):
            x = spec[0, f]
            y = spec[1, f]
            out[0, r, f] = sxx[o, f] * x + sxy[o, f] * y
            out[1, r, f] = sxy[o, f] * x + syy[o, f] * y


class RowInfluence:
    """The xx, xy, yy kernels of a (ny, nx) grid, kernel[oy + ny - 1, ox + nx - 1] the displacement at offset
    (ox dx, oy dy) from a unit traction on an element (shape (2 ny - 1, 2 nx - 1)), set up for `add`."""

    def __init__(self, kxx, kxy, kyy):
        rows2, cols2 = kxx.shape
        self.ny, self.nx = (rows2 + 1) // 2, (cols2 + 1) // 2
        self.length = fft_length(2 * self.nx - 1)  # the kernel row's support: no wrap onto the outputs read
        wrapped = np.arange(-(self.nx - 1), self.nx) % self.length
        self.spectra = []
        for k in (kxx, kxy, kyy):
            circ = np.zeros((rows2, self.length))
            circ[:, wrapped] = k
            self.spectra.append(np.ascontiguousarray(np.fft.rfft(circ, axis=1) / self.length))  # 1/L of the c2r
        nf = self.length // 2 + 1
        self._change = pyfftw.zeros_aligned((2, self.length), dtype=np.float64)
        self._spec = pyfftw.empty_aligned((2, nf), dtype=np.complex128)
        self._forward = pyfftw.FFTW(self._change, self._spec, axes=(-1,), flags=("FFTW_ESTIMATE",))
        self._backward = {}  # by the number of target rows

    def _inverse(self, rows):
        plan = self._backward.get(rows)
        if plan is None:
            nf = self.length // 2 + 1
            spec = pyfftw.empty_aligned((2, rows, nf), dtype=np.complex128)
            real = pyfftw.empty_aligned((2, rows, self.length), dtype=np.float64)
            plan = self._backward[rows] = pyfftw.FFTW(spec, real, axes=(-1,), direction="FFTW_BACKWARD",
                                                      flags=("FFTW_ESTIMATE", "FFTW_DESTROY_INPUT"))
        return plan

    def add(self, disp, j, change, rows: slice):
        """disp[:, rows] += the (u_x, u_y) (mm) of the traction change `change` (2, nx) (MPa) on row j.

        disp: (2, ny, nx) array; rows: a slice of target rows (step 1)."""
        nx, ny = self.nx, self.ny
        self._change[:, :nx] = change
        self._forward.execute()
        plan = self._inverse(rows.stop - rows.start)
        _row_products(*self.spectra, rows.start - j + ny - 1, self._spec, plan.input_array)
        plan.execute()
        _accumulate(disp, rows.start, plan.output_array, nx)
