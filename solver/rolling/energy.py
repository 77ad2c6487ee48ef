"""The frictional work of a step (docs/theory.md §11.2): the energy Coulomb friction dissipates, N mm.

With the traction tau_n (MPa) at the end of step n and the slip s_n of the step (mm; substrate particle
relative to the sphere, docs/theory.md §5.1), the work of the step is

    D_n = - sum_I tau_n,I . s_n,I dA        (N mm)

the end-of-step traction times the slip increment: the dissipation of the implicit (backward-Euler) Coulomb
law the tangential solver enforces. In slip tau = -mu p s/|s|, so each slipping element adds mu p |s| dA >= 0;
in stick s = 0 to the solver's tolerance and the element adds nothing. An element that starts to slip within
the step slips at the bound, so this rule is exact for it, where a midpoint traction (tau_n + tau_n-1)/2 would
count part of its slip at the stick traction. Over a closed load cycle (the elastic state returns) the sum
equals the loop area of F against U up to the load-step discretisation (docs/theory.md §11.2; tests/solver/
test_load_schedule.py measures both).
"""
import numpy as np


def frictional_work(traction, slip, cell_area) -> float:
    """-sum tau . s dA (N mm) of traction (2, ny, nx) MPa, slip (2, ny, nx) mm, element area cell_area mm^2."""
    return -float(np.vdot(traction, slip)) * cell_area
