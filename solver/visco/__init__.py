"""Viscoelastic bodies: the Standard Linear Solid's element states, their exact step update, and the steady-rolling operator (docs/theory.md §12.3)."""
from rollcontact.solver.visco.sls import StandardLinearSolid, effective_pair, history_pair
from rollcontact.solver.visco.memory import ViscoMemory

__all__ = ["StandardLinearSolid", "effective_pair", "history_pair", "ViscoMemory"]
