"""Shared set-up of the tangential solver tests (test_tangential_*.py): the seed's Hertz contact, its closed forms
and the element-by-element check of Coulomb's law and the force balance (docs/theory.md §5, closed forms docs/theory.md
§7.2).

Scene of the seed (Table 1): rigid-ish sphere R = 40 mm (steel) on rubber (E = 4.35 MPa, nu = 0.5), Fn = 21.19 N,
mu = 0.93; the pressure comes from `solve_normal`, so sum(mu p) dA = mu Fn exactly. Units mm, N, MPa.
"""
import math

import numpy as np

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.normal.normcg import solve_normal
from rollcontact.solver.tangential.shift import solve_tangential, traction_capacity

R, FN, MU = 40.0, 21.19, 0.93
MATERIALS = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
HERTZ = HertzSphere(R, MATERIALS.E_star, FN)
MINDLIN = CattaneoMindlin(HERTZ, MU, MATERIALS.G_star)


class Scene:
    def __init__(self, dx):
        a = HERTZ.a
        self.grid = Grid.covering(-a - 0.6, a + 0.6, -a - 0.6, a + 0.6, dx, dx)
        self.op = HalfSpaceOperator(self.grid, MATERIALS)
        X, Y = self.grid.mesh()
        self.X, self.Y = X, Y
        self.normal = solve_normal(self.op, (X ** 2 + Y ** 2) / (2 * R), force=FN)
        self.bound = MU * self.normal.pressure
        self.zero = np.zeros((2,) + self.grid.shape)
        self.dx = dx

    def cattaneo(self, f_t, **kw):
        return solve_tangential(self.op, self.bound, self.zero, force=(f_t * MU * FN, 0.0), **kw)


def check_invariants(result, bound, op, previous, force=None, extra=None, tol=1e-8, alignment=0.999):
    """Coulomb's law and the force balance, element by element (docs/theory.md §5.1), on the slip recomputed from the
    returned traction, s = A (tau - tau') + e - dU (one product here; the solver's own `slip` field is zero in
    stick by construction, so it cannot show a stick violation):

    * force balance sum tau dA = F to 1e-10 mu Fn (it is held by construction, so only round-off);
    * |tau| <= g (1 + 1e-9) everywhere and tau = 0 outside the contact;
    * stick elements: |s| <= 10 tol (self coefficient x max g) -- the solver's own stopping measure is
      max |s| / (a_self max g) < tol, and the traction error it leaves is below tol max g (module docstring
      of solver.tangential), so a factor 10 covers the self coefficient's estimate below;
    * slip elements: |tau| = g, the reported slip equal to s, and s opposite to the traction (cosine below
      -alignment), unless the slip itself is at the round-off level of the stopping tolerance.
    """
    tau, region = result.traction, result.region
    grid = op.grid
    g = bound
    dA = grid.cell_area
    capacity = traction_capacity(bound, grid)
    assert np.all(np.isfinite(tau)) and np.all(np.isfinite(result.slip)) and np.all(np.isfinite(result.shift_increment))
    total = np.array([tau[0].sum(), tau[1].sum()]) * dA
    if force is not None:
        np.testing.assert_allclose(total, force, rtol=0, atol=1e-10 * capacity)
    mag = np.hypot(tau[0], tau[1])
    assert np.all(mag <= g * (1 + 1e-9))
    assert np.all(mag[g == 0] == 0) and np.all(region[g == 0] == 0)
    dtau = tau - previous
    slip = op.tangential(dtau[0], dtau[1])
    if extra is not None:
        slip += extra
    slip[0] -= result.shift_increment[0]
    slip[1] -= result.shift_increment[1]
    a_self = 1.0 / (math.pi * MATERIALS.G) * 4 * grid.dx * math.log(1 + math.sqrt(2))  # ~ A^xx(0)
    slip_tol = 10 * tol * a_self * g.max()
    smag = np.hypot(slip[0], slip[1])
    stick = region == 1
    assert smag[stick].max(initial=0.0) <= slip_tol, (smag[stick].max(), slip_tol)
    sl = region == 2
    np.testing.assert_allclose(mag[sl], g[sl], rtol=1e-9)
    np.testing.assert_allclose(result.slip[:, sl], slip[:, sl], rtol=0, atol=1e-3 * slip_tol)
    big = sl & (smag > 100 * slip_tol)
    cosang = (tau[0] * slip[0] + tau[1] * slip[1])[big] / (mag[big] * smag[big])
    assert np.all(cosang < -alignment), cosang.max()
