"""Figures a reader can trust: in every figure the CLI draws, no two text labels overlap and none is cut off.

Every family of figures of the README walkthrough and the study pages is drawn from small real runs (coarse grids,
a few periods; ~20 s on a quiet machine): `plot` of a run (history, maps, centre lines; seed Figs. 4-7), of a
ratcheting run, of a Mindlin-Deresiewicz run (history and loads), of a run with subsurface stresses, of a
viscoelastic run and a viscoelastic [rolling] run (maps, pressure), of a wheel-rail run; `compare`; `plot` of a
sweep folder (u_sd, limits with limit-search brackets, ratcheting, the alignment panels), of a phase sweep and of
a phase limit search (docs/oscillating_loads.md), of a cone sweep (docs/shapes.md), of a sweep over a wheel's
lateral displacement (docs/wheelrail.md); `creep-curve`.
Each figure is checked as it is saved: the text the renderer actually draws (titles, axis and tick labels,
legends, annotations, colour-bar labels) is measured with `Text.get_window_extent`. Two boxes overlapping by more
than OVERLAP_PX in both directions, a box leaving the figure, and a data label (an annotation) crossing the frame
of its axes or drawn over a curve or a marker are defects, reported with the texts.
"""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

from matplotlib.colors import to_hex
import matplotlib.figure
import matplotlib.text
import numpy as np
import pytest

from rollcontact.cases.cli.main import main as run_cli

#: pixels (at the PNG's DPI) by which two text boxes may touch: anti-aliasing and glyph side bearings.
OVERLAP_PX = 1.0
#: sweeps and limit searches: a/dx = 6, one rolling step per quarter period, 4 periods
COARSE = ["--set", "grid.dx=0.8", "--set", "motion.dW=10", "--set", "motion.periods=4",
          "--set", "solver.shakedown_tol=1e-3"]


@contextmanager
def recorded_texts():
    """Yields a dict that collects, per Text artist, (text, window extent, page size) as it was last drawn meanwhile
    (savefig may draw twice: the layout pass, then the rendering). An annotation whose point lies outside its axes,
    an invisible or empty text, a tick outside the view are not drawn, so not recorded."""
    drawn = {}
    original = matplotlib.text.Text.draw

    def draw(self, renderer):
        original(self, renderer)
        if self.get_visible() and self.get_text().strip():
            box = self.get_window_extent(renderer).frozen()
            frame, crossed = None, []
            if isinstance(self, matplotlib.text.Annotation) and self.axes is not None:
                frame = self.axes.get_window_extent(renderer).frozen()      # a label of data in its axes
                crossed = [_line_name(line) for line in self.axes.get_lines() if _crosses(line, box, renderer)]
            drawn[id(self)] = (self.get_text(), box, (renderer.width, renderer.height), frame, crossed)

    matplotlib.text.Text.draw = draw
    try:
        yield drawn
    finally:
        matplotlib.text.Text.draw = original


def _line_name(line) -> str:
    label = line.get_label()
    return repr(label) if label and not label.startswith("_") else f"a {to_hex(line.get_color())} line"


