"""Figures from real (coarse) runs: `rollcontact plot RUN.h5`, `plot OUTDIR`, `compare A B`.

Every figure is written as PNG and PDF; a PNG is FIGSIZE * DPI pixels (no tight bounding box). Coarse grid
(dx = 0.4 mm, dW = 0.4 mm, 5 periods, shakedown tolerance 1e-3) so the whole module runs in well under a minute.
"""
from __future__ import annotations

import csv
from pathlib import Path
import shutil

import matplotlib.image as mpimg
import numpy as np
import pytest

from rollcontact.cases.cli.main import build_parser
from rollcontact.cases.cli.main import main as run_cli
from rollcontact.cases.plots.common import DPI, FIGSIZE, open_run, seed_regions
from rollcontact.cases.plots.sweep_figures import read_folder, read_limits
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import Scene, default_scene

COARSE = ["grid.dx=0.4", "motion.dW=0.4", "motion.periods=5", "solver.shakedown_tol=1e-3"]


def _run(path, *overrides):
    run_scene(default_scene().with_overrides(COARSE + list(overrides)), path)
    return path


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """A 4-run sweep folder (parallel/perpendicular x shakedown/ratcheting) and a run without fields."""
    root = tmp_path_factory.mktemp("plots")
    sweep = root / "sweep"
    files = {}
    for angle in (0, 90):
        for ft in (0.46, 0.8):
            files[(angle, ft)] = _run(sweep / f"a{angle}_ft{ft}.h5", f"motion.angle={angle}", f"load.ft={ft}")
    files["none"] = _run(root / "nofields.h5", "output.fields=none")
    return root, sweep, files


def _check_png_pdf(paths, expected: dict):
    """Each stem in `expected` (kind -> list of stems matched by suffix) has a PNG of FIGSIZE * DPI and a PDF."""
    names = {Path(p).name for p in paths}
    for p in paths:
        assert Path(p).exists() and Path(p).stat().st_size > 1000, p
    for kind, stem in expected.items():
        assert f"{stem}.png" in names and f"{stem}.pdf" in names, (stem, sorted(names))
        png = Path(paths[0]).parent / f"{stem}.png"
        img = mpimg.imread(png)
        w, h = FIGSIZE[kind]
        assert img.shape[:2] == (round(h * DPI), round(w * DPI)), (stem, img.shape)
        assert np.ptp(img[..., :3]) > 0.5           # not blank
        assert (Path(paths[0]).parent / f"{stem}.pdf").read_bytes()[:4] == b"%PDF"


def _written(capsys):
    return [Path(line) for line in capsys.readouterr().out.splitlines() if line.startswith("/")]


def test_plot_run_writes_history_maps_and_centrelines_at_last_stored_step(runs, tmp_path, capsys):
    _, _, files = runs
    run = files[(90, 0.46)]
    assert run_cli(["plot", str(run), "-o", str(tmp_path)]) == 0
    paths = _written(capsys)
    last = open_run(run).stored_steps[-1]
    _check_png_pdf(paths, {"history": f"{run.stem}_history", "maps": f"{run.stem}_maps_step{last}",
                           "centrelines": f"{run.stem}_centrelines_step{last}"})


def test_plot_run_at_a_chosen_stored_step(runs, tmp_path, capsys):
    _, _, files = runs
    run = files[(0, 0.8)]
    step = open_run(run).stored_steps[2]
    assert run_cli(["plot", str(run), "--step", str(step), "-o", str(tmp_path)]) == 0
    _check_png_pdf(_written(capsys), {"maps": f"{run.stem}_maps_step{step}"})


