"""Contact temperatures: the frictional heat of a rolling contact and its partition between the two bodies
(docs/theory.md §12.2; docs/friction.md, "Temperatures").

The frictional power density of an element, q = tau . s (W/mm^2: traction in MPa times the slip velocity in mm/s,
times 1e-3 W per N mm/s), enters the two surfaces, q = q1 + q2. Each body's surface temperature is its bulk
temperature plus the steady temperature rise of a half-space moving at the rolling speed under its own flux
(`bem.heat.MovingHeatSource`; both bodies' material passes through the contact at the rolling speed, up to the
creepage). In the contact the two surfaces touch, so their temperatures are equal there (perfect thermal contact):
on the contact elements

    T_bulk1 + K1 q1 = T_bulk2 + K2 (q - q1)

a linear system for q1 (GMRES with the FFT products; q1 = q/2 without a solve when the bodies are thermally alike
at one bulk temperature). Outside the contact no heat crosses the surfaces. This also carries heat from the hotter
to the colder body without friction (different bulk temperatures), and gives Blok's partition
q1/q -> e1/(e1 + e2) (e = sqrt(k rho c_p), the effusivity) at high Peclet numbers. Units: mm, s, W, degC.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollcontact.bem.errors import ConvergenceError
from rollcontact.bem.heat import MovingHeatSource, ThermalBody

#: W per (MPa mm/s) = N mm/s per mm^2
WATT_PER_NMM_S = 1e-3
#: relative tolerance of the partition solve
PARTITION_TOL = 1e-10


@dataclass
class Temperatures:
    """Surface temperatures T1, T2 (degC, (ny, nx)) of body 1 (the sphere / wheel) and body 2 (the substrate /
    rail), the heat fluxes q1, q2 into them (W/mm^2) and the frictional power (W), sum q dA."""

    T1: np.ndarray
    T2: np.ndarray
    q1: np.ndarray
    q2: np.ndarray
    power: float


def frictional_flux(traction, slip_velocity) -> np.ndarray:
    """q = |tau| s (W/mm^2) from the traction (2, ny, nx) MPa and the slip velocity magnitude (ny, nx) mm/s (in slip
    the traction opposes the slip, so tau . s = |tau| |s|)."""
    return np.hypot(traction[0], traction[1]) * np.asarray(slip_velocity, dtype=float) * WATT_PER_NMM_S


class ContactTemperature:
    """The surface temperatures of the two bodies rolling at `speed` (mm/s) on `grid` (x along the rolling
    direction, the leading edge at the larger x) with bulk temperatures T_bulk1, T_bulk2 (degC)."""

    def __init__(self, grid, body1: ThermalBody, body2: ThermalBody, speed, T_bulk1, T_bulk2):
        self.grid, self.speed = grid, float(speed)
        self.T_bulk1, self.T_bulk2 = float(T_bulk1), float(T_bulk2)
        self.heat1 = MovingHeatSource(grid, body1, speed)
        self.heat2 = self.heat1 if body2 == body1 else MovingHeatSource(grid, body2, speed)
        e1, e2 = body1.effusivity, body2.effusivity
        #: Blok's high-speed partition e1/(e1 + e2): the start of the partition solve
        self.blok_share = e1 / (e1 + e2)
        centre = (grid.ny - 1, grid.nx - 1)
        self._self_sum = float(self.heat1.kernel[centre] + self.heat2.kernel[centre])

    @property
    def symmetric(self) -> bool:
        """Bodies alike and at one bulk temperature: q1 = q2 = q/2."""
        return self.heat2 is self.heat1 and self.T_bulk1 == self.T_bulk2

    def solve(self, flux, contact) -> Temperatures:
        """Temperatures under the frictional flux (W/mm^2, (ny, nx), zero outside the contact) on the contact (bool)."""
        flux = np.where(contact, np.asarray(flux, dtype=float), 0.0)
        if self.symmetric:
            q1 = 0.5 * flux
        else:
            q1 = self._partition(flux, contact)
        q2 = flux - q1
        T1 = self.T_bulk1 + self.heat1.temperature(q1)
        T2 = self.T_bulk2 + self.heat2.temperature(q2)
        return Temperatures(T1, T2, q1, q2, float(flux.sum()) * self.grid.cell_area)

    def _partition(self, flux, contact) -> np.ndarray:
        """q1 on the contact from T_bulk1 + K1 q1 = T_bulk2 + K2 (q - q1) (GMRES, Jacobi-preconditioned)."""
        from scipy.sparse.linalg import LinearOperator, gmres
        idx = np.flatnonzero(contact.ravel())
        if idx.size == 0:
            return np.zeros_like(flux)
        shape = flux.shape

        def spread(v):
            full = np.zeros(flux.size)
            full[idx] = v
            return full.reshape(shape)

        def matvec(v):
            f = spread(v)
            return (self.heat1.temperature(f) + self.heat2.temperature(f)).ravel()[idx]

        rhs = (self.heat2.temperature(flux)).ravel()[idx] + (self.T_bulk2 - self.T_bulk1)
        n = idx.size
        A = LinearOperator((n, n), matvec=matvec, dtype=float)
        M = LinearOperator((n, n), matvec=lambda v: v / self._self_sum, dtype=float)
        x0 = self.blok_share * flux.ravel()[idx]
        x, info = gmres(A, rhs, x0=x0, M=M, rtol=PARTITION_TOL, atol=0.0, restart=60, maxiter=20)
        if info != 0:
            residual = float(np.linalg.norm(matvec(x) - rhs) / max(np.linalg.norm(rhs), 1e-300))
            raise ConvergenceError("heat partition between the bodies (equal contact temperatures) did not converge",
                                   solver="gmres", iterations=info, residual=residual, tol=PARTITION_TOL,
                                   regime=f"{n} contact elements, speed {self.speed:.6g} mm/s")
        return spread(x)