def _crosses(line, box, renderer) -> bool:
    """Whether a drawn data line or one of its markers passes through the text box (shrunk by OVERLAP_PX)."""
    if not line.get_visible():
        return False
    xy = line.get_transform().transform(np.asarray(line.get_xydata(), float))
    xy = xy[np.isfinite(xy).all(axis=1)]
    x0, y0, x1, y1 = box.x0 + OVERLAP_PX, box.y0 + OVERLAP_PX, box.x1 - OVERLAP_PX, box.y1 - OVERLAP_PX
    if x0 >= x1 or y0 >= y1 or not len(xy):
        return False
    if line.get_marker() not in (None, "None", "", " ") and line.get_markersize() > 0:
        r = renderer.points_to_pixels(line.get_markersize()) / 2
        if np.any((xy[:, 0] > x0 - r) & (xy[:, 0] < x1 + r) & (xy[:, 1] > y0 - r) & (xy[:, 1] < y1 + r)):
            return True
    if line.get_linestyle() in ("None", "", " ") or len(xy) < 2:
        return False
    # segment P + t (Q - P), 0 <= t <= 1, against the rectangle (Liang-Barsky)
    p, d = xy[:-1], np.diff(xy, axis=0)
    lo, hi = np.zeros(len(d)), np.ones(len(d))
    inside = np.ones(len(d), bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        for step, gap in ((-d[:, 0], p[:, 0] - x0), (d[:, 0], x1 - p[:, 0]), (-d[:, 1], p[:, 1] - y0),
                          (d[:, 1], y1 - p[:, 1])):
            t = gap / step
            inside &= ~((step == 0) & (gap < 0))
            lo = np.where(step < 0, np.maximum(lo, t), lo)
            hi = np.where(step > 0, np.minimum(hi, t), hi)
    return bool(np.any(inside & (lo <= hi)))


def label_defects(drawn: dict) -> list[str]:
    """Pairs of drawn texts that overlap, and texts that leave the page."""
    drawn = list(drawn.values())
    defects = []
    for i, (a, box_a, (width, height), frame, crossed) in enumerate(drawn):
        for b, box_b, _, _, _ in drawn[i + 1:]:
            w = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            h = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if w > OVERLAP_PX and h > OVERLAP_PX:
                defects.append(f"{a!r} overlaps {b!r} ({w:.0f} x {h:.0f} px)")
        if (box_a.x0 < -OVERLAP_PX or box_a.y0 < -OVERLAP_PX or box_a.x1 > width + OVERLAP_PX
                or box_a.y1 > height + OVERLAP_PX):
            defects.append(f"{a!r} is cut off at the figure's edge")
        if frame is not None and (box_a.x0 < frame.x0 - OVERLAP_PX or box_a.y0 < frame.y0 - OVERLAP_PX
                                  or box_a.x1 > frame.x1 + OVERLAP_PX or box_a.y1 > frame.y1 + OVERLAP_PX):
            defects.append(f"{a!r} crosses the frame of its axes")
        defects += [f"{a!r} is drawn over {line}" for line in crossed]
    return defects


@contextmanager
def checked_figures():
    """Collect {figure file stem: defects} of every figure saved as PNG meanwhile (cases.plots.common.save_figure
    writes `.<stem>.<pid>.tmp.png`, then renames it), measured as the PNG is rendered."""
    found = {}
    original = matplotlib.figure.Figure.savefig

    def savefig(fig, fname, *args, **kwargs):
        name = Path(str(fname)).name
        if kwargs.get("format", Path(name).suffix[1:]) != "png":
            return original(fig, fname, *args, **kwargs)
        with recorded_texts() as drawn:
            result = original(fig, fname, *args, **kwargs)
        stem = name[1:-len(".png")].rsplit(".", 2)[0] if name.startswith(".") else name[:-len(".png")]
        found[stem] = label_defects(drawn)
        return result

    matplotlib.figure.Figure.savefig = savefig
    try:
        yield found
    finally:
        matplotlib.figure.Figure.savefig = original


def _cli(*argv):
    assert run_cli([str(a) for a in argv]) == 0, argv


ROOT = Path(__file__).resolve().parents[2]
FINE = ["--set", "grid.dx=0.6", "--set", "motion.dW=0.6", "--set", "motion.periods=5", "--set",
        "solver.shakedown_tol=1e-3", "-q"]
CREEP = ["--set", "grid.dx=1.4"]
VISCO = ["--set", "materials.E2=8.7", "--set", "materials.E2_relaxed=4.35", "--set", "materials.tau2=0.1", "--set",
         'materials.visco2="sls"']


def make_inputs(root: Path):
    """The run files and folders every figure is drawn from (small real runs)."""
    runs = root / "runs"
    # the walkthrough: a run in each setting (one with subsurface stresses), a ratcheting run (its history only)
    _cli("run", *FINE, "-o", runs / "perp.h5")
    _cli("stresses", runs / "perp.h5", "--depths", "0,0.5,1,2,3", "-q")
    _cli("run", *FINE, "--set", "motion.angle=0", "-o", runs / "par.h5")
    _cli("run", *FINE, "--set", "load.ft=0.77", "--set", "output.fields=none", "-o", runs / "perp_rat.h5")
    # Mindlin-Deresiewicz: no rolling, Ft oscillating about 0 (history and loads)
    _cli("run", "--set", "motion.w=0", "--set", "load.ft=0", "--set", "load.ft_amplitude=0.6", "--set",
         "motion.periods=3", "--set", "grid.dx=0.6", "--set", "output.fields=none", "-q", "-o", runs / "md.h5")
    # a sweep over alignment, amplitude and load, with a limit search in the same folder
    _cli("sweep", "--vary", "motion.angle=0,45,90", "--vary", "motion.w=0.1,0.4", "--vary", "load.ft=0.3,0.9",
         *COARSE, "-o", root / "sweep", "--jobs", "1", "-q")
    _cli("limit-search", "--vary", "motion.w=0.23", "--vary", "motion.angle=0,90", *COARSE, "--tol", "0.1",
         "-o", root / "sweep", "--jobs", "1", "-q")
    # oscillating loads: a phase sweep and a phase limit search (docs/oscillating_loads.md)
    _cli("sweep", "--vary", "motion.angle=0,90", "--vary", "load.ft_amplitude=0.1,0.3", "--vary",
         "load.phase=0,180", *COARSE, "--set", "output.fields=none", "-o", root / "osc_ft", "--jobs", "1", "-q")
    _cli("limit-search", "--vary", "motion.w=0.23", "--vary", "motion.angle=90", "--vary", "load.phase=0,180",
         "--set", "load.ft_amplitude=0.2", *COARSE, "--set", "output.fields=none", "--tol", "0.1",
         "-o", root / "osc_lim", "--jobs", "1", "-q")
    # a non-spherical profile (docs/shapes.md)
    _cli("sweep", ROOT / "docs" / "shapes" / "cone.toml", "--vary", "load.ft=0.2,0.5,0.8", "--vary",
         "motion.angle=0,90", *COARSE, "-o", root / "cone_sweep", "--jobs", "1", "-q")
    # viscoelastic substrate (docs/viscoelastic.md): the walkthrough's run, and steady rolling with creepage
    _cli("run", *FINE, *VISCO, "--set", "motion.speed=47.9", "-o", runs / "visco.h5")
    _cli("run", ROOT / "cases" / "creep_steady.toml", *CREEP, "--set", "materials.E2_relaxed=105e3", "--set",
         "materials.tau2=0.001", "--set", 'materials.visco2="sls"', "--set", "rolling.speed=1000", "-q", "-o",
         runs / "creep.h5")
    # a wheel on a rail (docs/wheelrail.md): one position with two patches, a sweep over the lateral displacement
    wheelrail = ROOT / "cases" / "mbench_s1002_uic60.toml"
    _cli("run", wheelrail, "--set", "wheelrail.y=5.5", "-q", "-o", runs / "y55.h5")
    _cli("sweep", wheelrail, "--vary", "wheelrail.y=0,5.5,10", "-o", root / "sweep_y", "--jobs", "1", "-q")


def draw_all(root: Path, out: Path) -> dict:
    """Every figure the CLI draws from make_inputs' files, into `out`: {figure stem: defects}."""
    runs = root / "runs"
    with checked_figures() as found:
        for name in ("perp", "perp_rat", "md", "visco", "creep", "y55"):
            _cli("plot", runs / f"{name}.h5", "-o", out, "--overwrite")
        _cli("compare", runs / "par.h5", runs / "perp.h5", "-o", out, "--overwrite")
        for folder in ("sweep", "osc_ft", "osc_lim", "cone_sweep", "sweep_y"):
            _cli("plot", root / folder, "-o", out, "--overwrite")
        _cli("creep-curve", ROOT / "cases" / "creep_steady.toml", *CREEP, "--points", "5", "-o", out, "--overwrite")
    return found


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    root = tmp_path_factory.mktemp("figures")
    make_inputs(root)
    return root


@pytest.fixture(scope="module")
def figures(inputs):
    return draw_all(inputs, inputs / "plots")


FAMILIES = {
    "run": ["perp_history", "perp_maps_step", "perp_centrelines_step", "perp_rat_history"],
    "compare": ["compare_par_vs_perp_history", "compare_par_vs_perp_maps", "compare_par_vs_perp_centrelines"],
    "subsurface": ["perp_subsurface_step", "perp_subsurface_maxima"],
    "mindlin_deresiewicz": ["md_history", "md_loads"],
    "sweep": ["sweep_usd", "sweep_limits", "sweep_ratcheting", "sweep_angles"],
    "phase": ["osc_ft_phase", "osc_lim_phase_limits"],
    "shape": ["cone_sweep_usd"],
    "creep": ["creep_maps", "creep_steady_creep_xi"],
    "viscoelastic": ["visco_history", "visco_step", "creep_pressure"],
    "wheelrail": ["y55_wheelrail", "sweep_y_contact_points", "sweep_y_forces"],
}


@pytest.mark.parametrize("family", list(FAMILIES))
def test_no_two_labels_overlap_and_none_is_cut_off(figures, family):
    for prefix in FAMILIES[family]:
        stems = [s for s in figures if s.startswith(prefix)]
        assert stems, (prefix, sorted(figures))
        for stem in stems:
            assert not figures[stem], f"{stem}:\n" + "\n".join(figures[stem])


def test_a_run_without_rolling_is_titled_as_such(inputs):
    from rollcontact.cases.plots.common import open_run
    title = open_run(inputs / "runs" / "md.h5").title
    assert title.startswith("no rolling:") and "Ft" not in title and "cyclic slip" in title
    assert open_run(inputs / "runs" / "perp.h5").title.startswith("W ⊥ Ft:")


def test_cyclic_slip_is_neither_fitted_with_eq_13_nor_drawn_in_fig_8_nor_called_shakedown(inputs, figures):
    """The phase sweep's runs (loads oscillating within the period) include runs in cyclic slip: U settles but the
    contact slips in every period. Seed Eq. 13 (a monotonic ramp, constant loads) describes none of them: no kappa
    is fitted, the seed's Figs. 8, 9, 11 are not drawn for the folder, and the phase map tells cyclic slip apart."""
    from rollcontact.cases.plots.phase_figures import phase_figure, read_phase_points
    from rollcontact.cases.plots.sweep_figures import kappa_fits, read_folder
    points = read_folder(inputs / "osc_ft")
    assert any(p.state == "cyclic_slip" for p in points) and not any(p.on_eq13 for p in points)
    assert kappa_fits(points) == {}
    assert "osc_ft_phase" in figures and not any(s.startswith(("osc_ft_usd", "osc_ft_limits")) for s in figures)
    fig = phase_figure(read_phase_points(sorted((inputs / "osc_ft").glob("*.h5"))), "osc_ft")
    titles = [ax.get_title() for ax in fig.axes]
    assert all("◇ cyclic slip" in t for t in titles if "shakedown" in t)
    import matplotlib.pyplot as plt
    plt.close(fig)


def test_the_check_sees_overlapping_and_cut_off_labels():
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.text(0.5, 0.5, "first label", transform=ax.transAxes)
    ax.text(0.52, 0.5, "second label", transform=ax.transAxes)
    ax.annotate("outside", (1.0, 0.5), xycoords="axes fraction", xytext=(300, 0), textcoords="offset points")
    ax.plot([0, 1], [0.2, 0.2], label="a curve")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.annotate("on the curve", (0.5, 0.2), ha="center", va="center")
    ax.annotate("on the edge", (0.01, 0.9), ha="center")
    with recorded_texts() as drawn:
        fig.canvas.draw()
    plt.close(fig)
    defects = label_defects(drawn)
    assert any("'first label' overlaps 'second label'" in d for d in defects)
    assert any("'outside' is cut off" in d for d in defects)
    assert "'on the curve' is drawn over 'a curve'" in defects
    assert "'on the edge' crosses the frame of its axes" in defects
    assert not any(d.startswith(("'second label' overlaps", "'on the edge' overlaps")) for d in defects)
