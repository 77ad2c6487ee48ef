"""Elastic half-space: materials, world-fixed grid, influence coefficients, FFT convolution operator.

Imports nothing else of rollcontact. Units: mm, N, MPa (influence coefficients in mm/MPa).
"""
from .errors import (ConvergenceError, ContactEdgeError, GrossSlidingError, InputError,
                     RollcontactError, SceneError)
from .grid import Grid, contact_box
from .influence import influence_coefficients
from .materials import Material, MaterialPair
from .operator import HalfSpaceOperator

__all__ = ["ConvergenceError", "ContactEdgeError", "GrossSlidingError", "InputError", "RollcontactError",
           "SceneError", "Grid", "contact_box", "influence_coefficients", "Material", "MaterialPair",
           "HalfSpaceOperator"]
