"""Steady rolling over viscoelastic bodies in contact-fixed coordinates (docs/theory.md §11.5, §12.3;
docs/viscoelastic.md, "Steady rolling").

`SteadyVisco` holds, for a grid, a pair of bodies (a bem Material or a StandardLinearSolid each) and the rolling speed,
the steady operator K of `steady_kernels` (a bem.ToeplitzOperator), the effective elastic operator whose contact warm
starts the normal problem, and the tangential problem of `solver.creep.steady` on K (`ViscoSteadyRolling`: Kalker's
Gauss-Seidel in traction differences, for which u_I - u_{I+1} = (K dp)_I holds as for any Toeplitz operator).

Its outputs for a steady state: the element states along the rolling direction (`states`), and the power the viscous
dashpots dissipate (`viscous_power`, W), the infinite wake behind the grid included in closed form: behind the grid the
traction is zero and a state decays as e^k over k cells, so its products with the history operator are the exponential
sums of `steady_kernels.tail_kernels` (docs/viscoelastic.md). Kalker's convention as in solver.creep.steady: body 1
rolls in +x. Units: mm, N, MPa, s, W.
"""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.bem.rows import RowInfluence
from rollcontact.bem.toeplitz import ToeplitzOperator
from rollcontact.solver.creep.steady import SteadyRolling
from rollcontact.solver.normal import NormalParams, solve_normal
from rollcontact.solver.visco.memory import dot
from rollcontact.solver.visco.normal_steady import solve_normal_steady
from rollcontact.solver.visco.sls import StandardLinearSolid, effective_pair, history_pair
from rollcontact.solver.visco.steady_kernels import influence, steady_kernels, tail_kernels

#: mm N/s per W
MILLI = 1e-3


class ViscoSteadyRolling(SteadyRolling):
    """The steady tangential problem of `solver.creep.steady` with the viscoelastic steady operator `op` (a
    bem.ToeplitzOperator whose kernels include 'xx', 'xy', 'yy' and, when coupled, 'xz', 'yz'). Its rows are swept
    with the material's flow, from the leading edge: the memory makes the displacement at a cell depend most on the
    traction upstream, which that order takes in as a forward substitution (21-32 sweeps for E_g/E_r = 1.5-5 and
    V tau/a = 0.3-3 at a/dx = 12; Kalker's order, from the trailing edge, needs 36-115 at E_g/E_r <= 2 and diverges
    from E_g/E_r = 3 at V tau/a = 0.3)."""

    with_flow = True

    def __init__(self, op: ToeplitzOperator, materials):
        grid = op.grid
        ny = grid.shape[0]
        self.grid, self.materials = grid, materials
        k = op.kernels
        self.kernels = tuple(np.ascontiguousarray(k[c]) for c in ("xx", "xy", "yy"))
        self.rows = (np.ascontiguousarray(k["xx"][ny - 1]), np.ascontiguousarray(k["yy"][ny - 1]))
        self.row_influence = RowInfluence(*self.kernels)
        self._coupling = (k["xz"], k["yz"]) if op.coupled else None
        self._operator = op


