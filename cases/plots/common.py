"""Shared pieces of the figures (`run_figures`, `sweep_figures` and the others of `cases.plots`): reading a run for plotting, normalisations,
colours, the seed's contact regions, centre-line sampling and saving.

Normalisations (seed Eq. 9 with the consistent constants, docs/theory.md §8.2 and docs/theory.md P3):
u = U/U0 with U0 = mu E* d/G* (U measured along Ft), f_t = Ft/(mu Fn), w = W/a, tractions over mu p0,
pressures in MPa, coordinates in mm. Sign conventions as in docs/theory.md §0: tau is the traction exerted by the
sphere on the substrate, u_x the displacement of the substrate surface relative to the sphere.

Colours are fixed across every figure: parallel (rolling along Ft) blue, perpendicular red, other angles in
between; the pure-MDR reference (kappa = 3/2) grey.
"""
from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rollcontact.bem.errors import InputError, OutputExistsError  # noqa: E402

from rollcontact.cases.arguments import arg, flag, on_command_line  # noqa: E402
from rollcontact.cases.results.hdf5 import read_run_file  # noqa: E402
from rollcontact.cases.results.writing import write_failed  # noqa: E402
from rollcontact.cases.results.run_result import RunResult  # noqa: E402
from rollcontact.cases.results.outputs import output_folder  # noqa: E402
from rollcontact.cases.scene.scene import Scene  # noqa: E402

PARALLEL_COLOUR = "#1f5fa8"        # W parallel to Ft (seed "(1)")
PERPENDICULAR_COLOUR = "#c8312b"   # W perpendicular to Ft (seed "(2)")
MDR_COLOUR = "0.45"                # pure MDR, kappa = 3/2 (seed Eq. 12)
DPI = 120                          # PNG resolution; PDFs are vector
#: Figure sizes (inches); PNGs are FIGSIZE * DPI pixels (no tight bounding box, so the size is predictable).
FIGSIZE = {"history": (8, 6), "maps": (14, 8.5), "centrelines": (12, 7.5), "compare_maps": (24, 11.5),
           "usd": (9, 6.5), "limits": (8, 6.5), "ratcheting": (8, 6)}
BOUND_TOL = 0.98                   # |tau| >= BOUND_TOL mu p_min counts as "at the bound" (region II)

#: Seed regions of the shaken-down contact (Sect. 3.2) plus slip and no contact; codes of `seed_regions`.
REGION_NAMES = ("no contact", "stick (I)", "stick at $\\mu p_{min}$ (II)", "released in period, $\\tau$=0 (III)",
                "slip")
REGION_COLOURS = ("#f2f2f2", "#3b7dd8", "#8fd18a", "#f0c24b", "#d9412b")


class PlotError(InputError):
    """A plotting input is unusable (missing file, not a run file, step not stored); exit code 2."""


