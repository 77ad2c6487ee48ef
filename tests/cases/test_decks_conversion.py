"""Converting CONTACT decks into scenes (cases.decks): the mapping of each supported kind (the test decks of
tests/data/contact_decks, written for these tests), the refusal of what rollcontact cannot pose (named with value,
line and what it would need), the files, report and command. Physics: Hertz's ellipse (the curvatures against the
semi-axes, Johnson 1985 §4.2, and the circle's closed form) and the converted Hertzian case run on its grid against
Hertz's approach and contact area."""
import json
import math
from pathlib import Path

import pytest

import rollcontact
from rollcontact.bem.errors import OutputExistsError
from rollcontact.cases.cli.main import main
from rollcontact.cases.decks import hertz

DECKS = Path(__file__).resolve().parents[1] / "data" / "contact_decks"
EXAMPLES = DECKS.parent / "contact_examples"


def _imported(name, out=None):
    return rollcontact.import_contact(DECKS / f"{name}.inp", out)


# --- Hertz ---------------------------------------------------------------------------------------------------------
def test_hertz_circle_has_the_closed_form_curvature_and_the_ellipse_round_trips():
    E_star, Fn = 1.0e5, 1000.0
    a = 0.8
    A, B = hertz.curvatures(a, a, Fn, E_star)
    assert A == B == pytest.approx(3 * Fn / (8 * a ** 3 * E_star), rel=1e-14)   # a^3 = 3 Fn R / (4 E*), A = 1/(2R)
    for ratio in (1.0001, 1.5, 3.0, 10.0):
        A, B = hertz.curvatures(2.0 * ratio, 2.0, Fn, E_star)
        assert hertz.semi_axes(A, B, Fn, E_star) == pytest.approx((2.0 * ratio, 2.0), rel=1e-10)
        assert hertz.b_curvature(A, ratio) == pytest.approx(B, rel=1e-10)
        assert hertz.semi_axes(B, A, Fn, E_star) == pytest.approx((2.0, 2.0 * ratio), rel=1e-10)   # axes swapped
    # near the circle the ellipse's curvatures tend to the circle's (continuity of (K - E)/e^2 -> pi/4)
    A, B = hertz.curvatures(a * (1 + 1e-6), a, Fn, E_star)
    assert A == pytest.approx(3 * Fn / (8 * a ** 3 * E_star), rel=1e-5)


def test_converted_hertzian_case_has_hertz_approach_and_area_on_its_grid():
    """Case 1 of hertz_shift.inp: A1 = 0.01, B1 = 0.02 1/mm, FN = 1000 N, G = 80000, nu = 0.3. Hertz: a, b from the
    curvatures, approach 3 Fn K(e) / (2 pi a E*) (Johnson eq. 3.58 with L = pi p0 b K). The BEM on the deck's grid
    (23 x 21 elements over the scaled ellipse, ~8.8 elements per semi-axis): approach within 0.5 %, area within 4 %
    (the area is a count of whole elements)."""
    from scipy.special import ellipk
    result = _imported("hertz_shift")
    scene = rollcontact.load_scene(None).__class__.from_toml_text(result.scene_text(result.problems[0]), name="h")
    run = rollcontact.run(scene)
    E_star = 2 * 80000.0 / (2 * (1 - 0.3))
    a, b = hertz.semi_axes(0.01, 0.02, 1000.0, E_star)
    approach = 3 * 1000.0 * ellipk(1 - (b / a) ** 2) / (2 * math.pi * a * E_star)
    assert run.history["approach"][0] == pytest.approx(approach, rel=5e-3)
    assert run.history["contact_area"][0] == pytest.approx(math.pi * a * b, rel=4e-2)


# --- the supported kinds ---------------------------------------------------------------------------------------------
def test_normal_then_shift_map_materials_geometry_grid_and_the_load_opposite_to_fx():
    one, two = _imported("hertz_shift").problems
    s1, s2 = one.draft.sections, two.draft.sections
    assert s1["materials"] == {"E1": 2 * 80000 * 1.3, "nu1": 0.3, "E2": 2 * 80000 * 1.3, "nu2": 0.3}
    assert s1["geometry"] == {"Rx": 50.0, "Ry": 25.0} and s1["load"]["Fn"] == 1000.0 and s1["load"]["mu"] == 0.25
    a, b = hertz.semi_axes(0.01, 0.02, 1000.0, 80000 / 0.7)
    assert s1["grid"]["dx"] == pytest.approx(2 * a * 1.3 / 23) and s1["grid"]["dy"] == pytest.approx(2 * b * 1.3 / 21)
    assert two.kind == "shift" and two.steps == {2: 1}       # step 0: the compression, step 1: case 2
    assert s2["load"]["ft"] == 0.6 and s2["load"]["load_angle"] == 0.0   # FX = -0.6 on body 1: the load along +x


