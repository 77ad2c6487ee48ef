"""The axisymmetric profiles (solver.rolling.axisymmetric) and their exact MDR answers (solver.mdr.exact) against
the transform that defines g(s) and the closed forms of docs/theory.md §7.1-7.2 and §11.4. Units mm, N, MPa.

The seed's materials (steel on rubber, E* = 5.80 MPa) and Fn = 21.19 N; the profiles of the scene tests: cone
slope 6 deg, power law n = 4 with R = 10 mm, flat punch b = 4 mm with edge radius R = 5 mm.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from rollcontact.bem import MaterialPair
from rollcontact.bem.errors import InputError
from rollcontact.solver.analytic import CattaneoMindlin, HertzSphere
from rollcontact.solver.mdr.exact import MDRContact, MDRTangential
from rollcontact.solver.rolling.axisymmetric import ConeProfile, PowerProfile, RoundedFlatProfile

PAIR = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
E, G, FN, MU = PAIR.E_star, PAIR.G_star, 21.19, 0.93
PROFILES = [ConeProfile(6.0), PowerProfile(4.0, 10.0), RoundedFlatProfile(4.0, 5.0), PowerProfile(3.0, 7.0)]


@pytest.mark.parametrize("profile", PROFILES, ids=lambda p: type(p).__name__)
def test_mdr_profile_is_the_transform_of_the_profile(profile):
    """g(s) = s int_0^s h'(r)/sqrt(s^2 - r^2) dr (docs/theory.md §8.1), computed by quadrature in r = s sin(t) (which
    removes the inverse square root) with h' by central differences of `radial`: agreement to 1e-7 relative (the
    difference quotient's error, step 1e-6 mm); g' against a difference quotient of g and G against the
    quadrature of g to 1e-7."""
    for s in (0.7, 2.5, 4.2, 6.0):
        def dh(r):
            return (profile.radial(r + 1e-6) - profile.radial(max(r - 1e-6, 0.0))) / (r + 1e-6 - max(r - 1e-6, 0.0))
        kink = [math.asin(profile.b / s)] if getattr(profile, "b", 0) and profile.b < s else None
        g = s * quad(lambda t: float(dh(s * math.sin(t))), 0.0, 0.5 * math.pi, points=kink, limit=200)[0]
        assert float(profile.mdr(s)) == pytest.approx(g, rel=1e-7, abs=1e-12)
        slope = (float(profile.mdr(s + 1e-6)) - float(profile.mdr(s - 1e-6))) / 2e-6
        assert float(profile.mdr_slope(s)) == pytest.approx(slope, rel=1e-7)
        at_b = [profile.b] if getattr(profile, "b", 0) and profile.b < s else None   # g starts at s = b
        integral = quad(lambda t: float(profile.mdr(t)), 0.0, s, points=at_b, limit=200, epsabs=0, epsrel=1e-12)[0]
        assert float(profile.mdr_integral(s)) == pytest.approx(integral, rel=1e-9)


def test_power_law_n2_is_hertz_and_cattaneo_mindlin():
    """n = 2 is the sphere: a, d, p0, p(r), the stick radius and the shift equal HertzSphere/CattaneoMindlin (§7.1-
    7.2) to round-off (1e-12; the contact radius is a root found to 1e-15)."""
    R = 40.0
    hertz, mdr = HertzSphere(R, E, FN), MDRContact(PowerProfile(2.0, R), E, FN)
    cm, tg = CattaneoMindlin(hertz, MU, G), MDRTangential(mdr, MU, G)
    assert mdr.a == pytest.approx(hertz.a, rel=1e-12)
    assert mdr.approach == pytest.approx(hertz.approach, rel=1e-12)
    assert mdr.p0 == pytest.approx(hertz.p0, rel=1e-12)
    r = np.array([0.0, 1.0, 3.0, 4.5])
    np.testing.assert_allclose(mdr.pressure(r), hertz.pressure(r), rtol=1e-9)
    for f in (0.25, 0.5, 0.9):
        assert tg.stick_radius(f) == pytest.approx(cm.stick_radius(f), rel=1e-12)
        assert tg.shift(f) == pytest.approx(cm.shift(f), rel=1e-10)
    assert tg.U0 == pytest.approx(cm.U0, rel=1e-12)


def test_cone_and_power_law_closed_forms():
    """docs/theory.md §11.4: cone d = (pi/2) a tan(s), Fn = (pi/2) E* a^2 tan(s), p(r) = (E* tan(s)/2) arccosh(a/r)
    (Love 1939 / Sneddon); power law n = 4: d = 2 a^4/(3 R^3), Fn = 16 E* a^5/(15 R^3). To 1e-12 (1e-8 for the
    pressure by quadrature)."""
    cone = MDRContact(ConeProfile(6.0), E, FN)
    t = math.tan(math.radians(6.0))
    a = cone.a
    assert FN == pytest.approx(0.5 * math.pi * E * a * a * t, rel=1e-12)
    assert cone.approach == pytest.approx(0.5 * math.pi * a * t, rel=1e-12)
    r = np.array([0.3, 1.0, 2.5, 4.0])
    np.testing.assert_allclose(cone.pressure(r), 0.5 * E * t * np.arccosh(a / r), rtol=1e-8)
    p4 = MDRContact(PowerProfile(4.0, 10.0), E, FN)
    a = p4.a
    assert FN == pytest.approx(16 * E * a ** 5 / (15 * 1000.0), rel=1e-12)
    assert p4.approach == pytest.approx(2 * a ** 4 / (3 * 1000.0), rel=1e-12)


@pytest.mark.parametrize("profile", PROFILES, ids=lambda p: type(p).__name__)
def test_pressure_carries_the_load_and_tangential_limits(profile):
    """The MDR pressure integrates to Fn (2 pi int p r dr, quadrature to 1e-6), vanishes at r = a; the shift is 0
    at f_t = 0 and the full-slip U0 = mu E* d/G* at f_t = 1 (c = 0), and the stick radius decreases with f_t."""
    c = MDRContact(profile, E, FN)
    a = c.a
    kink = [profile.b] if getattr(profile, "b", None) else None
    total = 2 * math.pi * quad(lambda r: float(c.pressure(r)) * r, 0.0, a, points=kink, limit=200)[0]
    assert total == pytest.approx(FN, rel=1e-6)
    assert float(c.pressure(a)) == 0.0
    tg = MDRTangential(c, MU, G)
    assert tg.shift(0.0) == pytest.approx(0.0, abs=1e-12)
    assert tg.shift(1.0) == pytest.approx(tg.U0, rel=1e-12)
    radii = [tg.stick_radius(f) for f in (0.0, 0.25, 0.5, 0.75, 0.9)]
    assert radii[0] == pytest.approx(a, rel=1e-12) and np.all(np.diff(radii) < 0)


@pytest.mark.parametrize("make, message", [
    (lambda: ConeProfile(0.0), "slope"), (lambda: ConeProfile(90.0), "slope"),
    (lambda: PowerProfile(0.5, 10.0), "n = 0.5"), (lambda: PowerProfile(4.0, -1.0), "R = -1.0"),
    (lambda: RoundedFlatProfile(0.0, 5.0), "b = 0.0"), (lambda: RoundedFlatProfile(4.0, math.inf), "R = inf")])
def test_bad_profiles_are_refused_with_the_parameter_named(make, message):
    with pytest.raises(InputError, match=message):
        make()


def test_shakedown_closed_form_for_n2_is_seed_eq_12():
    """docs/theory.md §8.3 written for any profile (MDRTangential.shakedown_shift, limit) reduces for the sphere to seed
    Eq. 12 with kappa = 3/2, f_t = 1 - 1.5 w u_sd - (1 - u_sd)^(3/2), and to f_t,lim = 1 - 1.5 w + 0.5 w^3,
    u_lim = 1 - w^2 (to 1e-12; u_sd is a root found to 1e-14 a)."""
    tg = MDRTangential(MDRContact(PowerProfile(2.0, 40.0), E, FN), MU, G)
    a = tg.contact.a
    for w in (0.1, 0.23, 0.4):
        f_lim, u_lim = tg.limit(w * a)
        assert f_lim == pytest.approx(1 - 1.5 * w + 0.5 * w ** 3, rel=1e-12)
        assert u_lim == pytest.approx(1 - w * w, rel=1e-12)
        for f in (0.2, 0.5 * f_lim, 0.99 * f_lim):
            u = tg.shakedown_shift(f, w * a)
            assert 1 - 1.5 * w * u - (1 - u) ** 1.5 == pytest.approx(f, rel=1e-12)
        assert tg.shakedown_shift(1.01 * f_lim, w * a) is None
