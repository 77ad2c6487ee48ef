"""Viscoelastic bodies: the Standard Linear Solid's element states, their exact step update, and the steady-rolling operator (docs/theory.md §12.3).

    sls             the SLS of one body: creep compliance, the exact coefficients of a step, effective and history pairs
    memory          the element states on a world-fixed grid, stepped with a constant step time (ViscoMemory)
    steady_kernels  the Toeplitz kernels of steady rolling in contact-fixed coordinates (the material's memory)
    normal_steady   frictionless contact with a non-symmetric operator (active set + GMRES)
    gmres           restarted right-preconditioned GMRES
    steady          steady rolling: the operator, the normal and tangential problems, the viscous power
    hunter          Hunter's rigid cylinder on an SLS half-space (closed form)

The names below are imported on first use (the scene module reads `sls` without loading pyfftw). Units: mm, N, MPa, s.
"""
from importlib import import_module

_WHERE = {"StandardLinearSolid": "sls", "effective_pair": "sls", "history_pair": "sls", "ViscoMemory": "memory",
          "SteadyVisco": "steady", "hunter_cylinder": "hunter"}
__all__ = list(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        return getattr(import_module(f"{__name__}.{_WHERE[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_WHERE))