def test_plot_run_without_fields_draws_history_only_with_a_note(runs, tmp_path, capsys):
    _, _, files = runs
    assert run_cli(["plot", str(files["none"]), "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "note:" in out and "only the history figure" in out
    paths = [Path(line) for line in out.splitlines() if line.startswith("/")]
    assert sorted(p.suffix for p in paths) == [".pdf", ".png"]
    _check_png_pdf(paths, {"history": "nofields_history"})


def test_plot_step_not_stored_exits_2_and_lists_the_stored_steps(runs, tmp_path, capsys):
    _, _, files = runs
    run = files[(90, 0.46)]
    stored = open_run(run).stored_steps
    missing = next(s for s in range(1, 10 ** 4) if s not in stored)
    assert run_cli(["plot", str(run), "--step", str(missing), "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert f"step {missing} were not stored" in err and f"{stored[0]}, {stored[1]}" in err
    assert run_cli(["plot", str(files["none"]), "--step", "3", "-o", str(tmp_path)]) == 2


def test_plot_missing_file_or_non_run_file_exits_2(tmp_path, capsys):
    assert run_cli(["plot", str(tmp_path / "nothing.h5")]) == 2
    assert "no such file" in capsys.readouterr().err
    bogus = tmp_path / "bogus.h5"
    bogus.write_text("not hdf5")
    assert run_cli(["plot", str(bogus)]) == 2
    assert "not a run file written by rollcontact run (not an HDF5 file)" in capsys.readouterr().err
    assert run_cli(["compare", str(bogus), str(bogus)]) == 2
    empty = tmp_path / "empty"
    empty.mkdir()
    assert run_cli(["plot", str(empty)]) == 2
    assert "nothing to plot" in capsys.readouterr().err


def test_plot_sweep_folder_draws_usd_limits_ratcheting_and_prints_fitted_kappa(runs, tmp_path, capsys):
    _, sweep, _ = runs
    assert run_cli(["plot", str(sweep), "-o", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "fitted kappa (seed Eq. 13), parallel" in out and "perpendicular" in out
    paths = [Path(line) for line in out.splitlines() if line.startswith("/")]
    _check_png_pdf(paths, {"usd": "sweep_usd", "limits": "sweep_limits", "ratcheting": "sweep_ratcheting"})
    states = {(p.setting, round(p.f_t, 2)): p.state for p in read_folder(sweep)}
    assert states[("perpendicular", 0.46)] == "shakedown" and states[("parallel", 0.8)] == "ratcheting"


def test_sweep_kappa_excludes_limit_search_probes_and_says_so(runs, tmp_path, capsys):
    _, sweep, files = runs
    folder = tmp_path / "with_probes"
    shutil.copytree(sweep, folder)
    (folder / "runs").mkdir()
    shutil.copy(files[(90, 0.46)], folder / "runs" / "probe.h5")       # a limit-search probe
    assert run_cli(["plot", str(folder), "-o", str(tmp_path / "figs")]) == 0
    out = capsys.readouterr().out
    assert "kappa fitted to the 4 sweep runs; 1 limit-search probe(s) (runs/) excluded" in out
    line = next(x for x in out.splitlines() if x.startswith("fitted kappa (seed Eq. 13), perpendicular"))
    assert "(n = 1," in line                          # the sweep's one shaken-down perpendicular run only
    pts = read_folder(folder)
    assert sum(p.probe for p in pts) == 1 and len(pts) == 5              # the figures still show the probe
    shutil.rmtree(folder / "runs")
    assert run_cli(["plot", str(folder), "-o", str(tmp_path / "figs"), "--overwrite"]) == 0
    assert "limit-search" not in capsys.readouterr().out


def test_a_stored_run_beyond_todays_run_limits_is_still_plotted(tmp_path):
    """A file an older version wrote for a/dx = 1.5 (refused for new runs today: a/dx >= 3) stays readable."""
    toml = default_scene().with_overrides(COARSE).to_toml().replace("dx = 0.4", "dx = 3.2")
    path = run_scene(Scene.from_toml_text(toml, run_limits=False), tmp_path / "old" / "coarse.h5").path
    assert open_run(path).scene.grid.dx == 3.2
    assert [p.file for p in read_folder(tmp_path / "old")] == ["coarse.h5"]


def test_limits_csv_of_limit_search_is_read_with_its_brackets(tmp_path):
    path = tmp_path / "limits.csv"
    header = ["motion.w", "motion.angle", "index", "searched", "lower", "upper", "midpoint", "width", "status",
              "probes", "undecided", "mdr_kappa=1", "mdr_kappa=1.1", "mdr_kappa=1.5", "f_t", "w", "error"]
    with open(path, "w", newline="") as fh:
        wr = csv.writer(fh)
        wr.writerow(header)
        wr.writerow([0.23, 90, 0, "f_t", 0.70, 0.72, 0.71, 0.02, "ok", 7, "", 0.77, 0.75, 0.66, "", 0.23, ""])
        wr.writerow([0.4, 90, 1, "f_t", "", "", "", "", "failed", 2, "", 0.6, 0.57, 0.43, "", 0.4, "boom"])
    rows = read_limits(path)
    assert len(rows) == 1
    r = rows[0]
    assert (r["w"], r["f_t"], r["angle"]) == (0.23, 0.71, 90.0)
    assert np.allclose(r["f_err"], [[0.01], [0.01]]) and r["w_err"] is None


def test_compare_parallel_and_perpendicular_writes_maps_with_difference_and_one_history(runs, tmp_path, capsys):
    _, _, files = runs
    a, b = files[(0, 0.46)], files[(90, 0.46)]
    assert run_cli(["compare", str(a), str(b), "-o", str(tmp_path)]) == 0
    stem = f"compare_{a.stem}_vs_{b.stem}"
    _check_png_pdf(_written(capsys), {"history": f"{stem}_history", "compare_maps": f"{stem}_maps",
                                      "centrelines": f"{stem}_centrelines"})


def test_seed_regions_tell_stick_bound_released_and_slip_apart():
    mu = 0.5
    p = np.array([[0.0, 1.0, 1.0, 1.0, 1.0]])
    p_min = np.array([[0.0, 0.8, 0.8, 0.0, 0.8]])
    tau_x = np.array([[0.0, 0.1, 0.4, 0.0, 0.5]])
    region = np.array([[0, 1, 1, 1, 2]])
    codes, seed = seed_regions(region, p, tau_x, np.zeros_like(tau_x), mu, p_min)
    assert seed and codes.tolist() == [[0, 1, 2, 3, 4]]
    codes, seed = seed_regions(region, p, tau_x, np.zeros_like(tau_x), mu, None)
    assert not seed and codes.tolist() == [[0, 1, 1, 1, 4]]


def test_main_cli_registers_plot_and_compare():
    parser = build_parser()
    assert parser.parse_args(["plot", "x.h5", "--step", "3"]).step == 3
    assert parser.parse_args(["compare", "a.h5", "b.h5"]).b == "b.h5"


def test_history_of_a_reversed_load_shows_its_negative_shift_and_no_mdr_lines(tmp_path):
    """load.levels = [0, -f_t] (Mindlin-Deresiewicz reversal, then rolling): u goes negative, so the axis must not
    start at 0 (the whole oscillation would be cut off), and the MDR u_sd of a monotonic ramp to f_t do not
    apply. A static run's axis counts steps, not periods."""
    from rollcontact.cases.plots.run_figures import history_figure
    rolled = open_run(_run(tmp_path / "rev.h5", "load.ramp_steps=2", "load.levels=[0.0, -0.46]"))
    fig = history_figure([rolled])
    ax, ax2 = fig.axes[:2]
    assert rolled.u().min() < -0.3 and ax.get_ylim()[0] <= rolled.u().min()  # u_stat(0.46) = 0.34, reversed
    assert not any("MDR" in t.get_text() for t in fig.legends[0].get_texts())     # the legend is above the axes
    assert "periods" in ax2.get_xlabel()
    static = open_run(_run(tmp_path / "static.h5", "motion.periods=0"))
    fig = history_figure([static])
    assert fig.axes[1].get_xlabel().startswith("steps") and fig.axes[0].get_ylim()[0] == 0.0
    assert any("MDR" in t.get_text() for t in history_figure([open_run(_run(tmp_path / "mono.h5"))]).legends[0]
               .get_texts())