# ------------------------------------------------------------------------------------------ run data
@dataclass
class RunView:
    """One run file, with the normalisations and labels the figures need."""

    path: Path
    data: RunResult
    scene: Scene

    # --- scalars -------------------------------------------------------------------------------
    def _s(self, key, default=None):
        v = self.data.summary.get(key, default)
        return None if isinstance(v, str) and v == "none" else v

    @property
    def U0(self) -> float:
        return float(self._s("U0"))

    @property
    def a(self) -> float:
        return float(self._s("a"))

    @property
    def p0(self) -> float:
        return float(self._s("p0"))

    @property
    def mu(self) -> float:
        return float(self.scene.load.mu)

    @property
    def f_t(self) -> float:
        return float(self._s("f_t", self.scene.f_t))

    @property
    def w(self) -> float:
        return float(self._s("w", 0.0))

    @property
    def state(self) -> str:
        return str(self._s("state", "?"))

    @property
    def u_sd(self):
        v = self._s("u_sd")
        return None if v is None else float(v)

    @property
    def u_stat(self):
        v = self._s("u_stat")
        return None if v is None else float(v)

    @property
    def du(self):
        v = self._s("du")
        return None if v is None else float(v)

    @property
    def angle(self) -> float:
        """Rolling direction relative to Ft (deg), folded to 0..90."""
        t = float(self.scene.motion.angle) % 180.0
        return 180.0 - t if t > 90.0 else t

    @property
    def setting(self) -> str:
        """'parallel', 'perpendicular' or 'angle NN deg'."""
        return setting_of(self.angle)

    @property
    def is_mdr(self) -> bool:
        return self.scene.solver.fidelity == "mdr" or self._s("fidelity") == "mdr"

    @property
    def colour(self):
        return setting_colour(self.angle)

    @property
    def label(self) -> str:
        """The rolling setting ('W ∥ Ft', 'W ⊥ Ft', 'W at 30° to Ft'), or 'no rolling' for w = 0."""
        if self.w == 0:
            s = "no rolling"
        else:
            s = "W ∥ Ft" if self.setting == "parallel" else "W ⊥ Ft" if self.setting == "perpendicular" \
                else f"W at {self.angle:g}° to Ft"
        return s + (" (MDR 1-D)" if self.is_mdr else "")

    @property
    def title(self) -> str:
        return f"{self.label}:  $f_t$ = {self.f_t:.3g}, $w$ = {self.w:.3g}  ({self.state.replace('_', ' ')})"

    # --- history ---------------------------------------------------------------------------------
    @property
    def e_f(self) -> np.ndarray:
        return np.array(self.scene.load_direction)

    @property
    def e_r(self) -> np.ndarray:
        return np.array(self.scene.rolling_direction)

    def u(self) -> np.ndarray:
        """Rigid shift along Ft over U0, one value per step."""
        h = self.data.history
        return (np.asarray(h["U_x"]) * self.e_f[0] + np.asarray(h["U_y"]) * self.e_f[1]) / self.U0

    def steps_per_period(self) -> int:
        return int(np.count_nonzero(np.asarray(self.data.history["period"]) == 1))

    def periods(self) -> np.ndarray:
        """Time axis in periods: 0 at the end of the loading phase (negative during loading)."""
        h = self.data.history
        step, period = np.asarray(h["step"], float), np.asarray(h["period"])
        n = self.steps_per_period()
        loaded = np.flatnonzero(period == 0)
        i_load = step[loaded[-1]] if len(loaded) else 0.0
        return (step - i_load) / n if n else step - i_load

    def centre(self, step: int) -> np.ndarray:
        """Sphere centre (mm) at `step`."""
        h = self.data.history
        k = int(np.flatnonzero(np.asarray(h["step"]) == step)[0])
        return np.array([h["W_x"][k], h["W_y"][k]], dtype=float)

    # --- fields ----------------------------------------------------------------------------------
    @property
    def stored_steps(self) -> list[int]:
        return [int(s) for s in np.asarray(self.data.field_steps)]

    @property
    def has_fields(self) -> bool:
        return bool(self.stored_steps) and "p" in self.data.fields and not self.is_mdr

    def no_fields_note(self) -> str:
        why = ("the 1-D MDR model has no 2-D fields" if self.is_mdr
               else f"output.fields = '{self.scene.output.fields}' stored no field snapshots")
        return f"{self.path}: {why}; only the history figure is drawn"

    def resolve_step(self, step: int | None) -> int:
        """The stored step to draw (default: the last stored); PlotError listing the stored steps."""
        steps = self.stored_steps
        if not steps:
            raise PlotError(self.no_fields_note())
        if step is None:
            return steps[-1]
        if int(step) not in steps:
            raise PlotError(f"{self.path}: fields of step {step} were not stored; stored steps: "
                            f"{_compact(steps)}")
        return int(step)

    def field(self, name: str, step: int) -> np.ndarray:
        return self.data.fields[name][self.stored_steps.index(step)]

    def normalised_fields(self, step: int) -> dict:
        """p (MPa), tau_x/mu p0, tau_y/mu p0, u_x/U0, u_y/U0 and the contact mask at `step`."""
        mp0 = self.mu * self.p0
        p = self.field("p", step)
        return dict(p=p, tau_x=self.field("tau_x", step) / mp0, tau_y=self.field("tau_y", step) / mp0,
                    u_x=self.field("u_x", step) / self.U0, u_y=self.field("u_y", step) / self.U0,
                    contact=p > 0)

    def window(self, step: int) -> list[int]:
        """Stored steps of the period ending at `step` (both reversal points included), else []."""
        n = self.steps_per_period()
        if not n or self.is_mdr:
            return []
        steps = [s for s in self.stored_steps if step - n <= s <= step]
        W = float(self._s("W", 0.0))
        along = [float(self.centre(s) @ self.e_r) for s in steps]
        tol = 1e-6 * max(W, 1.0)
        if W > 0 and any(abs(v - W) < tol for v in along) and any(abs(v + W) < tol for v in along):
            return steps
        return []

    def p_min(self, step: int):
        """Smallest pressure (MPa) over the period ending at `step` (from the stored snapshots), or None."""
        steps = self.window(step)
        if not steps:
            return None
        return np.min([self.field("p", s) for s in steps], axis=0)

    def regions(self, step: int) -> tuple[np.ndarray, bool]:
        """Region codes at `step` (see REGION_NAMES) and whether the seed's I/II/III could be told apart."""
        return seed_regions(self.field("region", step), self.field("p", step), self.field("tau_x", step),
                            self.field("tau_y", step), self.mu, self.p_min(step))


