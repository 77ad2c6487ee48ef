"""The rolling speed of a scene (`motion.speed`, `rolling.speed`, mm/s) and the time of a step it gives: the
displacement of the step over the speed, every step of the path (loading steps included) taking the same time."""
import math

import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases.run.discretise import scene_path
from rollcontact.cases.scene.scene import Scene, default_scene


def test_oscillating_scene_step_time_is_the_rolling_step_over_the_speed():
    scene = default_scene().with_overrides({"motion.speed": 10.0})
    assert scene.speed == 10.0
    assert scene.step_time == pytest.approx(scene.rolling_step / 10.0, rel=1e-15)
    path = scene_path(scene)
    assert path.step_time == scene.step_time


def test_scene_at_rest_takes_motion_dW_over_the_speed():
    scene = Scene.from_dict({"geometry": {"R": 40}, "load": {"ft": 0.5}, "motion": {"dW": 0.25, "speed": 5.0}})
    assert scene.amplitude == 0
    assert scene.step_time == pytest.approx(0.05, rel=1e-15)


def test_without_a_speed_a_scene_is_time_independent():
    scene = default_scene()
    assert scene.speed is None and scene.step_time is None
    assert scene_path(scene).step_time is None


def test_transient_rolling_step_time_is_the_rolling_step_over_the_speed():
    scene = Scene.from_dict({"geometry": {"R": 40}, "rolling": {"mode": "transient", "xi": 1e-3, "step": 0.3,
                                                                 "speed": 1500.0}})
    assert scene.step_time == pytest.approx(0.3 / 1500.0, rel=1e-15)
    dx_default = Scene.from_dict({"geometry": {"R": 40}, "rolling": {"mode": "transient", "xi": 1e-3,
                                                                      "speed": 1500.0}})
    assert dx_default.step_time == pytest.approx(dx_default.spacing[0] / 1500.0, rel=1e-15)


def test_steady_rolling_has_a_speed_but_no_step_time():
    scene = Scene.from_dict({"geometry": {"R": 40}, "rolling": {"mode": "steady", "xi": 1e-3, "speed": 2000.0}})
    assert scene.speed == 2000.0 and scene.step_time is None


@pytest.mark.parametrize("value", [0, -1.0, math.inf, "fast"])
def test_a_speed_out_of_range_is_refused_naming_the_key(value):
    with pytest.raises(SceneError, match=r"\[motion\] speed"):
        Scene.from_dict({"geometry": {"R": 40}, "motion": {"w": 0.2, "speed": value}})


def test_rolling_speed_needs_a_rolling_mode():
    with pytest.raises(SceneError, match="mode = 'none'"):
        Scene.from_dict({"geometry": {"R": 40}, "rolling": {"mode": "none", "speed": 10.0}})
