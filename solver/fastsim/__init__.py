"""Fast tangential models of rolling with creepage and spin: FASTSIM and FaStrip, on a grid, arrays in and out.

    flexibility  the simplified theory's flexibilities L1, L2, L3 (and Kalker's weighted L) and the strip theory's
                 stiffnesses, from Kalker's C11, C22, C23 (docs/theory.md §7.3, §12.4)
    strips       strip edges of a contact on a grid, Hertz's semi-ellipsoidal and Kalker's parabolic bounds
    fastsim      FASTSIM (Kalker 1982): steady on a contact-fixed grid, transient on a world-fixed grid
    fastrip      FaStrip (Sichani, Enblom & Berg 2016): strip theory with Kalker's coefficients, steady
    patch        one call for a contact patch: semi-axes, or a grid with a pressure, in; tractions and forces out
    error_map    the measured force error of each model against the exact theory, for choosing the cheapest model
    _kernels     the compiled strip loops

Kalker's convention (solver.creep.kalker): body 1 rolls in +x over body 2; forces and tractions on body 1.
Units: mm, N, MPa; creepages xi, eta dimensionless, spin phi in 1/mm. Derivations: docs/creep_fidelity.md.
"""
from rollcontact.solver.fastsim.fastrip import solve_fastrip
from rollcontact.solver.fastsim.fastsim import FLEXIBILITY_MODELS, FastResult, FastsimRolling, solve_fastsim
from rollcontact.solver.fastsim.flexibility import Flexibilities, kalker_flexibilities
from rollcontact.solver.fastsim.patch import Patch, fast_patch
from rollcontact.solver.fastsim.strips import BOUNDS, ellipse_edges, ellipse_pressure, equivalent_ellipse, strip_edges

#: The fast models by their `solver.fidelity` names.
MODELS = {"fastsim": solve_fastsim, "fastrip": solve_fastrip}

__all__ = ["BOUNDS", "FLEXIBILITY_MODELS", "FastResult", "FastsimRolling", "Flexibilities", "MODELS", "Patch",
           "ellipse_edges", "ellipse_pressure", "equivalent_ellipse", "fast_patch", "kalker_flexibilities",
           "solve_fastrip", "solve_fastsim", "strip_edges"]