def seed_regions(region, p, tau_x, tau_y, mu, p_min):
    """Seed Sect. 3.2 regions at one step: 0 no contact, 1 stick (I), 2 stick at mu p_min (II),
    3 in contact but released during the last period so tau = 0 (III), 4 slip.

    Without p_min (no full period stored before the step) stick elements are all code 1.
    Returns (codes int8 (ny, nx), True if I/II/III were distinguished).
    """
    codes = np.zeros(region.shape, dtype=np.int8)
    contact = p > 0
    codes[contact] = 1
    if p_min is not None:
        tau = np.hypot(tau_x, tau_y)
        released = contact & (p_min <= 0)
        at_bound = contact & (p_min > 0) & (tau >= BOUND_TOL * mu * p_min)
        codes[at_bound] = 2
        codes[released] = 3
    codes[contact & (region == 2)] = 4
    return codes, p_min is not None


def open_run(path) -> RunView:
    """Read a run file for plotting; PlotError for a missing file or a file that is not a run file."""
    path = Path(path)
    data = read_run_file(path, PlotError, str(path))
    scene = Scene.from_toml_text(data.scene_toml, name=path.stem, run_limits=False)
    view = RunView(path, data, scene)
    if "U0" not in data.summary or len(data.history.get("step", [])) == 0:
        raise PlotError(f"{path}: the run file has no summary or no steps (status '{data.status}'"
                        f"{': ' + data.error if data.error else ''})")
    return view


# ------------------------------------------------------------------------------------------ helpers
def setting_of(angle: float) -> str:
    if abs(angle) < 1e-9:
        return "parallel"
    if abs(angle - 90.0) < 1e-9:
        return "perpendicular"
    return f"angle {angle:g} deg"


def setting_colour(angle: float):
    """Blue (parallel) to red (perpendicular), linear in sin^2(angle)."""
    t = math.sin(math.radians(angle)) ** 2
    c0, c1 = np.array(matplotlib.colors.to_rgb(PARALLEL_COLOUR)), np.array(
        matplotlib.colors.to_rgb(PERPENDICULAR_COLOUR))
    return tuple((1 - t) * c0 + t * c1)


