"""`solver.fidelity = "auto"` against held-out measurements (docs/creep_fidelity.md): scenes that were not used to
build the error maps, each measured on every model, on which the map's prediction must never let `auto` choose a
model whose measured error exceeds the request.

The measurements are data of the program's own runs (benchmarks/creep_error_map.py and benchmarks/mdr_error_map.py
write them with the maps: tests/solver/data/fastsim_held_out.json, tests/cases/data/mdr_held_out.json), so these
tests check the choice, not the physics; the physics of each model is checked in tests/solver/test_fastsim.py and
by the MDR's closed forms. One live check solves held-out scenes end to end (scene -> choice -> run -> the exact
run of the same scene).
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from rollcontact.cases.run.fidelity import FAST_BY_COST, choose_fidelity
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.fastsim.error_map import load_error_map
from rollcontact.solver.mdr.error_map import load_mdr_map

HERE = Path(__file__).resolve().parent
REQUESTS = (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3)


def _rows(path):
    return json.loads(path.read_text())["rows"]


@pytest.mark.parametrize("rows_key", ["rows", "rows_fine"])
def test_auto_never_exceeds_any_request_on_held_out_rolling_scenes(rows_key):
    """For every held-out scene (a/b, nu, creepages drawn at random inside the map, off its nodes; measured at the
    map's 41 elements across, and another draw at 81) and every request: auto takes FASTSIM for any request at or
    above its predicted error, FaStrip for a request between FaStrip's prediction and FASTSIM's, else the exact
    theory; so each fast model's measured error must lie within its prediction wherever a request chooses it."""
    emap = load_error_map()
    data = json.loads((HERE.parent / "solver" / "data" / "fastsim_held_out.json").read_text())
    rows = data[rows_key]
    assert len(rows) >= (100 if rows_key == "rows" else 40)
    for row in rows:
        bound = math.inf                                  # requests below this take a cheaper model
        for model in FAST_BY_COST:
            predicted = emap.predict(model, row["ratio"], row["nu"], row["xi_hat"], row["eta_hat"], row["phi_hat"])
            if predicted is None or predicted >= bound:
                continue
            assert row[model] <= predicted, (model, predicted, row)
            bound = predicted


@pytest.mark.parametrize("accuracy", REQUESTS)
def test_auto_takes_the_fast_models_where_the_map_allows(accuracy):
    """The same held-out scenes at the requests 0.5 % ... 30 %: the model chosen is within the request, and the fast
    models are taken on some of them from 5 % on (the map is not vacuous)."""
    emap = load_error_map()
    rows = _rows(HERE.parent / "solver" / "data" / "fastsim_held_out.json")
    chosen = []
    for row in rows:
        model = "bem"
        for candidate in FAST_BY_COST:
            predicted = emap.predict(candidate, row["ratio"], row["nu"], row["xi_hat"], row["eta_hat"],
                                     row["phi_hat"])
            if predicted is not None and predicted <= accuracy:
                model = candidate
                break
        assert (0.0 if model == "bem" else row[model]) <= accuracy, (row, model)
        chosen.append(model)
    if accuracy >= 0.05:
        assert set(chosen) & set(FAST_BY_COST)


def test_auto_never_exceeds_any_request_on_held_out_shakedown_scenes():
    """For every held-out shakedown scene (w, f_t between the map's nodes, both alignments) the MDR model is taken for
    any request at or above its predicted u_sd error: its measured error must lie within the prediction (a run that
    does not shake down has no u_sd: then the prediction must be infinite, never the MDR); and at 10 % it is taken
    somewhere."""
    mdr_map = load_mdr_map()
    rows = _rows(HERE / "data" / "mdr_held_out.json")
    assert len(rows) >= 20
    taken = 0
    for row in rows:
        predicted = mdr_map.predict(dict(angle=row["angle"], w=row["w"], f_t=row["f_t"]))
        if predicted is not None and math.isfinite(predicted):
            assert row["error"] is not None and row["error"] <= predicted, row
            taken += predicted <= 0.1
    assert taken


STEEL = """
[materials]
E1 = 210e3
nu1 = 0.28
E2 = 210e3
nu2 = 0.28
[load]
Fn = 1000.0
mu = 0.3
"""


@pytest.mark.parametrize("geometry, creep, accuracy, model", [
    ("Rx = 60.0\nRy = 25.0", "xi = 3e-4", 0.08, "fastsim"),
    ("R = 40.0", "eta = 2e-4\nphi = 1e-3", 0.05, "fastrip"),
    ("Rx = 25.0\nRy = 60.0", "xi = 1e-4\neta = -3e-4", 0.03, "fastrip"),
])
def test_auto_choice_holds_on_live_scenes(geometry, creep, accuracy, model):
    """End to end on scenes off the map's nodes (ellipses of other a/b from Hertz's estimated semi-axes, the scene's
    own grid at its default resolution and its BEM pressure, creepages between the map's nodes): auto takes a fast
    model here, and its forces are within the request of the exact run of the same scene (the map's measure,
    |F - F_exact| / |F_exact|)."""
    text = f"{STEEL}\n[geometry]\n{geometry}\n[rolling]\nmode = \"steady\"\n{creep}\n"
    auto = Scene.from_toml_text(text + f'[solver]\nfidelity = "auto"\naccuracy = {accuracy}\n')
    choice = choose_fidelity(auto)
    assert choice.model == model
    result = run_scene(auto, None).summary
    exact = run_scene(Scene.from_toml_text(text), None).summary
    got, ref = np.array([result["F_x"], result["F_y"]]), np.array([exact["F_x"], exact["F_y"]])
    assert result["fidelity_used"] == choice.model
    assert np.hypot(*(got - ref)) <= accuracy * np.hypot(*ref)
    assert math.isfinite(result["predicted_error"]) and result["predicted_error"] <= accuracy
