"""`rollcontact plot OUTDIR` on a sweep of a non-sphere profile (cases.plots.shape_figures): the runs are drawn
against the MDR of their own profile, not the sphere's kappa curves. Real run files (the 1-D MDR model and a
coarse 3-D run of the cone) and a real PNG. Units mm, N, MPa."""
import matplotlib.image as mpimg

from rollcontact.cases.cli.main import main as run_cli
from rollcontact.cases.plots.common import DPI, FIGSIZE
from rollcontact.cases.run.scene_run import run_scene
from test_geometry_shapes import shape_scene


def test_cone_sweep_folder_is_plotted_against_the_cone_mdr(tmp_path, capsys):
    """Three runs at w = 0.23 (two MDR shakedown runs, one 3-D run on a coarse grid): the u_sd figure is written
    (PNG of FIGSIZE * DPI pixels) and the table lists each run beside the cone's MDR u_sd and the cone's MDR limit
    f_t,lim = 0.5929 (docs/theory.md §8.3 for the cone; the sphere's would be 0.6611)."""
    folder = tmp_path / "cone_sweep"
    base = shape_scene("cone", motion={"w": 0.23, "periods": 10})
    for f in (0.2, 0.4):
        run_scene(base.with_overrides({"load.ft": f, "solver.fidelity": "mdr"}), folder / f"mdr_{f}.h5")
    run_scene(base.with_overrides({"load.ft": 0.3, "grid.dx": 1.0, "solver.shakedown_tol": 1e-3}),
              folder / "bem_0.3.h5")
    assert run_cli(["plot", str(folder), "-o", str(tmp_path / "figs")]) == 0
    text = capsys.readouterr().out
    assert "MDR limit at w = 0.23: f_t,lim = 0.5929" in text and "cone profile" in text
    assert text.count("shakedown") == 3
    png = mpimg.imread(tmp_path / "figs" / "cone_sweep_usd.png")
    assert png.shape[:2] == (FIGSIZE["usd"][1] * DPI, FIGSIZE["usd"][0] * DPI)
