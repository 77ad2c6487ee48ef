"""Stresses inside the substrate from the surface tractions of a grid, depth layer by depth layer (docs/theory.md
§11.6).

Element influence. A uniform traction (pressure p, shears q_x, q_y, 1 MPa each) on one dx x dy element gives at
the offset (X, Y) (mm, observation point minus element centre) and depth z >= 0 (mm) the stresses

    4 pi sigma = [[C]](X, Y, z),  [[C]] = C(X+hx, Y+hy) - C(X+hx, Y-hy) - C(X-hx, Y+hy) + C(X-hx, Y-hy)

with closed-form corner functions C. They come from Love's potential method (Love 1929; Johnson 1985 §3.2):
for a uniform load every potential is a derivative of Phi = int int Omega over the element, Omega = z ln(rho + z)
- rho, rho = (X^2 + Y^2 + z^2)^(1/2). Omega is harmonic, Omega_X = -X/(rho + z), Omega_z = ln(rho + z), so each
stress is a sum of third derivatives of Phi and z times fourth ones, and d^2/dXdY of a corner function is the
integrand. With s = rho + z, L_X = ln(X + rho), L_Y = ln(Y + rho), i_X = 1/(X + rho), i_Y = 1/(Y + rho) and
T_X = atan(XY(X^2 + Y^2) / (s (X^2 rho + z Y^2))) (= atan(Y/X) - atan(zY/(X rho))), T_Y = T_X with X <-> Y:

    pressure p   xx  -2 T_X - 4 nu T_Y - 2 z X i_Y / rho
                 yy  -2 T_Y - 4 nu T_X - 2 z Y i_X / rho
                 zz  -2 (T_X + T_Y) + 2 z (X i_Y + Y i_X)/rho
                 yz  -2 z^2 i_X/rho
                 xz  -2 z^2 i_Y/rho
                 xy  -2 (1 - 2 nu) ln s - 2 z/rho
    shear q_x    xx  4 L_Y + 4 nu Y/s + 2 z Y/(rho s) + 2 z^2 i_Y/rho
                 yy  4 nu (L_Y - Y/s) - 2 z Y/(rho s)
                 zz  -2 z^2 i_Y/rho
                 yz  -2 z/rho
                 xz  -2 (T_X + T_Y) - 2 z X i_Y/rho
                 xy  2 L_X - 4 nu X/s - 2 z X/(rho s)

and q_y as q_x with x <-> y (X <-> Y). The derivation (the displacements of Johnson's §3.2 from the potentials
H1 = Phi for p, F1 = Phi for q_x, G1 = Phi for q_y; Hooke's law; Phi_zz = -Phi_xx - Phi_yy) was checked term by term
against adaptive quadrature of the Boussinesq-Cerruti point-load stresses over an element (1e-9 relative);
tests/bem/test_subsurface.py repeats it with Gauss-Legendre quadrature.
Stresses depend on the substrate's Poisson ratio nu only (not on its modulus).

Conventions (docs/theory.md §0): p presses on the substrate, (q_x, q_y) = (tau_x, tau_y) act on it; z is the depth
below the surface, the frame (x, y, z) has z pointing into the substrate; tension positive. At the surface
sigma_zz = -p, sigma_xz = -tau_x, sigma_yz = -tau_y; over any plane z = const the integrals of sigma_zz,
sigma_xz, sigma_yz are -Fn, -F_x, -F_y.

Cancellation: ln(Y + rho) and 1/(Y + rho) lose digits for Y < 0, |Y| >> (X^2 + z^2)^(1/2); they are evaluated as
ln(X^2 + z^2) - ln(rho - Y) and (rho - Y)/(X^2 + z^2) there (docs/theory.md §2.2a). T_X is written without the
difference rho - z. On a grid (observation points at cell centres) no corner has X = 0 or Y = 0, so every corner
function is finite also at z = 0.

Layers. On a `Grid` the stresses at depth z are aperiodic convolutions of the three traction fields with the 15
distinct kernels [[C]] (qx zz = p xz, qy zz = p yz, qx yz = qy xz); they are evaluated by zero-padded FFT on the
padded size of `bem.operator.HalfSpaceOperator` (DC-FFT, docs/theory.md §3): the tractions are transformed once, and
each
layer costs the kernel evaluation (numba) and 15 forward plus 6 inverse FFTs, with plans and buffers built once.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.compiled import internal, kernel
from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.operator import fft_length
from rollcontact.bem import wisdom as _wisdom
from rollcontact.bem._fftw import pyfftw

#: stress components, in the order of every (6, ...) array of this module (the frame x, y, z = depth)
COMPONENTS = ("s_xx", "s_yy", "s_zz", "s_yz", "s_xz", "s_xy")
#: the 15 distinct kernels: (traction, component) for each row of `_corners_at`' output
KERNELS = (("p", "s_xx"), ("p", "s_yy"), ("p", "s_zz"), ("p", "s_yz"), ("p", "s_xz"), ("p", "s_xy"),
           ("q_x", "s_xx"), ("q_x", "s_yy"), ("q_x", "s_yz"), ("q_x", "s_xz"), ("q_x", "s_xy"),
           ("q_y", "s_xx"), ("q_y", "s_yy"), ("q_y", "s_yz"), ("q_y", "s_xy"))
#: for each component, the kernel row applied to (p, q_x, q_y)
_ROWS = {"s_xx": (0, 6, 11), "s_yy": (1, 7, 12), "s_zz": (2, 4, 3), "s_yz": (3, 8, 13), "s_xz": (4, 9, 8),
         "s_xy": (5, 10, 14)}
ROWS = np.array([_ROWS[c] for c in COMPONENTS], dtype=np.int64)


@internal
def _log_plus(a, b, rho, rest2):
    """ln(a + rho) with rho^2 = a^2 + b^2 ... : rest2 = rho^2 - a^2 (> 0), written without cancellation for a < 0."""
    if a >= 0.0:
        return math.log(a + rho)
    return math.log(rest2) - math.log(rho - a)


@internal
def _inv_plus(a, rho, rest2):
    """1/(a + rho), without cancellation for a < 0 (rest2 = rho^2 - a^2)."""
    if a >= 0.0:
        return 1.0 / (a + rho)
    return (rho - a) / rest2


@internal
def _corners_at(X, Y, z, nu, out):
    """The 15 corner functions (divided by 4 pi) at one corner offset (X, Y) and depth z, into out[0:15]."""
    x2, y2, z2 = X * X, Y * Y, z * z
    rho = math.sqrt(x2 + y2 + z2)
    s = rho + z
    rx2, ry2 = y2 + z2, x2 + z2          # rho^2 - X^2, rho^2 - Y^2
    LX = _log_plus(X, Y, rho, rx2)
    LY = _log_plus(Y, X, rho, ry2)
    iX = _inv_plus(X, rho, rx2)
    iY = _inv_plus(Y, rho, ry2)
    h2 = x2 + y2
    TX = math.atan2(X * Y * h2, s * (x2 * rho + z * y2))
    TY = math.atan2(X * Y * h2, s * (y2 * rho + z * x2))
    c = 0.25 / math.pi
    zr = z / rho
    out[0] = c * (-2.0 * TX - 4.0 * nu * TY - 2.0 * zr * X * iY)
    out[1] = c * (-2.0 * TY - 4.0 * nu * TX - 2.0 * zr * Y * iX)
    out[2] = c * (-2.0 * (TX + TY) + 2.0 * zr * (X * iY + Y * iX))
    out[3] = c * (-2.0 * z * zr * iX)
    out[4] = c * (-2.0 * z * zr * iY)
    out[5] = c * (-2.0 * (1.0 - 2.0 * nu) * math.log(s) - 2.0 * zr)
    out[6] = c * (4.0 * LY + 4.0 * nu * Y / s + 2.0 * zr * Y / s + 2.0 * z * zr * iY)
    out[7] = c * (4.0 * nu * (LY - Y / s) - 2.0 * zr * Y / s)
    out[8] = c * (-2.0 * zr)
    out[9] = c * (-2.0 * (TX + TY) - 2.0 * zr * X * iY)
    out[10] = c * (2.0 * LX - 4.0 * nu * X / s - 2.0 * zr * X / s)
    out[11] = c * (4.0 * nu * (LX - X / s) - 2.0 * zr * X / s)
    out[12] = c * (4.0 * LX + 4.0 * nu * X / s + 2.0 * zr * X / s + 2.0 * z * zr * iX)
    out[13] = c * (-2.0 * (TX + TY) - 2.0 * zr * Y * iX)
    out[14] = c * (2.0 * LY - 4.0 * nu * Y / s - 2.0 * zr * Y / s)


@kernel("void(f8[::1], f8[::1], f8[::1], f8, f8, f8, f8[:, ::1])")
def _element_kernels(X, Y, z, hx, hy, nu, out):
    """out[k, i] = [[C_k]] at the offsets (X[i], Y[i]) and depths z[i] of points from an element's centre."""
    f = np.empty(15)
    for i in range(X.shape[0]):
        for k in range(15):
            out[k, i] = 0.0
        for sx, sy, sign in ((hx, hy, 1.0), (hx, -hy, -1.0), (-hx, hy, -1.0), (-hx, -hy, 1.0)):
            _corners_at(X[i] + sx, Y[i] + sy, z[i], nu, f)
            for k in range(15):
                out[k, i] += sign * f[k]


