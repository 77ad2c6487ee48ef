"""HDF5 run files: layout, units, atomic writes (real files in a temporary folder)."""
import os

import h5py
import numpy as np
import pytest

from rollcontact.cases.results.hdf5 import is_complete, read_run, write_run
from rollcontact.cases.results.run_result import RunResult


def sample(status="complete"):
    rng = np.random.default_rng(0)
    return RunResult(scene_toml="[geometry]\nR = 40.0\n", status=status, x=np.arange(4) * 0.2,
                   y=np.arange(3) * 0.2, history={"step": np.arange(5), "approach": rng.random(5)},
                   fields={"p": rng.random((2, 3, 4)), "region": np.ones((2, 3, 4), dtype=np.int8)},
                   field_steps=np.array([0, 4]), summary={"state": "shakedown", "u_sd": 0.5, "x": None})


def test_write_then_read_gives_back_every_array_and_attribute(tmp_path):
    (tmp_path / "sub").mkdir()
    path = write_run(tmp_path / "sub" / "run.h5", sample())
    back = read_run(path)
    ref = sample()
    assert back.status == "complete" and back.scene_toml == ref.scene_toml
    np.testing.assert_array_equal(back.x, ref.x)
    np.testing.assert_array_equal(back.history["approach"], ref.history["approach"])
    np.testing.assert_array_equal(back.fields["p"], ref.fields["p"])
    assert back.fields["region"].dtype == np.int8
    np.testing.assert_array_equal(back.field_steps, [0, 4])
    assert back.summary["state"] == "shakedown" and back.summary["u_sd"] == 0.5
    assert back.summary["x"] is None
    with h5py.File(path) as h5:
        assert h5["history/approach"].attrs["units"] == "mm"
        assert h5["fields/p"].attrs["units"] == "MPa"
        assert h5["fields/p"].shape == (2, 3, 4)  # (snapshots, ny, nx)
        assert "rollcontact_version" in h5.attrs
        assert np.isnan(h5["summary"].attrs["x"])  # numeric on disk: a value that does not apply is NaN


def test_write_is_atomic_and_leaves_no_temporary_file(tmp_path):
    path = tmp_path / "run.h5"
    write_run(path, sample())
    assert os.listdir(tmp_path) == ["run.h5"]


def test_failed_write_keeps_the_previous_file_intact(tmp_path):
    path = tmp_path / "run.h5"
    write_run(path, sample())
    bad = sample()
    bad.fields["p"] = object()  # h5py cannot store this: the write fails midway
    with pytest.raises(TypeError, match="HDF5"):  # h5py's own error for an object array, passed on unchanged
        write_run(path, bad)
    assert is_complete(path) and os.listdir(tmp_path) == ["run.h5"]


def test_is_complete_distinguishes_failed_partial_and_garbage_files(tmp_path):
    write_run(tmp_path / "ok.h5", sample())
    write_run(tmp_path / "failed.h5", sample(status="failed"))
    (tmp_path / "garbage.h5").write_bytes(b"not hdf5")
    assert is_complete(tmp_path / "ok.h5")
    assert not is_complete(tmp_path / "failed.h5")
    assert not is_complete(tmp_path / "garbage.h5")
    assert not is_complete(tmp_path / "missing.h5")


def test_summary_values_that_do_not_apply_are_numeric_on_disk_and_none_when_read(tmp_path):
    """A ratcheting run has no u_sd and no periods_to_shakedown: NaN and -1 on disk (readable as numbers, as in
    a sweep's summary.h5), None when read back; the text 'none' of older files reads as None too."""
    data = sample()
    data.summary.update(state="ratcheting", u_sd=None, periods_to_shakedown=None)
    path = write_run(tmp_path / "run.h5", data)
    with h5py.File(path) as h5:
        attrs = h5["summary"].attrs
        assert np.isnan(float(attrs["u_sd"])) and int(attrs["periods_to_shakedown"]) == -1
    back = read_run(path)
    assert back.summary["u_sd"] is None and back.summary["periods_to_shakedown"] is None
    with h5py.File(path, "a") as h5:
        h5["summary"].attrs["u_sd"] = "none"
    assert read_run(path).summary["u_sd"] is None
