"""Spence's self-similar stick zone of a normally loaded Hertz contact of dissimilar materials, reproduced
by the coupled (Panagiotopoulos) step solver (docs/theory.md §6.2 step 5; reference
`solver.analytic.spence_stick_ratio`).

A sphere (R = 10 mm) is pressed onto a half-space of another material with no tangential force, the normal
load growing from a small value to Fn = 100 N in many steps. The pressure displaces the two surfaces radially
by different amounts (Dundurs' beta != 0); friction holds a central disc r < c in stick and slips, |tau| = mu p,
in the annulus c < r < a. Under monotonic loading the problem is self-similar and c/a is a constant fixed by
|beta|/mu (Spence 1975). Two cases, one per sign of beta, chosen so that c/a is well inside (0.2, 0.9):

    sphere E = 210e3, nu = 0.3 on substrate E = 150e3, nu = 0.3:  beta = -0.0476, mu = 0.035  ->  c/a = 0.7633
    sphere E = 150e3, nu = 0.3 on substrate E = 210e3, nu = 0.3:  beta = +0.0476, mu = 0.020  ->  c/a = 0.3493

Units mm, N, MPa.
"""
import math

import numpy as np
import pytest

from rollcontact.bem import Grid, HalfSpaceOperator, MaterialPair
from rollcontact.solver.analytic import HertzSphere, spence_stick_ratio
from rollcontact.solver.rolling.coupled import solve_coupled_step
from rollcontact.solver.rolling.profiles import QuadricProfile

R, FN = 10.0, 100.0
ELEMENTS_PER_A = 20     # dx = a/20, a the Hertz radius at the final load Fn
A_START = 0.15          # the first step loads to a contact radius of 0.15 a (3 elements) at once
N_STEPS = 60            # then the contact radius grows linearly to a: da = 0.85 a / 59 = 0.0144 a per step

# Discrete c/a measured with this set-up (c = sqrt(stick area / pi), a = Hertz radius), and its error against
# spence_stick_ratio, on this grid and on refinements (contact radius grown linearly from 0.15 a):
#     dx = a/10, 30 steps:   0.7674 (+0.0041)   0.3432 (-0.0059)
#     dx = a/20, 60 steps:   0.7679 (+0.0046)   0.3443 (-0.0048)     <- this test, 1-2 s per case
#     dx = a/20, 120 steps:  0.7720 (+0.0087)   0.3579 (+0.0088)
#     dx = a/40, 120 steps:  0.7649 (+0.0016)   0.3492 (+0.0001)
#     dx = a/40, 300 steps:  0.7649 (+0.0016)   0.3515 (+0.0024)
#     dx = a/60, 300 steps:  0.7628 (-0.0005)   0.3484 (-0.0007)
#     dx = a/80, 400 steps:  0.7630 (-0.0003)   0.3490 (-0.0001)
# i.e. within a fraction of an element on every grid, with no drift under refinement (starting from 0.05 a
# instead of 0.15 a changed the dx = a/40, 120-step values by less than 0.001).
CASES = {
    "beta<0, c/a~0.76": (MaterialPair.from_moduli(210e3, 0.3, 150e3, 0.3), 0.035),
    "beta>0, c/a~0.35": (MaterialPair.from_moduli(150e3, 0.3, 210e3, 0.3), 0.020),
}