class SteadyVisco:
    """Steady rolling at `speed` (mm/s) over `body1`, `body2` on the contact-fixed `grid` (module docstring).
    coupled: include the normal-tangential coupling ('auto': when the effective pair's |beta| exceeds the operator's
    threshold, as bem.HalfSpaceOperator decides); threads: FFTW threads."""

    def __init__(self, grid, body1, body2, speed: float, *, coupling="auto", threads: int = 1):
        self.grid, self.speed = grid, float(speed)
        self.bodies = {i: b for i, b in ((1, body1), (2, body2)) if isinstance(b, StandardLinearSolid)}
        self.dt = grid.dx / self.speed
        # the effective pair decides the coupling, as for an elastic run
        pair = effective_pair(body1, body2, self.dt)
        self.elastic = HalfSpaceOperator(grid, pair, threads=threads, coupling=coupling)
        kernels, self.materials = steady_kernels(grid, body1, body2, self.speed, coupled=self.elastic.coupled)
        self.operator = ToeplitzOperator(grid, kernels, materials=self.materials, threads=threads)
        self.tangential_problem = ViscoSteadyRolling(self.operator, self.materials)
        self._wake = {}

    @property
    def coupled(self) -> bool:
        return self.operator.coupled

    def solve_normal(self, profile, force, *, initial=None, extra_displacement=None, params=NormalParams()):
        """The steady normal problem (`normal_steady.solve_normal_steady`), its contact set started from `initial`
        or from `contact_estimate`; the products of both are counted."""
        start, products = (initial, 0) if initial is not None else \
            self.contact_estimate(profile, force, extra_displacement, params)
        result = solve_normal_steady(self.operator, profile, force=force, initial=start,
                                     extra_displacement=extra_displacement, params=params)
        result.iterations += products
        return result

    def contact_estimate(self, profile, force, extra_displacement=None, params=NormalParams()):
        """(pressure, products): an elastic contact whose support starts the steady problem's active set. Each
        viscoelastic body gets the creep compliance averaged over the time 2 a / V its material spends in the contact,
        C_g + (C_r - C_g)(1 - (ell / 2a)(1 - exp(-2a/ell))), ell = V tau, with a the half-length along x of the
        relaxed contact. Both elastic contacts are solved on the effective pair's operator: a pair whose compliances
        all scale by one factor has the same contact at the force scaled by it (exact for one compliant body or
        proportional ones; an estimate otherwise, which only the start needs). Starting from the nearly glassy
        effective pair instead took 10-20 contact-set changes (docs/viscoelastic.md)."""
        bodies = {i: (self.bodies.get(i) or self._elastic_body(i)) for i in (1, 2)}

        def solve_with(compliance, start=None):
            pair = MaterialPair(*(Material(1.0 / compliance[i], bodies[i].nu) if i in compliance else bodies[i]
                                  for i in (1, 2)))
            scaled = force * self.materials.E_star / pair.E_star
            return solve_normal(self.elastic, profile, force=scaled, initial=start,
                                extra_displacement=extra_displacement, params=params)

        relaxed = solve_with({i: b.C_relaxed for i, b in self.bodies.items()})
        X, _ = self.grid.mesh()
        on = relaxed.contact
        half = 0.5 * (float(X[on].max() - X[on].min()) + self.grid.dx) if on.any() else self.grid.dx
        mean = {}
        for i, b in self.bodies.items():
            ratio = 2.0 * half / (self.speed * b.tau)
            kept = -math.expm1(-ratio) / ratio if ratio > 0 else 1.0        # (ell / 2a)(1 - exp(-2a/ell))
            mean[i] = b.C_glassy + (b.C_relaxed - b.C_glassy) * (1.0 - kept)
        estimate = solve_with(mean, relaxed.pressure)
        return estimate.pressure, relaxed.iterations + estimate.iterations

    def _elastic_body(self, index):
        return (self.elastic.materials.body1, self.elastic.materials.body2)[index - 1]

    def states(self, traction, index: int):
        """The states q (MPa, (3, ny, nx)) of body `index` in the steady state of the traction t = (p, tau_x, tau_y)
        (MPa, substrate convention), from the leading edge: q_I = e q_{I+1} + b (t_I - t_{I+1})."""
        st = self.bodies[index].step(self.dt)
        t = np.asarray(traction, dtype=float)
        q = np.zeros_like(t)
        ahead_q = np.zeros(t.shape[:2])
        ahead_t = np.zeros(t.shape[:2])
        for i in range(t.shape[2] - 1, -1, -1):
            ahead_q = st.decay * ahead_q + st.ramp * (t[:, :, i] - ahead_t)
            q[:, :, i] = ahead_q
            ahead_t = t[:, :, i]
        return q

    def viscous_power(self, traction) -> float:
        """The power (W) the viscous dashpots of all viscoelastic bodies dissipate in the steady state of the traction
        t = (p, tau_x, tau_y) (MPa, (3, ny, nx)), wake included (module docstring)."""
        t = np.asarray(traction, dtype=float)
        if np.any(t[:, :, 0]) or np.any(t[:, :, -1]):
            raise ValueError("viscous_power: the traction must vanish on the grid's first and last columns")
        total = 0.0
        for index, body in self.bodies.items():
            total += self._body_work(index, body, t)
        return total / self.dt * MILLI

    def _body_work(self, index, body, t):
        """The work (N mm) body `index` dissipates over one step dt in the steady state (the sum over every material
        element, each passing one cell; sls module docstring)."""
        st = body.step(self.dt)
        q = self.states(t, index)
        shifted = np.zeros_like(q)                 # the state each element starts the step with: q_{I+1}
        shifted[:, :, :-1] = q[:, :, 1:]
        jump = t.copy()                            # the step's traction increment t_I - t_{I+1}
        jump[:, :, :-1] -= t[:, :, 1:]
        op = self._history_operator(index, body)
        A_s, A_j = _product(op, shifted), _product(op, jump)
        wake = q[:, :, 0]                          # behind the grid: e^(k-1) q_0 at the k-th column behind it
        cross, wake_wake = self._wake_terms(index, body, st.decay, wake)
        ss = dot(shifted, A_s) + 2.0 * dot(shifted, cross) + wake_wake
        sj = dot(shifted, A_j) + dot(jump, cross)
        jj = dot(jump, A_j)
        return (st.I_aa * ss + 2.0 * st.I_ac * sj + st.I_cc * jj) * self.grid.cell_area / body.tau

    def _history_operator(self, index, body):
        if ("op", index) not in self._wake:
            self._wake[("op", index)] = HalfSpaceOperator(self.grid, history_pair(body, index),
                                                          threads=self.elastic.threads, coupling=self.coupled)
        return self._wake[("op", index)]

    def _wake_terms(self, index, body, decay, wake):
        """(A_h W on the grid (3, ny, nx), W . A_h W) for the wake W = e^(k-1) q_0 in the k-th column behind the grid
        (k >= 1): the one-sided exponential sums T(d) = sum_{k>=1} e^(k-1) A_h(d + k dx) for the grid's columns, and
        sum_m e^|m| A_h(m dx) for the wake itself (whose double sum over k, k' is that over m = k' - k times
        1 / (1 - e^2))."""
        grid = self.grid
        ny, nx = grid.shape
        comps = ("zz", "xx", "yy", "xy") + (("xz", "yz") if self.coupled else ())
        if ("tail", index) not in self._wake:
            pair = history_pair(body, index)
            T = tail_kernels(grid, pair, decay, 1.0, comps)
            oy = np.arange(-(ny - 1), ny) * grid.dy
            A0 = influence(np.zeros_like(oy), oy, grid.dx, grid.dy, pair, comps)
            both = {c: A0[c] + 2.0 * decay * T[c][:, nx - 1] if c not in ("xy", "xz") else np.zeros(2 * ny - 1)
                    for c in comps}
            self._wake[("tail", index)] = (T, both)
        T, both = self._wake[("tail", index)]
        blocks = _blocks(comps)
        cross = np.zeros((3, ny, nx))
        ww = 0.0
        for (a, b), (c, sign) in blocks.items():
            # cross[a](i, j) = sum_j' T_c(i, j - j') W_b(j'): columns d = i >= 0 of the tail kernel
            kern = sign * T[c][:, nx - 1:]                       # (2 ny - 1, nx): offsets oy, d = 0 .. nx - 1
            for j in range(ny):
                cross[a, j] += np.einsum("k,ki->i", wake[b], kern[j - np.arange(ny) + ny - 1])
            conv = np.array([dot(wake[b], (sign * both[c])[j - np.arange(ny) + ny - 1]) for j in range(ny)])
            ww += dot(wake[a], conv)
        return cross, ww / (1.0 - decay * decay)


