"""Kalker's quasi-static transient ("shift") problem with a prescribed tangential force (docs/theory.md §5).

`shift` is the entry point (`solve_tangential`); the private modules are its iteration (`_tangcg`), the linearised
problem on a fixed stick/slip division (`_linearised`) and its preconditioner (`_preconditioner`), the division
(`_division`), the moves on the Coulomb discs (`_moves`), the force constraint (`_force_projection`), the cycling
safeguard (`_gradient_phase`) and the shared numba helpers (`_common`). Units: mm, N, MPa.
"""
from rollcontact.solver.tangential.shift import (TangentialParams, TangentialResult, kernels_cached,
                                                 solve_tangential, traction_capacity)

__all__ = ["TangentialParams", "TangentialResult", "kernels_cached", "solve_tangential", "traction_capacity"]
