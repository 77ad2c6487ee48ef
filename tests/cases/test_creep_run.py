"""Scenes with a [rolling] section (cases/run/creep_run.py): steady rolling with creepage and spin, run to a real
HDF5 file and read back. Kalker's convention in the summary (forces on the rolling sphere, opposing the creepages),
the run-file meaning (the sphere's traction on the substrate) in /fields and /history. Steel on steel, a sphere
R = 40 mm under Fn = 1000 N (Hertz a = 0.64 mm), the scene's default resolution (a / 12)."""
import math

import h5py
import numpy as np
import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene, default_scene

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


def rolling_scene(rolling: str, geometry: str = "R = 40.0") -> Scene:
    return Scene.from_toml_text(f"{STEEL}\n[geometry]\n{geometry}\n[rolling]\nmode = \"steady\"\n{rolling}\n")


@pytest.fixture(scope="module")
def linear_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("creep") / "linear.h5"
    run_scene(rolling_scene("xi = 1e-5"), out)
    return read_run(out)


def test_small_creepage_gives_kalkers_linear_force_on_the_rolling_sphere(linear_run):
    """xi = 1e-5 (|F| = 0.5 % of mu Fn: the linear range; Vermeulen-Johnson's correction 0.2 %): F_x = -G c^2 C11 xi
    with Hertz's c, within 5 % at the default a/12: measured +3.8 %, of which the discrete contact area (NormCG's
    cells with p > 0) is +2.9 % above Hertz's (a/24: +1.3 % and +1.0 %; a/40: +0.5 % and +0.5 %). F_y = 0 by
    symmetry; the summary's F_x is opposite to history's (the force on the substrate)."""
    s, h = linear_run.summary, linear_run.history
    assert linear_run.status == "complete" and s["state"] == "steady"
    assert s["F_x"] < 0
    assert s["F_x"] == pytest.approx(s["F_x_linear"], rel=0.05)
    assert abs(s["F_y"]) < 1e-6 * abs(s["F_x"])
    assert h["F_x"][0] == pytest.approx(-s["F_x"], rel=1e-12)
    tau_x = linear_run.field("tau_x", 0)
    dA = (linear_run.x[1] - linear_run.x[0]) * (linear_run.y[1] - linear_run.y[0])
    assert tau_x.sum() * dA == pytest.approx(h["F_x"][0], rel=1e-12)


