"""Friction beyond Coulomb: slip-velocity and temperature laws, friction memory, the slip-velocity iteration and the
contact temperatures (docs/theory.md §12.1-12.2; docs/friction.md).

    laws        the friction laws: Coulomb, linear, rational, exponential (slip velocity), temperature
    memory      the coefficient relaxing towards the law over a sliding distance
    iteration   the slip-velocity iteration: the coefficient field consistent with the solution it bounds
    model       a run's friction (law, memory, speed, tolerances) and what a solve with it gives (FrictionState)
    transient   one step of a stepped run with a law
    steady      steady rolling with a law
    thermal     the frictional heat, its partition between the bodies and their surface temperatures

Units: mm, N, MPa, s, mm/s, W, degC.
"""
from rollcontact.solver.friction.iteration import Consistent, FrictionParams, consistent_coefficient
from rollcontact.solver.friction.laws import KINDS, VELOCITY_KINDS, FrictionLaw
from rollcontact.solver.friction.memory import FrictionMemory
from rollcontact.solver.friction.model import FrictionState, LocalFriction
from rollcontact.solver.friction.steady import solve_steady_friction, upwind_self_coefficient
from rollcontact.solver.friction.thermal import ContactTemperature, Temperatures, frictional_flux
from rollcontact.solver.friction.transient import friction_step

__all__ = ["Consistent", "FrictionParams", "consistent_coefficient", "KINDS", "VELOCITY_KINDS", "FrictionLaw",
           "FrictionMemory", "FrictionState", "LocalFriction", "solve_steady_friction", "upwind_self_coefficient",
           "ContactTemperature", "Temperatures", "frictional_flux", "friction_step"]
