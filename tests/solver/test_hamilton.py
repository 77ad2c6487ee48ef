"""Hamilton's closed form for the sliding Hertz sphere (solver/hamilton.py, docs/theory.md §11.6): the frictionless
axis,
the surface tractions, the trailing-edge tension, near-axis continuity, scaling and refused input. The comparison with
the point-load quadrature is in tests/bem/test_subsurface_sliding.py (where that reference lives)."""
import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.hamilton import NEAR_AXIS, hamilton_stresses


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_frictionless_axis_is_hertz_closed_form(nu):
    """mu = 0, r = 0: sigma_z = -p0/(1 + z^2/a^2), sigma_r = -p0 [(1 + nu)(1 - (z/a) atan(a/z)) - 1/(2 (1 + z^2/a^2))]
    (docs/theory.md §11.6), shears zero: to 1e-13 p0 (both exact). 1e-4 a off the axis (the near-axis cubic) the normal
    stresses move by O((r/a)^2) = 1e-8 (checked against 1e-7 p0) and the shears by O(r/a) (checked against 1e-3 p0).
    """
    a, p0 = 2.0, 3.0
    z = np.linspace(0.01, 3.0, 60) * a
    s = hamilton_stresses(0.0, 0.0, z, a, p0, 0.0, nu)
    zeta = z / a
    s_r = -p0 * ((1 + nu) * (1 - zeta * np.arctan(1 / zeta)) - 0.5 / (1 + zeta**2))
    assert np.abs(s[2] + p0 / (1 + zeta**2)).max() <= 1e-13 * p0
    assert np.abs(s[0] - s_r).max() <= 1e-13 * p0 and np.abs(s[1] - s_r).max() <= 1e-13 * p0
    assert np.abs(s[3:]).max() == 0.0
    near = hamilton_stresses(1e-4 * a, 0.0, z, a, p0, 0.0, nu)
    assert np.abs(near[:3] - s[:3]).max() <= 1e-7 * p0
    assert np.abs(near[3:]).max() <= 1e-3 * p0


@pytest.mark.parametrize("mu", [0.0, 0.3, 0.5])
def test_surface_tractions_are_the_applied_ones(mu):
    """At z = 0: s_zz = -p, s_xz = -mu p, s_yz = 0 inside the contact and all three zero outside (docs/theory.md §0
    signs),
    to 1e-13 p0 (exact expressions, round-off only; no point within the near-axis zone)."""
    a, p0, nu = 1.5, 2.0, 0.3
    x, y = np.meshgrid(np.linspace(-2.0, 2.0, 81) * a + 0.0323, np.linspace(-1.7, 1.7, 35) * a)
    s = hamilton_stresses(x, y, 0.0, a, p0, mu, nu)
    p = p0 * np.sqrt(np.clip(1 - (x * x + y * y) / a**2, 0, None))
    assert np.abs(s[2] + p).max() <= 1e-13 * p0
    assert np.abs(s[4] + mu * p).max() <= 1e-13 * p0
    assert np.abs(s[3]).max() <= 1e-13 * p0


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_trailing_and_leading_edge_stress_matches_the_published_value(nu):
    """On the surface at x = -a (trailing edge for the traction along +x on the substrate) sigma_x = p0 [(1 - 2 nu)/3
    + mu pi (4 + nu)/8], the largest tension of the sliding contact, and at x = +a p0 [(1 - 2 nu)/3 - mu pi (4 + nu)/8]
    (Hamilton & Goodman 1966; Johnson 1985 §7.1), mu = 0.5. The edge point itself is singular in the formulas (S = 0),
    so it is taken 1e-10 a outside; the field has a square-root slope there: a 1e-5 p0 shift, checked to 5e-5 p0."""
    a, p0, mu = 1.0, 1.0, 0.5
    edge = (1 + 1e-10) * a
    s = hamilton_stresses(np.array([-edge, edge]), 0.0, 0.0, a, p0, mu, nu)
    base, fric = (1 - 2 * nu) / 3, mu * np.pi * (4 + nu) / 8
    assert s[0, 0] == pytest.approx(p0 * (base + fric), abs=5e-5 * p0)
    assert s[0, 1] == pytest.approx(p0 * (base - fric), abs=5e-5 * p0)


