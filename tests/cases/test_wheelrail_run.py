"""[wheelrail] runs (cases.run.wheelrail_run; docs/wheelrail.md): two crowns give Hertz's ellipse; at the two-point
position of the Manchester benchmark's profiles both patches are found and balance Fz; the benchmark's cases agree
with the reference program's published output; the run file holds /patches/<k>/ with units; the figures render.
Units: mm, N, MPa, rad."""
import math

import h5py
import numpy as np
import pytest

import rollcontact
from rollcontact.cases.scene.scene import Scene, shipped_scene_path
from rollcontact.cases.scene.wheelrail import search
from rollcontact.solver.analytic import HertzEllipse

from test_units import datasets_without_units

STEEL = "[materials]\nE1 = 210000.0\nnu1 = 0.28\nE2 = 210000.0\nnu2 = 0.28\n"


def crowns(folder, wheel_crown=150.0, rail_crown=300.0):
    """Two-column profile files of a wheel crown (whitespace) and a rail crown (CSV) of the given radii (mm)."""
    y = np.linspace(-40.0, 40.0, 801)
    np.savetxt(folder / "wheel.txt", np.c_[y, wheel_crown - np.sqrt(wheel_crown ** 2 - y ** 2)],
               header="y z (mm)", comments="# ")
    y = np.linspace(-35.0, 35.0, 701)
    np.savetxt(folder / "rail.csv", np.c_[y, -(rail_crown - np.sqrt(rail_crown ** 2 - y ** 2))], delimiter=",",
               header="y,z", comments="")
    return folder / "wheel.txt", folder / "rail.csv"


def crown_scene(folder, **grid):
    wheel, rail = crowns(folder)
    text = STEEL + f"""[load]
mu = 0.3
[wheelrail]
wheel_profile = "{wheel}"
rail_profile = "{rail}"
wheel_radius = 460.0
rail_inclination = 0.0
side = "left"
gauge = 1500.0
gauge_height = 0.0
back_to_back = 1500.0
flange_back = 0.0
Fz = 10000.0
[grid]
""" + "".join(f"{k} = {v}\n" for k, v in grid.items())
    return Scene.from_toml_text(text, name="crowns")


def test_two_crowns_on_a_cylinder_give_hertz_ellipse(tmp_path):
    """Wheel crown 150 mm on rail crown 300 mm (Ry = 100 mm) and rolling radius 460 mm under 10 kN: one patch, the
    semi-axes (from the pressure's second moments, <x^2> = a^2/5), the approach and p0 within 1 % of Hertz
    (measured: 0.05 % at a / dx = 19, b / dy = 14), the vertical balance to the solver's tolerance."""
    scene = crown_scene(tmp_path, dx=0.2, dy=0.1)
    result = rollcontact.run(scene, tmp_path / "crowns.h5")
    s, patch = result.summary, result.patches[0]
    hertz = HertzEllipse(460.0, 100.0, scene.material_pair.E_star, 10000.0)
    assert s["n_patches"] == 1 and result.status == "complete"
    p = patch.fields["p"]
    X, Y = np.meshgrid(patch.x, patch.y)
    a = math.sqrt(5.0 * float((p * X ** 2).sum() / p.sum()))
    b = math.sqrt(5.0 * float((p * Y ** 2).sum() / p.sum()))
    assert a == pytest.approx(hertz.a, rel=0.01)
    assert b == pytest.approx(hertz.b, rel=0.01)
    assert s["lowering"] == pytest.approx(hertz.approach, rel=0.01)
    assert s["patch_penetration"][0] == pytest.approx(hertz.approach, rel=0.01)
    assert s["patch_pmax"][0] == pytest.approx(hertz.p0, rel=0.01)
    assert s["patch_contact_angle"][0] == pytest.approx(0.0, abs=1e-9)
    assert s["F_track_z"] == pytest.approx(10000.0, rel=1e-5)
    assert abs(s["F_track_y"]) < 1e-3 and abs(s["F_track_x"]) < 1e-3     # symmetric, free rolling, no spin
    assert datasets_without_units(result.path) == []
    with h5py.File(result.path, "r") as h5:
        assert h5["patches/0/fields/p"].shape == (1,) + p.shape and h5["patches/0/grid/x"].attrs["units"] == "mm"
        assert h5["patches/0/fields/gap"].attrs["units"] == "mm"
        assert h5["patches/0"].attrs["Fn"] == pytest.approx(s["patch_Fn"][0])
    back = rollcontact.read_run(result.path)
    np.testing.assert_array_equal(back.patches[0].fields["p"], p)
    assert back.summary["n_patches"] == 1 and np.allclose(back.summary["patch_y_rail"], s["patch_y_rail"])


@pytest.fixture(scope="module")
def mbench():
    return rollcontact.load_scene(shipped_scene_path("mbench_s1002_uic60.toml"))


