"""What was silently guessed or refused too late (issue #39) is refused before any work, with the key and the allowed
range named and nothing written; and a sweep resumes a run killed part-way from its last checkpoint."""
from pathlib import Path
import warnings

import numpy as np
import pytest

import rollcontact
from rollcontact.bem.errors import InputError, SceneError
from rollcontact.cases.cli.main import main
from rollcontact.cases.results.hdf5 import read_run, write_run
from rollcontact.cases.scene.limits import MAX_STEPS, PEAK_MISS
from rollcontact.cases.scene.scene import Scene, default_scene, shipped_scene_path
from rollcontact.cases.sweep.runner import run_sweep

CREEP = shipped_scene_path("creep_steady.toml")


def test_a_thousand_load_cycles_in_24_steps_are_refused_naming_the_keys_and_the_remedy():
    """They ran and reported 'cyclic_slip, u_sd = 0.44555' for loads the steps never visited (aliasing)."""
    with pytest.raises(SceneError, match=r"\[load\] cycles_per_period = 1000 with 24 steps per period: 0.024 steps per "
                                         r"load cycle; allowed is at least 4 steps per load cycle"):
        default_scene().with_overrides({"load.ft_amplitude": 0.1, "load.cycles_per_period": 1000})


@pytest.mark.parametrize("steps, cycles, phase, accepted", [
    (24, 1, 7.0, True),      # 24 steps per cycle: any phase
    (24, 2, 0.0, True),      # 12 steps per cycle, the peaks on steps 3 and 9
    (24, 2, 10.0, False),    # 12 steps per cycle, a peak 10 deg from its step: 1.5 % short
    (24, 6, 0.0, True),      # 4 steps per cycle on the peaks
    (24, 4, 0.0, False),     # 6 steps per cycle: the peaks 30 deg from the nearest step
    (24, 12, 90.0, False),   # 2 steps per cycle: fewer than 4
    (48, 2, 7.5, True),      # 24 steps per cycle
])
def test_a_load_cycle_must_reach_its_peaks_within_the_shortfall_of_24_steps(steps, cycles, phase, accepted):
    overrides = {"motion.w": 0, "load.ft": 0, "load.ft_amplitude": 0.3, "motion.steps_per_period": steps,
                 "load.cycles_per_period": cycles, "load.phase": phase}
    if accepted:
        scene = default_scene().with_overrides(overrides)
        assert scene.load_peak_miss()[1] <= PEAK_MISS * (1 + 1e-9)
    else:
        with pytest.raises(SceneError, match=rf"use motion.steps_per_period >= {24 * cycles} \(it is {steps}\)"):
            default_scene().with_overrides(overrides)


def test_rolling_forces_at_full_sliding_are_refused_before_the_run():
    """|F| >= mu Fn in a [rolling] scene ran and failed (exit 1, a failed run file) where the README says refused."""
    scene = Scene.from_toml(CREEP)
    data = scene.to_dict()
    data["rolling"].pop("xi"), data["rolling"].pop("eta")
    data["rolling"].update(Fx=-12000.0, Fy=9000.0)              # |F| = 15000 N = mu Fn
    with pytest.raises(SceneError, match=r"\[rolling\] Fx = -12000.0, Fy = 9000.0 N: \|F\| = 15000 N reaches mu Fn = "
                                         r"15000 N .* allowed range is \|\(Fx, Fy\)\| < mu Fn = 15000 N"):
        Scene.from_dict(data)
    data["rolling"].update(Fx=-11999.0)
    assert Scene.from_dict(data).prescribed_forces == (-11999.0, 9000.0)