def test_steady_rolling_turns_creepages_to_the_contact_centre_and_the_rolling_direction():
    """CHI = 180 d, spin about (SPINXO, SPINYO) = (0.2, 0.1) on a contact centred at x0 = 0.5: xi = CKSI - CPHI
    (y0 - SPINYO), eta = CETA + CPHI (x0 - SPINXO) about the centre, then turned by 180 degrees (a comparison of the
    converted deck with the reference program's own output of it agreed to 0.3 % of FX, FY)."""
    one, two = _imported("steady_spin").problems
    ro = one.draft.sections["rolling"]
    cksi, ceta, cphi = 2.0e-4, -1.0e-4, 1.0e-4
    assert ro["direction"] == 180.0 and ro["speed"] == 20000.0
    assert ro["xi"] == pytest.approx(-(cksi - cphi * (0 - 0.1))) and ro["phi"] == cphi
    assert ro["eta"] == pytest.approx(-(ceta + cphi * (0.5 - 0.2)))
    assert one.draft.sections["geometry"] == {"R": 125.0} and one.frame["x0"] == 0.5 and one.frame["h_min"] == 0.0
    forces = two.draft.sections["rolling"]
    assert forces["Fx"] == pytest.approx(0.2 * 0.3 * 5000) and forces["Fy"] == pytest.approx(-0.1 * 0.3 * 5000)


def test_a_shift_history_is_one_run_with_ft_and_levels_one_step_per_case():
    (p,) = _imported("shift_history").problems
    load = p.draft.sections["load"]
    assert p.kind == "shift" and p.numbers == [1, 2, 3, 4, 5] and p.steps == {1: 0, 2: 1, 3: 2, 4: 3, 5: 4}
    assert load["ft"] == 0.3 and load["levels"] == [0.6, 0.2, -0.4] and load["ramp_steps"] == 1


def test_a_cattaneo_shift_then_rolling_is_one_transient_run():
    (p,) = _imported("transient").problems
    ro = p.draft.sections["rolling"]
    assert p.kind == "transient" and p.steps == {1: 0, 2: 1, 3: 2, 4: 3, 5: 4}
    assert ro["initial"] == "cattaneo" and ro["step"] == 0.2 and ro["distance"] == pytest.approx(0.8)
    assert ro["Fx"] == pytest.approx(-0.5 * 0.3 * 100) and ro["Fy"] == 0.0       # F = 1 with CETA = 0: FY = 0
    assert any("FY = 0" in n for n in p.draft.notes)


def test_an_undeformed_distance_given_per_element_runs_as_the_same_ellipsoid(tmp_path):
    """sampled.inp: h = x^2/100 + y^2/50 as the quadric (case 1) and given per element (IBASE = 9, case 2, a sampled
    `file` profile): the same steady rolling problem on the same grid, so the same forces, approach and area (the
    profile's cubic interpolation reproduces a quadratic; a wrong element order would swap Rx and Ry)."""
    import numpy as np
    result = _imported("sampled", tmp_path)
    quadric, sampled = result.problems
    assert sampled.draft.sections["geometry"] == {"shape": "file", "path": "sampled_case2_profile.npz"}
    with np.load(tmp_path / "sampled_case2_profile.npz") as f:
        x, y, h = f["x"], f["y"], f["h"]
    X, Y = np.meshgrid(x, y)
    inside = (np.abs(X) < 2.5) & (np.abs(Y) < 1.9)
    assert np.allclose(h[inside], (X ** 2 / 100 + Y ** 2 / 50)[inside], rtol=0, atol=1e-9)
    runs = [rollcontact.run(rollcontact.load_scene(tmp_path / f"{p.name}.toml")) for p in (quadric, sampled)]
    for key in ("F_x", "F_y"):
        assert runs[1].summary[key] == pytest.approx(runs[0].summary[key], rel=1e-5)
    for key in ("approach", "contact_area"):
        assert runs[1].history[key][0] == pytest.approx(runs[0].history[key][0], rel=1e-5)


