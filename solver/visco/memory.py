"""The element states of viscoelastic bodies on a world-fixed grid, stepped with a constant step time (docs/theory.md
§12.3; docs/viscoelastic.md).

One state q (MPa) per element, traction component (p, tau_x, tau_y) and viscoelastic body (`sls`): no history is
stored. A step of dt seconds is an elastic problem with the effective pair (`sls.effective_pair`, the operator the
solvers get) plus the history displacement H_n = -sum_i A_h,i (e_i q_i - b_i t_{n-1}) of the states the step starts
from, which the stepping hands to the solvers: H_n's normal part as the normal solver's extra displacement, the change
of its tangential part, H_n - H_{n-1}, as the tangential solver's extra slip (the solver's own A (tau - tau') is the
effective operator's share of the slip). After the step the states take the step's traction (`advance`) and the
work the viscous dashpots dissipated during it is integrated exactly (`sls` module docstring).

The history operator A_h,i of body i is a bem.HalfSpaceOperator of that body alone (with the history modulus against
a rigid partner); one product of it per step and body (the traction of the step), its products of the states and of
the previous traction are carried along linearly. Traction convention of docs/theory.md §0 (p on the substrate, tau the
sphere's traction on the substrate; each body's quadratic form is its own strain energy). Units: mm, MPa, N mm, s.
"""
from __future__ import annotations

import numpy as np

from rollcontact.bem.errors import InputError
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.visco.sls import StandardLinearSolid, history_pair


def dot(a, b) -> float:
    """sum a * b of two arrays of one shape, by numpy's own loop (einsum): a BLAS dot of a grid's size is threaded and
    took milliseconds instead of microseconds on a loaded machine."""
    return float(np.einsum("i,i->", a.ravel(), b.ravel()))


def _product(op, t):
    """The displacements (u_z, u_x, u_y) (mm), shape (3, ny, nx), of the tractions t = (p, tau_x, tau_y) (MPa)."""
    out = np.empty_like(t)
    op.normal(t[0], out=out[0])
    op.tangential(t[1], t[2], out=out[1:])
    if op.coupled:
        out[0] += op.normal_from_tangential(t[1], t[2])
        out[1:] += op.tangential_from_pressure(t[0])
    return out


class _Body:
    """The states of one viscoelastic body and the products its history operator gave them."""

    def __init__(self, index, sls: StandardLinearSolid, op, dt, shape):
        self.index, self.sls, self.op = index, sls, op
        self.step = sls.step(dt)
        self.q = np.zeros((3,) + shape)             # states (MPa)
        self.Aq = np.zeros((3,) + shape)            # A_h q (mm)
        self.t = np.zeros((3,) + shape)             # traction of the last step (MPa)
        self.At = np.zeros((3,) + shape)            # A_h t (mm)

    def history(self):
        """This body's history displacement -A_h (e q - b t) (mm) for the coming step."""
        return -(self.step.decay * self.Aq - self.step.ramp * self.At)

    def advance(self, t, dA):
        """Take the step's traction t: new states, products, and the work dissipated in the step (N mm)."""
        st = self.step
        At = _product(self.op, t)
        dt_, dAt = t - self.t, At - self.At
        work = (st.I_aa * dot(self.q, self.Aq) + 2.0 * st.I_ac * dot(self.q, dAt)
                + st.I_cc * dot(dt_, dAt)) * dA / self.sls.tau
        self.q = st.decay * self.q + st.ramp * dt_
        self.Aq = st.decay * self.Aq + st.ramp * dAt
        self.t, self.At = t, At
        return work

    def restore(self, q, t):
        self.q = np.array(q, dtype=float)
        self.t = np.array(t, dtype=float)
        self.Aq = _product(self.op, self.q)
        self.At = _product(self.op, self.t)


class ViscoMemory:
    """The SLS states of the viscoelastic bodies of a run on `op`'s world-fixed grid (module docstring).

    op: the bem.HalfSpaceOperator of the effective pair of the step time (its grid, threads and coupling are the
    history operators'); bodies: {1: StandardLinearSolid} and/or {2: ...}; dt: the step time (s), the same for every
    step. Use: `terms()` before a step (extra displacement and slip for the solvers), `advance(pressure, traction,
    displacement)` after it (returns the total tangential displacement and records the dissipated work in
    `dissipation`, N mm)."""

    def __init__(self, op, bodies: dict, dt: float):
        if not bodies or set(bodies) - {1, 2}:
            raise InputError(f"ViscoMemory: bodies must map 1 and/or 2 to a StandardLinearSolid, got {sorted(bodies)}")
        self.op, self.dt = op, float(dt)
        self.grid = op.grid
        shape = op.grid.shape
        self.bodies = []
        for index in sorted(bodies):
            sls = bodies[index]
            if not isinstance(sls, StandardLinearSolid):
                raise InputError(f"ViscoMemory: body {index} must be a StandardLinearSolid, got {sls!r}")
            hop = HalfSpaceOperator(op.grid, history_pair(sls, index), threads=op.threads, coupling=op.coupled)
            self.bodies.append(_Body(index, sls, hop, self.dt, shape))
        self._history = np.zeros((3,) + shape)     # H of the last step (mm)
        self._coming = None
        self.dissipation = 0.0                      # work dissipated in the last step (N mm)

    def terms(self):
        """(extra_displacement (ny, nx), extra_slip (2, ny, nx)) in mm for the coming step: the history displacement's
        normal part and the change of its tangential part since the last step."""
        self._coming = sum(b.history() for b in self.bodies)
        return self._coming[0], self._coming[1:] - self._history[1:]

    def advance(self, pressure, traction, displacement):
        """Record the step just solved (p (ny, nx), tau (2, ny, nx) MPa, and the tangential displacement (2, ny, nx)
        mm the solver returned, the effective operator's share): advance the states and return the total tangential
        displacement (mm), the history displacement added. The dissipated work is in `dissipation` (N mm)."""
        if self._coming is None:
            raise InputError("ViscoMemory.advance before terms(): each step takes its terms first")
        t = np.concatenate([np.asarray(pressure, float)[None], np.asarray(traction, float)])
        dA = self.grid.cell_area
        self.dissipation = sum(b.advance(t, dA) for b in self.bodies)
        self._history, self._coming = self._coming, None
        return np.asarray(displacement) + self._history[1:]

    def states(self) -> dict:
        """The states as named (ny, nx) arrays (MPa): q_p<i>, q_x<i>, q_y<i> for each viscoelastic body i."""
        out = {}
        for b in self.bodies:
            for k, name in enumerate("pxy"):
                out[f"q_{name}{b.index}"] = b.q[k]
        return out

    def restore(self, states: dict, pressure, traction, displacement):
        """Continue from a stored step: its states (as `states()` names them), pressure, traction and total tangential
        displacement (2, ny, nx) mm. The history displacement of that step is the total minus the effective
        operator's share A tau (+ A^tz p)."""
        t = np.concatenate([np.asarray(pressure, float)[None], np.asarray(traction, float)])
        for b in self.bodies:
            try:
                q = np.stack([states[f"q_{n}{b.index}"] for n in "pxy"])
            except KeyError as exc:
                raise InputError(f"viscoelastic restart: the state {exc.args[0]} of body {b.index} was not stored") \
                    from None
            b.restore(q, t)
        own = self.op.tangential(t[1], t[2])
        if self.op.coupled:
            own = own + self.op.tangential_from_pressure(t[0])
        self._history = np.zeros_like(t)
        self._history[1:] = np.asarray(displacement, float) - own
        self._coming = None
