"""Subsurface stresses of real run files: `rollcontact stresses RUN.h5`, `run --stresses`, the /subsurface layout and
the Hertz closed form on the axis (docs/theory.md §11.6)."""
from __future__ import annotations

import h5py
import numpy as np
import pytest

from rollcontact.cases.cli.main import main as cli
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.results.lock import OutputLock
from rollcontact.cases.results.run_result import SUBSURFACE_UNITS
from rollcontact.cases.results.subsurface import read_subsurface
from rollcontact.cases.run.stresses import default_depths
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene

#: frictionless Hertz contact, nu = 0.3 (identical bodies: uncoupled, so tau = 0), default grid a/dx = 12
HERTZ = """
[materials]
E1 = 210.0
nu1 = 0.3
E2 = 210.0
nu2 = 0.3
[geometry]
R = 40.0
[load]
Fn = 21.19
"""


@pytest.fixture(scope="module")
def hertz_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("subsurface") / "hertz.h5"
    run_scene(Scene.from_toml_text(HERTZ, name="hertz"), path)
    return path


def test_stresses_command_writes_the_layout_and_keeps_the_run(hertz_run, capsys):
    before = read_run(hertz_run)
    assert cli(["stresses", str(hertz_run), "-q"]) == 0
    assert "written to" in capsys.readouterr().out
    after = read_run(hertz_run)
    for name, values in before.fields.items():
        np.testing.assert_array_equal(after.fields[name], values)
    for name, values in before.history.items():
        np.testing.assert_array_equal(after.history[name], values)
    assert after.summary == before.summary and after.status == before.status
    assert not [p for p in hertz_run.parent.iterdir() if p.name.endswith(".tmp") or p.name.endswith(".lock")]
    with h5py.File(hertz_run) as h5:
        g = h5["subsurface"]
        a = h5["summary"].attrs["a"]
        ny, nx = h5["fields/p"].shape[1:]
        np.testing.assert_allclose(g["z"][()], default_depths(a))
        assert g["z"].attrs["units"] == "mm" and list(g["step"][()]) == [int(h5["fields/step"][-1])]
        for name, unit in SUBSURFACE_UNITS.items():
            assert g[name].shape == (1, 30, ny, nx) and g[name].attrs["units"] == unit
        assert g.attrs["nu"] == 0.3


def test_hertz_axis_from_a_run_file_matches_the_closed_form(hertz_run):
    """The solver's pressure on the default grid (a/dx = 12): on the axis sigma_z, sigma_r within 1 % of p0 of the
    closed form (measured 0.034 %) (docs/theory.md §11.6, with the run's a and p0), max shear 0.31 p0 at 0.48 a within
    one default depth
    step (0.065 a there) and von Mises 0.62 p0 at the same depth."""
    depths = ",".join(f"{z:.6f}" for z in np.linspace(0, 3.5, 71))
    assert cli(["stresses", str(hertz_run), "-q", "--depths", depths]) == 0
    s = read_subsurface(hertz_run)
    with h5py.File(hertz_run) as h5:
        a, p0 = h5["summary"].attrs["a"], h5["summary"].attrs["p0"]
    j, i = int(np.argmin(np.abs(s["y"]))), int(np.argmin(np.abs(s["x"])))
    zeta = s["z"] / a
    with np.errstate(divide="ignore"):
        s_r = -p0 * ((1.3) * (1 - np.where(zeta > 0, zeta * np.arctan(1 / zeta), 0.0)) - 0.5 / (1 + zeta**2))
    s_z = -p0 / (1 + zeta**2)
    for name, want in (("s_xx", s_r), ("s_yy", s_r), ("s_zz", s_z)):
        assert np.abs(s[name][0, :, j, i] - want).max() <= 0.01 * p0, name
    tresca = s["tresca"][0, :, j, i]
    k = int(np.argmax(tresca))
    assert tresca[k] == pytest.approx(0.31 * p0, abs=0.005 * p0)
    assert abs(s["z"][k] - 0.48 * a) <= 0.065 * a
    assert s["von_mises"][0, :, j, i].max() == pytest.approx(0.62 * p0, abs=0.01 * p0)
    assert int(np.argmax(s["von_mises"][0, :, j, i])) == k