def centre_line(view: RunView, values: np.ndarray, step: int, direction, order=1):
    """Values along the line through the sphere centre at `step` in `direction` (unit 2-vector).

    Sampled at the grid spacing (cell centres when the line is a grid row/column), linear interpolation
    (order=1) or nearest (order=0). Returns s (mm, from the centre) and the values (NaN off the grid).
    """
    from scipy.ndimage import map_coordinates
    x, y = view.data.x, view.data.y
    dx, dy = x[1] - x[0], y[1] - y[0]
    d = np.asarray(direction, float) / np.hypot(*direction)
    ds = abs(d[0]) * dx + abs(d[1]) * dy
    half = 0.5 * math.hypot(x[-1] - x[0], y[-1] - y[0])
    s = ds * np.arange(-math.ceil(half / ds), math.ceil(half / ds) + 1)
    c = view.centre(step)
    px, py = c[0] + s * d[0], c[1] + s * d[1]
    ix, iy = (px - x[0]) / dx, (py - y[0]) / dy
    inside = (ix >= -1e-9) & (ix <= len(x) - 1 + 1e-9) & (iy >= -1e-9) & (iy <= len(y) - 1 + 1e-9)
    v = map_coordinates(np.asarray(values, float), [iy, ix], order=order, mode="nearest")
    v[~inside] = np.nan
    return s[inside], v[inside]


def save_figure(fig, out_dir, stem, overwrite=False) -> list[Path]:
    """Write `stem`.png (DPI) and `stem`.pdf into out_dir, each through a temporary file renamed into place;
    returns both paths. An existing one is not replaced unless `overwrite` (OutputExistsError naming it and
    --overwrite; the figure is then not written at all); OutputWriteError naming the file when it cannot be written.
    Inside `all_or_none()` the two files are renamed into place only when the whole block succeeds."""
    out_dir = output_folder(out_dir)
    paths = [out_dir / f"{stem}.png", out_dir / f"{stem}.pdf"]
    existing = [p for p in paths if p.exists()]
    if existing and not overwrite:
        plt.close(fig)
        raise OutputExistsError(f"{existing[0]}: exists; rollcontact does not replace a file unless asked: "
                                f"{'add ' if on_command_line() else 'pass '}{flag('overwrite')}, or give another "
                                f"folder with {arg('output')}")
    pending = _batch.get()
    try:
        _render(fig, paths[0], pending, dpi=DPI)
        fig.set_layout_engine("none")       # keep the layout just computed: the PDF needs no second pass
        _render(fig, paths[1], pending)
    finally:
        plt.close(fig)
    return paths


def _render(fig, path: Path, pending, **kwargs):
    """The figure into `path` (through its temporary file; kept in `pending` for all_or_none's rename)."""
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        fig.savefig(tmp, format=path.suffix[1:], **kwargs)
        if pending is None:
            os.replace(tmp, path)
        else:
            pending.append((tmp, path))
            tmp = None
    except OSError as exc:
        raise write_failed(path, exc, "figure") from None
    finally:
        if tmp is not None:
            _unlink(tmp)


_batch = ContextVar("rollcontact_figure_batch", default=None)


@contextmanager
def all_or_none():
    """The figures saved inside (save_figure) are renamed into place together when the block ends without an error;
    after an error (a step not stored, a figure that exists, a full disk) none is, and their temporary files go: a
    command that refuses or fails leaves no figure of its own behind."""
    pending = []
    token = _batch.set(pending)
    try:
        yield
        for tmp, path in pending:
            try:
                os.replace(tmp, path)
            except OSError as exc:
                raise write_failed(path, exc, "figure") from None
    finally:
        _batch.reset(token)
        for tmp, _ in pending:
            _unlink(tmp)


def _unlink(path: Path):
    try:
        path.unlink(missing_ok=True)
    except OSError:
        pass


def _compact(steps) -> str:
    """'1, 7, 19, ... 241 (31 steps)' for long lists."""
    steps = list(steps)
    if len(steps) <= 40:
        return ", ".join(map(str, steps))
    return ", ".join(map(str, steps[:8])) + ", ..., " + ", ".join(map(str, steps[-3:])) + f" ({len(steps)} steps)"
