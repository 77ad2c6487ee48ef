"""Friction beyond Coulomb: slip-velocity and temperature laws, friction memory, the slip-velocity iteration and the
contact temperatures (docs/theory.md §12.1-12.2; docs/friction.md).

    laws        the friction laws: Coulomb, linear, rational, exponential (slip velocity), temperature
    memory      the coefficient relaxing towards the law over a sliding distance
    iteration   the slip-velocity iteration: the coefficient field consistent with the solution it bounds
    model       a run's friction (law, memory, speed, tolerances) and what a solve with it gives (FrictionState)
    transient   one step of a stepped run with a law
    steady      steady rolling with a law
    thermal     the frictional heat, its partition between the bodies and their surface temperatures

The names below are imported on first use (a run without a law loads none of the steady solver). Units: mm, N,
MPa, s, mm/s, W, degC.
"""
from importlib import import_module

_WHERE = {"Consistent": "iteration", "FrictionParams": "iteration", "consistent_coefficient": "iteration",
          "KINDS": "laws", "VELOCITY_KINDS": "laws", "FrictionLaw": "laws", "FrictionMemory": "memory",
          "FrictionState": "model", "LocalFriction": "model", "solve_steady_friction": "steady",
          "upwind_self_coefficient": "steady", "ContactTemperature": "thermal", "Temperatures": "thermal",
          "frictional_flux": "thermal", "friction_step": "transient"}
__all__ = list(_WHERE)


def __getattr__(name):
    if name in _WHERE:
        return getattr(import_module(f"{__name__}.{_WHERE[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_WHERE))
