"""A measured error table over a rectangular grid of parameters, and the conservative prediction read from it.

The models of a fidelity ladder (solver.fastsim: FASTSIM and FaStrip against the exact steady theory; solver.mdr:
the 1-D MDR model against the 3-D solver) each have an error measured at the nodes of a grid of dimensionless
parameters. Between nodes the error is not interpolated but bounded: the prediction at a point is the largest
error at the corners of the grid cell that holds it (2^d nodes), so a model is only trusted where it was measured
to be good on every side. Outside the grid in a `bounded` axis there is no prediction (None); an `unbounded` axis
clamps to its end nodes (e.g. the creepage beyond full sliding). A node without a measurement (nan) or a failed one
(inf) makes the prediction None or inf.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np


@dataclass(frozen=True)
class Axis:
    """One parameter of the grid: its name, increasing node values, and whether points beyond the end nodes take
    the end node's value (clamped) or have no prediction."""
    name: str
    nodes: tuple
    clamped: bool = False

    def bracket(self, value: float):
        """The indices (i0, i1) of the nodes around value (equal at a node or when clamped), or None outside."""
        nodes = self.nodes
        if not math.isfinite(value):
            return None
        tol = 1e-9 * max(1.0, abs(nodes[-1] - nodes[0]))
        if value < nodes[0] - tol:
            return (0, 0) if self.clamped else None
        if value > nodes[-1] + tol:
            return (len(nodes) - 1,) * 2 if self.clamped else None
        for i, node in enumerate(nodes):
            if abs(value - node) <= tol:
                return (i, i)
        i = int(np.searchsorted(nodes, value)) - 1
        return (i, i + 1)


@dataclass
class ErrorTable:
    """Errors of named models over the grid of `axes`: errors[model] has one axis per grid axis."""
    axes: tuple
    errors: dict

    def predict(self, model: str, point: dict) -> float | None:
        """The largest error at the corners of the cell holding `point` ({axis name: value}); None outside a
        bounded axis or where a corner was not measured."""
        brackets = []
        for axis in self.axes:
            b = axis.bracket(float(point[axis.name]))
            if b is None:
                return None
            brackets.append(sorted(set(b)))
        values = np.asarray(self.errors[model])[np.ix_(*brackets)]
        if np.isnan(values).any():
            return None
        return float(values.max())

    def corners(self, point: dict) -> dict | None:
        """The node values of the cell holding `point` per axis (for saying where a prediction came from)."""
        out = {}
        for axis in self.axes:
            b = axis.bracket(float(point[axis.name]))
            if b is None:
                return None
            out[axis.name] = tuple(axis.nodes[i] for i in sorted(set(b)))
        return out
