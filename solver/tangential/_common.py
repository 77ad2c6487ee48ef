"""Shared parts of the tangential solver's element loops (`solver.tangential`): the magnitude of a traction or
slip, with the conventions of all the kernels.

The kernels (numba, compiled once per machine: `rollcontact.bem.compiled`) live by idea in `_division` (stick/slip
division, shift fit, releases), `_linearised` (residual, curvature operator and vector operations of the linearised
problem), `_moves` (the step back onto the discs, the force restoration and the turns of reversed slips),
`_force_projection` and `_preconditioner`. All fields are (ny, nx) or (2, ny, nx) float64 arrays on the grid;
`region` is int8 with 0 = exterior (bound g = 0), 1 = stick (|tau| < g), 2 = slip (|tau| = g). Tractions and bounds
in MPa, displacements and slips in mm. Nothing here allocates a grid-sized array; every kernel writes into buffers
owned by the caller.

Notation (docs/theory.md §5): w = A(tau - tau') + extra slip (mm), dU the rigid-shift increment (mm),
s = w - dU the slip of the step, n = tau/|tau| and t = (-n_y, n_x) in slip elements. `classify` stores
n of the slip elements in a (2, ny, nx) buffer `nrm` that the kernels of the same iteration read (one
square root per element and iteration instead of one per kernel); entries outside the slip area are not used.

With numba's JIT (ROLLCONTACT_KERNELS=jit) the cache is invalidated per file: a kernel in another file that inlines
`_mag` keeps its cached code when only this file changes; after changing it here, clear that cache (NUMBA_CACHE_DIR
or the __pycache__ folders of `solver`). The compiled library is rebuilt when any kernel file of the layer changes.
"""
import math

from rollcontact.bem.compiled import inline


@inline
def _mag(x, y):
    """|(x, y)|. Tractions (MPa) and slips (mm) are far from overflow, so the plain root serves: a third of
    the cost of math.hypot in these loops."""
    return math.sqrt(x * x + y * y)