def element_stresses(X, Y, z, dx, dy, nu, traction="p"):
    """Stresses (MPa; dict by COMPONENTS, arrays shaped like the broadcast X, Y, z) at offsets X, Y (mm) from the
    centre of a dx x dy element and depths z >= 0 (mm) below it, for 1 MPa of `traction` ('p', 'q_x' or 'q_y') on
    the element; nu: the substrate's Poisson ratio. A point on an element edge at z = 0 is a discontinuity (NaN)."""
    if traction not in ("p", "q_x", "q_y"):
        raise InputError(f"traction = {traction!r}: allowed values are 'p', 'q_x', 'q_y'")
    X, Y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (X, Y, z)))
    if np.any(z < 0):
        raise InputError("depth z: must be >= 0 mm (z is measured into the substrate)")
    out = np.empty((15, X.size))
    _element_kernels(X.ravel(), Y.ravel(), z.ravel(), 0.5 * dx, 0.5 * dy, float(nu), out)
    column = {"p": 0, "q_x": 1, "q_y": 2}[traction]
    return {c: out[ROWS[m, column]].reshape(X.shape) for m, c in enumerate(COMPONENTS)}


def _parity(axis: str) -> np.ndarray:
    """The sign of each of the 15 kernels under the mirror axis -> -axis: a stress component changes sign once for
    each index along that axis, and the response to q_x (q_y) once more under x -> -x (y -> -y)."""
    return np.array([(-1.0) ** (component[2:].count(axis) + (load == "q_" + axis)) for load, component in KERNELS])


