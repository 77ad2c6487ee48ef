"""Frictionless normal contact on the elastic half-space (docs/theory.md §4): NormCG in `normcg`, its compiled element
loops in `_kernels`. Units: mm, N, MPa."""
from rollcontact.solver.normal.normcg import NormalParams, NormalResult, solve_normal

__all__ = ["NormalParams", "NormalResult", "solve_normal"]
