"""The [friction] and [thermal] sections of a scene (cases.scene.friction) and what a run with them writes: the keys
each law takes, what they need, that Coulomb's law is load.mu bit for bit, the fields and history of a law, the memory
state through a restart, and a steady run with temperatures. Units: mm, N, MPa, s, mm/s, degC."""
import numpy as np
import pytest

import rollcontact
from rollcontact.bem.errors import SceneError
from rollcontact.cases.scene.scene import Scene, default_scene

LAW = {"friction.law": "exponential", "friction.mu_kin": 0.6, "friction.mu_1": 0.33, "friction.s_1": 10.0}
ROLLING = {"geometry": {"R": 300.0}, "materials": {"E1": 210e3, "nu1": 0.28, "E2": 210e3, "nu2": 0.28},
           "load": {"Fn": 20e3}, "rolling": {"mode": "steady", "xi": 0.002, "speed": 30000.0}, "grid": {"dx": 0.5}}
THERMAL = {"conductivity1": 50.0, "density1": 7850.0, "heat_capacity1": 450.0,
           "conductivity2": 50.0, "density2": 7850.0, "heat_capacity2": 450.0}


def rolling(**sections):
    data = {k: dict(v) for k, v in ROLLING.items()}
    for name, values in sections.items():
        data.setdefault(name, {}).update(values)
    return Scene.from_dict(data)