def _blocks(comps):
    """(target, source) component indices (0 = z, 1 = x, 2 = y) -> (kernel name, sign) of the 3 x 3 operator; the
    coupling rows u_z from tau are zx = -xz, zy = -yz."""
    blocks = {(0, 0): ("zz", 1.0), (1, 1): ("xx", 1.0), (2, 2): ("yy", 1.0), (1, 2): ("xy", 1.0),
              (2, 1): ("xy", 1.0)}
    if "xz" in comps:
        blocks.update({(1, 0): ("xz", 1.0), (2, 0): ("yz", 1.0), (0, 1): ("xz", -1.0), (0, 2): ("yz", -1.0)})
    return blocks


def _product(op, t):
    """(u_z, u_x, u_y) (mm) of the tractions t = (p, tau_x, tau_y) (MPa) by a bem operator."""
    out = np.empty_like(t)
    op.normal(t[0], out=out[0])
    op.tangential(t[1], t[2], out=out[1:])
    if op.coupled:
        out[0] += op.normal_from_tangential(t[1], t[2])
        out[1:] += op.tangential_from_pressure(t[0])
    return out


def pressure_centroid(grid, pressure, centre=0.0) -> float:
    """int x p dA / int p dA (mm) along the grid's x (the rolling direction), relative to x = centre (mm)."""
    X, _ = grid.mesh()
    p = np.asarray(pressure, dtype=float)
    return float(((X - centre) * p).sum() / p.sum())