@pytest.mark.parametrize("name", list(CASES))
def test_stick_zone_of_monotonic_normal_loading_matches_spence(name):
    """Load monotonically from (almost) zero; the final stick zone is a central disc of radius c = (c/a) a
    with c/a from Spence's equation, tractions are radial with the sign Spence predicts, and Coulomb's law,
    the (zero) tangential force and the mirror symmetries hold at every step.

    Tolerance on c/a, from the discretisation and the reference's own approximation (no fitted slack):
      * dx/a: the stick zone is a union of whole elements, and which ring of elements straddling r = c is
        counted as stick is decided by the element-centre values, so the equivalent radius sqrt(area/pi) and
        the stick-slip border can each be off by up to about one element;
      * (c/a) da/a for the last load increment da: a finite increment lets the edge of the stick zone
        settle anywhere between its positions at the start and at the end of the increment, (c/a) a_{N-1}
        and (c/a) a_N;
      * |beta| mu: Spence's solution neglects the effect of the tangential traction on the pressure (first
        order in beta); the coupled solver keeps it, which lowers c/a by 0.6-0.85 beta mu (measured at
        beta mu = 0.008 and 0.083 at |beta|/mu = 1.67). Here beta mu <= 0.0017, so this term is small.
    Total 0.063 (first case) and 0.056 (second case); measured errors +0.0046 and -0.0048 (see CASES above).
    """
    mats, mu = CASES[name]
    beta = mats.beta
    assert 0.04 < abs(beta) < 0.05
    ratio = spence_stick_ratio(beta, mu)
    assert 0.2 < ratio < 0.9

    a = HertzSphere(R, mats.E_star, FN).a
    dx = a / ELEMENTS_PER_A
    half = a + 3 * dx                       # margin of three elements around the final contact
    grid = Grid.covering(-half, half, -half, half, dx, dx)
    op = HalfSpaceOperator(grid, mats, coupling=True)
    assert op.coupled
    X, Y = grid.mesh()
    r = np.hypot(X, Y)
    h = QuadricProfile(R, R)(X, Y)
    dA = grid.cell_area

    radii = np.linspace(A_START, 1.0, N_STEPS)          # contact radius / a at each step
    da_last = radii[-1] - radii[-2]
    p = np.zeros(grid.shape)
    tau = np.zeros((2,) + grid.shape)
    shift = np.zeros(2)
    for rho in radii:
        Fn = FN * rho ** 3                               # Hertz: a ~ Fn^(1/3)
        normal, tang, _ = solve_coupled_step(op, h, Fn, (0.0, 0.0), p, tau, mu=mu, coupling_tol=1e-8)
        p, tau = normal.pressure, tang.traction
        shift += tang.shift_increment
        # conservation and Coulomb's law at every step
        assert normal.force == pytest.approx(Fn, rel=1e-9)
        assert np.all(np.abs(tang.force) <= 1e-9 * mu * Fn)          # sum tau dA = (0, 0), imposed
        assert np.all(np.hypot(*tau) <= mu * p * (1 + 1e-9))           # |tau| <= mu p

    hz = HertzSphere(R, mats.E_star, FN)
    mp0 = mu * float(p.max())
    # by symmetry the sphere does not shift, and tau_x is odd in x, tau_y odd in y, tau_y(x, y) = tau_x(y, x)
    # (the grid is symmetric about the centre element); measured |U| ~ 1e-20 mm, asymmetry 1e-14 - 4e-9 mu p0
    # (round-off up to the solvers' 1e-8 tolerances)
    U0 = mu * hz.E_star * hz.approach / mats.G_star                    # Cattaneo's full-slip shift (scale)
    assert np.all(np.abs(shift) <= 1e-9 * U0)
    assert np.abs(tau[0] + tau[0][:, ::-1]).max() <= 1e-7 * mp0
    assert np.abs(tau[1] + tau[1][::-1, :]).max() <= 1e-7 * mp0
    assert np.abs(tau[1] - tau[0].T).max() <= 1e-7 * mp0

    stick, slip = tang.region == 1, tang.region == 2
    tol = dx / a + ratio * da_last + abs(beta) * mu
    c_eq = math.sqrt(np.count_nonzero(stick) * dA / math.pi) / a
    # measured: 0.7679 vs 0.7633 (+0.0046) for beta < 0; 0.3443 vs 0.3493 (-0.0048) for beta > 0
    assert abs(c_eq - ratio) <= tol, (c_eq, ratio, tol)
    # the stick zone is the central disc: no stick element outside, no slip element inside, (c/a +- tol) a
    assert r[stick].max() <= (ratio + tol) * a
    assert r[slip].min() >= (ratio - tol) * a
    # slip annulus: the traction on the substrate is radial with sign -sign(beta), |tau| = mu p (Spence;
    # a rigid sphere, beta < 0, pulls the substrate surface outward against its inward radial displacement)
    tau_r = (tau[0] * X + tau[1] * Y) / np.where(r > 0, r, 1.0)
    assert np.all(np.sign(tau_r[slip]) == -np.sign(beta))
    np.testing.assert_allclose(np.hypot(*tau)[slip], mu * p[slip], rtol=1e-6)


def test_spence_ratio_limits_and_inverse():
    """The reference itself: root of its equation (round trip through spence_beta_over_mu), monotone in
    |beta|/mu, even in beta, full stick at beta = 0, and the two asymptotes c/a ~ 4 exp(-|beta|/mu) (almost
    full slip) and 1 - c/a ~ 2 exp(-pi mu/|beta|) (almost full stick)."""
    from rollcontact.bem.errors import InputError
    from rollcontact.solver.analytic import spence_beta_over_mu

    xs = np.array([0.3, 0.6, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0])
    ks = np.array([spence_stick_ratio(0.25, 0.25 / x) for x in xs])
    assert np.all(np.diff(ks) < 0) and np.all((ks > 0) & (ks < 1))
    for x, k in zip(xs, ks):
        assert spence_beta_over_mu(k) == pytest.approx(x, rel=1e-10)
        assert spence_stick_ratio(-0.25, 0.25 / x) == k
    assert spence_stick_ratio(0.0, 0.3) == 1.0
    assert spence_stick_ratio(0.5, 0.5 / 20.0) == pytest.approx(4 * math.exp(-20.0), rel=1e-12)
    # next-order terms are relatively O(1 - c/a) = 6e-5 here (measured 2.7e-4 of the deviation itself)
    assert 1 - spence_stick_ratio(0.5, 0.5 / 0.3) == pytest.approx(2 * math.exp(-math.pi / 0.3), rel=1e-3)
    for beta, mu in ((0.6, 0.1), (0.1, 0.0), (0.1, -0.2), (float("nan"), 0.1)):
        with pytest.raises(InputError):
            spence_stick_ratio(beta, mu)
