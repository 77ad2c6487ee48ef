"""Scenes with viscoelastic bodies (materials.visco<i> = 'sls'; docs/viscoelastic.md): refused without what they need,
the elastic limits of oscillating and steady runs, a transient rolled from rest converging to the steady state, the
outputs in the run file with their units, a restart continuing from the stored element states, the maps."""
import math

import h5py
import numpy as np
import pytest

import rollcontact
from rollcontact.bem.errors import InputError, SceneError
from rollcontact.cases.results.run_result import HISTORY_NAMES, UNITS, SUMMARY_UNITS
from rollcontact.cases.scene.scene import Scene, default_scene

SLS2 = ['materials.visco2="sls"', "materials.E2=43.5", "materials.E2_relaxed=4.35", "materials.tau2=1.0"]
COARSE = ["grid.dx=0.6", "grid.dy=0.6", "motion.dW=0.6", "motion.periods=3", "motion.W=1.1"]
ROLLING = """
[materials]
E1 = inf
E2 = 40.0
nu2 = 0.5
visco2 = "sls"
E2_relaxed = 4.0
tau2 = 1.0
[geometry]
R = 20.0
[load]
Fn = 2.0
mu = 0.5
[rolling]
mode = "{mode}"
xi = 0.002
speed = {speed}
{extra}
[grid]
dx = {dx}
"""
A_R = 1.7784         # relaxed Hertz radius of ROLLING (mm)


@pytest.mark.parametrize("overrides, match", [
    (SLS2, r"without a speed.*motion\.speed"),
    (SLS2[:2] + ["materials.tau2=1", "motion.speed=1"], r"needs materials\.E2_relaxed"),
    (SLS2[:3] + ["motion.speed=1"], r"needs materials\.tau2"),
    (SLS2[:2] + ["materials.E2_relaxed=43.5", "materials.tau2=1", "motion.speed=1"], r"E2_relaxed = 43.5 MPa.*\(0, 43\.5\)"),
    (SLS2[:3] + ["materials.tau2=0", "motion.speed=1"], r"tau2 = 0\.0 s: allowed range is \(0, inf\)"),
    (['materials.visco1="sls"', "materials.E1=inf", "materials.E1_relaxed=1", "materials.tau1=1", "motion.speed=1"],
     r"E1 = inf with visco1 = 'sls'"),
    (["materials.tau2=1"], r"tau2 = 1.0 for an elastic body"),
    (SLS2 + ["motion.speed=1", 'solver.fidelity="mdr"'], r"fidelity = 'mdr'.*allowed value is 'bem'")])
def test_a_viscoelastic_body_without_what_it_needs_is_refused_naming_the_key(overrides, match):
    with pytest.raises(SceneError, match=match):
        default_scene().with_overrides(overrides)


def assert_runs_agree(a, b, rel=1e-6):
    """Approach, contact area, forces and rigid shift of every step within rel of the largest value."""
    for key in ("approach", "contact_area", "Fn", "F_x", "F_y", "U_x", "U_y"):
        x, y = np.asarray(a.history[key]), np.asarray(b.history[key])
        assert np.abs(x - y).max() <= rel * max(np.abs(y).max(), 1e-300) + 1e-15, key


@pytest.mark.parametrize("speed, elastic_E2", [(1e-9, 4.35), (1e12, 43.5)])
def test_oscillating_rolling_at_the_speed_limits_is_the_relaxed_and_the_glassy_elastic_run(speed, elastic_E2):
    """The paper scene (coarse) with an SLS substrate: slow rolling is the elastic run with E_r, fast rolling with
    E_g: approach, contact area, forces and U of every step within 1e-6."""
    base = default_scene().with_overrides(COARSE, replaces=("motion.W",))
    visco = rollcontact.run(base.with_overrides(SLS2 + [f"motion.speed={speed}"]))
    elastic = rollcontact.run(base.with_overrides([f"materials.E2={elastic_E2}"]))
    assert_runs_agree(visco, elastic)
    assert visco.state == elastic.state


@pytest.mark.parametrize("speed, E2", [(1e-9, 4.0), (1e12, 40.0)])
def test_steady_rolling_at_the_speed_limits_is_the_relaxed_and_the_glassy_elastic_run(speed, E2):
    """[rolling] steady: F_x, approach, contact area within 1e-6 of the elastic run with E_r (slow) or E_g (fast)."""
    scene = Scene.from_toml_text(ROLLING.format(mode="steady", speed=speed, extra="", dx=A_R / 8))
    visco = rollcontact.run(scene)
    text = ROLLING.format(mode="steady", speed=speed, extra="", dx=A_R / 8)
    text = text.replace('visco2 = "sls"\nE2_relaxed = 4.0\ntau2 = 1.0\n', "").replace("E2 = 40.0", f"E2 = {E2}")
    elastic = rollcontact.run(Scene.from_toml_text(text))
    for key in ("F_x", "p0"):
        assert visco.summary[key] == pytest.approx(elastic.summary[key], rel=1e-6)
    for key in ("approach", "contact_area"):
        assert visco.history[key][0] == pytest.approx(elastic.history[key][0], rel=1e-6)


