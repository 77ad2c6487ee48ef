"""Scene files: TOML <-> dataclasses, validation messages, overrides."""
import math

import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases.scene.scene import MAX_STEPS, MIN_ELEMENTS_PER_RADIUS, Scene, default_scene, shipped_scene_path


def test_default_scene_is_the_seed_table1_perpendicular_setting():
    s = default_scene()
    m = s.materials
    assert (m.E1, m.nu1, m.E2, m.nu2) == (206e3, 0.3, 4.35, 0.5)
    assert s.geometry.R == 40.0 and s.load.Fn == 21.19 and s.load.mu == 0.93
    assert s.spacing == (0.2, 0.2)
    assert s.f_t == 0.46 and s.motion.w == 0.23 and s.motion.angle == 90.0
    assert s.contact_radius == pytest.approx(4.7857, abs=1e-4)  # docs/theory.md §7.1
    assert s.rolling_direction == pytest.approx((0.0, 1.0), abs=1e-15)


def test_rolling_step_hits_the_reversal_points_exactly():
    s = default_scene()
    n = s.amplitude / s.rolling_step
    assert n == pytest.approx(round(n), abs=1e-12) and s.rolling_step <= s.motion.dW


def test_round_trip_through_toml_text_preserves_every_key():
    data = default_scene().to_dict()
    data["load"].pop("ft")
    data["load"]["Ft"] = 5.5          # the load in N (an override may not switch the scene's spelling)
    s = Scene.from_dict(data, name="paper_perpendicular").with_overrides(["materials.E1=inf",
                                                                          "load.levels=[0.2, -0.3]"])
    back = Scene.from_toml_text(s.to_toml(), name=s.name)
    assert back.to_dict() == s.to_dict()
    assert math.isinf(back.materials.E1) and back.load.Ft == 5.5 and back.load.levels == [0.2, -0.3]


@pytest.mark.parametrize("name", ["paper_perpendicular", "paper_parallel"])
def test_refining_dx_of_a_shipped_scene_refines_dy_too(name):
    # the shipped files leave dy unset, so one override changes the element size in both directions
    s = Scene.from_toml(shipped_scene_path(name + ".toml")).with_overrides(["grid.dx=0.1"])
    assert s.spacing == (0.1, 0.1)
    assert s.with_overrides(["grid.dy=0.3"]).spacing == (0.1, 0.3)


def test_a_minimal_file_takes_neutral_defaults(tmp_path):
    f = tmp_path / "hertz.toml"
    f.write_text("[geometry]\nR = 10.0\n")
    s = Scene.from_toml(f)
    assert s.f_t == 0.0 and s.amplitude == 0.0 and s.name == "hertz"


@pytest.mark.parametrize("override, message", [
    ("load.ft=1.5", r"\[load\] ft = 1.5: allowed range is \[0, 1\]"),
    ("grid.dx=0", r"\[grid\] dx = 0.0 mm: allowed range is \(0, inf\) mm"),
    ("motion.dW=-0.2", r"\[motion\] dW = -0.2 mm: allowed range"),
    ("motion.periods=-1", r"\[motion\] periods = -1: allowed range"),
    ("load.bogus=1", r"\[load\] unknown key\(s\) \['bogus'\]"),
    ("solver.fidelity=\"fem\"", r"fidelity = 'fem': allowed values are \['bem', 'mdr', 'fastsim', 'fastrip', 'auto'\]"),
    ("materials.nu2=0.7", r"\[materials\] nu2 = 0.7: allowed range"),
    ("load.Fn=\"heavy\"", r"\[load\] Fn = 'heavy': expected a number in N"),
    ("load.ft=1.5", r"\[load\] ft = 1.5: allowed range is \[0, 1\]"),
    ("noequals", r"expected section.key=value"),
    ("physics.g=9.81", r"unknown section 'physics'"),
])
def test_bad_input_is_refused_naming_key_and_allowed_range(override, message):
    with pytest.raises(SceneError, match=message):
        default_scene().with_overrides([override])


