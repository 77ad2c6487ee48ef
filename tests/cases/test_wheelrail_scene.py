"""[wheelrail] scenes (cases.scene.wheelrail, cases.scene.wheelrail_profiles): the profile files in their formats,
their checksums, and every refusal up front with the key named; a sweep over wheelrail.y with its figures, and the
figure of one run (docs/wheelrail.md). Units: mm, N, MPa, rad."""
import numpy as np
import pytest

import rollcontact
from rollcontact.bem.errors import SceneError
from rollcontact.cases.plots.sweep_figures import plot_folder
from rollcontact.cases.scene.scene import Scene, shipped_scene_path
from rollcontact.cases.scene.wheelrail_profiles import read_profile
from rollcontact.cases.plots.wheelrail_figures import plot_wheelrail_run
from rollcontact.cases.sweep.runner import run_sweep

from test_wheelrail_run import STEEL, crowns

WHEELRAIL = """[wheelrail]
wheel_profile = "{wheel}"
rail_profile = "{rail}"
wheel_radius = 460.0
rail_inclination = 0.0
side = "right"
gauge = 1500.0
gauge_height = 0.0
back_to_back = 1500.0
flange_back = 0.0
Fz = 10000.0
"""


@pytest.fixture
def files(tmp_path):
    return crowns(tmp_path)


def scene_text(files, extra="", materials=STEEL, wheelrail_extra=""):
    wheel, rail = files
    return materials + "[load]\nmu = 0.3\n" + WHEELRAIL.format(wheel=wheel, rail=rail) + wheelrail_extra + extra


def test_a_wheelrail_scene_fills_in_the_checksums_and_the_grid_and_reads_back(files):
    scene = Scene.from_toml_text(scene_text(files))
    wr = scene.wheelrail
    assert len(wr.wheel_sha256) == 64 and wr.rail_sha256 == read_profile(str(files[1]), "rail_profile")[2]
    assert {"wheelrail.wheel_sha256", "wheelrail.rail_sha256", "grid.dx"} <= scene.derived
    assert scene.shape == "wheelrail" and scene.grid.dx == pytest.approx(min(scene.semi_axes) / 12, rel=0.05)
    text = scene.to_toml()
    assert "[geometry]" not in text and "[motion]" not in text and "Fn" not in text and "margin" not in text
    again = Scene.from_toml_text(text)
    assert again.wheelrail == wr and again.grid == scene.grid
    moved = scene.with_overrides({"wheelrail.y": 1.5})
    assert moved.wheelrail.y == 1.5 and moved.wheelrail.wheel_sha256 == wr.wheel_sha256


def test_a_changed_profile_file_is_refused_when_its_checksum_is_given(files):
    scene = Scene.from_toml_text(scene_text(files))
    text = scene.to_toml()
    with open(files[0], "a") as fh:
        fh.write("# changed\n")
    with pytest.raises(SceneError, match="wheel_sha256 = .* does not match"):
        Scene.from_toml_text(text)


@pytest.mark.parametrize("extra, message", [
    ("[geometry]\nR = 40.0\n", r"\[wheelrail\] and \[geometry\] exclude each other"),
    ("[motion]\nw = 0.2\n", r"\[wheelrail\] and \[motion\] exclude each other"),
    ("[rolling]\nmode = \"steady\"\nphi = 0.001\n", r"\[rolling\] phi with \[wheelrail\]"),
    ("[grid]\nmargin = 1.0\n", r"\[grid\] margin with \[wheelrail\]"),
    ("[solver]\nfidelity = \"mdr\"\n", r"\[solver\] fidelity = 'mdr' with \[wheelrail\]"),
])
def test_sections_a_wheelrail_scene_cannot_have_are_refused(files, extra, message):
    with pytest.raises(SceneError, match=message):
        Scene.from_toml_text(scene_text(files, extra))


def test_loads_other_than_mu_missing_keys_and_materials_are_refused(files):
    with pytest.raises(SceneError, match=r"\[load\] Fn with \[wheelrail\].*\[wheelrail\] Fz"):
        Scene.from_toml_text(scene_text(files).replace("mu = 0.3", "mu = 0.3\nFn = 100.0"))
    with pytest.raises(SceneError, match="needs both materials: give \\[materials\\] E2, nu2"):
        Scene.from_toml_text(scene_text(files, materials="[materials]\nE1 = 210000.0\nnu1 = 0.28\n"))
    with pytest.raises(SceneError, match="needs flange_back, Fz"):
        Scene.from_toml_text(scene_text(files).replace("flange_back = 0.0\n", "").replace("Fz = 10000.0\n", ""))
    with pytest.raises(SceneError, match="give either xi .* or omega"):
        Scene.from_toml_text(scene_text(files, wheelrail_extra="xi = 0.001\nomega = 4.3\nspeed = 2000.0\n"))
    with pytest.raises(SceneError, match="omega = 4.3 rad/s needs the forward speed"):
        Scene.from_toml_text(scene_text(files, wheelrail_extra="omega = 4.3\n"))
    with pytest.raises(SceneError, match=r"\[wheelrail\] side = 'middle': allowed values"):
        Scene.from_toml_text(scene_text(files).replace('"right"', '"middle"'))
    soft = "[materials]\nE1 = 210000.0\nnu1 = 0.28\nE2 = 3000.0\nnu2 = 0.45\n"
    with pytest.raises(SceneError, match="dissimilar materials .* coupling = \"off\""):
        Scene.from_toml_text(scene_text(files, materials=soft))
    Scene.from_toml_text(scene_text(files, materials=soft, extra="[solver]\ncoupling = \"off\"\n"))