def test_a_sphere_rolled_from_rest_reaches_the_steady_viscoelastic_state():
    """V tau / a_r = 1 (E_g/E_r = 10), xi = 0.002, rolled from rest over 12 a_r on the world-fixed grid (step = dx =
    a_r/8): F_x, pressure_centroid_x and the viscous power within 0.5 % of the steady state's (measured 0.04 %,
    6e-8, 3e-6)."""
    scene = Scene.from_toml_text(ROLLING.format(mode="transient", speed=A_R, extra=f"distance = {12 * A_R}",
                                                dx=A_R / 8))
    s = rollcontact.run(scene).summary
    assert s["pressure_centroid_x"] > 0.2 * A_R
    for key in ("F_x", "pressure_centroid_x", "viscous_power"):
        steady = s["F_x_steady"] if key == "F_x" else s[f"{key}_steady"]
        assert s[key] == pytest.approx(steady, rel=0.005), key


def test_a_viscoelastic_run_file_holds_its_outputs_with_units_and_restarts_from_its_states(tmp_path):
    """The run file: history time, pressure_centroid_x, viscous_dissipation, fields q_p2, q_x2, q_y2, summary
    pressure_centroid_x, rolling_resistance_moment (= Fn x_c), viscous_dissipation_per_period, each with its units;
    a restart from step 7 equals the uninterrupted run to round-off (1e-12); without the states it is refused."""
    scene = default_scene().with_overrides(COARSE + SLS2 + ["motion.speed=2", 'output.fields="all"'],
                                           replaces=("motion.W",))
    full = rollcontact.run(scene, tmp_path / "full.h5")
    with h5py.File(tmp_path / "full.h5", "r") as h5:
        for name in ("history/time", "history/pressure_centroid_x", "history/viscous_dissipation", "fields/q_p2"):
            assert h5[name].attrs["units"] == UNITS[name.split("/")[1]]
    s = full.summary
    assert s["rolling_resistance_moment"] == pytest.approx(full.history["Fn"][-1] * s["pressure_centroid_x"])
    assert s["viscous_dissipation_per_period"] > 0
    assert {"pressure_centroid_x", "rolling_resistance_moment", "viscous_dissipation_per_period"} <= set(SUMMARY_UNITS)
    assert np.allclose(full.history["time"], full.history["step"] * scene.step_time, rtol=1e-15)
    again = rollcontact.restart(tmp_path / "full.h5", step=7, output=tmp_path / "again.h5")
    for key in ("U_x", "approach", "viscous_dissipation", "pressure_centroid_x"):
        x, y = np.asarray(again.history[key]), np.asarray(full.history[key])
        assert np.abs(x - y).max() <= 1e-12 * np.abs(y).max(), key
    with h5py.File(tmp_path / "full.h5", "a") as h5:
        del h5["fields/q_x2"]
    with pytest.raises(InputError, match="q_x2"):
        rollcontact.restart(tmp_path / "full.h5", step=7, output=tmp_path / "refused.h5")
    assert not (tmp_path / "refused.h5").exists()


def test_a_run_without_a_speed_keeps_its_history_columns():
    """No speed: no time column, no viscoelastic columns (the elastic runs' files are unchanged)."""
    result = rollcontact.run(default_scene().with_overrides(COARSE, replaces=("motion.W",)))
    assert set(result.history) == set(HISTORY_NAMES)


def test_the_maps_of_a_steady_viscoelastic_run_show_its_forward_leaning_pressure(tmp_path):
    """`plot` draws a steady viscoelastic run, with its pressure figure (PNG written); its summary has the steady
    outputs."""
    from rollcontact.cases.plots.creep_figures import plot_creep_run
    scene = Scene.from_toml_text(ROLLING.format(mode="steady", speed=A_R, extra="", dx=A_R / 8))
    result = rollcontact.run(scene, tmp_path / "steady.h5")
    assert result.summary["pressure_centroid_x"] > 0.2 * A_R and result.summary["viscous_power"] > 0
    assert math.isclose(result.summary["rolling_resistance_moment"], 2.0 * result.summary["pressure_centroid_x"],
                        rel_tol=1e-9)
    paths = plot_creep_run(rollcontact.read_run(tmp_path / "steady.h5"), tmp_path / "plots", "steady")
    assert (tmp_path / "plots" / "steady_pressure.png").stat().st_size > 0 and len(paths) == 4