def two_point_position(scene) -> float:
    """The lateral position (mm) where the S1002 wheel's tread and flange root touch the UIC60 rail first together:
    the two minima of the vertical gap are equal (bisection on the geometry)."""
    def difference(y):
        found = search(scene.with_overrides({"wheelrail.y": y}).wheelrail)
        y_r = found.rail.to_profile(found.y, found.rail_z)[0]
        return found.gap[(y_r > -38) & (y_r < -30)].min() - found.gap[(y_r > -28) & (y_r < -15)].min()
    lo, hi = 4.0, 6.0
    for _ in range(25):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if difference(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.fixture(scope="module")
def two_point(mbench):
    return two_point_position(mbench)


@pytest.mark.parametrize("mu", [0.3, 1e-4])
def test_tread_and_flange_root_patches_balance_fz(mbench, two_point, mu):
    """At the two-point position both patches carry load, and their forces balance Fz in the vertical: with mu = 0.3
    sum (Fn cos delta + Fy sin delta) = Fz (the tangential forces lean too); with mu = 1e-4 the normal forces alone,
    sum Fn cos delta = Fz within 0.1 %."""
    y = two_point
    assert 4.9 < y < 5.2
    result = rollcontact.run(mbench.with_overrides({"wheelrail.y": y, "load.mu": mu}))
    s = result.summary
    assert s["n_patches"] == 2
    Fn, Fy, angle = s["patch_Fn"], s["patch_Fy"], s["patch_contact_angle"]
    assert Fn.min() > 0.2 * Fn.sum()                              # both carry a good share
    assert angle[0] < -0.25 and -0.2 < angle[1] < -0.05          # flange root, then tread (right rail: delta < 0)
    vertical = float(np.sum(Fn * np.cos(angle) + Fy * np.sin(angle)))
    assert vertical == pytest.approx(10000.0, rel=1e-5)
    assert s["F_track_z"] == pytest.approx(vertical, rel=1e-9)
    assert s["F_track_y"] == pytest.approx(float(np.sum(Fy * np.cos(angle) - Fn * np.sin(angle))), rel=1e-9)
    if mu < 1e-3:
        assert float(np.sum(Fn * np.cos(angle))) == pytest.approx(10000.0, rel=1e-3)


#: (side, case) of CONTACT's decks mbench_a22_left / _right compared here: tread (left and right), the flange root and
#: the flange (right); docs/wheelrail.md has all 42 (benchmarks/wheelrail_mbench.py)
MBENCH_CASES = [("right", 5), ("right", 10), ("right", 17), ("left", 7), ("left", 15)]


@pytest.fixture(scope="module")
def mbench_reference():
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    import wheelrail_mbench
    rows = {(r["side"], int(r["case"])): r for r in wheelrail_mbench.reference_cases()}
    return wheelrail_mbench, rows


@pytest.mark.parametrize("side, case", MBENCH_CASES)
def test_manchester_benchmark_case_agrees_with_the_reference_program(mbench, mbench_reference, side, case):
    """Case A-2.2 (S1002 on UIC60 1:40, 10 kN, yaw 2.4 mrad per mm of lateral shift) against CONTACT's published output
    on the same 0.2 mm grid (tests/data/wheelrail/mbench_a22_contact.csv). Tolerances: the codes place a patch's
    reference differently (rollcontact: the load centre; CONTACT: a weighted centre of the interpenetration), which
    moves it by up to 0.03 mm on these patches and turns the plane by up to 0.002 rad; the forces then agree within
    0.2 % (Fn) and 0.15 % of mu Fn (Fx, Fy), the peak pressure within 1 % (the flange's narrow patch: 6 cells across)."""
    bench, rows = mbench_reference
    row = rows[(side, case)]
    result = rollcontact.run(bench.scene_of(row, mbench))
    mine, ref = bench.ours(result), bench.to_rollcontact(row)
    assert mine["n_patches"] == ref["n_patches"] == 1
    mu_fn = 0.3 * ref["Fn"]
    assert mine["y_rail"] == pytest.approx(ref["y_rail"], abs=0.05)
    assert mine["y_wheel"] == pytest.approx(ref["y_wheel"], abs=0.05)
    assert mine["contact_angle"] == pytest.approx(ref["contact_angle"], abs=0.003)
    assert mine["Fn"] == pytest.approx(ref["Fn"], rel=0.005)
    assert mine["Fx"] == pytest.approx(ref["Fx"], abs=0.005 * mu_fn)
    assert mine["Fy"] == pytest.approx(ref["Fy"], abs=0.005 * mu_fn)
    assert mine["pmax"] == pytest.approx(ref["pmax"], rel=0.015)
    for name in ("xi", "eta"):     # CONTACT prints 4 digits; the reference point's shift adds phi ds, 2e-5 at the flange
        assert mine[name] == pytest.approx(ref[name], abs=2e-5 + 3e-3 * abs(ref[name]))
    assert mine["phi"] == pytest.approx(ref["phi"], rel=0.01)
    assert mine["z_ws"] == pytest.approx(ref["z_ws"], abs=0.004)
    for name in ("F_track_x", "F_track_y", "F_track_z"):      # Fn's 0.2 % and the plane's 0.002 rad, turned
        assert mine[name] == pytest.approx(ref[name], abs=0.005 * (mu_fn + abs(ref[name])))


def test_a_patch_rolled_from_rest_tends_to_its_steady_state(tmp_path):
    """[rolling] mode = "transient": the crowns' patch rolled from rest over four contact lengths (the default) at
    xi = -0.001 (partial slip) ends within 0.5 % of the steady forces (the transient's memory falls about 5x per
    contact length with step = dx, docs/creep_rolling.md); its history is stored per step, with units."""
    scene = crown_scene(tmp_path, dx=0.4, dy=0.2).with_overrides(
        {"wheelrail.xi": -0.001, "rolling.mode": "transient"})
    result = rollcontact.run(scene, tmp_path / "rolled.h5")
    s, patch = result.summary, result.patches[0]
    assert s["mode"] == "transient" and s["distance"] >= 4 * s["patch_length"][0]
    force = math.hypot(s["patch_Fx_steady"][0], s["patch_Fy_steady"][0])
    assert force > 0.1 * 0.3 * s["patch_Fn"][0]
    assert s["patch_Fx"][0] == pytest.approx(s["patch_Fx_steady"][0], abs=5e-3 * force)
    assert s["F_track_x"] == pytest.approx(s["patch_Fx"][0], rel=1e-12)
    h = patch.history
    assert h["step"][0] == 0 and h["F_x"][0] == pytest.approx(0.0, abs=1e-9)        # at rest: no tangential force
    assert h["F_x"][-1] == pytest.approx(-s["patch_Fx"][0], rel=1e-12)             # on the rail
    assert patch.fields["p"].shape == (patch.y.size, patch.x.size) and patch.x.size > 3 * s["patch_length"][0] / 0.4
    assert datasets_without_units(result.path) == []
    back = rollcontact.read_run(result.path)
    np.testing.assert_array_equal(back.patches[0].history["F_x"], h["F_x"])


def test_the_right_wheel_is_the_mirror_image_of_the_left(mbench):
    """The left wheel at y (towards its field side), yaw psi, roll phi is the mirror image y -> -y of the right wheel at
    y, -psi, -phi: the same normal and longitudinal forces and positions, opposite lateral forces, spin, contact angles
    and moments."""
    common = {"wheelrail.y": 4.0, "wheelrail.omega": 4.34}
    right = rollcontact.run(mbench.with_overrides({**common, "wheelrail.yaw": 0.008, "wheelrail.roll": 2e-4})).summary
    left = rollcontact.run(mbench.with_overrides({**common, "wheelrail.side": "left", "wheelrail.yaw": -0.008,
                                                  "wheelrail.roll": -2e-4})).summary
    for name in ("patch_y_rail", "patch_y_wheel", "patch_x", "patch_Fn", "patch_Fx", "patch_xi", "patch_pmax"):
        np.testing.assert_allclose(left[name], right[name], rtol=1e-9, atol=1e-9, err_msg=name)
    for name in ("patch_contact_angle", "patch_Fy", "patch_Mz", "patch_eta", "patch_phi"):
        np.testing.assert_allclose(left[name], -right[name], rtol=1e-9, atol=1e-9, err_msg=name)
    assert (left["F_track_x"], left["F_track_z"]) == pytest.approx((right["F_track_x"], right["F_track_z"]), rel=1e-9)
    assert left["F_track_y"] == pytest.approx(-right["F_track_y"], rel=1e-9)
    assert abs(right["patch_eta"][0]) > 1e-3                      # the yaw gives a lateral creepage



def test_fast_patch_models_keep_the_exact_normal_problem_and_their_measured_force_error(tmp_path):
    """solver.fidelity = "fastsim" / "fastrip" in a [wheelrail] scene: the contact search and the normal problem stay
    exact (the same Fn), and the longitudinal force of the crowns' patch under pure creepage is within the largest
    error the fast models' map measured for pure xi against the exact theory over a/b = 0.2-5 (docs/creep_fidelity.md:
    FASTSIM 6.4 %, FaStrip 2.0 % of |F|; measured here 1.5-4.4 % and 0.04-1.4 %) from partial slip to near saturation."""
    base = crown_scene(tmp_path, dx=0.2, dy=0.1)
    for xi in (-5e-4, -3e-3):
        exact = rollcontact.run(base.with_overrides({"wheelrail.xi": xi})).summary
        for fidelity, bound in (("fastsim", 0.064), ("fastrip", 0.020)):
            fast = rollcontact.run(base.with_overrides({"wheelrail.xi": xi, "solver.fidelity": fidelity})).summary
            assert fast["patch_Fn"][0] == pytest.approx(exact["patch_Fn"][0], rel=1e-12)
            assert abs(fast["patch_Fx"][0] - exact["patch_Fx"][0]) <= bound * abs(exact["patch_Fx"][0]), fidelity
            assert abs(fast["patch_Fx"][0]) <= 0.3 * fast["patch_Fn"][0] * (1 + 1e-12)      # never above mu Fn
