"""Quasi-static rolling on a world-fixed grid (docs/theory.md §6), in the order of one run:

    profiles    undeformed gap profiles h(x, y), shifted with the sphere centre (seed Eq. 7)
    coupled     one step: normal + tangential contact, nested when the materials are coupled (docs/theory.md §6.2)
    stepping    the load path (ramp, levels, oscillation) and the time stepping along it (docs/theory.md §6.1-6.2)
    shakedown   classification of the period-end shifts: shakedown, ratcheting, undecided (docs/theory.md §8.3)

Units: mm, N, MPa.
"""
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.rolling.profiles import ArrayProfile, FunctionProfile, QuadricProfile
from rollcontact.solver.rolling.shakedown import Classification, classify
from rollcontact.solver.rolling.stepping import LoadPath, StepParams, StepRecord, StepState, build_path, run_path

__all__ = ["solve_coupled_step", "ArrayProfile", "FunctionProfile", "QuadricProfile", "Classification", "classify",
           "LoadPath", "StepParams", "StepRecord", "StepState", "build_path", "run_path"]
