"""[rolling] scenes on the fast models and on `auto` (cases/run/creep_fast.py, cases/run/fidelity.py; docs/
creep_fidelity.md): real HDF5 files with the layout of the exact solver's, forces equal to the solver-level models
on the same grid and pressure, the transient rolling into the steady state, the choice `auto` makes and records, the
creep curves of several models side by side, and the refusals. Steel on steel, a sphere R = 40 mm, Fn = 1000 N
(Hertz a = 0.64 mm), mu = 0.3, the default resolution (a / 12)."""
from pathlib import Path

import h5py
import numpy as np
import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases import api
from rollcontact.cases.cli.main import main
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.run.creep_fast import contact_ellipse, fast_operator, solve_scene_normal
from rollcontact.cases.run.fidelity import choose_fidelity
from rollcontact.cases.run.rolling_frame import creep_grid
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.fastsim import kalker_flexibilities, solve_fastrip, solve_fastsim

STEEL = """
[materials]
E1 = 210e3
nu1 = 0.28
E2 = 210e3
nu2 = 0.28
[geometry]
R = 40.0
[load]
Fn = 1000.0
mu = 0.3
"""


def rolling_scene(rolling: str = "xi = 2e-4\neta = 1e-4", solver: str = "", mode: str = "steady") -> Scene:
    return Scene.from_toml_text(f"{STEEL}\n[rolling]\nmode = \"{mode}\"\n{rolling}\n[solver]\n{solver}\n",
                                name="roll")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The same steady scene on the exact solver and both fast models, written and read back."""
    folder = tmp_path_factory.mktemp("fidelity")
    out = {}
    for model in ("bem", "fastsim", "fastrip"):
        run_scene(rolling_scene(solver=f'fidelity = "{model}"'), folder / f"{model}.h5")
        out[model] = read_run(folder / f"{model}.h5")
    return out


def test_fast_runs_store_the_layout_of_the_exact_solver(runs):
    """Same history columns, fields and (Kalker's) summary values as the exact solver's run, plus the fast model's
    own summary values (docs/creep_fidelity.md); the stored fields are finite and the traction within mu p."""
    bem = runs["bem"]
    for model in ("fastsim", "fastrip"):
        r = runs[model]
        assert set(r.history) == set(bem.history) and set(r.fields) == set(bem.fields)
        assert set(bem.summary) - {"outer_iterations"} <= set(r.summary)
        assert r.summary["fidelity"] == r.summary["fidelity_used"] == model
        assert r.summary["traction_bound"] == "scene" and r.summary["flexibility"] > 0
        p, tx, ty = r.field("p"), r.field("tau_x"), r.field("tau_y")
        assert np.all(np.hypot(tx, ty) <= 0.3 * p * (1 + 1e-12))
        assert r.summary["F_x"] == pytest.approx(-r.history["F_x"][0], rel=1e-12)
    assert bem.summary["fidelity_used"] == "bem"


def test_fast_run_forces_are_the_models_on_the_scenes_grid_and_pressure(runs):
    """The run's F_x, F_y, M_z are the solver-level model's on the scene's contact-fixed grid, with the pressure of the
    normal problem as the bound and the flexibilities of the Hertz ellipse (a = b here), to rounding; and within the
    literature's spread of the exact run's (FaStrip within 5 %, FASTSIM within 30 %: xi and eta together at a fifth of
    saturation, where FASTSIM's one weighted flexibility is known to be off, docs/creep_fidelity.md)."""
    scene = rolling_scene()
    grid = creep_grid(scene)
    normal = solve_scene_normal(scene, fast_operator(scene, grid))
    a, b = contact_ellipse(scene, grid, normal.pressure)
    pair = scene.material_pair
    flex = kalker_flexibilities(a, b, pair.G, pair.nu)
    bem = np.array([runs["bem"].summary["F_x"], runs["bem"].summary["F_y"]])
    for model, solve, spread in (("fastsim", solve_fastsim, 0.3), ("fastrip", solve_fastrip, 0.05)):
        direct = solve(grid, normal.pressure, 0.3, 2e-4, 1e-4, 0.0, flexibilities=flex)
        s = runs[model].summary
        assert (s["F_x"], s["F_y"]) == pytest.approx(direct.force, rel=1e-9)
        assert s["M_z"] == pytest.approx(direct.moment, rel=1e-9, abs=1e-9 * abs(s["F_x"]))
        assert np.hypot(*(np.array([s["F_x"], s["F_y"]]) - bem)) < spread * np.hypot(*bem)


def test_transient_fastsim_reaches_its_steady_state(tmp_path):
    """Rolled from rest in steps of dx over the default 4 contact lengths, transient FASTSIM ends in the steady
    FASTSIM state beside it (the material leaves the contact with its memory: equal to rounding), with the history of
    the exact transient run's layout."""
    out = tmp_path / "t.h5"
    run_scene(rolling_scene(solver='fidelity = "fastsim"', mode="transient"), out)
    r = read_run(out)
    s = r.summary
    assert s["fidelity_used"] == "fastsim" and s["state"] == "transient"
    assert (s["F_x"], s["F_y"]) == pytest.approx((s["F_x_steady"], s["F_y_steady"]), rel=1e-9)
    assert r.history["F_x"][0] == 0.0 and r.history["F_x"][-1] == pytest.approx(-s["F_x"], rel=1e-12)
    assert {"M_z", "xi", "eta", "cpu_time"} <= set(r.history)


def test_hertz_bounds_carry_the_normal_force(tmp_path):
    """traction_bound = 'ellipsoid' and 'parabolic' bound the traction by mu times Hertz's semi-ellipsoid or Kalker's
    parabola over the Hertz ellipse carrying Fn: in full sliding |F| = mu Fn within the discretisation of the bound
    on the grid (2 %; measured 0.1-1 %), and the parabola's force differs from the ellipsoid's in partial slip."""
    forces = {}
    for bound in ("ellipsoid", "parabolic"):
        for xi in (0.05, 2e-4):
            r = run_scene(rolling_scene(f"xi = {xi}", f'fidelity = "fastsim"\ntraction_bound = "{bound}"'), None)
            forces[bound, xi] = r.summary["F_x"]
            assert r.summary["traction_bound"] == bound
        assert -forces[bound, 0.05] == pytest.approx(0.3 * 1000.0, rel=0.02)
    assert abs(forces["ellipsoid", 2e-4] - forces["parabolic", 2e-4]) > 0.01 * abs(forces["ellipsoid", 2e-4])


@pytest.mark.parametrize("accuracy, model", [(0.3, "fastsim"), (0.03, "fastrip"), (1e-4, "bem")])
def test_auto_takes_the_cheapest_model_within_the_accuracy_and_says_why(tmp_path, capfd, accuracy, model):
    """Pure xi at half its saturation value on the circle: FASTSIM's predicted error there is 7.3 %, FaStrip's 2.2 %
    (solver/fastsim/error_map.json with its margins): a loose request takes FASTSIM, 3 % FaStrip, 1e-4 the exact
    theory; stderr says which and why, the summary records fidelity_used and the predicted error (within the
    request)."""
    scene = rolling_scene("xi = 1e-3", f'fidelity = "auto"\naccuracy = {accuracy}')
    out = tmp_path / "auto.h5"
    run_scene(scene, out)
    err = capfd.readouterr().err
    assert "solver.fidelity = 'auto'" in err and f"'{model}'" in err
    s = read_run(out).summary
    assert s["fidelity_used"] == model and s["accuracy"] == accuracy
    assert 0 <= s["predicted_error"] <= accuracy and s["fidelity_reason"]
    with h5py.File(out, "r") as h5:
        assert h5["summary"].attrs["fidelity_used"] == model


def test_auto_runs_the_exact_theory_outside_the_map():
    """Prescribed forces, coupled materials and a file or cylinder shape lie outside the map: the boundary
    elements, and the reason names why."""
    forces = choose_fidelity(rolling_scene("Fx = -50.0\nFy = 0.0", 'fidelity = "auto"\naccuracy = 0.5'))
    assert forces.model == "bem" and "prescribed forces" in forces.reason
    coupled = Scene.from_toml_text(STEEL.replace("E2 = 210e3", "E2 = 70e3").replace("nu2 = 0.28", "nu2 = 0.33")
                                   + '[rolling]\nmode = "steady"\nxi = 2e-4\n[solver]\nfidelity = "auto"\n'
                                     'accuracy = 0.5\n')
    assert choose_fidelity(coupled).model == "bem" and "coupled" in choose_fidelity(coupled).reason


def test_creep_curve_draws_the_models_side_by_side(tmp_path, capsys):
    """`creep-curve --fidelity` (repeatable): one CSV per model (the exact theory's under the usual name), one figure
    with every curve; the fast models' curves saturate at mu Fn like the exact one (full sliding at 4 times the
    saturation creepage: within 2 %), and each costs a small fraction of the exact curve's CPU time."""
    path = tmp_path / "roll.toml"
    path.write_text(rolling_scene().to_toml())
    assert main(["creep-curve", str(path), "--of", "eta", "--points", "6", "--fidelity", "bem", "--fidelity",
                 "fastsim", "--fidelity", "fastrip", "-o", str(tmp_path / "c")]) == 0
    names = {p.name for p in (tmp_path / "c").iterdir()}
    stem = Path(path).stem + "_creep_eta"
    assert {f"{stem}.csv", f"{stem}_fastsim.csv", f"{stem}_fastrip.csv", f"{stem}.png", f"{stem}.pdf"} <= names
    curve = api.creep_curve(rolling_scene(), of="eta", points=6, fidelity=["bem", "fastsim", "fastrip"], output=None)
    tables = {t.fidelity: t for t in curve.tables}
    for model in ("fastsim", "fastrip"):
        assert tables[model].rows[-1]["F_over_muFn"] == pytest.approx(tables["bem"].rows[-1]["F_over_muFn"],
                                                                      rel=0.02)
        assert sum(r["cpu_time"] for r in tables[model].rows) < 0.5 * sum(r["cpu_time"] for r in tables["bem"].rows)
    assert curve.paths == [] and "fastsim" in curve.report()


@pytest.mark.parametrize("text, match", [
    ('[solver]\nfidelity = "fastsim"\n', "fidelity = 'fastsim': a model of rolling with creepage"),
    ('[rolling]\nmode = "transient"\nxi = 1e-4\n[solver]\nfidelity = "fastrip"\n', "steady-state theory"),
    ('[rolling]\nmode = "steady"\nFx = -1.0\nFy = 0.0\n[solver]\nfidelity = "fastsim"\n', "Fx, Fy"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\nfidelity = "fastsim"\ncoupling = "on"\n', "coupling"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\ntraction_bound = "ellipsoid"\n', "fast models only"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\nfidelity = "fastrip"\ntraction_bound = "parabolic"\n',
     "FASTSIM's"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\naccuracy = 0.02\n', "accuracy = 0.02 with fidelity = 'bem'"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\nfidelity = "auto"\naccuracy = 1.5\n', r"allowed range"),
    ('[rolling]\nmode = "steady"\nxi = 1e-4\n[solver]\nfidelity = "mdr"\n', "fidelity = 'mdr' with \\[rolling\\]"),
])
def test_bad_fidelity_settings_are_refused_naming_the_key(text, match):
    with pytest.raises(SceneError, match=match):
        Scene.from_toml_text(STEEL + text)


def test_hertz_bound_needs_a_hertzian_contact_rolling_along_an_axis():
    with pytest.raises(SceneError, match="traction_bound = 'ellipsoid'"):
        Scene.from_toml_text(STEEL.replace("R = 40.0", "Rx = 40.0\nRy = 20.0") + '[rolling]\nmode = "steady"\n'
                             'xi = 1e-4\ndirection = 30.0\n[solver]\nfidelity = "fastsim"\n'
                             'traction_bound = "ellipsoid"\n')



def test_a_fastsim_transient_rolls_on_the_world_grid_and_refuses_the_moving_one():
    """FASTSIM's transient steps the world-fixed grid (its strips carry their state with the material): that is the
    default grid of a FASTSIM transient, and an explicit grid = 'contact' is refused, naming both keys."""
    from rollcontact.cases.scene.scene import shipped_scene_path
    transient = {"rolling.mode": "transient", "solver.fidelity": "fastsim"}
    assert api.load_scene(shipped_scene_path("creep_steady.toml"), overrides=transient).transient_grid == "world"
    with pytest.raises(SceneError, match=r"\[rolling\] grid = 'contact' with \[solver\] fidelity = 'fastsim'"):
        api.load_scene(shipped_scene_path("creep_steady.toml"), overrides=dict(transient, **{"rolling.grid": "contact"}))
