"""Every dataset of every file rollcontact writes carries a `units` attribute (docs/hdf5_schema.md).

Real files on a coarse grid: a BEM run, an MDR run, a sweep's summary.h5 and a limit search's limits.h5.
"""
import h5py
import pytest

from rollcontact.cases.sweep.limit_search import search_limits
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene, shipped_scene_path
from rollcontact.cases.sweep.runner import run_sweep

COARSE = ["grid.dx=0.6", "grid.dy=0.6", "motion.dW=10", "motion.periods=3", "solver.shakedown_tol=1e-3"]


def datasets_without_units(path):
    missing = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and "units" not in obj.attrs:
            missing.append(name)
    with h5py.File(path, "r") as h5:
        h5.visititems(visit)
        n = []
        h5.visititems(lambda name, obj: n.append(name) if isinstance(obj, h5py.Dataset) else None)
    assert n, f"{path}: no datasets at all"
    return missing


@pytest.fixture(scope="module")
def base():
    return Scene.from_toml(shipped_scene_path("paper_parallel.toml"))


@pytest.mark.parametrize("fidelity", ["bem", "mdr"])
def test_every_dataset_of_a_run_file_has_units(base, tmp_path, fidelity):
    scene = base.with_overrides(COARSE + [f'solver.fidelity="{fidelity}"'])
    out = run_scene(scene, tmp_path / "run.h5").path
    assert datasets_without_units(out) == []
    with h5py.File(out, "r") as h5:
        assert h5["history/outer_iterations"].attrs["units"] == "-"


def test_every_dataset_of_a_sweep_summary_and_of_limits_has_units(base, tmp_path):
    report = run_sweep(base, ["load.ft=0.3,0.9"], tmp_path / "sweep", overrides=COARSE, jobs=1, progress=None)
    assert report.failed == 0
    assert datasets_without_units(tmp_path / "sweep" / "summary.h5") == []
    with h5py.File(tmp_path / "sweep" / "summary.h5", "r") as h5:
        assert h5["runs/load.ft"].attrs["units"] == "-" and h5["runs/U_sd"].attrs["units"] == "mm"
        assert h5["runs/wall_time"].attrs["units"] == "s" and h5["runs/angle"].attrs["units"] == "deg"
    search_limits(base, ["motion.w=0.3"], tmp_path / "lim", overrides=COARSE, tol=0.2, jobs=1, progress=None)
    assert datasets_without_units(tmp_path / "lim" / "limits.h5") == []