# --- refusals ---------------------------------------------------------------------------------------------------------
BASE = (DECKS / "steady_spin.inp").read_text().split(" 3   MODULE\n  203120")[0] + " 0   MODULE\n"


HERTZIAN = ("   1                               IPOTCN\n  40  36   -1.5  -1.8  0.10  0.10  MX, MY, XL, YL, DX, DY\n"
            "   1   1                           IBASE, IPLAN\n  0.004", "  -1   IPOTCN\n  40  36  0.004  0.004  1.1\n%")
FRICTION = ("  0.30   0.30                      FSTAT, FKIN", "  0.2 0.1 100.0 0.0 1.0   FKIN FEXP1 SABSH1 FEXP2 "
            "SABSH2\n  0.0  0.0   MEMDST MEM_S0")


@pytest.mark.parametrize("changes, name, needs", [
    ([("  203100", "  203000")], "control digit N (NORM) = 0 (line 6)", "prescribed approach"),
    ([("  022020  ", "  022320  "), ("82000.     POISS", "82000.\n 1.0 1.0 1.0    POISS")],
     "control digit M (MATER) = 3 (line 7)", "three blended flexibilities; rollcontact's solver.fidelity = 'fastsim' is "
                                             "another variant"),
    ([("  203100", "  223100"), HERTZIAN], "control digit B (BOUND) = 2 (line 6)", "elliptic traction bound"),
    ([("   1   1   ", "   1   2   "), ("     B(1..6): h", "\n  -9 9 -9 9 0 0   PL(1..6)\n% B(1..6): h")],
     "IPLAN = 2 (line 16)", "planform"),
    ([("0.004  0.0  0.004", "0.004  0.001  0.004")], "B(2) = 0.001 (line 17)", "turned in the plane"),
    ([("0.004  0.0  0.004", "0.004  0.0  0.0")], "undeformed distance", "line contact"),
    ([("  5000.0", "  0.5")], "scene refused_case1", "rollcontact refuses it"),
])
def test_what_rollcontact_cannot_pose_is_refused_with_its_value_line_and_need(tmp_path, changes, name, needs):
    text = BASE
    for old, new in changes:
        assert old in text
        text = text.replace(old, new, 1)
    deck = tmp_path / "refused.inp"
    deck.write_text(text)
    (p,) = rollcontact.import_contact(deck).problems
    assert not p.converted
    texts = [u.text() for u in p.draft.unsupported]
    hit = [t for t in texts if t.startswith(name)]
    assert hit and needs in hit[0], texts


def test_refusal_of_a_history_converts_its_head_alone_and_reports_the_rest(tmp_path):
    text = (DECKS / "shift_history.inp").read_text().replace("  100.0  -0.60  0.0  0.0", "  120.0  -0.60  0.0  0.0")
    (tmp_path / "changes.inp").write_text(text)
    result = rollcontact.import_contact(tmp_path / "changes.inp")
    head, rest = result.problems
    assert head.converted and head.numbers == [1] and not rest.converted and rest.numbers == [2, 3, 4, 5]
    assert "case 3: FN = 120 (line 24): differs from case 1 (100)" in rest.draft.unsupported[1].text()
    assert result.status == "partly"


# --- files, report, command -------------------------------------------------------------------------------------------
def test_import_writes_loadable_scenes_report_and_manifest_and_never_overwrites(tmp_path):
    out = tmp_path / "out"
    result = _imported("steady_spin", out)
    names = sorted(p.name for p in out.iterdir())
    assert names == ["steady_spin_case1.toml", "steady_spin_case2.toml", "steady_spin_import.json",
                     "steady_spin_import.md"]
    scene = rollcontact.load_scene(out / "steady_spin_case1.toml")
    assert scene.rolling.mode == "steady" and scene.rolling.direction == 180.0
    text = (out / "steady_spin_case1.toml").read_text()
    assert "# CKSI = 0.0002 (line 10)" in text
    manifest = json.loads((out / "steady_spin_import.json").read_text())
    assert manifest["status"] == "yes" and manifest["problems"][0]["scene"] == "steady_spin_case1.toml"
    assert "| case 1 | steady rolling (T = 3) | converted | `steady_spin_case1.toml` |" in result.markdown()
    before = {p: p.stat().st_mtime_ns for p in out.iterdir()}
    with pytest.raises(OutputExistsError):
        _imported("steady_spin", out)
    assert before == {p: p.stat().st_mtime_ns for p in out.iterdir()}