def test_a_transient_beyond_the_grid_limit_is_refused_with_the_longest_distance(tmp_path, capsys):
    """On the world-fixed grid the distance rolled is bounded by the element limit, on the grid moving with the
    contact by the step limit; both refused before any work, naming the longest distance."""
    out = tmp_path / "t.h5"
    assert main(["run", str(CREEP), "-q", "--set", 'rolling.mode="transient"', "--set", "rolling.distance=1e9",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "[rolling] distance = 1e+09 mm in steps of" in err and f"more than {MAX_STEPS} steps per run" in err
    longest = float(err.split("allowed range is distance <= ")[1].split(" mm")[0])
    rollcontact.load_scene(CREEP, {"rolling.mode": "transient", "rolling.distance": longest * (1 - 1e-6)})
    with pytest.raises(SceneError):
        rollcontact.load_scene(CREEP, {"rolling.mode": "transient", "rolling.distance": longest * 1.01})
    assert main(["run", str(CREEP), "-q", "--set", 'rolling.mode="transient"', "--set", "rolling.distance=1e9",
                 "--set", 'rolling.grid="world"', "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "[rolling] distance = 1e+09 mm: the world-fixed grid of the transient would exceed the element limit" in err
    longest = float(err.split("allowed range is distance <= ")[1].split(" mm")[0])
    world = {"rolling.mode": "transient", "rolling.grid": "world"}
    rollcontact.load_scene(CREEP, {**world, "rolling.distance": longest})
    with pytest.raises(SceneError):
        rollcontact.load_scene(CREEP, {**world, "rolling.distance": longest + 0.25})
    assert not out.exists()


def test_a_limit_search_outside_its_range_is_refused_before_any_probe(tmp_path, capsys):
    """--vary motion.w=1.5 ran 117 s and then failed (`limits` refuses w > 1 at once)."""
    assert main(["limit-search", "--vary", "motion.w=0.23,1.5", "-o", str(tmp_path / "ls")]) == 2
    err = capsys.readouterr().err
    assert "--vary motion.w=1.5: w = W/a = 1.5; a limit search in ft needs 0.006667 < w < 0.9172" in err
    assert not (tmp_path / "ls").exists()
    with pytest.raises(SceneError, match="the limit search searches load.ft"):
        rollcontact.limit_search(default_scene(), {"motion.w": [0.23]}, tmp_path / "ls", overrides={"load.ft": 0.3})


def test_depths_out_of_order_or_repeated_are_refused(tmp_path):
    """--depths 2,1,0.5 and 1,1 were sorted and deduplicated unannounced."""
    for text, message in (("2,1,0.5", "1 follows 2"), ("1,1", "1 follows 1")):
        with pytest.raises(InputError, match=rf"depths '{text}': depths must increase, each given once .*{message}"):
            rollcontact.cases.api.parse_depths(text)
    scene = rollcontact.load_scene(overrides={"grid.dx": 0.6, "motion.dW": 0.6, "motion.periods": 1})
    with pytest.raises(InputError, match=r"depths \[1.0, 0.5\]: depths must increase"):
        rollcontact.run(scene, tmp_path / "r.h5", stresses=True, depths=[1.0, 0.5])
    assert not list(tmp_path.iterdir())


def test_an_empty_profile_file_is_refused_without_a_numpy_warning(tmp_path):
    (tmp_path / "h.csv").write_text("x,y,h\n")
    (tmp_path / "s.toml").write_text('[geometry]\nshape = "file"\npath = "h.csv"\n')
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(SceneError, match=r"path = '.*h.csv': holds no rows of x, y, h"):
            rollcontact.load_scene(tmp_path / "s.toml")


def test_a_sweep_continues_a_run_killed_part_way_from_its_checkpoint(tmp_path):
    """A killed run leaves its file with the finished steps (status 'incomplete', the fields of its last step); a
    rerun of the sweep recomputed it from step 0. Here that checkpoint is the first steps of the run itself."""
    vary = ["motion.periods=3"]
    base = default_scene()
    over = ["grid.dx=0.6", "grid.dy=0.6", "motion.dW=0.6"]
    done = run_sweep(base, vary, tmp_path / "full", overrides=over, jobs=1, progress=None)
    path = tmp_path / "full" / done.rows[0]["file"]
    full = read_run(path)
    k = int(full.field_steps[len(full.field_steps) // 2])               # a stored step in the middle
    keep = [i for i, s in enumerate(full.field_steps) if s <= k]
    cut = rollcontact.RunResult(scene_toml=full.scene_toml, status="incomplete", x=full.x, y=full.y,
                                history={n: v[:k + 1] for n, v in full.history.items()},
                                fields={n: v[keep] for n, v in full.fields.items()},
                                field_steps=full.field_steps[keep], summary={"state": "incomplete"},
                                version=full.version)
    (tmp_path / "killed").mkdir()
    write_run(tmp_path / "killed" / path.name, cut)
    again = run_sweep(base, vary, tmp_path / "killed", overrides=over, jobs=1, progress=None)
    resumed = read_run(tmp_path / "killed" / path.name)
    assert again.ran == 1 and resumed.status == "complete" and resumed.attrs["restart_step"] == k
    assert resumed.attrs["restarted_from"] == str((tmp_path / "killed" / path.name).resolve())
    np.testing.assert_array_equal(resumed.history["U_x"][:k + 1], full.history["U_x"][:k + 1])
    np.testing.assert_allclose(resumed.history["U_x"], full.history["U_x"], rtol=1e-12, atol=1e-15)
    assert resumed.summary["state"] == full.summary["state"] and resumed.scene_toml == full.scene_toml
    assert Path(again.rows[0]["file"]).name == path.name
