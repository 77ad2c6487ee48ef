"""Surface temperature of a half-space moving under a steady heat flux: the moving heat source (docs/friction.md,
"Temperatures"; Carslaw & Jaeger 1959, Jaeger 1942).

The heat source (the contact) moves along +x over the half-space at speed V (mm/s); in the source's frame the material
flows along -x, so the leading edge of a contact is at its largest x. A uniform flux q (W/mm^2) on the rectangle
|x'| <= hx, |y'| <= hy raises the steady surface temperature at the offset (X, Y) from its centre (X > 0 ahead) by

    theta = q / k * G(X, Y),   G = 1/(4 sqrt(pi)) int_0^inf [erf((X + hx)/u + c u/2) - erf((X - hx)/u + c u/2)]
                                                          x [erf((Y + hy)/u) - erf((Y - hy)/u)] du,      c = V/(2 kappa)

with k the conductivity (W/(mm K)) and kappa the diffusivity (mm^2/s): the instantaneous surface point source
2 Q/(rho c_p (4 pi kappa t)^(3/2)) exp(-r^2/(4 kappa t)) summed over the heat released at all earlier times t ago, the
rectangle integrated in closed form (u = sqrt(4 kappa t), the diffusion length). For V = 0 it is the element integral
of 1/(2 pi R) (Boussinesq's for the pressure, `bem.influence`); for a point source it is Rosenthal's
exp(-c (R + X)) / (2 pi R).

`element_response` evaluates G for arrays of offsets by Gauss-Legendre quadrature after a change of variable that
follows the heat's passage under the field point, so that it holds at any Peclet number, also where the thermal wake
behind a cell is far narrower than the cell (V dx / kappa >> 1): behind the element's leading edge (X < hx) the
variable is A = (X - hx)/u + c u/2, monotone in u, mapped by A = sinh(z); ahead of it (X > hx) log u.
`MovingHeatSource` holds these influence coefficients of one grid, conductivity, diffusivity and speed, built once,
and applies them to a flux field by zero-padded FFT (a linear, not a periodic, convolution). Units: mm, s, W, K (or
degC for temperature differences).
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid

#: Gauss-Legendre rule per panel.
_GAUSS = 8
#: Offsets ahead of the element whose smallest argument sqrt(2 c (X - hx)) exceeds this get no heat (erfc < 1e-21).
_AHEAD_CUTOFF = 6.8


def _panels(edges) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights over consecutive panels [edges[i], edges[i+1]]."""
    x, w = np.polynomial.legendre.leggauss(_GAUSS)
    a, b = np.asarray(edges[:-1], float), np.asarray(edges[1:], float)
    half, mid = 0.5 * (b - a), 0.5 * (b + a)
    return (mid[:, None] + half[:, None] * x[None, :]).ravel(), (half[:, None] * w[None, :]).ravel()


def _erf_difference(hi, lo, erfc):
    """erf(hi) - erf(lo) for hi >= lo from erfc(|hi|) and erfc(|lo|), without cancellation when both lie far on one
    side of 0."""
    a, b = erfc(np.abs(hi)), erfc(np.abs(lo))
    return np.where(lo >= 0.0, b - a, np.where(hi <= 0.0, a - b, 2.0 - a - b))


#: Behind the leading edge, A = EPS_A sinh(z): logarithmic in A down to |A| ~ EPS_A (the heat of distant cells, which
#: passes under the field point late, at u ~ d/|A|), linear below.
_EPS_A = 1e-3
#: Smallest diffusion length resolved, as a fraction of the element's smaller half-width; below it only the element
#: under the field point is heated (its integrand 4 is added in closed form).
_U_CUT = 0.02


