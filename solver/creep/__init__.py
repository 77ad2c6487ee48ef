"""Rolling with creepage and spin (docs/theory.md §7.3, §11.5), in Kalker's sign convention (`kalker`).

    kalker   Kalker's linear-theory coefficients C11, C22, C23 (CONTACT's table and interpolation)
    steady   the steady rolling problem in contact-fixed coordinates, Kalker's element Gauss-Seidel
    hertz_grid  a Hertzian ellipse on a contact-fixed grid (validation, creep curves)
    curve    creep-force curves with warm starts, the linear theory and Vermeulen-Johnson's saturation
    prescribed  the creepages for prescribed forces Fx, Fy (Broyden from the linear theory)
    world    transient rolling on the world-fixed grid from an initial state (rest, Cattaneo) towards the steady
             state: the shifted gap and the nested normal / tangential step of solver.rolling, Kalker's shift problem
    moving   the same transient on a grid that moves with the contact (the previous step's tractions carried by the
             step): the world-fixed solution near the contact, at a cost per step that does not grow with the distance
    _sweep   its compiled element loops

Units: mm, N, MPa; creepages xi, eta dimensionless, spin phi in 1/mm.
"""
from rollcontact.solver.creep.curve import CreepCurve, creep_curve, saturation_creepage, vermeulen_johnson
from rollcontact.solver.creep.hertz_grid import ellipse_grid, hertz_pressure
from rollcontact.solver.creep.kalker import kalker_coefficients, linear_creep_forces
from rollcontact.solver.creep.prescribed import PrescribedForceResult, solve_for_forces
from rollcontact.solver.creep.steady import SteadyParams, SteadyResult, SteadyRolling, solve_steady
from rollcontact.solver.creep.moving import roll_moving
from rollcontact.solver.creep.world import INITIAL_STATES, CreepStep, roll_world, rolling_steps

__all__ = ["CreepCurve", "creep_curve", "saturation_creepage", "vermeulen_johnson", "SteadyParams", "SteadyResult", "SteadyRolling", "ellipse_grid", "hertz_pressure", "kalker_coefficients",
           "linear_creep_forces", "PrescribedForceResult", "roll_moving", "roll_world", "rolling_steps", "CreepStep",
           "INITIAL_STATES", "solve_for_forces", "solve_steady"]