def test_continuous_across_the_near_axis_zone():
    """The cubic used within 0.01 a of the axis joins the full expressions: at r = 0.01 a on both sides of the switch
    the stresses agree within 1e-9 p0 (the cubic's truncation, ~ (0.01)^4 times the fourth radial derivative)."""
    a, p0 = 1.0, 1.0
    z = np.array([0.0, 0.05, 0.3, 1.0])
    for mu in (0.0, 0.5):
        inside = hamilton_stresses(0.6 * NEAR_AXIS * a * (1 - 1e-12), 0.8 * NEAR_AXIS * a * (1 - 1e-12), z, a, p0, mu,
                                   0.3)
        outside = hamilton_stresses(0.6 * NEAR_AXIS * a, 0.8 * NEAR_AXIS * a, z, a, p0, mu, 0.3)
        assert np.abs(inside - outside).max() <= 1e-9 * p0


def test_stresses_scale_with_p0_and_a():
    """sigma(lambda x; lambda a, p0) = sigma(x; a, p0) and sigma is proportional to p0 (1e-13 relative)."""
    x, y, z = np.array([0.3, -0.7, 1.2]), np.array([0.2, 0.5, -0.4]), np.array([0.1, 0.6, 0.9])
    one = hamilton_stresses(x, y, z, 1.0, 1.0, 0.4, 0.3)
    two = hamilton_stresses(2.5 * x, 2.5 * y, 2.5 * z, 2.5, 7.0, 0.4, 0.3)
    assert np.abs(two - 7.0 * one).max() <= 1e-13 * 7.0


def test_bad_input_is_refused_with_the_key():
    with pytest.raises(InputError, match="nu"):
        hamilton_stresses(0.0, 0.0, 1.0, 1.0, 1.0, 0.3, 0.6)
    with pytest.raises(InputError, match="depth"):
        hamilton_stresses(0.0, 0.0, -1.0, 1.0, 1.0, 0.3, 0.3)
    with pytest.raises(InputError, match="contact radius"):
        hamilton_stresses(0.0, 0.0, 1.0, 0.0, 1.0, 0.3, 0.3)
    with pytest.raises(InputError, match="edge"):
        hamilton_stresses(1.0, 0.0, 0.0, 1.0, 1.0, 0.3, 0.3)


def _interior_maximum(mu, nu=0.3):
    """The local von Mises maximum below the surface (Nelder-Mead from the frictionless one; y = 0 by symmetry)."""
    from scipy.optimize import minimize
    from rollcontact.bem.subsurface import invariants

    def minus(v):
        return -float(invariants(hamilton_stresses(v[0], 0.0, abs(v[1]), 1.0, 1.0, mu, nu))["von_mises"])
    res = minimize(minus, (0.3, 0.43), method="Nelder-Mead", options=dict(xatol=1e-8, fatol=1e-12))
    return -res.fun, res.x[0], abs(res.x[1])


def test_von_mises_maximum_reaches_the_surface_just_above_mu_0_3():
    """nu = 0.3, a = p0 = 1. Without friction the maximum is 0.620 at z = 0.481 on the axis; with mu = 0.3 it is still
    below the surface, 0.6598 at x = 0.319, z = 0.428 (moved towards +x, the traction's direction), larger than the
    surface's largest value, at the trailing edge x = -a: 0.6539; at mu = 0.31 the trailing edge wins (Hamilton 1983:
    the maximum moves to the surface above mu ~ 0.3; measured switch mu = 0.3047). Values to 5e-4, places to 5e-3."""
    from rollcontact.bem.subsurface import invariants

    def edge(mu):
        return float(invariants(hamilton_stresses(-(1 + 1e-10), 0.0, 0.0, 1.0, 1.0, mu, 0.3))["von_mises"])
    v0, x0, z0 = _interior_maximum(0.0)
    assert v0 == pytest.approx(0.620, abs=5e-4) and abs(x0) <= 5e-3 and z0 == pytest.approx(0.481, abs=5e-3)
    v3, x3, z3 = _interior_maximum(0.3)
    assert v3 == pytest.approx(0.6598, abs=5e-4) and x3 == pytest.approx(0.319, abs=5e-3)
    assert z3 == pytest.approx(0.428, abs=5e-3)
    assert edge(0.3) == pytest.approx(0.6539, abs=5e-4) and edge(0.3) < v3
    assert edge(0.31) > _interior_maximum(0.31)[0]