@pytest.mark.parametrize("data, match", [
    ({"friction": {"law": "coulomb", "mu": 0.5}, "load": {"mu": 0.5}}, r"\[load\] mu = 0.5 together with \[friction\]"),
    ({"friction": {"mu_kin": 0.2}}, r"\[friction\] \['mu_kin'\] without law"),
    ({"friction": {"law": "coulomb", "mu": 0.5, "s_1": 3.0}}, r"s_1 = 3.0 does not apply to law = 'coulomb'"),
    ({"friction": {"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1}}, r"law = 'exponential' needs s_1"),
    ({"friction": {"law": "rational", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 1.0, "mu_2": 0.1}}, "mu_2 = 0.1 needs s_2"),
    ({"friction": {"law": "linear", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 1.0, "memory_s0": 1.0}},
     "memory_s0 = 1.0 mm/s applies with memory_distance > 0"),
    ({"friction": {"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 1.0}},
     r"needs the rolling speed motion\.speed"),
    ({"friction": {"law": "temperature", "mu_ref": 0.3, "T_ref": 0.0, "dmu_heat": -0.1, "dT_heat": 100.0},
      "motion": {"speed": 1.0}}, "needs the surface temperatures"),
    ({"friction": {"law": "temperature", "mu_ref": 0.3, "T_ref": 0.0, "dmu_heat": -0.4, "dT_heat": 100.0}},
     "mu_ref \\+ dmu_heat must be > 0"),
    ({"friction": {"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 1.0}, "motion": {"speed": 1.0},
      "solver": {"fidelity": "mdr"}}, r"fidelity = 'mdr' with \[friction\]"),
    ({"thermal": THERMAL, "motion": {"speed": 1.0}}, r"\[thermal\] applies to \[rolling\] scenes"),
    ({"thermal": {"conductivity1": 50.0}}, r"\[thermal\] needs density1"),
    ({"friction": {"law": "exponential", "mu_kin": 0.0, "mu_1": 0.1, "s_1": 1.0}},
     r"\[friction\] mu_kin = 0.0: allowed"),
])
def test_friction_and_thermal_keys_that_do_not_fit_are_refused_naming_them(data, match):
    base = {"geometry": {"R": 40.0}, "motion": {"w": 0.2}}
    for sec, values in data.items():
        base.setdefault(sec, {}).update(values)
    with pytest.raises(SceneError, match=match):
        Scene.from_dict(base)


def test_rolling_scene_refusals():
    with pytest.raises(SceneError, match=r"\[rolling\] Fx, Fy with \[friction\] law = 'exponential'"):
        Scene.from_dict({"geometry": {"R": 300.0}, "rolling": {"mode": "steady", "Fx": 10.0, "Fy": 0.0,
                                                                "speed": 10.0},
                         "friction": {"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 1.0}})
    with pytest.raises(SceneError, match=r"\[thermal\] needs rolling.speed"):
        Scene.from_dict({"geometry": {"R": 300.0}, "rolling": {"mode": "steady", "xi": 1e-3}, "thermal": THERMAL})


def test_a_law_takes_the_place_of_load_mu_with_its_static_coefficient():
    scene = default_scene().with_overrides({**LAW, "motion.speed": 10.0})
    assert scene.friction_on and scene.load.mu == pytest.approx(0.93)
    assert scene.Ft == pytest.approx(0.46 * 0.93 * 21.19)
    text = scene.to_toml()
    assert "[friction]" in text and "\nmu = " not in text.split("[load]")[1].split("[")[0]
    again = Scene.from_toml_text(text, name=scene.name)
    assert again == scene
    with pytest.raises(SceneError, match="load.mu"):
        scene.with_overrides({"load.mu": 0.5})
    assert "[friction]" not in default_scene().to_toml() and "[thermal]" not in default_scene().to_toml()


def test_coulombs_law_in_friction_is_load_mu_bit_for_bit():
    plain = default_scene().with_overrides({"motion.periods": 1})
    law = plain.with_overrides({"friction.law": "coulomb", "friction.mu": 0.93})
    a, b = rollcontact.run(plain), rollcontact.run(law)
    for name, values in a.history.items():
        if name != "wall_time":
            assert np.array_equal(values, b.history[name]), name
    for name, values in a.fields.items():
        assert np.array_equal(values, b.fields[name]), name
    assert set(b.fields) - set(a.fields) == {"mu", "slip_velocity"}
    assert np.all(b.fields["mu"] == 0.93)


def test_a_run_with_a_law_writes_the_local_coefficient_slip_velocity_and_time(tmp_path):
    scene = default_scene().with_overrides({**LAW, "motion.speed": 10.0, "motion.periods": 1})
    res = rollcontact.run(scene, tmp_path / "law.h5")
    back = rollcontact.read_run(tmp_path / "law.h5")
    assert back.history["time"] == pytest.approx(back.history["step"] * scene.step_time, rel=1e-15)
    mu, s, p = back.fields["mu"], back.fields["slip_velocity"], back.fields["p"]
    law = rollcontact.cases.scene.friction.friction_law(scene)
    slipping = (back.fields["region"] == 2) & (s > 0)
    assert mu[slipping] == pytest.approx(law.coefficient(s[slipping]), abs=1e-7)   # the law at the slip velocity
    assert np.all((mu >= law.mu_kin - 1e-12) & (mu <= law.mu_static + 1e-12))
    assert np.all(np.hypot(back.fields["tau_x"], back.fields["tau_y"]) <= mu * p * (1 + 1e-9) + 1e-15)
    assert res.summary["mu_static"] == pytest.approx(0.93) and "exponential" in res.summary["friction_law"]
    assert "frictional_power" in back.history and "friction_iterations" in back.history
    plain = rollcontact.run(default_scene().with_overrides({"motion.periods": 1}))
    assert "time" not in plain.history and "mu" not in plain.fields


def test_a_restart_carries_the_memory_state(tmp_path):
    """The local coefficient is the memory of a law with memory_distance: stored in /fields/mu at every stored step
    and read back by --restart, so that the continued run is the uninterrupted one (to the solver tolerance)."""
    scene = default_scene().with_overrides({**LAW, "friction.memory_distance": 0.05, "friction.memory_s0": 0.5,
                                            "motion.speed": 10.0, "motion.periods": 2, "grid.dx": 0.4,
                                            "motion.dW": 0.4})
    whole = rollcontact.run(scene, tmp_path / "whole.h5")
    rollcontact.run(scene.with_overrides({"motion.periods": 1}), tmp_path / "first.h5")
    continued = rollcontact.restart(tmp_path / "first.h5", overrides={"motion.periods": 2},
                                    output=tmp_path / "continued.h5")
    assert continued.history["U_x"] == pytest.approx(whole.history["U_x"], rel=1e-6, abs=1e-9)
    assert continued.fields["mu"][-1] == pytest.approx(whole.fields["mu"][-1], abs=1e-6)


def test_a_steady_run_with_temperatures_writes_them_and_their_maxima(tmp_path):
    scene = rolling(thermal={**THERMAL, "T_bulk1": 20.0, "T_bulk2": 40.0},
                    friction={"law": "exponential", "mu_kin": 0.15, "mu_1": 0.15, "s_1": 100.0})
    res = rollcontact.run(scene, tmp_path / "hot.h5")
    back = rollcontact.read_run(tmp_path / "hot.h5")
    T1, T2, p = back.fields["T1"][0], back.fields["T2"][0], back.fields["p"][0]
    assert np.max(np.abs(T1 - T2)[p > 0]) < 1e-6                      # one temperature in the contact
    assert res.summary["T1_max"] == pytest.approx(T1.max()) and res.summary["T2_max"] == pytest.approx(T2.max())
    assert T1.min() >= 20.0 - 1e-9 and T2.max() <= 40.0 + 1e-9 + np.max(T1 - 20.0)   # heated, and body 2 cooled
    assert T1[:, -1] == pytest.approx(20.0, abs=1e-6) and T2[:, -1] == pytest.approx(40.0, abs=1e-6)   # ahead: bulk
    assert res.summary["frictional_power"] > 0
    assert back.history["time"] == pytest.approx([0.0])
    from rollcontact.cases.cli.main import main
    assert main(["plot", str(tmp_path / "hot.h5"), "-o", str(tmp_path / "figures")]) == 0
    assert (tmp_path / "figures" / "hot_friction.png").stat().st_size > 10_000


def test_creep_curve_takes_a_friction_law_and_falls_beyond_its_peak(tmp_path):
    """`rollcontact creep-curve` with the exponential law: the CSV adds the law's columns, the curve peaks below
    mu_static Fn and falls towards mu_kin Fn, and the figure marks mu_kin Fn."""
    from rollcontact.cases.run.creep_curve import compute_curve, write_csv
    from rollcontact.cases.plots.creep_figures import plot_curve
    scene = rolling(friction={"law": "exponential", "mu_kin": 0.15, "mu_1": 0.15, "s_1": 100.0})
    table = compute_curve(scene, "xi", np.geomspace(0.05, 8.0, 9))
    ratio = np.array([r["F_over_muFn"] for r in table.rows])
    k = int(np.argmax(ratio))
    assert 0 < k < len(ratio) - 1 and ratio[k] < 1.0 and ratio[-1] < ratio[k]
    assert table.rows[-1]["mu_min"] == pytest.approx(0.15, abs=0.02) and table.lowest_ratio == pytest.approx(0.5)
    path = write_csv(table, tmp_path / "curve.csv")
    header = open(path).read().splitlines()[1].split(",")
    assert {"mu_min", "slip_velocity_max", "frictional_power"} <= set(header)
    assert "exponential" in open(path).readline()
    assert all(p.stat().st_size > 0 for p in plot_curve(table, tmp_path, "curve"))


def test_friction_laws_and_temperatures_with_the_other_models_are_refused_or_combined():
    """Viscoelastic bodies take neither a [friction] section nor [thermal] (the slip-velocity iteration and the
    temperatures are of elastic half-spaces); [thermal] needs the boundary elements; a law other than Coulomb's
    needs them too; Coulomb's law gives its mu to a fast model like load.mu; a wheel-rail scene takes neither."""
    sls = {"visco2": "sls", "E2": 43.5, "E2_relaxed": 4.35, "tau2": 1.0}
    with pytest.raises(SceneError, match=r"\[friction\] with materials.visco2 = 'sls'.*\[load\] mu"):
        Scene.from_dict({"geometry": {"R": 40.0}, "motion": {"w": 0.2, "speed": 1.0}, "materials": sls,
                         "friction": {"law": "coulomb", "mu": 0.5}})
    with pytest.raises(SceneError, match=r"\[thermal\] with materials.visco2 = 'sls'"):
        rolling(materials=sls, thermal=THERMAL)
    with pytest.raises(SceneError, match=r"\[thermal\] with \[solver\] fidelity = 'fastsim'.*'bem'"):
        rolling(thermal=THERMAL, solver={"fidelity": "fastsim"})
    with pytest.raises(SceneError, match=r"fidelity = 'fastsim' with \[friction\] law = 'exponential'.*'bem'"):
        rolling(friction={"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 100.0},
                solver={"fidelity": "fastsim"})
    fast = rolling(friction={"law": "coulomb", "mu": 0.25}, solver={"fidelity": "fastsim"})
    assert fast.load.mu == 0.25 and rollcontact.run(fast).summary["mu_Fn"] == pytest.approx(0.25 * 20e3, rel=1e-9)
    with pytest.raises(SceneError, match=r"\[friction\] with \[wheelrail\]"):
        Scene.from_dict({"wheelrail": {"wheel_radius": 460.0}, "friction": {"law": "coulomb", "mu": 0.3}})


def test_creep_curve_of_a_law_refuses_the_fast_models(tmp_path):
    scene = rolling(friction={"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 100.0})
    with pytest.raises(rollcontact.InputError, match=r"fidelity.*'fastsim'.*one coefficient of friction"):
        rollcontact.creep_curve(scene, points=3, output=tmp_path, fidelity=["bem", "fastsim"])
    assert not any(tmp_path.iterdir())