def element_response(X, Y, hx, hy, c, chunk=2048) -> np.ndarray:
    """G(X, Y) in mm (module docstring): the steady temperature rise times k/q at offsets (X, Y) (mm, arrays of one
    shape; X > 0 ahead along the motion) from the centre of a 2 hx x 2 hy element under a unit uniform flux, the
    half-space moving with c = V / (2 kappa) (1/mm, >= 0). No offset may lie on an element edge (|X| = hx, |Y| = hy:
    grid offsets never do)."""
    from scipy.special import erfc
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    if not (hx > 0 and hy > 0 and c >= 0 and math.isfinite(c)):
        raise InputError(f"element_response: hx = {hx!r}, hy = {hy!r} mm must be > 0 and c = {c!r} 1/mm >= 0")
    x, y = X.ravel(), np.abs(Y.ravel())
    out = np.zeros(x.size)
    u_cut = _U_CUT * min(hx, hy)
    # behind the leading edge (d = hx - X > 0): A = -d/u + c u/2 = EPS_A sinh z, from u = u_cut to A = 7.5 (no heat
    # beyond: erfc(7.5) ~ 3e-26); panels fine enough for the step of the cell's trailing edge at A ~ -sqrt(2 c hx)
    behind = np.flatnonzero(x < hx)
    if 2.0 * c * hx < 1e-20:       # a speed this small changes G by O(sqrt(c hx)) < 1e-10: the stationary source
        c = 0.0
    if behind.size:
        width = min(0.5, 6.0 / math.sqrt(1.0 + 2.0 * c * hx))
        eps_min = min(_EPS_A, math.sqrt(2.0 * c * hx)) if c > 0 else _EPS_A
        z_lo = -math.asinh((float(np.max(hx - x[behind])) / u_cut) / eps_min)
        z_hi = math.asinh(7.5 / eps_min) if c > 0 else 0.0
        z, wz = _panels(np.linspace(z_lo, z_hi, max(2, math.ceil((z_hi - z_lo) / width)) + 1))
        z, wz = np.concatenate([[z_lo], z]), np.concatenate([[0.0], wz])    # z_lo itself: the closed-form part below
        for part in np.array_split(behind, math.ceil(behind.size / chunk)):
            d, yy = (hx - x[part])[:, None], y[part][:, None]
            # the scale of A where -d/u gives way to c u/2 (A ~ sqrt(2 c d)): resolved below EPS_A when c is small
            eps = np.minimum(_EPS_A, np.sqrt(2.0 * c * d)) if c > 0 else _EPS_A
            A, dA = eps * np.sinh(z), eps * np.cosh(z) * wz
            s = np.sqrt(A * A + 2.0 * c * d)
            with np.errstate(divide="ignore", invalid="ignore"):
                u = np.where(A <= 0.0, 2.0 * d / (s - A), (A + s) / max(c, 1e-300))
            f = _erf_difference(A + 2.0 * hx / u, A, erfc) * _erf_difference((yy + hy) / u, (yy - hy) / u, erfc)
            f = np.where(np.isfinite(u), f * (u / s), 0.0)
            out[part] = np.sum(f * dA, axis=1) + f[:, 0] * s[:, 0]   # + below z_lo: (Ex Ey)(z_lo) u(z_lo)
    # ahead of it (d = X - hx > 0): u = d e^t up to u = 2e5 d; beyond, the far-field 16 hx hy/(pi u^2) exp(-(c u/2)^2)
    ahead = np.flatnonzero((x > hx) & (np.sqrt(2.0 * c * np.maximum(x - hx, 0.0)) < _AHEAD_CUTOFF))
    if ahead.size:
        t, wt = _panels(np.arange(-4.0, 12.01, 0.5))
        et = np.exp(t)
        for part in np.array_split(ahead, math.ceil(ahead.size / chunk)):
            d, yy = (x[part] - hx)[:, None], y[part][:, None]
            u = d * et
            lo = d / u + 0.5 * c * u
            f = _erf_difference(lo + 2.0 * hx / u, lo, erfc) * _erf_difference((yy + hy) / u, (yy - hy) / u, erfc)
            u_end = d[:, 0] * math.exp(12.0)
            tail = 16.0 * hx * hy / (math.pi * u_end) * np.exp(-(0.5 * c * u_end) ** 2)
            out[part] = np.sum(f * u * wt, axis=1) + tail
    return (out / (4.0 * math.sqrt(math.pi))).reshape(X.shape)


#: Panels of the grid rule (`grid_response`) in the diffusion length u: at most this ratio per panel (log spacing)...
_LOG_RATIO = 1.25
#: ... and at most this many times 1/c wide (the heat of a cell passes under a point behind it over du ~ 6/c).
_PANEL_C = 2.0


