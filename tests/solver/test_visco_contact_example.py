"""The reference program's viscoelastic example, posed here: CONTACT's `examples/visc_cylindr.inp` (eve70a/CONTACT;
user guide, "Steady rolling of two viscoelastic cylinders"; Wang & Knothe 1993): two identical PA6 cylinders (G_g =
1143 MPa, nu = 0.4, f = E_g/E_r - 1 = 1, combined R = 50 mm) rolling steadily at 1000 mm/s under 600 N/mm, mu = 0.3,
Fx = -0.6 mu Fn, on CONTACT's grid (99 cells of 0.16 mm along x, one strip of 1000 mm across). Its reference output
(`examples/visc_cylindr.ref_out`) for tau_c = 0 (elastic, relaxed), 0.009, 0.045 and 2 s: the creepage found for Fx,
the approach, the peak pressure and the numbers of cells in contact and in adhesion.

These are another program's results, not a closed form: the test says that rollcontact poses the same discrete problem
(docs/viscoelastic.md reports the differences: creepage within 0.03 %, approach within 2e-5, peak pressure within
0.02 %, the same cells in contact and in adhesion)."""
import math

import pytest

from rollcontact.bem.grid import Grid
from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.creep.prescribed import solve_for_forces
from rollcontact.solver.creep.steady import SteadyRolling
from rollcontact.solver.normal import solve_normal
from rollcontact.solver.visco.sls import StandardLinearSolid
from rollcontact.solver.visco.steady import SteadyVisco

G, NU, F = 1143.0, 0.4, 1.0
E_G = 2.0 * G * (1.0 + NU)
E_R = E_G / (1.0 + F)
FN, MU, SPEED = 600000.0, 0.3, 1000.0        # N on the 1000 mm strip, -, mm/s
#: tau_c (s) -> CONTACT's CREEP X, APPROACH (mm), PMAX (MPa), NCON, NADH (visc_cylindr.ref_out, cases 1-4)
REFERENCE = {0.0: (1.378e-2, 2.50845, 60.32, 80, 51), 0.009: (1.365e-2, 2.36736, 78.74, 62, 37),
             0.045: (1.152e-2, 2.06321, 84.72, 57, 36), 2.0: (9.932e-3, 1.45462, 85.31, 56, 35)}


@pytest.mark.parametrize("tau", sorted(REFERENCE))
def test_contact_visc_cylindr_is_reproduced(tau):
    grid = Grid(99, 1, 0.16, 1000.0, -49, 0)      # CONTACT's cell centres -7.92 ... 7.76 mm are ours minus 0.08 mm
    X, _ = grid.mesh()
    h = 0.01 * (X - 0.08) ** 2
    if tau == 0.0:                                  # CONTACT's tau_c = 0: the relaxed elastic material
        pair = MaterialPair(Material(E_R, NU), Material(E_R, NU))
        op = HalfSpaceOperator(grid, pair)
        normal, problem = solve_normal(op, h, force=FN), SteadyRolling(grid, pair, operator=op)
    else:
        body = StandardLinearSolid(E_G, E_R, tau, NU)
        sv = SteadyVisco(grid, body, body, SPEED)
        normal, problem = sv.solve_normal(h, FN), sv.tangential_problem
    found = solve_for_forces(problem, normal.pressure, MU, -0.6 * MU * FN, 0.0, 0.0)
    xi, approach, pmax, ncon, nadh = REFERENCE[tau]
    assert found.xi == pytest.approx(xi, rel=1e-3)           # CONTACT prints 4 digits
    assert normal.approach == pytest.approx(approach, rel=1e-4)
    assert normal.pressure.max() == pytest.approx(pmax, rel=1e-3)
    assert int(normal.contact.sum()) == ncon and int(found.steady.stick.sum()) == nadh
    assert math.isclose(found.steady.force[0], -0.6 * MU * FN, rel_tol=1e-5)     # solve_for_forces: 1e-6 of mu Fn
