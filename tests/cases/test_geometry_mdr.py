"""[solver] fidelity = "mdr" for the axisymmetric shapes (cone, power n = 4, rounded flat punch): the 1-D spring
model with the shape's MDR profile g(s) (solver.mdr.simulate_mdr(profile=...)) against the exact MDR answers
(solver.mdr.exact) and against the 3-D runs where the MDR is exact (the static loading: docs/theory.md §11.4), and its
shakedown state under the seed's oscillating rolling against the closed form of docs/theory.md §8.3 written for any
profile (MDRTangential.shakedown_shift / limit). Units mm, N, MPa.

The 1-D model runs 4001 springs (ds = (a + W)/1999); its discretisation error is O(ds/a) ~ 5e-4 at most, measured
below 1e-6 relative on every quantity checked here.
"""
import math

import pytest

from rollcontact.bem import MaterialPair
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.solver.mdr.simulate import simulate_mdr
from rollcontact.solver.rolling.axisymmetric import PowerProfile
from test_geometry_shapes import SHAPES, shape_scene


@pytest.mark.parametrize("name", SHAPES)
def test_mdr_fidelity_static_matches_exact_and_3d(name):
    """Fn, then Ft to f_t = 0.5: the spring model's approach, U_stat and stick radius against the exact MDR (1e-5
    relative; measured at most 5e-7, the stick radius within one spring spacing), and U_stat within 1 % of the 3-D
    run on the default grid (measured +0.13 % cone, +0.07 % n = 4, -0.003 % flat)."""
    mdr = run_scene(shape_scene(name, load={"ft": 0.5}, motion={"periods": 0}, solver={"fidelity": "mdr"}), None)
    bem = run_scene(shape_scene(name, load={"ft": 0.5}, motion={"periods": 0}), None)
    scene = mdr.scene
    ref, tg = scene.normal_reference, scene.tangential_reference
    assert mdr.history["approach"][-1] == pytest.approx(ref.approach, rel=1e-5)
    assert mdr.summary["U_stat"] == pytest.approx(tg.shift(0.5), rel=1e-5)
    c = math.sqrt(mdr.history["stick_area"][-1] / math.pi)       # pi L^2/4: L/2
    assert abs(c - tg.stick_radius(0.5)) <= mdr.summary["ds"]
    assert mdr.summary["a"] == ref.a and mdr.summary["U0"] == pytest.approx(tg.U0, rel=1e-15)
    assert mdr.summary["U_stat"] == pytest.approx(bem.summary["U_stat"], rel=0.01)


@pytest.mark.parametrize("name", SHAPES)
def test_mdr_fidelity_shakedown_matches_the_closed_form_for_the_profile(name):
    """Seed's oscillating rolling at w = 0.23 (30 periods): below the MDR limit f_t,lim of the profile (0.02 under
    it) and at f_t = 0.3 the spring row shakes down to u_sd = 1 - g(b)/d of docs/theory.md §8.3 (to 1e-5; measured at
    most
    4e-7); 0.03 above the limit it ratchets. Limits at w = 0.23: cone 0.5929, n = 4 0.7127, flat 0.7514."""
    scene = shape_scene(name, motion={"w": 0.23, "periods": 30}, solver={"fidelity": "mdr"})
    tg = scene.tangential_reference
    W = scene.amplitude
    f_lim, _ = tg.limit(W)
    for f in (0.3, round(f_lim - 0.02, 4)):
        s = run_scene(scene.with_overrides({"load.ft": f}), None).summary
        assert s["state"] == "shakedown", (f, s["state"])
        assert s["u_sd"] == pytest.approx(tg.shakedown_shift(f, W), rel=1e-5)
    s = run_scene(scene.with_overrides({"load.ft": round(f_lim + 0.03, 4)}), None).summary
    assert s["state"] == "ratcheting"


def test_profile_path_of_the_spring_model_is_the_sphere_path():
    """The power law n = 2 through the profile path (gaps g(s - c) from numpy, `_step_gap_kernel`) gives the
    sphere's R path (gaps in the compiled kernel) to round-off: the same springs and steps, kappa_2 = 2 from
    Gamma functions (1e-12 relative on every U)."""
    pair = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)
    common = dict(E_star=pair.E_star, G_star=pair.G_star, Fn=21.19, mu=0.93, Ft=0.46 * 0.93 * 21.19, W=1.1,
                  dW=0.2, periods=3, n_springs=801)
    ref = simulate_mdr(R=40.0, **common)
    got = simulate_mdr(profile=PowerProfile(2.0, 40.0), **common)
    assert got.a == pytest.approx(ref.a, rel=1e-12) and got.U0 == pytest.approx(ref.U0, rel=1e-12)
    assert got.history["U"] == pytest.approx(ref.history["U"], rel=1e-12)
