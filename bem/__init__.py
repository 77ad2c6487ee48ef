"""Elastic half-space: materials, world-fixed grid, influence coefficients, FFT convolution operator.

Imports nothing else of rollcontact. Units: mm, N, MPa (influence coefficients in mm/MPa).
"""
from rollcontact.bem.errors import (
    ConvergenceError, ContactEdgeError, GrossSlidingError, InputError, RollcontactError, SceneError)
from rollcontact.bem.grid import Grid, contact_box
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator

__all__ = ["ConvergenceError", "ContactEdgeError", "GrossSlidingError", "InputError", "RollcontactError",
           "SceneError", "Grid", "contact_box", "influence_coefficients", "Material", "MaterialPair",
           "HalfSpaceOperator"]
