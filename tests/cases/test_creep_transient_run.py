"""[rolling] mode = "transient" scenes (cases/run/creep_transient.py): stepped from an initial state on the grid that
moves with the contact (the default) or on the world-fixed grid, run to a real HDF5 file and read back, beside the
steady state of the same scene. The keys step, distance, initial and grid and their errors."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import SceneError
from rollcontact.cases.results.hdf5 import read_run
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene

#: steel (sphere, R = 40 mm) on a stiff polymer (E = 3 GPa, nu = 0.4): Dundurs beta = -0.159, Kalker's K = -0.096;
#: Fn = 1000 N gives Hertz a = 2.0 mm, at the default a/12 24 elements across.
COUPLED = """
[materials]
E1 = 210e3
nu1 = 0.28
E2 = 3000.0
nu2 = 0.4
[load]
Fn = 1000.0
mu = 0.3
[geometry]
R = 40.0
[grid]
margin = 0.1
[rolling]
mode = "transient"
"""


def scene(rolling: str = "", extra: str = "") -> Scene:
    return Scene.from_toml_text(COUPLED + rolling + "\n" + extra)


def test_coupled_materials_roll_to_the_coupled_steady_state_and_every_stored_step_is_admissible(tmp_path):
    """Coupled materials (beta = -0.16) through the nested normal / tangential loop at every step (measured 7 outer
    iterations per step): after 4 contact lengths from rest, at a/8 (16 elements across), Fx and Fy within 0.5 % of
    |F| (the issue's bound) of the coupled steady state of the same scene (the steady run's own alternation,
    cases.run.creep_run): measured -0.04 % and +0.002 % at xi = -3e-3, eta = -5e-4 (partial slip, half the contact
    in stick, |F| = 0.55 mu Fn; the coupling alone gives 0.29 mu Fn at zero creepage). Closer to full stick the
    memory lasts longer: xi = +2e-3 (|F| = 0.08 mu Fn, 86 % stick) is -0.45 % off after 4 lengths. The maximum
    pressure as the steady one's within 1e-3 (measured 1.3e-5). Every stored step (output.fields = 'all') keeps
    |tau| <= mu p (round-off) and its force: the sum of the stored traction is the history's F_x, F_y (1e-9 of
    mu Fn) and M_z (1e-9 of mu Fn a)."""
    result = run_scene(scene("xi = -3e-3\neta = -5e-4",
                             '[solver]\ncoupling = "on"\n[output]\nfields = "all"').with_overrides(["grid.dx=0.25"]),
                       tmp_path / "coupled.h5")
    back = read_run(result.path)
    s, h = back.summary, back.history
    assert back.status == "complete" and h["outer_iterations"][1:].min() >= 2          # the nested loop ran
    scale = math.hypot(s["F_x_steady"], s["F_y_steady"])
    assert abs(s["F_x"] - s["F_x_steady"]) <= 5e-3 * scale and abs(s["F_y"] - s["F_y_steady"]) <= 5e-3 * scale
    assert s["p0"] == pytest.approx(s["p0_steady"], rel=1e-3)
    X, Y = np.meshgrid(back.x, back.y)
    dA = (back.x[1] - back.x[0]) * (back.y[1] - back.y[0])
    assert list(back.field_steps) == list(range(s["steps"]))
    for k in back.field_steps:
        tau_x, tau_y, p = back.field("tau_x", k), back.field("tau_y", k), back.field("p", k)
        assert np.all(np.hypot(tau_x, tau_y) <= 0.3 * p * (1 + 1e-12) + 1e-300)
        assert tau_x.sum() * dA == pytest.approx(h["F_x"][k], abs=1e-9 * s["mu_Fn"])
        assert tau_y.sum() * dA == pytest.approx(h["F_y"][k], abs=1e-9 * s["mu_Fn"])
        centre = 0.0 if s["rolling_grid"] == "contact" else h["W_x"][k]      # x of the grid moving with the contact
        moment = -((X - centre) * tau_y - Y * tau_x).sum() * dA
        assert moment == pytest.approx(h["M_z"][k], abs=1e-9 * s["mu_Fn"] * s["a"])


def test_coupled_transient_on_the_contact_grid_gives_the_world_grid_forces_at_every_step():
    """The coupled scene above (the pressure's memory p' carried with the tractions' through the nested loop) over
    one contact length on both grids: forces, moment and maximum pressure agree at every step to the solvers'
    tolerance (1e-6 of mu Fn, of mu Fn a and of p0; measured 6e-10, 3e-11 and 4e-11); the contact grid is the default
    for the default step dx, covers the contact and a step behind it only, and stores its fields there."""
    base = scene("xi = -3e-3\neta = -5e-4\ndistance = 4.0", '[solver]\ncoupling = "on"\n[output]\nfields = "last"')
    runs = {g: run_scene(base.with_overrides(["grid.dx=0.25", f'rolling.grid="{g}"'])) for g in ("contact", "world")}
    default = run_scene(base.with_overrides(["grid.dx=0.25"]))
    assert default.summary["rolling_grid"] == "contact"
    assert np.array_equal(default.history["F_x"], runs["contact"].history["F_x"])
    c, w = runs["contact"], runs["world"]
    s = w.summary
    assert c.summary["nx"] < w.summary["nx"] and c.summary["ny"] == w.summary["ny"]
    assert c.x[0] - 0.125 <= -s["a"] - 0.25 and c.x[-1] - c.x[0] <= 2 * (1.1 * s["a"] + 0.25) + 0.25   # + a step
    for key, scale in (("F_x", s["mu_Fn"]), ("F_y", s["mu_Fn"]), ("M_z", s["mu_Fn"] * s["a"])):
        assert np.abs(c.history[key] - w.history[key]).max() <= 1e-6 * scale
    assert c.summary["p0"] == pytest.approx(s["p0"], rel=1e-6)
    p_c, p_w = c.field("p", c.field_steps[-1]), w.field("p", w.field_steps[-1])
    cols = np.nonzero(p_w.any(axis=0))[0]                  # the world grid's contact, moved onto the contact grid
    first = int(np.argmin(np.abs(c.x - w.x[cols[0]] + w.history["W_x"][-1])))
    assert np.abs(p_c[:, first:first + cols.size] - p_w[:, cols]).max() <= 1e-6 * s["p0"]


def test_prescribed_forces_from_cattaneos_state_give_the_steady_creepages():
    """Fx, Fy (N, on the sphere) with mode = 'transient' and initial = 'cattaneo': every step carries them, and the
    last step's creepages (its rigid shift per step length) are the steady creepages found for them (within 0.5 %
    of |(xi, eta)|; measured 1.5e-6 relative) with the default step dx (a step of 2 dx converges to creepages 3 % off:
    the upwind difference over two cells, first order in the step); the accumulated rigid shift U is the sum of
    step (xi, eta). Uncoupled steel on steel, a = 0.64 mm."""
    steel = Scene.from_toml_text("[materials]\nE1 = 210e3\nnu1 = 0.28\nE2 = 210e3\nnu2 = 0.28\n[load]\n"
                                 "Fn = 1000.0\nmu = 0.3\n[geometry]\nR = 40.0\n[grid]\nmargin = 0.1\n[rolling]\n"
                                 "mode = \"transient\"\nFx = -30.0\nFy = 10.0\ninitial = \"cattaneo\"\n")
    result = run_scene(steel)
    s, h = result.summary, result.history
    assert result.status == "complete" and s["forces_prescribed"] and s["initial"] == "cattaneo"
    assert np.allclose(h["F_x"], 30.0, rtol=1e-9) and np.allclose(h["F_y"], -10.0, rtol=1e-9)
    assert math.hypot(s["xi"] - s["xi_steady"], s["eta"] - s["eta_steady"]) <= \
        5e-3 * math.hypot(s["xi_steady"], s["eta_steady"])
    assert h["U_x"][-1] == pytest.approx(sum(h["xi"][1:]) * s["step"] + h["xi"][0] * s["step"], rel=1e-9)


@pytest.mark.parametrize("keys, message", [
    ("step = 0.0", r"\[rolling\] step = 0.0 mm: allowed range is \(0, inf\) mm"),
    ("step = -0.1", r"\[rolling\] step = -0.1 mm: allowed range"),
    ("step = 2.5", r"\[rolling\] step = 2.5 mm: allowed range is 0 < step <= 2\.\d+ mm \(the contact's half-length"),
    ("step = \"dx\"", r"\[rolling\] step = 'dx': expected a number in mm"),
    ("initial = \"moving\"", r"\[rolling\] initial = 'moving': allowed values are \['rest', 'cattaneo'\]"),
    ("distance = 0.0", r"\[rolling\] distance = 0.0 mm: allowed range is \(0, inf\) mm"),
    ("step = 1e-6\ndistance = 1e3", r"\[rolling\] distance / step = 1000 / 1e-06 mm: more than 1000000 steps"),
    ("grid = \"moving\"", r"\[rolling\] grid = 'moving': allowed values are \['contact', 'world'\]"),
    ("grid = \"contact\"\nstep = 0.25", r"\[rolling\] grid = 'contact' with step = 0.25 mm = 1.47\d* elements of dx = "
                                        r"0.17 mm: .* set step = k dx, or grid = 'world'"),
])
def test_transient_keys_are_refused_outside_their_range(keys, message):
    with pytest.raises(SceneError, match=message):
        scene("xi = 1e-3\n" + keys)


def test_the_default_grid_moves_with_the_contact_when_the_step_is_whole_elements():
    """[rolling] grid left out: 'contact' for the default step dx and for k dx, 'world' for any other step (the moving
    grid carries the memory by whole cells); none outside a transient."""
    assert scene("xi = 1e-3").transient_grid == "contact" and scene("xi = 1e-3\nstep = 0.34").transient_grid == "contact"
    assert scene("xi = 1e-3\nstep = 0.25").transient_grid == "world"
    assert scene("xi = 1e-3\nstep = 0.25\ngrid = \"world\"").transient_grid == "world"
    assert Scene.from_toml_text(COUPLED.replace('"transient"', '"steady"') + "xi = 1e-3").transient_grid is None


@pytest.mark.parametrize("key", ["step = 0.1", "initial = \"cattaneo\"", "distance = 5.0", "grid = \"world\""])
def test_transient_keys_are_refused_with_mode_steady(key):
    name = key.partition(" ")[0]
    with pytest.raises(SceneError, match=rf"\[rolling\] {name} = .* with mode = 'steady': {name} applies to mode = "
                                         "'transient' only"):
        Scene.from_toml_text(COUPLED.replace('"transient"', '"steady"') + "xi = 1e-3\n" + key)


def test_transient_rolling_direction_turns_the_profile():
    """Rolling along y (direction 90 deg) over Rx = 40, Ry = 80 is rolling along x over Rx = 80, Ry = 40: the world
    grid is laid along the rolling direction, so every step has the same forces and moment in the rolling frame (to
    the solver tolerance, 1e-6 of |F|); one contact length from rest with creepage and spin."""
    def run(geometry, direction):
        text = (f"[materials]\nE1 = 210e3\nnu1 = 0.28\nE2 = 210e3\nnu2 = 0.28\n[load]\nFn = 1000.0\nmu = 0.3\n"
                f"[geometry]\n{geometry}\n[grid]\nmargin = 0.1\ndx = 0.09\n[rolling]\nmode = \"transient\"\n"
                f"xi = 3e-4\neta = 1e-4\nphi = 1e-3\ndirection = {direction}\ndistance = 1.2\n[output]\n"
                "fields = \"none\"\n")
        return run_scene(Scene.from_toml_text(text)).history
    turned, plain = run("Rx = 40.0\nRy = 80.0", 90.0), run("Rx = 80.0\nRy = 40.0", 0.0)
    scale = np.hypot(plain["F_x"][-1], plain["F_y"][-1])
    for key in ("F_x", "F_y"):
        assert np.abs(turned[key] - plain[key]).max() <= 1e-6 * scale
    assert np.abs(turned["M_z"] - plain["M_z"]).max() <= 1e-6 * abs(plain["M_z"][-1])