def test_run_file_holds_fields_with_units_and_the_stick_zone_at_the_leading_edge(linear_run):
    region = linear_run.field("region", 0)
    with h5py.File(linear_run.path, "r") as h5:
        for name in ("p", "tau_x", "tau_y", "slip_x", "slip_y", "u_x", "u_y", "u_z", "region"):
            assert h5[f"fields/{name}"].shape == (1,) + region.shape and "units" in h5[f"fields/{name}"].attrs
    middle = region[region.shape[0] // 2]
    cells = np.nonzero(middle)[0]
    assert middle[cells[-1]] == 1                       # the leading edge (largest x) sticks


def test_large_creepage_saturates_at_mu_fn():
    """Full sliding: |F| = mu Fn up to the elastic part of the slip direction (1e-4, solver/creep tests)."""
    result = run_scene(rolling_scene("xi = 0.05"))
    s = result.summary
    assert s["stick_fraction"] == 0.0
    assert -s["F_x"] == pytest.approx(s["mu_Fn"], rel=1e-4)


def test_rolling_direction_turns_the_profile():
    """Rolling along y (direction 90 deg) over Rx = 40, Ry = 80 is rolling along x over Rx = 80, Ry = 40: the
    same forces in the rolling frame (to the solver tolerance)."""
    turned = run_scene(rolling_scene("xi = 2e-4\neta = 1e-4\nphi = 1e-3\ndirection = 90.0",
                                     "Rx = 40.0\nRy = 80.0")).summary
    plain = run_scene(rolling_scene("xi = 2e-4\neta = 1e-4\nphi = 1e-3",
                                    "Rx = 80.0\nRy = 40.0\n[grid]\ndx = " + repr(
                                        rolling_scene("", "Rx = 40.0\nRy = 80.0").grid.dx))).summary
    for key in ("F_x", "F_y", "M_z"):
        assert turned[key] == pytest.approx(plain[key], rel=1e-5)


def test_rolling_scene_refuses_motion_a_tangential_load_and_mdr():
    with pytest.raises(SceneError, match=r"\[rolling\] and \[motion\] exclude each other"):
        Scene.from_toml_text(STEEL + "[geometry]\nR = 40.0\n[motion]\nw = 0.5\n[rolling]\nmode = \"steady\"\n")
    with pytest.raises(SceneError, match=r"\[load\] ft = 0.5 with \[rolling\]"):
        Scene.from_toml_text("[geometry]\nR = 40.0\n[load]\nft = 0.5\n[rolling]\nmode = \"steady\"\n")
    with pytest.raises(SceneError, match="fidelity"):
        Scene.from_toml_text("[geometry]\nR = 40.0\n[solver]\nfidelity = \"mdr\"\n[rolling]\nmode = \"steady\"\n")
    with pytest.raises(SceneError, match=r"\[rolling\] xi = 2.0"):
        rolling_scene("xi = 2.0")
    with pytest.raises(SceneError, match="mode"):
        Scene.from_toml_text("[geometry]\nR = 40.0\n[rolling]\nxi = 0.001\n")
    with pytest.raises(SceneError, match="distance applies to mode = 'transient' only"):
        rolling_scene("distance = 5.0")


@pytest.mark.parametrize("geometry", ['shape = "cone"\nslope = 3.0', 'shape = "flat_rounded"\nb = 0.5\nR = 40.0'])
def test_other_shapes_roll_to_kalkers_linear_force_and_saturate_at_mu_fn(geometry):
    """Any profile rolls: the cone (log-singular pressure at the centre) and the rounded flat punch (steep pressure at
    its edge). In full adhesion the traction does not depend on the pressure, so Kalker's linear theory holds for any
    circular contact: F_x = -G a^2 C11(a/b = 1) xi with the shape's exact (MDR) contact radius a. Within 2 % once the
    discrete contact area (cells with p > 0: +2.9 % and +2.4 % above pi a^2 at a/12) is divided out: measured
    +0.9 % and +1.2 %, the sphere's +0.9 % on the same grid (about 24 elements across; Kalker's table at n = 21:
    within 1.2 % area-corrected, docs/creep_rolling.md). At a creepage far beyond saturation the whole contact slides
    and |F| = mu Fn (1e-4: the elastic part of the slip direction, as for the sphere)."""
    small = run_scene(rolling_scene("xi = 1e-5", geometry=geometry))
    s = small.summary
    area = small.history["contact_area"][0] / (math.pi * s["a"] * s["b"])
    assert s["F_x"] / area == pytest.approx(s["F_x_linear"], rel=0.02)
    sliding = run_scene(rolling_scene("xi = 0.5", geometry=geometry)).summary
    assert sliding["stick_fraction"] == 0.0
    assert -sliding["F_x"] == pytest.approx(sliding["mu_Fn"], rel=1e-4)


def test_scenes_without_rolling_keep_their_toml():
    """No [rolling] section in the TOML of a scene without it (run files of existing scenes stay identical), and a
    rolling scene's TOML round-trips without [motion]."""
    text = default_scene().to_toml()
    assert "[rolling]" not in text and "[motion]" in text
    scene = rolling_scene("xi = 1e-3\nphi = 0.01")
    again = Scene.from_toml_text(scene.to_toml())
    assert "[motion]" not in scene.to_toml() and again.rolling == scene.rolling


COUPLED = """
[geometry]
R = 40.0
[load]
Fn = 10.0
mu = 0.3
[rolling]
mode = "steady"
xi = {xi}
[materials]
E1 = {E1}
nu1 = {nu1}
E2 = {E2}
nu2 = {nu2}
"""


def test_coupled_materials_converge_and_swapping_the_bodies_mirrors_the_forces():
    """Steel on a compressible soft body (Dundurs beta = -0.44): the normal and steady tangential problems are
    alternated until the pressure settles (outer iterations > 1). Swapping the bodies turns beta, the creepage
    and the force on body 1 around: F_x(swapped, -xi) = -F_x(xi), to the solver tolerances (a consistency check
    of the coupling terms' signs; no closed form of coupled steady rolling is tested here)."""
    one = run_scene(Scene.from_toml_text(COUPLED.format(xi=0.002, E1=210e3, nu1=0.28, E2=2e3, nu2=0.1)))
    two = run_scene(Scene.from_toml_text(COUPLED.format(xi=-0.002, E1=2e3, nu1=0.1, E2=210e3, nu2=0.28)))
    assert one.status == two.status == "complete"
    assert one.history["outer_iterations"][0] > 1
    assert two.summary["F_x"] == pytest.approx(-one.summary["F_x"], rel=1e-5)


def test_plot_of_a_rolling_run_draws_its_traction_and_stick_maps(linear_run, tmp_path, capsys):
    from rollcontact.cases.cli.main import main
    assert main(["plot", str(linear_run.path), "-o", str(tmp_path)]) == 0
    png = (tmp_path / f"{linear_run.path.stem}_maps.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20000


def test_transient_scene_rolls_on_the_world_grid_towards_the_steady_state(tmp_path):
    """mode = 'transient' over 8 a (the default distance: 4 contact lengths) in steps of dx (the default step) on a
    world-fixed grid just long enough: one history row per step plus the initial state (step 0, at rest, zero force),
    the contact centre's travel in W_x, the force on the substrate rising towards the steady value, and the end
    within 0.5 % of the steady state computed beside it (the issue's bound; measured -0.26 % for F_x, -0.06 % for F_y,
    the deficit decaying by about 6x per contact length); the default output stores the initial state, each contact
    length and the last step on the world grid."""
    scene = rolling_scene('xi = 2e-4\neta = 1e-4\n[grid]\nmargin = 0.1').with_overrides(['rolling.mode="transient"',
                                                                                       'rolling.grid="world"'])
    result = run_scene(scene, tmp_path / "transient.h5")
    back = read_run(result.path)
    s, h = back.summary, back.history
    assert back.status == "complete" and s["state"] == "transient" and s["initial"] == "rest"
    n = math.ceil(8 * s["a"] / scene.grid.dx - 1e-9)
    assert len(h["step"]) == s["steps"] == n + 1 and s["step"] == scene.grid.dx
    assert h["W_x"][0] == 0.0 and h["F_x"][0] == 0.0 and np.all(np.diff(h["W_x"]) > 0)
    assert h["W_x"][-1] == pytest.approx(s["distance"]) and s["distance"] == pytest.approx(n * scene.grid.dx)
    margin = max(scene.grid.margin, scene.grid.dx)
    assert back.x[0] - scene.grid.dx / 2 <= -s["a"] - margin + 1e-12 and back.x[-1] + scene.grid.dx / 2 >= \
        s["distance"] + s["a"] + margin - 1e-12
    assert back.x[-1] - back.x[0] < s["distance"] + 2 * (s["a"] + margin) + scene.grid.dx   # no longer than needed
    assert f"{back.x.size} x {back.y.size}" in s["grid_extent"] and s["rolling_grid"] == "world"
    assert np.all(np.diff(h["F_x"]) > -1e-9 * h["F_x"][-1])
    assert s["F_x"] == pytest.approx(s["F_x_steady"], rel=5e-3)
    assert s["F_y"] == pytest.approx(s["F_y_steady"], rel=5e-3)
    assert h["F_x"][-1] == pytest.approx(-s["F_x"], rel=1e-12) and h["M_z"][-1] == s["M_z"]
    per_length = math.ceil(2 * s["a"] / scene.grid.dx - 1e-9)
    assert list(back.field_steps) == sorted(set(range(0, n + 1, per_length)) | {n})
    assert back.fields["tau_x"].shape == (len(back.field_steps), back.y.size, back.x.size)


def test_prescribed_forces_give_back_the_creepages_of_a_creepage_run():
    """[rolling] Fx, Fy (N, on the sphere) in place of xi, eta: the run finds the creepages of the run whose forces
    they are (to the force tolerance 1e-6 mu Fn; measured 1.4e-6, 5.9e-6 relative for xi, eta and 2.7e-7 mu Fn),
    and reports them; xi with Fx, or Fx alone, is refused."""
    forward = run_scene(rolling_scene("xi = 2e-4\neta = -1e-4\nphi = 1e-3")).summary
    inverse = run_scene(rolling_scene(f"Fx = {forward['F_x']!r}\nFy = {forward['F_y']!r}\nphi = 1e-3")).summary
    assert inverse["forces_prescribed"] and not forward["forces_prescribed"]
    assert inverse["xi"] == pytest.approx(2e-4, rel=1e-4) and inverse["eta"] == pytest.approx(-1e-4, rel=1e-4)
    assert math.hypot(inverse["F_x"] - forward["F_x"], inverse["F_y"] - forward["F_y"]) <= 1e-6 * forward["mu_Fn"]
    with pytest.raises(SceneError, match="either xi"):
        rolling_scene("xi = 1e-4\nFx = -10.0\nFy = 0.0")
    with pytest.raises(SceneError, match="together"):
        rolling_scene("Fx = -10.0")


def test_a_sweep_over_a_creepage_tabulates_the_creep_forces(tmp_path):
    """`rollcontact sweep --vary rolling.xi=...` on a [rolling] scene: summary.csv gets the creep columns (xi, eta,
    phi, F_x, F_y, M_z, stick_fraction; units in summary.h5), with the forces of the run files."""
    from rollcontact.cases.cli.main import main
    from rollcontact.cases.sweep.table import read_summary
    scene = tmp_path / "roll.toml"
    scene.write_text(rolling_scene("eta = 1e-4").to_toml())
    assert main(["sweep", str(scene), "--vary", "rolling.xi=1e-4,3e-4", "-o", str(tmp_path / "sw"),
                 "--jobs", "1"]) == 0
    rows = read_summary(tmp_path / "sw" / "summary.csv")
    assert [r["xi"] for r in rows] == [1e-4, 3e-4]
    for r in rows:
        assert r["F_x"] == read_run(tmp_path / "sw" / r["file"]).summary["F_x"] < 0
    with h5py.File(tmp_path / "sw" / "summary.h5") as h5:
        assert h5["runs/F_x"].attrs["units"] == "N" and h5["runs/phi"].attrs["units"] == "1/mm"
