"""Multiply stage of the uncoupled products and of the circulant preconditioners: spectra times real symbols.

The zz, xx, yy kernels are even and the xy kernel is odd in both offsets, so their spectra (padded products)
and the Strang-circulant inverses built from them (preconditioners, `HalfSpaceOperator._build_inverses`) are
real: each spectral value is scaled, not rotated.
The complex spectra are passed as float64 views (re, im interleaved along the last axis), so a symbol
value applies to two neighbouring entries. On the small grids of a preconditioner the numpy route (one
ufunc call per block and a temporary) costs more in call overhead than in arithmetic. `out` may be `spec` itself
(the operator scales in place): each entry is read before it is written.
"""
from rollcontact.bem.compiled import kernel


@kernel("void(f8[:, :, ::1], f8[:, ::1], f8[:, :, ::1])")
def scale_1(spec, sym, out):
    """out = sym * spec for one field: spec, out (1, Py, 2*(Px//2+1)) float views; sym (Py, Px//2+1)."""
    py, pxh = sym.shape
    for j in range(py):
        for k in range(pxh):
            s = sym[j, k]
            out[0, j, 2 * k] = s * spec[0, j, 2 * k]
            out[0, j, 2 * k + 1] = s * spec[0, j, 2 * k + 1]


@kernel("void(f8[:, :, ::1], f8[:, ::1], f8[:, ::1], f8[:, ::1], f8[:, :, ::1])")
def scale_2(spec, sxx, sxy, syy, out):
    """(out_x, out_y) = [[sxx, sxy], [sxy, syy]] (spec_x, spec_y) for a symmetric 2x2 block of symbols."""
    py, pxh = sxx.shape
    for j in range(py):
        for h in range(pxh):
            a, b, c = sxx[j, h], sxy[j, h], syy[j, h]
            for k in (2 * h, 2 * h + 1):  # real and imaginary part
                x = spec[0, j, k]
                y = spec[1, j, k]
                out[0, j, k] = a * x + b * y
                out[1, j, k] = b * x + c * y
