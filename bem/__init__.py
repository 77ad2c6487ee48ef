"""Elastic half-space: materials, world-fixed grid, influence coefficients, FFT convolution operator.

    errors      the project's exceptions (RollcontactError and its kinds)
    materials   elastic constants of a pair of bodies (docs/theory.md §1)
    grid        the world-fixed grid of piecewise-constant elements
    influence   Boussinesq-Cerruti influence coefficients of a rectangular element (docs/theory.md §2)
    operator    the influence coefficients applied by zero-padded FFT convolution (docs/theory.md §3)
    toeplitz    given (non-symmetric) Toeplitz kernels applied the same way (steady viscoelastic rolling)
    subsurface  stresses below the grid from its tractions, depth layer by depth layer (docs/theory.md §11.6)
    rows        the tangential influence of one grid row's change on the other rows, by 1-D FFTs
    wisdom      FFTW wisdom cached on disk (and the pyfftw import the operator uses)
    heat        surface temperature of a half-space moving under a heat flux (moving heat source, by FFT)

Imports nothing else of rollcontact. Units: mm, N, MPa (influence coefficients in mm/MPa). The names below are
imported on first use, so that `rollcontact.bem.errors` does not load numpy, pyfftw and numba.
"""
from importlib import import_module

_WHERE = {"ConvergenceError": "errors", "ContactEdgeError": "errors", "GrossSlidingError": "errors",
          "OutputExistsError": "errors", "OutputInUseError": "errors",
          "InputError": "errors", "RollcontactError": "errors", "SceneError": "errors", "Grid": "grid",
          "contact_box": "grid", "influence_coefficients": "influence", "Material": "materials",
          "MaterialPair": "materials", "HalfSpaceOperator": "operator", "ToeplitzOperator": "toeplitz",
          "SubsurfaceStresses": "subsurface", "MovingHeatSource": "heat", "ThermalBody": "heat"}
__all__ = list(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        return getattr(import_module(f"{__name__}.{_WHERE[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_WHERE))