#: signs of the kernels under x -> -x and y -> -y (element kernels of a centred element: exact mirror symmetries)
PARITY_X, PARITY_Y = _parity("x"), _parity("y")


@kernel("void(i8, i8, f8, f8, f8, f8, f8[::1], f8[::1], f8[:, :, ::1])")
def _wrapped_kernels(nx, ny, dx, dy, z, nu, sign_x, sign_y, out):
    """All 15 kernels at depth z on the padded domain in wrap-around order: out[k, oy mod Py, ox mod Px] =
    [[C_k]](ox dx, oy dy, z) for |ox| < nx, |oy| < ny (the rest of `out` is left as it is: zero). The quadrant
    ox, oy >= 0 is evaluated, its corner functions once per corner of the (nx + 1) x (ny + 1) lattice at
    ((ic - 1/2) dx, (jc - 1/2) dy), a row at a time; the other three quadrants are its mirror images with the signs
    sign_x, sign_y of each kernel (PARITY_X, PARITY_Y)."""
    py, px = out.shape[1], out.shape[2]
    prev = np.empty((nx + 1, 15))
    cur = np.empty((nx + 1, 15))
    f = np.empty(15)
    for jc in range(ny + 1):
        Yc = (jc - 0.5) * dy
        for ic in range(nx + 1):
            _corners_at((ic - 0.5) * dx, Yc, z, nu, f)
            for k in range(15):
                cur[ic, k] = f[k]
        if jc > 0:
            oy = jc - 1
            for ic in range(1, nx + 1):
                ox = ic - 1
                for k in range(15):
                    v = cur[ic, k] - cur[ic - 1, k] - prev[ic, k] + prev[ic - 1, k]
                    out[k, oy, ox] = v
                    if ox > 0:
                        out[k, oy, px - ox] = sign_x[k] * v
                    if oy > 0:
                        out[k, py - oy, ox] = sign_y[k] * v
                        if ox > 0:
                            out[k, py - oy, px - ox] = sign_x[k] * sign_y[k] * v
        prev, cur = cur, prev