def test_profile_files_in_columns_and_in_simpack_format_read_alike(tmp_path):
    y = np.linspace(-40.0, 30.0, 71)
    z = -(y + 5.0) ** 2 / 400.0
    (tmp_path / "r.txt").write_text("# a rail\ny z\n\n" + "\n".join(f"{a}  {b}" for a, b in zip(y[::-1], z[::-1])))
    (tmp_path / "r.csv").write_text("y_mm,z_mm\n" + "\n".join(f"{a},{b}" for a, b in zip(y, z)))
    # SIMPACK: metres, z down, y mirrored, listed the other way round
    points = "\n".join(f"{-a / 1000:.12e} {-b / 1000:.12e}" for a, b in zip(y, z))
    (tmp_path / "r.prr").write_text(
        "  header.begin\n    type = 0 ! rail\n  header.end\n  spline.begin\n    type = 0 ! original file type\n"
        "    mirror.y = 1\n    units.len.f = 1.0\n    point.begin\n" + points + "\n    point.end\n  spline.end\n")
    for name in ("r.txt", "r.csv", "r.prr"):
        yy, zz, digest = read_profile(str(tmp_path / name), "rail_profile")
        np.testing.assert_allclose(yy, y, atol=1e-9)
        np.testing.assert_allclose(zz, z, atol=1e-9)
    with pytest.raises(SceneError, match="a SIMPACK rail profile .type = 0., given for wheel_profile"):
        read_profile(str(tmp_path / "r.prr"), "wheel_profile")


def test_bad_profile_files_are_refused_naming_the_key(tmp_path):
    def refused(text, key, message, name="p.txt"):
        (tmp_path / name).write_text(text)
        with pytest.raises(SceneError, match=message):
            read_profile(str(tmp_path / name), key)
    refused("0 0\n1 0.1\n0.5 0.2\n2 0.3\n3 0.4\n", "rail_profile", r"\[wheelrail\] rail_profile .* y turns back")
    refused("0 0\n1 0\n2 0\n", "rail_profile", "3 points; a profile needs at least 4")
    refused("0 0 0\n1 0 0\n", "rail_profile", "line 1 has 3 values")
    refused("a b\nc d\n", "rail_profile", "line 2 is not two numbers")
    y = np.linspace(-60.0, 70.0, 131)
    flange_on_field_side = np.where(y > 50, -25.0 * (y - 50) / 20, 0.0)
    refused("\n".join(f"{a} {b}" for a, b in zip(y, flange_on_field_side)), "wheel_profile",
            r"the flange .* lies at y = 70 mm > 0")
    refused("header.begin\nheader.end\n", "rail_profile", "not a SIMPACK profile", name="p.prr")
    with pytest.raises(SceneError, match="no such file"):
        read_profile(str(tmp_path / "missing.txt"), "rail_profile")


def test_a_profile_that_does_not_cover_the_contact_is_refused(tmp_path):
    wheel, rail = crowns(tmp_path)
    y, z = np.loadtxt(rail, delimiter=",", skiprows=1).T
    keep = y > 0.5                                  # the crown's contact is at y = 0: cut it off
    np.savetxt(tmp_path / "short.csv", np.c_[y[keep], z[keep]], delimiter=",")
    text = scene_text((wheel, tmp_path / "short.csv"))
    with pytest.raises(SceneError, match="reaches the end of the rail profile"):
        Scene.from_toml_text(text)


def test_a_sweep_over_y_draws_the_contact_point_diagram_and_a_run_its_patches(tmp_path):
    base = rollcontact.load_scene(shipped_scene_path("mbench_s1002_uic60.toml"))
    report = run_sweep(base, ["wheelrail.y=3,5.5"], tmp_path / "sweep", jobs=1, progress=None)
    assert report.failed == 0 and [r["n_patches"] for r in report.rows] == [1, 1]
    assert all(abs(r["F_track_z"] - 10000.0) < 0.1 for r in report.rows)
    lines = []
    paths = plot_folder(tmp_path / "sweep", tmp_path / "plots", out=lines.append)
    names = sorted(p.name for p in paths)
    assert names == ["sweep_contact_points.pdf", "sweep_contact_points.png", "sweep_forces.pdf", "sweep_forces.png"]
    assert "the number of patches changes at y = none" in lines[-1]
    run = rollcontact.read_run(next((tmp_path / "sweep").glob("y=5.5*.h5")))
    paths = plot_wheelrail_run(run, tmp_path / "plots", "y55")
    assert all(p.stat().st_size > 10000 for p in paths)


def test_rolling_takes_only_the_transient_keys_with_wheelrail(files):
    with pytest.raises(SceneError, match=r"\[rolling\] xi with \[wheelrail\]: the creepages follow"):
        Scene.from_toml_text(scene_text(files, "[rolling]\nmode = \"steady\"\nxi = 0.001\n"))
    with pytest.raises(SceneError, match="distance with mode = 'steady': distance applies to mode = 'transient'"):
        Scene.from_toml_text(scene_text(files, "[rolling]\nmode = \"steady\"\ndistance = 10.0\n"))
    scene = Scene.from_toml_text(scene_text(files, "[rolling]\nmode = \"transient\"\ndistance = 10.0\n"))
    again = Scene.from_toml_text(scene.to_toml())
    assert again.rolling.mode == "transient" and again.rolling.distance == 10.0 and again.rolling.phi == 0.0