def grid_response(x, y, hx, hy, c) -> np.ndarray:
    """G at every offset (X, Y) of the 1-D arrays x (mm, along the motion) and y (mm): the same integral as
    `element_response`, shape (len(y), len(x)), by one Gauss-Legendre rule in the diffusion length u shared by all
    offsets, on which the integrand separates, [erf-difference in X](u) x [erf-difference in Y](u): a matrix product
    of a (len(y), n_u) by an (n_u, len(x)) array. The panels are logarithmic in u (ratio _LOG_RATIO) and at most
    _PANEL_C / c wide, from u_cut = min(_U_CUT min(hx, hy), 0.1 sqrt(2 min(hx, hy) / c)) (below it only the element
    under the point is heated, 4 u_cut in closed form) to where c u/2 - max|X|/u exceeds 7.5 (no heat arrives
    later); without motion the far field 16 hx hy / (pi u^2) is added in closed form beyond u = 1e6 max(|X|, |Y|,
    hx, hy). Offsets on element edges are not allowed (grid offsets never are). Agrees with `element_response` to 1e-9 of the element's own value (tested).
    """
    from scipy.special import erfc
    x, y = np.asarray(x, dtype=float), np.abs(np.asarray(y, dtype=float))
    reach = max(float(np.max(np.abs(x))), float(np.max(y)), hx, hy)
    if 2.0 * c * hx < 1e-20:
        c = 0.0
    # below u_cut the element under the point alone is heated, and it fully: u_cut well below the time its own heat
    # takes to pass, sqrt(2 hx / c)
    u_cut = min(_U_CUT * min(hx, hy), 0.1 * math.sqrt(2.0 * min(hx, hy) / c) if c > 0 else math.inf)
    u_end = (7.5 + math.sqrt(56.25 + 2.0 * c * (reach + hx))) / c if c > 0 else 1e6 * reach
    edges = [u_cut]
    while edges[-1] < u_end:
        step = (_LOG_RATIO - 1.0) * edges[-1]
        edges.append(edges[-1] + (min(step, _PANEL_C / c) if c > 0 else step))
    u, w = _panels(np.array(edges))
    ex = _erf_difference((x[:, None] + hx) / u + 0.5 * c * u, (x[:, None] - hx) / u + 0.5 * c * u, erfc)
    ey = _erf_difference((y[:, None] + hy) / u, (y[:, None] - hy) / u, erfc)
    G = np.einsum("yu,xu->yx", ey * w, ex)     # numpy's own loops: BLAS would spin a thread per core here
    own = (np.abs(x)[None, :] < hx) & (y[:, None] < hy)        # the element under the point: 4 u_cut below u_cut
    G += np.where(own, 4.0 * u_cut, 0.0)
    if c * edges[-1] < 15.0:                                   # the far field beyond the last panel
        G += 16.0 * hx * hy / (math.pi * edges[-1]) * math.exp(-(0.5 * c * edges[-1]) ** 2)
    return G / (4.0 * math.sqrt(math.pi))


@dataclass(frozen=True)
class ThermalBody:
    """Thermal constants of one body: conductivity k (W/(mm K)), diffusivity kappa (mm^2/s)."""

    conductivity: float
    diffusivity: float

    def __post_init__(self):
        for name in ("conductivity", "diffusivity"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"ThermalBody.{name} = {v!r}: must be finite and > 0")

    @classmethod
    def from_si(cls, conductivity, density, heat_capacity) -> "ThermalBody":
        """From k in W/(m K), rho in kg/m^3 and c_p in J/(kg K)."""
        return cls(conductivity * 1e-3, conductivity / (density * heat_capacity) * 1e6)

    @property
    def effusivity(self) -> float:
        """sqrt(k rho c_p) = k / sqrt(kappa) (W s^(1/2) / (mm^2 K)): the weight of a body in Blok's high-speed
        partition of the heat."""
        return self.conductivity / math.sqrt(self.diffusivity)


class MovingHeatSource:
    """The steady surface temperature rise (K) of one body moving at `speed` (mm/s) under a heat flux on `grid`, the
    flux moving along +x relative to the body (module docstring): the influence coefficients G/k of the grid's
    element on every offset (built once), applied by zero-padded FFT."""

    def __init__(self, grid: Grid, body: ThermalBody, speed: float):
        if not (isinstance(speed, (int, float)) and math.isfinite(speed) and speed >= 0):
            raise InputError(f"MovingHeatSource: speed = {speed!r} mm/s must be finite and >= 0")
        from scipy import fft
        self.grid, self.body, self.speed = grid, body, float(speed)
        ny, nx = grid.shape
        ox, oy = np.arange(-(nx - 1), nx) * grid.dx, np.arange(0, ny) * grid.dy
        c = self.speed / (2.0 * body.diffusivity)
        half = grid_response(ox, oy, 0.5 * grid.dx, 0.5 * grid.dy, c) / body.conductivity
        #: influence coefficients (K per W/mm^2), shape (2 ny - 1, 2 nx - 1), offset (0, 0) at [ny - 1, nx - 1]
        self.kernel = np.concatenate([half[:0:-1], half])
        self._shape = (fft.next_fast_len(2 * ny - 1, real=True), fft.next_fast_len(2 * nx - 1, real=True))
        padded = np.zeros(self._shape)
        rows = np.arange(-(ny - 1), ny) % self._shape[0]
        cols = np.arange(-(nx - 1), nx) % self._shape[1]
        padded[np.ix_(rows, cols)] = self.kernel
        self._spectrum = fft.rfft2(padded)
        self._fft = fft

    @property
    def peclet_per_cell(self) -> float:
        """V dx / (2 kappa): the Peclet number of one element."""
        return self.speed * self.grid.dx / (2.0 * self.body.diffusivity)

    def temperature(self, flux) -> np.ndarray:
        """Temperature rise (K) on the grid, shape (ny, nx), under the flux (W/mm^2, (ny, nx)) into this body."""
        flux = np.asarray(flux, dtype=float)
        if flux.shape != self.grid.shape:
            raise InputError(f"heat flux has shape {flux.shape}, the grid is {self.grid.shape}")
        ny, nx = self.grid.shape
        spec = self._fft.rfft2(flux, s=self._shape)
        return self._fft.irfft2(spec * self._spectrum, s=self._shape)[:ny, :nx]
