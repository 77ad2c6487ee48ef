"""Multiply stage of the circulant preconditioners: spectra times real symbols, one compiled pass.

The preconditioners' symbols (Strang-circulant inverses of the even zz, xx, yy kernels and the odd xy
kernel) are real (`HalfSpaceOperator._build_inverses`), so each spectral value is scaled, not rotated.
The complex spectra are passed as float64 views (re, im interleaved along the last axis), so a symbol
value applies to two neighbouring entries. On the small grids of a preconditioner the numpy route (one
ufunc call per block and a temporary) costs more in call overhead than in arithmetic.
"""
import numba as nb


@nb.njit(cache=True, nogil=True)
def scale_1(spec, sym, out):
    """out = sym * spec for one field: spec, out (1, Py, 2*(Px//2+1)) float views; sym (Py, Px//2+1)."""
    py, pxh = sym.shape
    for j in range(py):
        for k in range(pxh):
            s = sym[j, k]
            out[0, j, 2 * k] = s * spec[0, j, 2 * k]
            out[0, j, 2 * k + 1] = s * spec[0, j, 2 * k + 1]


@nb.njit(cache=True, nogil=True)
def scale_2(spec, sxx, sxy, syy, out):
    """(out_x, out_y) = [[sxx, sxy], [sxy, syy]] (spec_x, spec_y) for a symmetric 2x2 block of symbols."""
    py, pxh = sxx.shape
    for j in range(py):
        for k in range(2 * pxh):
            h = k // 2
            x = spec[0, j, k]
            y = spec[1, j, k]
            out[0, j, k] = sxx[j, h] * x + sxy[j, h] * y
            out[1, j, k] = sxy[j, h] * x + syy[j, h] * y
