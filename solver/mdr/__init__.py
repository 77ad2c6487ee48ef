"""The 1-D model of the method of dimensionality reduction (MDR) for oscillating rolling (docs/theory.md §8, seed §2.3):

    simulate    the spring-row simulation under constant Fn and Ft (`simulate_mdr`)
    step        one exact step of the spring row in plain numpy (the reference of the compiled `_kernels`)
    bisection   the model's shakedown limit by bisection in f_t
    limits      the closed forms of the shakedown theory (seed Eqs. 4-5, 12-21)

Units: mm, N, MPa; f_t = Ft/(mu Fn), w = W/a, u = U/U0 (seed Eq. 9). The names below are imported on first use,
so that the closed forms (`limits`) do not load the compiled simulator.
"""
from importlib import import_module

_WHERE = {"LimitBracket": "bisection", "shakedown_limit_ft": "bisection", "MDRResult": "simulate",
          "simulate_mdr": "simulate",
          "LoadSchedule": "simulate"}
__all__ = list(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        return getattr(import_module(f"{__name__}.{_WHERE[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