class SubsurfaceStresses:
    """The stress tensor below a grid from its surface tractions, one depth at a time.

    Parameters: grid (`Grid`), nu (the substrate's Poisson ratio), threads (FFTW threads), planner (FFTW flag;
    plans are measured once per size and machine and kept as wisdom, like `HalfSpaceOperator`'s).
    Use `set_tractions(p, tau_x, tau_y)` (MPa, shape (ny, nx)), then `layer(z)` for each depth. The kernels of the
    last depth are kept: for several steps, loop over the depths outside and the steps inside. kept_bytes: the
    kernel spectra of further depths kept up to that many bytes (15 half-spectra a depth: 2.1 MB on the paper's grid,
    32 MB at 256 x 256), for tractions that come one step at a time: a kept depth costs its products and inverse FFTs
    alone (on the paper's grid 30 depths take 0.055 s instead of 0.19 s). The values are the same to the bit.
    Memory: the size of 48 padded real arrays (15 kernels and their spectra, 3 tractions and their spectra, 6 output
    spectra and fields): 100 MB for a 256 x 256 grid (padded 512 x 512), whatever the number of depths, and kept_bytes.
    """

    def __init__(self, grid: Grid, nu: float, *, threads: int = 1, planner: str = "FFTW_MEASURE",
                 kept_bytes: int = 0):
        if not (-1.0 < nu <= 0.5):
            raise InputError(f"Poisson ratio nu = {nu!r}: allowed range is -1 < nu <= 0.5")
        self.grid, self.nu = grid, float(nu)
        ny, nx = grid.shape
        self.padded = py, px = (fft_length(2 * ny - 1), fft_length(2 * nx - 1))
        with _wisdom.lock:
            _wisdom.load()
            self._kernels = pyfftw.zeros_aligned((15, py, px), dtype=np.float64)
            self._kernel_spec = pyfftw.empty_aligned((15, py, px // 2 + 1), dtype=np.complex128)
            self._fields = pyfftw.zeros_aligned((3, py, px), dtype=np.float64)
            self._field_spec = pyfftw.empty_aligned((3, py, px // 2 + 1), dtype=np.complex128)
            self._out_spec = pyfftw.empty_aligned((6, py, px // 2 + 1), dtype=np.complex128)
            self._out = pyfftw.empty_aligned((6, py, px), dtype=np.float64)
            flags = (planner,)
            args = dict(axes=(-2, -1), flags=flags, threads=int(threads))
            self._fft_kernels = pyfftw.FFTW(self._kernels, self._kernel_spec, **args)
            self._fft_fields = pyfftw.FFTW(self._fields, self._field_spec, **args)
            self._ifft = pyfftw.FFTW(self._out_spec, self._out, direction="FFTW_BACKWARD",
                                     axes=(-2, -1), flags=flags + ("FFTW_DESTROY_INPUT",), threads=int(threads))
            _wisdom.save_if_new({("subsurface", (py, px), int(threads), planner)})
        self._kernels[...] = 0.0
        self._fields[...] = 0.0
        self._have_tractions = False
        self._kernel_z = None          # the depth whose kernel spectra are in _kernel_spec
        self._kept = {}                # depth -> its kernel spectra, while they fit in kept_bytes
        self._kept_bytes = int(kept_bytes)
        self.scale = 1.0 / (py * px)   # the inverse transform is unnormalised

    def set_tractions(self, pressure, tau_x, tau_y):
        """Transform the surface tractions (MPa, shape (ny, nx); p on the substrate, tau by the sphere on it)."""
        ny, nx = self.grid.shape
        for i, f in enumerate((pressure, tau_x, tau_y)):
            f = np.asarray(f, dtype=float)
            if f.shape != (ny, nx):
                raise InputError(f"traction field of shape {f.shape}: must be the grid's (ny, nx) = {(ny, nx)}")
            if not np.all(np.isfinite(f)):
                raise InputError("traction field: contains NaN or inf")
            self._fields[i, :ny, :nx] = f
        self._fft_fields.execute()
        self._field_spec *= self.scale
        self._have_tractions = True

    def layer(self, z: float, out=None) -> np.ndarray:
        """The six components (COMPONENTS order; MPa) at depth z (mm, >= 0) below every cell centre: (6, ny, nx)."""
        if not self._have_tractions:
            raise InputError("SubsurfaceStresses.layer: call set_tractions(p, tau_x, tau_y) first")
        if not (z >= 0.0 and math.isfinite(z)):
            raise InputError(f"depth z = {z!r} mm: must be finite and >= 0 (measured into the substrate)")
        g, z = self.grid, float(z)
        spectra = self._kept.get(z)
        if spectra is None:
            if self._kernel_z != z:        # the kernels depend on z alone: kept for the next tractions at this depth
                _wrapped_kernels(g.nx, g.ny, g.dx, g.dy, z, self.nu, PARITY_X, PARITY_Y, self._kernels)
                self._fft_kernels.execute()
                self._kernel_z = z
                if (len(self._kept) + 1) * self._kernel_spec.nbytes <= self._kept_bytes:
                    self._kept[z] = self._kernel_spec.copy()
            spectra = self._kernel_spec
        _combine(spectra, self._field_spec, ROWS, self._out_spec)
        self._ifft.execute()
        ny, nx = g.shape
        if out is None:
            out = np.empty((6, ny, nx))
        out[...] = self._out[:, :ny, :nx]
        return out


@kernel("void(c16[:, :, ::1], c16[:, :, ::1], i8[:, ::1], c16[:, :, ::1])")
def _combine(kernel_spec, field_spec, rows, out):
    """out[m] = sum_t kernel_spec[rows[m, t]] * field_spec[t]: the spectral products of one layer."""
    for m in range(rows.shape[0]):
        a, b, c = rows[m, 0], rows[m, 1], rows[m, 2]
        for j in range(out.shape[1]):
            for k in range(out.shape[2]):
                out[m, j, k] = (kernel_spec[a, j, k] * field_spec[0, j, k] + kernel_spec[b, j, k] * field_spec[1, j, k]
                                + kernel_spec[c, j, k] * field_spec[2, j, k])


@kernel("void(f8[:, ::1], f8[::1], f8[::1], f8[::1])")
def _invariants(s, vm, tresca, p1):
    """von Mises, max shear (s1 - s3)/2 and largest principal stress from (6, n) components (COMPONENTS order)."""
    for i in range(s.shape[1]):
        xx, yy, zz, yz, xz, xy = s[0, i], s[1, i], s[2, i], s[3, i], s[4, i], s[5, i]
        mean = (xx + yy + zz) / 3.0
        a, b, c = xx - mean, yy - mean, zz - mean
        j2 = 0.5 * (a * a + b * b + c * c) + yz * yz + xz * xz + xy * xy
        vm[i] = math.sqrt(3.0 * j2)
        if j2 <= 1e-300:
            tresca[i] = 0.0
            p1[i] = mean
            continue
        j3 = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz)
        r = math.sqrt(j2 / 3.0)
        cos3 = 0.5 * j3 / (r * r * r)
        cos3 = min(1.0, max(-1.0, cos3))
        theta = math.acos(cos3) / 3.0
        s1 = 2.0 * r * math.cos(theta)                       # largest deviatoric principal value
        s3 = 2.0 * r * math.cos(theta + 2.0 * math.pi / 3.0)  # smallest
        tresca[i] = 0.5 * (s1 - s3)
        p1[i] = mean + s1


def invariants(stresses) -> dict:
    """von_mises, tresca (the maximum shear stress (sigma_1 - sigma_3)/2) and principal_1 (the largest principal
    stress, tension positive), MPa, from an array (6, ...) of components in COMPONENTS order."""
    s = np.ascontiguousarray(stresses, dtype=float)
    shape = s.shape[1:]
    flat = s.reshape(6, -1)
    vm, tr, p1 = (np.empty(flat.shape[1]) for _ in range(3))
    _invariants(flat, vm, tr, p1)
    return {"von_mises": vm.reshape(shape), "tresca": tr.reshape(shape), "principal_1": p1.reshape(shape)}