def test_import_contact_command(tmp_path, capsys):
    out = tmp_path / "cli"
    assert main(["import-contact", str(DECKS / "transient.inp"), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "transient: 5 of 5 computed cases converted into 1 scene (converted: yes)" in printed
    assert "  cases 1-5: transient_cases1-5.toml (transient rolling (T = 2))" in printed
    assert (out / "transient_cases1-5.toml").is_file()
    assert main(["import-contact", str(DECKS / "transient.inp"), "-o", str(out)]) == 2
    assert "exists; rollcontact does not replace a file unless asked: add --overwrite, or give another folder with -o" \
        in capsys.readouterr().err
    bad = tmp_path / "bad.inp"
    bad.write_text(" 3 MODULE\n 200100\n 022020\n")
    assert main(["import-contact", str(bad), "-o", str(tmp_path / "b")]) == 2
    assert "bad.inp, end of file (after line 3): XHGIAOWR" in capsys.readouterr().err
    assert not (tmp_path / "b").exists()


def test_a_wheel_on_its_rail_maps_to_wheelrail_with_contacts_conventions(tmp_path):
    """mbench_a22_left case 2 (module 1): the left wheel's y is -Y_WS, yaw -YAW, omega -VPITCH; body 1 of CONTACT
    is the rail."""
    import gzip
    import shutil
    deck = tmp_path / "left.inp"
    deck.write_text(gzip.open(EXAMPLES / "mbench_a22_left.inp.gz", "rt").read())
    for name in ("MBench_S1002_v3.prw", "MBench_UIC60_v3.prr"):
        shutil.copy(EXAMPLES / name, tmp_path / name)
    p = rollcontact.import_contact(deck).problems[1]
    wr = p.draft.sections["wheelrail"]
    assert p.converted and wr["side"] == "left" and wr["y"] == -0.5 and wr["yaw"] == -0.0012
    assert wr["omega"] == pytest.approx(4.3474134) and wr["Fz"] == 10000.0 and wr["rail_inclination"] == 0.0


def test_a_prepared_case_is_skipped_and_the_history_goes_on(tmp_path):
    """R = 2: the reference program reads the case (its values are inherited) but computes nothing."""
    text = (DECKS / "shift_history.inp").read_text()
    third = " 0110330      H-G-I-A-O-W-R\n  100.0  -0.20"
    assert third in text
    (tmp_path / "prepared.inp").write_text(text.replace(third, " 0110332      H-G-I-A-O-W-R\n  100.0  -0.20"))
    result = rollcontact.import_contact(tmp_path / "prepared.inp")
    history, skipped = result.problems
    assert skipped.kind == "skipped" and skipped.numbers == [4] and "R = 2" in skipped.reason
    assert history.converted and history.numbers == [1, 2, 3, 5] and history.steps == {1: 0, 2: 1, 3: 2, 5: 3}
    assert history.draft.sections["load"]["levels"] == [0.6, -0.4]
    assert "| case 4 | skipped | skipped |  |" in result.markdown()


def test_subsurface_blocks_become_the_runs_depths(tmp_path):
    text = (DECKS / "steady_spin.inp").read_text().replace("  203100      P-B-T-N-F-S", "  203103      P-B-T-N-F-S")
    blocks = ("  0.004  0.0  0.004  -0.004  0.0  0.001     B(1..6): h = 0.004 (x - 0.5)^2 + 0.004 y^2\n"
              "  1 1     MATFIL_S, OUTPUT_S\n  1   ISUBS\n  3 0.0 0.5   NZ, ZL, DZ\n  5   ISUBS\n  2\n  2.0 0.25\n"
              "  0  ISUBS\n")
    text = text.replace("  0.004  0.0  0.004  -0.004  0.0  0.001     B(1..6): h = 0.004 (x - 0.5)^2 + 0.004 y^2\n",
                        blocks, 1)
    (tmp_path / "deep.inp").write_text(text)
    result = rollcontact.import_contact(tmp_path / "deep.inp")
    one = result.problems[0]
    assert one.converted and one.draft.run_options == {"stresses": True, "depths": [0.0, 0.25, 0.5, 1.0, 2.0]}
    assert "# run: rollcontact run deep_case1.toml --stresses --depths 0,0.25,0.5,1,2" in result.scene_text(one)
    assert not result.problems[1].draft.run_options                   # S = 0 in case 2


def test_viscoelastic_bodies_map_to_standard_linear_solids(tmp_path):
    """M = 1: GG is the glassy shear modulus, FG = E_g/E_r - 1, TC the creep relaxation time (docs/viscoelastic.md);
    a body with TC = 0 relaxes at once: elastic with its relaxed modulus."""
    text = (BASE.replace("  022020      L-D-C-M-Z-E", "  022120      L-D-C-M-Z-E")
            .replace("  180d   0.10  20000.", "  0.0    0.10  20000.")
            .replace("82000.     POISS 1,2, GG 1,2", "82000.     POISS 1,2, GG 1,2\n  1.0  3.0  0.01  0.0   FG1, FG2, TC1, TC2"))
    (tmp_path / "visco.inp").write_text(text)
    (p,) = rollcontact.import_contact(tmp_path / "visco.inp").problems
    m = p.draft.sections["materials"]
    E = 2 * 82000 * 1.28
    assert p.converted and m["visco1"] == "sls" and m["E1"] == E and m["tau1"] == 0.01
    assert m["E1_relaxed"] == pytest.approx(E / 2) and m["E2"] == pytest.approx(E / 4) and "visco2" not in m
    assert p.draft.sections["rolling"]["speed"] == 20000.0


def test_slip_velocity_laws_and_temperatures_map_to_friction_and_thermal(tmp_path):
    """L = 4 in steady rolling: [friction] law = "exponential" with FKIN, FEXP1, SABSH1 (mm/s) and the memory MEMDST,
    MEM_S0 (the second term left out at FEXP2 = 0); the temperatures of ertz_temperature (H = 3): [thermal] with LAMBDA
    W/(mm K) and DENS kg/mm^3 in W/(m K) and kg/m^3 (docs/friction.md)."""
    text = BASE.replace("  022020  ", "  422020  ", 1).replace(
        FRICTION[0], FRICTION[1].replace("0.0  0.0   MEMDST", "0.003  1.0   MEMDST"), 1)
    (tmp_path / "law.inp").write_text(text)
    (p,) = rollcontact.import_contact(tmp_path / "law.inp").problems
    assert p.converted, [u.text() for u in p.draft.unsupported]
    assert p.draft.sections["friction"] == {"law": "exponential", "mu_kin": 0.2, "mu_1": 0.1, "s_1": 100.0,
                                            "memory_distance": 0.003, "memory_s0": 1.0}
    assert "mu" not in p.draft.sections["load"]
    scene = rollcontact.Scene.from_toml_text(p.draft.toml(["law"]))
    assert scene.load.mu == pytest.approx(0.3) and scene.friction.memory_distance == 0.003   # mu(0) = 0.2 + 0.1
    ertz = rollcontact.import_contact(EXAMPLES / "ertz_temperature.inp.gz").problems
    assert all(q.converted for q in ertz)
    th = ertz[-1].draft.sections["thermal"]
    assert th["conductivity1"] == pytest.approx(50.0) and th["density2"] == pytest.approx(7850.0)
    assert (th["heat_capacity1"], th["T_bulk1"], th["T_bulk2"]) == (450.0, 0.0, 150.0)


def test_a_friction_law_in_a_shift_is_refused_naming_why(tmp_path):
    text = (DECKS / "shift_history.inp").read_text()
    text = text.replace("  022020      L-D-C-M-Z-E", "  422020      L-D-C-M-Z-E", 1).replace(
        "  0.40   0.40                      FSTAT, FKIN", "  0.3 0.1 10.0 0.0 1.0   FKIN FEXP1 SABSH1 FEXP2 SABSH2\n"
        "  0.0  0.0   MEMDST MEM_S0", 1)
    (tmp_path / "shift.inp").write_text(text)
    shift = rollcontact.import_contact(tmp_path / "shift.inp").problems[-1]
    texts = [u.text() for u in shift.draft.unsupported]
    assert not shift.converted and any("L (FRCLAW) = 4" in t and "in a shift (T = 1)" in t for t in texts), texts
