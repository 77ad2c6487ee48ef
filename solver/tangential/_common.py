"""Shared parts of the tangential solver's element loops (`solver.tangential`): the numba decorator and the
magnitude of a traction or slip, with the conventions of all the kernels.

The kernels, compiled with numba (cache=True), live by idea in `_division` (stick/slip division,
shift fit, releases), `_linearised` (residual, curvature operator and vector operations of the linearised
problem) and `_moves` (the step back onto the discs, the force restoration and the turns of
reversed slips). All fields are (ny, nx) or (2, ny, nx) float64 arrays on the grid; `region` is int8 with
0 = exterior (bound g = 0), 1 = stick (|tau| < g), 2 = slip (|tau| = g). Tractions and bounds in MPa,
displacements and slips in mm. Nothing here allocates a grid-sized array; every kernel writes into buffers
owned by the caller.

Notation (docs/theory.md §5): w = A(tau - tau') + extra slip (mm), dU the rigid-shift increment (mm),
s = w - dU the slip of the step, n = tau/|tau| and t = (-n_y, n_x) in slip elements. `classify` stores
n of the slip elements in a (2, ny, nx) buffer `nrm` that the kernels of the same iteration read (one
square root per element and iteration instead of one per kernel); entries outside the slip area are not used.

numba's cache is invalidated per file: a kernel in another file that inlines `_mag` (or is decorated with
`_jit`) keeps its cached code when only this file changes; after changing them here, clear the cache
(NUMBA_CACHE_DIR or the __pycache__ folders of `solver`).
"""
import math

import numba as nb


_jit = nb.njit(cache=True, nogil=True, fastmath=False)


@nb.njit(cache=True, inline="always")
def _mag(x, y):
    """|(x, y)|. Tractions (MPa) and slips (mm) are far from overflow, so the plain root serves: a third of
    the cost of math.hypot in these loops."""
    return math.sqrt(x * x + y * y)
