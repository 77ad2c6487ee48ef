"""Any alignment theta between Ft and the rolling direction (issue: the seed's open question I): the sideways
shift U_perp, the mirror symmetries of theta (docs/theory.md §11.1), the angle study's figure, and the continuation of
limit-search probes. Real runs on a coarse grid (dx = 0.6 mm, a/dx = 8), real HDF5 files and PNGs.
Units: mm, N; u = U/U0, f_t = Ft/(mu Fn), w = W/a (seed Eq. 9)."""
from __future__ import annotations

import numpy as np
import pytest

from rollcontact.cases.results.hdf5 import read_run, stored_history
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene, shipped_scene_path
from rollcontact.cases.sweep.limit_search import search_limits
from rollcontact.cases.sweep.plan import PlannedRun
from rollcontact.cases.sweep.runner import execute_run, is_done, run_sweep
from rollcontact.cases.plots.sweep_figures import plot_folder

COARSE = ["grid.dx=0.6", "motion.dW=0.4", "motion.periods=3", "output.fields=reversals"]


@pytest.fixture(scope="module")
def base():
    return Scene.from_toml(shipped_scene_path("paper_parallel.toml"))


def _run(base, tmp_path, angle, ft=0.46, extra=()):
    scene = base.with_overrides(COARSE + [f"motion.angle={angle}", f"load.ft={ft}", *extra])
    return run_scene(scene, tmp_path / f"theta={angle}_ft={ft}.h5")


@pytest.fixture(scope="module")
def oblique(base, tmp_path_factory):
    """theta = 30, -30 and 150 deg at f_t = 0.46, w = 0.23."""
    out = tmp_path_factory.mktemp("theta")
    return {a: _run(base, out, a) for a in (30, -30, 150)}


def test_u_perp_is_the_shift_across_ft_in_the_history_and_the_summary(oblique):
    """U_perp = U . (Ft turned by +90 deg) at every step (Ft along +x here: U_perp = U_y); the summary holds its
    final value and its change over the last period (mm); an oblique rolling walks sideways (|U_perp| > 0)."""
    r = read_run(oblique[30].path)
    h, s = r.history, r.summary
    np.testing.assert_array_equal(h["U_perp"], h["U_y"])
    assert s["U_perp"] == h["U_perp"][-1]
    ends = [int(np.flatnonzero(h["period"] == k)[-1]) for k in (2, 3)]
    assert s["dU_perp_per_period"] == pytest.approx(h["U_perp"][ends[1]] - h["U_perp"][ends[0]], abs=1e-15)
    assert abs(s["U_perp"]) > 1e-3 * abs(h["U_x"][-1])


def test_u_perp_follows_a_rotated_load(base, tmp_path):
    """Ft at 90 deg from +x (along +y): U_perp is then the component along -x (to the round-off of cos 90 deg =
    6e-17 times U_y)."""
    r = _run(base, tmp_path, 30, extra=["load.load_angle=90", "motion.periods=1"])
    np.testing.assert_allclose(r.history["U_perp"], -r.history["U_x"], rtol=0, atol=1e-16)


