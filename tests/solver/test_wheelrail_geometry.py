"""Wheel-rail geometry and kinematics (solver.wheelrail) against closed forms: the gauge point, the silhouette of an
upright and of a yawed coned wheel, the planar gap of two crowns, and the creepages of a yawed cylinder and a coned
wheel (docs/wheelrail.md, §2-§5). Units: mm, rad."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.wheelrail import ContactSearch, PatchFrame, Profile, WheelPlacement, WheelPosition, place_rail
from rollcontact.solver.wheelrail.patch import creepages, omega_per_speed, patch_gap, rail_distance
from rollcontact.solver.wheelrail.wheel import Wheel


def crown(radius, half_width, n=401, convex_up=True):
    """A circular arc z = -(R - sqrt(R^2 - y^2)) (a rail crown) or its mirror (a wheel tread), mm."""
    y = np.linspace(-half_width, half_width, n)
    sag = radius - np.sqrt(radius ** 2 - y ** 2)
    return y, (-sag if convex_up else sag)


def test_profile_refuses_a_profile_that_turns_back_or_is_not_finite():
    with pytest.raises(InputError, match="increase strictly"):
        Profile([0.0, 1.0, 0.5, 2.0, 3.0], [0.0] * 5, "rail profile")
    with pytest.raises(InputError, match="not finite"):
        Profile([0.0, 1.0, 2.0, 3.0], [0.0, math.nan, 0.0, 0.0])


def test_turned_profile_keeps_the_part_reachable_from_above():
    # a head with a vertical gauge face: inclined towards the centre, the face leans over and is cut off
    y = np.concatenate([np.full(5, -30.0) + np.linspace(-1e-3, 0, 5), np.linspace(-29.0, 30.0, 60)])
    z = np.concatenate([np.linspace(-20.0, -1.0, 5), -np.linspace(-29.0, 30.0, 60) ** 2 / 600.0])
    turned = Profile(y, z).turned(0.05)
    assert turned.lo > -31.0 and np.all(np.diff(turned.y) > 0) and turned.y.size < y.size


def test_gauge_point_lies_at_half_the_gauge_and_the_top_of_the_rail_at_zero():
    """A crown z = -(y + 10)^2/300 (top at y = -10) with a straight inner face of slope 20 from y = -34: 14 mm below
    the top the face lies at y = -34 - (14 - 24^2/300)/20; placed, that point is at gauge / 2, the top at z = 0."""
    y = np.linspace(-36.0, 30.0, 661)
    z = np.where(y < -34.0, -24.0 ** 2 / 300.0 - 20.0 * (-34.0 - y), -(y + 10.0) ** 2 / 300.0)
    rail = place_rail(Profile(y, z), 0.0, 1435.0, 14.0)
    gauge_point = -34.0 - (14.0 - 24.0 ** 2 / 300.0) / 20.0
    assert rail.shift_y == pytest.approx(717.5 - gauge_point, abs=1e-9)
    assert float(np.max(rail.surface.z)) == pytest.approx(0.0, abs=1e-12)
    # the gauge point is found on the profile's points (linear between them); the spline through the corner at
    # y = -34, 0.6 mm away, departs from the straight face by 1e-5 mm there
    assert float(rail.surface(717.5)) == pytest.approx(-14.0, abs=1e-4)
    with pytest.raises(InputError, match="gauge point is not on the profile"):
        place_rail(Profile(y, z), 0.0, 1435.0, 60.0)


def test_manchester_rail_is_placed_as_contact_places_it():
    """CONTACT's case 1 (y = 0): rail profile y_r = -8.6600 at track y = 751.8726, i.e. the profile's origin at
    760.5326 mm from the track centre (4 decimals printed)."""
    from rollcontact.cases.scene.wheelrail_profiles import read_profile
    from rollcontact.cases.scene.scene import shipped_scene_path
    y, z, _ = read_profile(str(shipped_scene_path("data/wheelrail/MBench_UIC60_v3.prr")), "rail_profile")
    rail = place_rail(Profile(y, z), 0.0, 1435.0, 14.0)
    assert rail.shift_y == pytest.approx(751.8726 + 8.6600, abs=2e-3)


def coned_wheel(slope, radius=460.0, half_width=40.0):
    """A conical tread r(y_w) = radius - slope y_w (z_w = slope y_w), profile coordinates in mm."""
    y = np.linspace(-half_width, half_width, 161)
    return WheelPlacement(Profile(y, slope * y), radius, 750.0)


def test_silhouette_of_an_upright_wheel_is_its_profile_below_the_axle():
    wheel = coned_wheel(0.05)
    sil = Wheel(wheel, WheelPosition(2.0, 500.0)).silhouette(np.array([-10.0, 0.0, 10.0]))
    np.testing.assert_allclose(sil.x, 0.0, atol=1e-12)
    np.testing.assert_allclose(sil.y, 752.0 + np.array([-10.0, 0.0, 10.0]), atol=1e-12)
    np.testing.assert_allclose(sil.z, 500.0 - (460.0 - 0.05 * np.array([-10.0, 0.0, 10.0])), atol=1e-9)


def test_silhouette_of_a_yawed_cone_is_shifted_by_r_tan_gamma_sin_yaw():
    """A cone of slope tan(gamma) yawed by psi touches a prismatic rail at the ring point with sin(theta) =
    -tan(gamma) tan(psi): x = -(arm + y_w) sin(psi) + r tan(gamma) sin(psi) (docs/wheelrail.md, §3)."""
    slope, psi = 0.2, 0.02
    wheel = coned_wheel(slope)
    y_w = np.array([-5.0, 0.0, 5.0])
    sil = Wheel(wheel, WheelPosition(0.0, 470.0, yaw=psi)).silhouette(y_w)
    r = 460.0 - slope * y_w
    np.testing.assert_allclose(sil.x, -(750.0 + y_w) * math.sin(psi) + r * slope * math.sin(psi), rtol=1e-12)
    theta = np.arcsin(-slope * math.tan(psi))
    np.testing.assert_allclose(sil.z, 470.0 - r * np.cos(theta), rtol=1e-12)


def test_planar_gap_of_two_crowns_is_the_sum_of_their_sags():
    """Wheel crown R_wy = 100 mm, rail crown R_ry = 300 mm, upright cylinder r = 460: along n = z the gap of the
    touching bodies is (r - sqrt(r^2 - x^2)) + the two sags, exactly (the wheel is a torus)."""
    rail = place_rail(Profile(*crown(300.0, 30.0)), 0.0, 1500.0, 0.0)
    yw, zw = crown(100.0, 30.0, convex_up=False)
    wheel = WheelPlacement.on_wheelset(Profile(yw, zw), 460.0, 1500.0, 0.0)
    search = ContactSearch(rail, wheel, 0.0)
    assert search.y_touch == pytest.approx(750.0, abs=0.02)
    frame = PatchFrame(np.array([0.0, 750.0, 0.0]), 0.0, 745.0, 755.0)
    x, s = np.linspace(-5, 5, 11), np.linspace(-4, 4, 9)
    gap, _ = patch_gap(rail_distance(rail, frame, s), search.wheel(0.0), frame, x, s)
    X, S = np.meshgrid(x, s)
    ring = 460.0 - (100.0 - np.sqrt(100.0 ** 2 - S ** 2))           # the torus' radius at lateral position s
    exact = (460.0 - np.sqrt(ring ** 2 - X ** 2) - (460.0 - ring)) + (100.0 - np.sqrt(100.0 ** 2 - S ** 2)) \
        + (300.0 - np.sqrt(300.0 ** 2 - S ** 2))
    np.testing.assert_allclose(gap, exact, atol=2e-12)


@pytest.mark.parametrize("psi", [0.0, 0.01, -0.03])
def test_creepages_of_a_yawed_cylinder_follow_the_rigid_motion(psi):
    """Cylinder on a flat rail, rotating at omega with omega r / V = k: xi = 2 (1 - k cos psi)/(1 + k cos psi),
    eta = -2 k sin psi / (1 + k cos psi), phi = 0."""
    wheel = coned_wheel(0.0)
    k = 1.002
    position = WheelPosition(0.0, 460.0, yaw=psi)
    point = np.array([-750.0 * math.sin(psi), 750.0 * math.cos(psi), 0.0])   # below the wheel's centre
    frame = PatchFrame(point, 0.0, 749.0, 751.0)
    xi, eta, phi = creepages(position, k / 460.0, frame)
    assert wheel.radius == 460.0
    assert xi == pytest.approx(2 * (1 - k * math.cos(psi)) / (1 + k * math.cos(psi)), abs=1e-12)
    assert eta == pytest.approx(-2 * k * math.sin(psi) / (1 + k * math.cos(psi)), abs=1e-12)
    assert phi == pytest.approx(0.0, abs=1e-15)


def test_spin_of_a_contact_at_angle_delta_is_minus_omega_sin_delta_over_the_rolling_speed():
    delta, k = 0.3, 1.0
    position = WheelPosition(0.0, 460.0)
    frame = PatchFrame(np.array([0.0, 750.0, 0.0]), delta, 749.0, 751.0)
    xi, eta, phi = creepages(position, k / 460.0, frame)
    assert phi == pytest.approx(-(k / 460.0) * math.sin(delta), rel=1e-12)
    assert xi == pytest.approx(0.0, abs=1e-15) and eta == pytest.approx(0.0, abs=1e-15)


def test_omega_per_speed_gives_the_nominal_creepage():
    for xi in (-0.01, 0.0, 0.003):
        k = omega_per_speed(460.0, xi) * 460.0
        assert 2 * (1 - k) / (1 + k) == pytest.approx(xi, abs=1e-14)


def test_inclining_the_rail_equals_a_profile_drawn_inclined():
    """rail_inclination = 0.025 on an upright crown places the same surface as the crown drawn turned by 0.025 rad
    with rail_inclination = 0 (the gauge point and the top found on the turned profile either way)."""
    y = np.linspace(-36.0, 30.0, 661)
    z = np.where(y < -34.0, -24.0 ** 2 / 300.0 - 20.0 * (-34.0 - y), -(y + 10.0) ** 2 / 300.0)
    upright = place_rail(Profile(y, z), 0.025, 1435.0, 14.0)
    drawn = Profile(y, z).turned(0.025)
    inclined = place_rail(Profile(drawn.y, drawn.z), 0.0, 1435.0, 14.0)
    probe = np.linspace(max(upright.surface.lo, inclined.surface.lo) + 1, min(upright.surface.hi, inclined.surface.hi) - 1, 50)
    np.testing.assert_allclose(upright.surface(probe), inclined.surface(probe), atol=1e-9)
    # the map to the profile's own coordinates inverts the placement (on the crown, away from the corner at y = -34,
    # where the spline through the turned points and the turned spline part by 0.01 mm)
    crown_part = probe[probe > upright.shift_y - 30.0]
    yp, zp = upright.to_profile(crown_part, upright.surface(crown_part))
    np.testing.assert_allclose(zp, -(yp + 10.0) ** 2 / 300.0, atol=1e-6)
