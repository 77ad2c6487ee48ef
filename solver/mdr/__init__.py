"""The 1-D model of the method of dimensionality reduction (MDR) for oscillating rolling (theory.md §8, seed §2.3):

    simulate    the spring-row simulation under constant Fn and Ft (`simulate_mdr`)
    step        one exact step of the spring row in plain numpy (the reference of the compiled `_kernels`)
    bisection   the model's shakedown limit by bisection in f_t
    limits      the closed forms of the shakedown theory (seed Eqs. 4-5, 12-21)

Units: mm, N, MPa; f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9).
"""
from rollcontact.solver.mdr.bisection import LimitBracket, shakedown_limit_ft
from rollcontact.solver.mdr.simulate import MDRResult, simulate_mdr

__all__ = ["LimitBracket", "shakedown_limit_ft", "MDRResult", "simulate_mdr"]