def test_rolling_steps_are_limited_naming_dw_or_periods_and_the_allowed_range():
    s = default_scene()                                 # W = 1.1007 mm, 10 periods, 2 loading steps
    with pytest.raises(SceneError, match=r"\[motion\] dW = 1e-09 mm, periods = 10: .*exceed the limit of "
                                         r"1000000 steps.* allowed range is dW >= 4.4\d*e-05 mm"):
        s.with_overrides(["motion.dW=1e-9"])
    dW_min = s.amplitude / ((MAX_STEPS - 2) // 40)
    s.with_overrides([f"motion.dW={dW_min * (1 + 1e-9)}"])          # just inside: accepted
    with pytest.raises(SceneError, match=r"dW >= 0.55\d* mm at these periods, or periods <= 41666 at this dW"):
        s.with_overrides(["motion.periods=100000"])
    s.with_overrides(["motion.periods=100000", "motion.w=0"])       # no rolling: no limit
    with pytest.raises(SceneError, match=r"\[load\] ramp_steps = 10000 .*loading steps"):
        s.with_overrides(["load.ramp_steps=10000", f"load.levels={[0.1] * 100}"])


def test_grid_must_resolve_the_contact_radius_naming_dx_or_dy():
    s = default_scene()                                 # a = 4.786 mm
    a = s.contact_radius
    s.with_overrides([f"grid.dx={a / MIN_ELEMENTS_PER_RADIUS}"])
    with pytest.raises(SceneError, match=r"\[grid\] dx = 100.0 mm: .*spans 0.048 elements"):
        s.with_overrides(["grid.dx=100"])
    with pytest.raises(SceneError, match=r"\[grid\] dy = 2.0 mm: .*allowed range is 0 < dy <= 1.59"):
        s.with_overrides(["grid.dy=2"])
    with pytest.raises(SceneError, match=r"\[grid\] dx = 1.0 mm: .*semi-axis along y"):   # ellipse, dy = dx
        s.with_overrides(["geometry.Rx=400", "geometry.Ry=1", "grid.dx=1"])
    s.with_overrides(['solver.fidelity="mdr"', "grid.dx=100"])   # the 1-D MDR model has no grid


def test_contradictory_alternatives_are_refused(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[geometry]\nR = 10.0\nRx = 5.0\n")
    with pytest.raises(SceneError, match="either R, or Rx and Ry"):
        Scene.from_toml(f)
    f.write_text("[geometry]\nR = 10.0\n[load]\nft = 0.2\nFt = 1.0\n")
    with pytest.raises(SceneError, match="either ft"):
        Scene.from_toml(f)


@pytest.mark.parametrize("override, scene_gives, equivalent", [
    ("load.Ft=5.5", "load.ft = 0.46", "load.ft = 0.279093 is Ft = 5.5 N here"),
    ("motion.W=1.2", "motion.w = 0.23", "motion.w = 0.250747 is W = 1.2 mm here")])
def test_an_override_in_the_other_spelling_of_a_key_the_scene_gives_is_refused(override, scene_gives, equivalent):
    """The paper scene gives ft and w: --set load.Ft (or motion.W) would drop them unannounced. Refused, with the
    value in the scene's spelling that gives the same load (Ft = ft mu Fn, mu Fn = 19.707 N) or amplitude (W = w a,
    a = 4.7857 mm)."""
    with pytest.raises(SceneError, match=f"overrides '{override}': the scene gives {scene_gives}, the same quantity "
                                         f"in its other spelling: give .*\\({equivalent}\\)"):
        default_scene().with_overrides([override])


def test_forces_over_creepages_of_a_rolling_scene_are_refused():
    """The shipped creep scene prescribes xi, eta: --set rolling.Fx, Fy dropped them unannounced."""
    scene = Scene.from_toml(shipped_scene_path("creep_steady.toml"))
    with pytest.raises(SceneError, match="the scene gives rolling.xi = 0.0005: prescribed forces .* exclude each other"):
        scene.with_overrides(["rolling.Fx=-100", "rolling.Fy=0"])


def test_a_sphere_becomes_an_ellipsoid_when_both_radii_are_given():
    """R and Rx, Ry name different shapes (as geometry.shape does): an override switches the shape."""
    s = default_scene().with_overrides(["geometry.Rx=80", "geometry.Ry=20"])
    assert s.shape == "ellipsoid" and s.geometry.R is None


@pytest.mark.parametrize("first, second", [("load.ft=0.3", "load.Ft=5"), ("motion.w=0.2", "motion.W=1.0"),
                                           ("geometry.Rx=20", "geometry.R=40")])
def test_both_spellings_in_one_set_of_overrides_are_refused_naming_both(first, second):
    """Within one command the two spellings of a quantity contradict each other (as in a scene file): neither may win
    silently. Repeating the same key is an ordinary override (the last wins)."""
    with pytest.raises(SceneError, match=rf"overrides '{first}' and overrides '{second}': give either"):
        default_scene().with_overrides([first, second])
    assert default_scene().with_overrides(["load.ft=0.3", "load.ft=0.4"]).f_t == 0.4


def test_shipped_scenes_differ_only_in_the_rolling_direction():
    par = Scene.from_toml(shipped_scene_path("paper_parallel.toml"))
    perp = Scene.from_toml(shipped_scene_path("paper_perpendicular.toml"))
    assert par.motion.angle == 0.0 and perp.motion.angle == 90.0
    d_par, d_perp = par.to_dict(), perp.to_dict()
    d_par["motion"].pop("angle"), d_perp["motion"].pop("angle")
    assert d_par == d_perp


def test_unreadable_or_invalid_files_give_scene_errors(tmp_path):
    with pytest.raises(SceneError, match="scene file"):
        Scene.from_toml(tmp_path / "missing.toml")
    f = tmp_path / "broken.toml"
    f.write_text("[load\nFn = 1")
    with pytest.raises(SceneError, match="not valid TOML"):
        Scene.from_toml(f)


def test_w_and_W_share_one_range():
    """w = W/a is open above like W (W = 10 mm is w = 2.09 on the paper scene); the step limit bounds both."""
    s = default_scene().with_overrides(["motion.w=1.5"])
    assert s.amplitude == pytest.approx(1.5 * s.contact_radius)
    data = default_scene().to_dict()
    data["motion"].pop("w")
    data["motion"]["W"] = 10.0
    assert Scene.from_dict(data).amplitude == 10.0
    with pytest.raises(SceneError, match=r"\[motion\] w = -0.1: allowed range"):
        default_scene().with_overrides(["motion.w=-0.1"])


def test_set_values_accept_numbers_as_python_writes_them():
    """--set load.ft=.5 and grid.dx=1. are not TOML and were refused as 'expected a number'."""
    s = default_scene().with_overrides(["load.ft=.5", "grid.dx=1.", "motion.periods=1e1"])
    assert (s.load.ft, s.grid.dx, s.motion.periods) == (0.5, 1.0, 10)
    with pytest.raises(SceneError, match="expected a number"):
        default_scene().with_overrides(["load.ft=.5x"])