def test_run_option_adds_the_stresses_of_every_stored_step(tmp_path, capsys):
    out = tmp_path / "roll.h5"
    scene = tmp_path / "roll.toml"
    scene.write_text(HERTZ + "ft = 0.4\nmu = 0.5\nramp_steps = 2\n[grid]\ndx = 0.3\n[output]\nfields = \"all\"\n")
    assert cli(["run", str(scene), "-o", str(out), "-q", "--stresses", "--depths", "0,0.5,1"]) == 0
    s = read_subsurface(out)
    with h5py.File(out) as h5:
        stored = h5["fields/step"][()]
        tau_x = h5["fields/tau_x"][()]
    np.testing.assert_array_equal(s["step"], stored)
    assert len(stored) == 3
    assert s["von_mises"].shape == (len(stored), 3, len(s["y"]), len(s["x"]))
    np.testing.assert_allclose(s["s_xz"][:, 0], -tau_x, atol=1e-12)       # the surface carries the applied traction
    assert "subsurface stresses of step(s)" in capsys.readouterr().out


def test_bad_requests_are_refused_before_any_work(hertz_run, tmp_path, capsys):
    assert cli(["stresses", str(hertz_run), "--step", "7"]) == 2
    assert "--step 7: not a stored step" in capsys.readouterr().err
    assert cli(["stresses", str(hertz_run), "--depths", "0,x"]) == 2
    assert cli(["stresses", str(tmp_path / "missing.h5")]) == 2
    (tmp_path / "text.h5").write_text("not hdf5")
    assert cli(["stresses", str(tmp_path / "text.h5")]) == 2
    assert cli(["stresses", str(tmp_path)]) == 2
    assert "is a folder" in capsys.readouterr().err
    assert cli(["stresses", str(hertz_run), "--all-steps", "--step", "0"]) == 2
    with OutputLock(hertz_run):
        assert cli(["stresses", str(hertz_run)]) == 2
    assert "is being written by" in capsys.readouterr().err


def test_plot_draws_the_sections_and_the_maxima_of_a_run_with_stresses(hertz_run, tmp_path):
    """The figures `rollcontact plot RUN.h5` adds when the file holds /subsurface (plot_run calls plot_subsurface; the
    whole plot command is not redrawn here, its other figures take 10 s): the x-z / y-z sections with the maxima
    marked and the maxima against the step, as PNG and PDF; the marked maximum is 0.31 p0 below the centre."""
    import matplotlib.image as mpimg
    from rollcontact.cases.plots.common import DPI, open_run
    from rollcontact.cases.plots.subsurface_figures import plot_subsurface
    assert cli(["stresses", str(hertz_run), "-q"]) == 0
    out = tmp_path / "plots"
    notes = []
    paths = plot_subsurface(open_run(hertz_run), out, step=5, notes=notes)
    assert len(paths) == 4 and "no subsurface stresses at step 5" in notes[0]
    stem = hertz_run.stem
    for name, size in ((f"{stem}_subsurface_step0", (13, 8.5)), (f"{stem}_subsurface_maxima", (9, 7))):
        png = mpimg.imread(out / f"{name}.png")
        assert png.shape[:2] == (round(size[1] * DPI), round(size[0] * DPI))
        assert (out / f"{name}.pdf").stat().st_size > 1000
    from rollcontact.cases.results.subsurface import block_maxima
    m = block_maxima(hertz_run)
    with h5py.File(hertz_run) as h5:
        p0, a = h5["summary"].attrs["p0"], h5["summary"].attrs["a"]
    assert m["tresca"]["value"][0] == pytest.approx(0.31 * p0, abs=0.005 * p0)
    assert abs(m["tresca"]["z"][0] - 0.48 * a) <= 0.065 * a and abs(m["tresca"]["x"][0]) < 1e-9