def test_minus_theta_is_the_mirror_image_step_by_step(oblique):
    """Mirror y -> -y (docs/theory.md §11.1): theta and -theta give the same U along Ft and opposite U_perp at every
    step.
    Both runs solve mirror-image problems to the solver tolerance (1e-8), so they agree to 1e-9 mm (|U| ~ 0.3 mm)."""
    a, b = oblique[30].history, oblique[-30].history
    np.testing.assert_allclose(a["U_x"], b["U_x"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(a["U_perp"], -b["U_perp"], rtol=0, atol=1e-9)
    assert np.max(np.abs(a["U_perp"])) > 1e-3


def test_180_minus_theta_reaches_the_same_state_step_by_step(oblique):
    """Mirror x -> -x together with reversing every traction maps the Cattaneo state after the ramp onto itself and
    theta onto 180 - theta: the same U along Ft and the same shakedown state (u_sd) at every step, U_perp
    opposite. Tolerance as above."""
    a, b = oblique[30], oblique[150]
    np.testing.assert_allclose(a.history["U_x"], b.history["U_x"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(a.history["U_perp"], -b.history["U_perp"], rtol=0, atol=1e-9)
    assert a.summary["state"] == b.summary["state"]
    assert a.summary["U_sd"] == pytest.approx(b.summary["U_sd"], abs=1e-9) if a.summary["U_sd"] is not None \
        else b.summary["U_sd"] is None


def test_an_extended_probe_continues_its_shorter_run_and_equals_a_run_from_the_start(base, tmp_path):
    """execute_run(extend_from=...) continues a complete 3-period run to 5 periods instead of starting again: the
    file records where it came from, a sweep or limit search recognises it as done, and its history equals a 5-period
    run from the start (bit for bit up to the restart step, to round-off after it: the restart recomputes the
    solver's memo A tau by FFT)."""
    scene3 = base.with_overrides(COARSE + ["load.ft=0.6"])
    scene5 = base.with_overrides(COARSE + ["load.ft=0.6", "motion.periods=5"])
    short, longer, direct = tmp_path / "p3.h5", tmp_path / "p5.h5", tmp_path / "direct.h5"
    run_scene(scene3, short)
    result = execute_run(scene5.to_toml(), scene5.name, str(longer), extend_from=str(short))
    assert result["status"] == "complete"
    extended = read_run(longer)
    assert extended.attrs["restarted_from"] == str(short.resolve())
    assert is_done(PlannedRun(0, {}, scene5.to_toml(), longer, scene5.name))
    reference = run_scene(scene5, direct)
    n = int(extended.attrs["restart_step"]) + 1
    for k in ("U_x", "U_y", "approach"):
        np.testing.assert_array_equal(extended.history[k][:n], reference.history[k][:n])
        np.testing.assert_allclose(extended.history[k], reference.history[k], rtol=1e-12, atol=1e-15)
    assert extended.summary["state"] == reference.summary["state"]


def test_extend_from_another_scene_starts_again(base, tmp_path):
    """A shorter run of another load is not continued: the run starts from the beginning."""
    other = base.with_overrides(COARSE + ["load.ft=0.5"])
    scene5 = base.with_overrides(COARSE + ["load.ft=0.6", "motion.periods=4"])
    run_scene(other, tmp_path / "other.h5")
    result = execute_run(scene5.to_toml(), scene5.name, str(tmp_path / "p.h5"), extend_from=str(tmp_path / "other.h5"))
    assert result["status"] == "complete"
    assert "restarted_from" not in read_run(tmp_path / "p.h5").attrs


def test_angle_sweep_and_limit_search_give_the_alignment_figure(base, tmp_path, capsys):
    """`sweep` over motion.angle plus `limit-search` with motion.angle varied, then `plot` on the folder: the
    summary table carries U_perp, the limits table one bracket per angle, and the plot writes <folder>_angles
    (PNG + PDF) and prints kappa per angle and the errors of the proposed closed forms."""
    out = tmp_path / "study"
    coarse = ["grid.dx=0.6", "motion.dW=10", "motion.periods=6", "solver.shakedown_tol=1e-3"]
    report = run_sweep(base, ["load.ft=0.3,0.5", "motion.w=0.23", "motion.angle=0,45,90"], out, overrides=coarse,
                       jobs=1, progress=None)
    assert all(r["status"] == "complete" for r in report.rows)
    assert all("U_perp" in r for r in report.rows)
    limits = search_limits(base, ["motion.w=0.23", "motion.angle=0,45,90"], out, overrides=coarse, tol=0.05,
                           jobs=1, progress=None)
    assert [r["status"] for r in limits.rows] == ["ok"] * 3
    assert all(r["width"] <= 0.05 + 1e-9 for r in limits.rows)
    notes = []
    paths = plot_folder(out, notes=notes)
    names = {p.name for p in paths}
    assert {"study_angles.png", "study_angles.pdf"} <= names
    assert (out / "study_angles.png").stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "theta = 45 deg: kappa = " in text and "f_t,lim = 1 - 1.5 w + 0.5 w^3: largest error" in text
    h = stored_history(out / report.rows[0]["file"], ("U_perp",))
    assert h["U_perp"].size > 0


@pytest.mark.slow
def test_a_slowly_decaying_probe_next_to_the_limit_is_continued_to_shakedown_not_called_ratcheting(base, tmp_path):
    """Paper grid, W || Ft, w = 0.23, f_t = 0.66: just below the 3-D limit (in [0.660, 0.665], as an independent
    CONTACT run finds), dU per period decays by a factor of only 0.89-0.94 per period, so after the scene's 10
    periods it is still 2e-3 U0 and the run is undecided. The limit search continues the probe from its own file
    (not from the start) until it has shaken down (|du| < 1e-4, about 40-45 periods)."""
    from rollcontact.cases.sweep.limit_search import _LimitSearch
    search = _LimitSearch(base, [], {"motion.w": 0.23}, "load.ft", 0.01, tmp_path, tmp_path, False)
    assert search.classify(0.66) == -1
    runs = sorted(tmp_path.glob("*.h5"), key=lambda p: p.stat().st_mtime)
    assert len(runs) >= 2 and search.probes == len(runs)
    final = read_run(runs[-1])
    assert final.summary["state"] == "shakedown" and 10 < final.summary["periods_to_shakedown"] <= 160
    assert final.attrs.get("restarted_from") == str(runs[-2].resolve())
