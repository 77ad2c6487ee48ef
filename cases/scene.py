"""Scenes: a TOML file <-> a `Scene` dataclass, validated key by key.

Units: mm, N, MPa, degrees. Sections and keys (public contract, see README):

    [materials] E1, nu1 (sphere; E1 = inf for a rigid sphere), E2, nu2 (substrate)
    [geometry]  R, or Rx and Ry (radii of the profile h = x^2/2Rx + y^2/2Ry)
    [load]      Fn; mu; ft (= Ft/(mu Fn)) or Ft; load_angle (direction of Ft from the x axis);
                ramp_steps (increments from 0 to Ft); levels (further f_t levels, each reached in
                ramp_steps increments: unloading and reversal)
    [motion]    w (= W/a) or W; angle (rolling direction relative to Ft); periods; dW
    [grid]      dx, dy, margin
    [solver]    tol, max_iter, fidelity ("bem" or "mdr"), threads, coupling, shakedown_tol
    [output]    fields ("reversals", "all", "last", "none")

A key left out takes its default (the field specs below): the seed paper's materials, Fn, mu and rolling
angle, but no tangential load and no motion; only [geometry] is required. So a scene file states only what
its scene needs (the README's scene-key table lists the defaults). Unknown keys, wrong types and
out-of-range values raise `SceneError` naming the key, the value and the allowed range; so do, for a new
run, a grid coarser than MIN_ELEMENTS_PER_RADIUS elements per Hertz semi-axis and a path of more than
MAX_STEPS steps.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
import math
from pathlib import Path
import tomllib
from importlib import resources

from bem.errors import SceneError
from bem.materials import MaterialPair

INF = math.inf


def _spec(default, lo=None, hi=None, *, lo_open=False, hi_open=False, choices=None, unit="", doc=""):
    """Field with its allowed range kept in the metadata, so validation and docs share one table."""
    meta = dict(lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, choices=choices, unit=unit, doc=doc)
    if isinstance(default, list):
        return field(default_factory=lambda: list(default), metadata=meta)
    return field(default=default, metadata=meta)


@dataclass
class Materials:
    E1: float = _spec(206e3, 0, INF, lo_open=True, unit="MPa", doc="sphere Young's modulus (inf: rigid)")
    nu1: float = _spec(0.3, -1, 0.5, lo_open=True, doc="sphere Poisson ratio")
    E2: float = _spec(4.35, 0, INF, lo_open=True, hi_open=True, unit="MPa", doc="substrate Young's modulus")
    nu2: float = _spec(0.5, -1, 0.5, lo_open=True, doc="substrate Poisson ratio")


@dataclass
class Geometry:
    R: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="sphere radius")
    Rx: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="radius in x")
    Ry: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="radius in y")


@dataclass
class Load:
    Fn: float = _spec(21.19, 0, INF, lo_open=True, hi_open=True, unit="N", doc="normal force")
    # from 1e-6: the tangential problem scales with mu, but squared tractions underflow far below it (mu = 1e-200
    # gave u_stat 1.6 % off, silently)
    mu: float = _spec(0.93, 1e-6, 10, doc="friction coefficient")
    ft: float | None = _spec(None, 0, 1, doc="tangential force / (mu Fn)")
    Ft: float | None = _spec(None, 0, INF, hi_open=True, unit="N", doc="tangential force")
    load_angle: float = _spec(0.0, -360, 360, unit="deg", doc="direction of Ft from the x axis")
    ramp_steps: int = _spec(1, 1, 10000, doc="increments from 0 to Ft")
    levels: list = _spec([], -1, 1, doc="further f_t levels after the ramp (unloading, reversal)")


@dataclass
class Motion:
    # no upper bound, as for W (w = 2 rolls two radii each way; the MDR limits of the seed hold for w <= 1)
    w: float | None = _spec(None, 0, INF, hi_open=True, doc="amplitude / contact radius a")
    W: float | None = _spec(None, 0, INF, hi_open=True, unit="mm", doc="amplitude of the centre")
    angle: float = _spec(90.0, -360, 360, unit="deg", doc="rolling direction relative to Ft")
    periods: int = _spec(10, 0, 100000, doc="oscillation periods")
    dW: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                             doc="largest rolling step (default: the element size dx)")


@dataclass
class GridSpec:
    dx: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                             doc="element size in x (default: the smaller Hertz semi-axis / 12, 2 digits)")
    dy: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="element size in y (default dx)")
    margin: float = _spec(0.6, 0, INF, hi_open=True, unit="mm",
                          doc="extra width around the swept contact (at least one element is kept)")


@dataclass
class SolverSpec:
    tol: float = _spec(1e-8, 0, 1e-2, lo_open=True, doc="relative tolerance of the contact solvers")
    max_iter: int = _spec(500, 1, 1000000, doc="iteration budget per solve")
    fidelity: str = _spec("bem", choices=("bem", "mdr"), doc="3D boundary elements or the 1D MDR model")
    threads: int = _spec(1, 1, 256, doc="FFTW threads")
    coupling: str = _spec("auto", choices=("auto", "on", "off"), doc="normal-tangential coupling")
    shakedown_tol: float = _spec(1e-4, 0, 1, lo_open=True, doc="per-period increment |dU|/U0 taken as shakedown")


@dataclass
class Output:
    fields: str = _spec("reversals", choices=("reversals", "all", "last", "none"),
                        doc="steps whose fields are stored")


#: Elements per contact radius when a scene leaves grid.dx out (motion.dW then defaults to dx). The
#: cheapest resolution whose shakedown displacement u_sd stays within 1 % of the converged value over the
#: seed's Fig. 8 family (its 32 shaken-down runs, both alignments: worst 0.20 %); a/dx = 6 is within 1 % at
#: the paper's point but 1.37 % off at f_t = 0.1 (benchmarks/default_resolution.py, benchmarks/README.md).
RESOLUTION_PER_RADIUS = 12


#: Fewest elements per Hertz contact semi-axis a grid may have ([grid] dx, dy <= a/3). a/dx = 3 is the coarsest
#: resolution benchmarks/stability.py verifies (Hertz + Cattaneo converge, approach within 0.1 %); on coarser
#: grids the discrete contact (a few elements) is not a useful approximation of the Hertz ellipse, and with
#: dx > a the grid sized for the contact is so small that the run stops at once with ContactEdgeError,
#: whose advice (a larger grid.margin) misses the cause.
MIN_ELEMENTS_PER_RADIUS = 3

#: Most steps (loading + rolling) one run may take. Generous: the seed's runs take ~250 steps, and a step
#: costs at least a few ms on the smallest grids (~10 ms on the paper's 55 x 65), so 1e6 steps are hours of
#: computing, while the load path and the history of 1e6 steps need only ~200 MB. Beyond it a typo such as
#: dW = 1e-9 would only show up as a MemoryError (tens of GiB) while the path is built.
MAX_STEPS = 1_000_000


def _round_sig(x: float, digits: int) -> float:
    return float(f"{x:.{digits}g}")


SECTIONS = {"materials": Materials, "geometry": Geometry, "load": Load, "motion": Motion,
            "grid": GridSpec, "solver": SolverSpec, "output": Output}
_ATTR = {"materials": "materials", "geometry": "geometry", "load": "load", "motion": "motion",
         "grid": "grid", "solver": "solver", "output": "output"}


@dataclass
class Scene:
    """A complete, validated scene. Build it with `Scene.from_toml`, `Scene.from_dict` or `default_scene`."""

    materials: Materials = field(default_factory=Materials)
    geometry: Geometry = field(default_factory=Geometry)
    load: Load = field(default_factory=Load)
    motion: Motion = field(default_factory=Motion)
    grid: GridSpec = field(default_factory=GridSpec)
    solver: SolverSpec = field(default_factory=SolverSpec)
    output: Output = field(default_factory=Output)
    name: str = "scene"
    #: keys filled in by `_resolve_resolution` ("grid.dx", "motion.dW"); `with_overrides` re-derives them
    derived: frozenset = field(default=frozenset(), repr=False, compare=False)

    # --- construction ----------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, name: str = "scene", run_limits: bool = True) -> "Scene":
        """run_limits=False skips the checks that only a new run needs (grid resolution, number of steps), for
        reading the scene stored in a run file written before those checks existed."""
        if not isinstance(data, dict):
            raise SceneError("scene: expected a table of sections")
        unknown = set(data) - set(SECTIONS)
        if unknown:
            raise SceneError(f"scene: unknown section(s) {sorted(unknown)}; allowed: {list(SECTIONS)}")
        parts = {}
        for sec, klass in SECTIONS.items():
            values = data.get(sec, {})
            if not isinstance(values, dict):
                raise SceneError(f"[{sec}] must be a table of keys, got {values!r}")
            names = {f.name: f for f in fields(klass)}
            unknown = set(values) - set(names)
            if unknown:
                raise SceneError(f"[{sec}] unknown key(s) {sorted(unknown)}; allowed: {sorted(names)}")
            kwargs = {k: _check(sec, names[k], v) for k, v in values.items()}
            parts[sec] = klass(**kwargs)
        scene = cls(**parts, name=name)
        scene._check_consistency()
        scene._resolve_resolution()
        if run_limits:
            scene._check_resolution()
            scene._check_steps()
        return scene

    @classmethod
    def from_toml(cls, path) -> "Scene":
        path = Path(path)
        try:
            text = path.read_text()
        except OSError as exc:
            raise SceneError(f"scene file {path}: {exc.strerror}") from None
        return cls.from_toml_text(text, name=path.stem)

    @classmethod
    def from_toml_text(cls, text: str, name: str = "scene", run_limits: bool = True) -> "Scene":
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError(f"scene {name}: not valid TOML ({exc})") from None
        return cls.from_dict(data, name=name, run_limits=run_limits)

    def to_dict(self, include_none: bool = False) -> dict:
        out = {}
        for sec in SECTIONS:
            obj = getattr(self, _ATTR[sec])
            vals = {f.name: getattr(obj, f.name) for f in fields(obj)}
            out[sec] = {k: v for k, v in vals.items() if include_none or v is not None}
        return out

    def to_toml(self) -> str:
        """The full scene as TOML text (every key, None-valued alternatives left out)."""
        lines = [f"# rollcontact scene '{self.name}' (units: mm, N, MPa, degrees)"]
        for sec, vals in self.to_dict().items():
            lines.append(f"\n[{sec}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in vals.items()]
        return "\n".join(lines) + "\n"

    def with_overrides(self, assignments) -> "Scene":
        """A new scene with `section.key=value` strings applied (values parsed as TOML, else as strings)."""
        data = self.to_dict()
        for key in self.derived:  # re-derived from the overridden scene unless set explicitly
            sec, name = key.split(".")
            data[sec].pop(name, None)
        for item in assignments:
            if "=" not in item or "." not in item.split("=", 1)[0]:
                raise SceneError(f"--set {item!r}: expected section.key=value, e.g. load.ft=0.5")
            key, raw = item.split("=", 1)
            sec, name = key.strip().split(".", 1)
            if sec not in SECTIONS:
                raise SceneError(f"--set {item!r}: unknown section {sec!r}; allowed: {list(SECTIONS)}")
            value = _parse_value(raw.strip())
            section = data.setdefault(sec, {})
            for a, b in (("ft", "Ft"), ("w", "W"), ("R", "Rx"), ("R", "Ry")):
                if name == a:
                    section.pop(b, None)
                elif name == b:
                    section.pop(a, None)
            section[name] = value
        return Scene.from_dict(data, name=self.name)

    def _check_consistency(self):
        g, ld, mo = self.geometry, self.load, self.motion
        if g.R is not None and (g.Rx is not None or g.Ry is not None):
            raise SceneError("[geometry] give either R, or Rx and Ry, not both")
        if g.R is None and (g.Rx is None) != (g.Ry is None):
            raise SceneError("[geometry] Rx and Ry must be given together")
        if g.R is None and g.Rx is None:
            raise SceneError("[geometry] R (or Rx and Ry) is required, in mm")
        if ld.ft is not None and ld.Ft is not None:
            raise SceneError("[load] give either ft (= Ft/(mu Fn)) or Ft (N), not both")
        if ld.Ft is not None and ld.Ft > ld.mu * ld.Fn * (1 + 1e-12):
            raise SceneError(f"[load] Ft = {ld.Ft} N exceeds mu*Fn = {ld.mu * ld.Fn:.6g} N: gross sliding, "
                             "no static state exists (allowed range 0 <= Ft <= mu*Fn)")
        if mo.w is not None and mo.W is not None:
            raise SceneError("[motion] give either w (= W/a) or W (mm), not both")

    def _resolve_resolution(self):
        """Fill an omitted grid.dx and motion.dW with the recommended resolution (RESOLUTION_PER_RADIUS)."""
        derived = set()
        if self.grid.dx is None:
            self.grid = replace(self.grid, dx=_round_sig(min(self.semi_axes) / RESOLUTION_PER_RADIUS, 2))
            derived.add("grid.dx")
        if self.motion.dW is None:
            self.motion = replace(self.motion, dW=self.grid.dx)
            derived.add("motion.dW")
        self.derived = frozenset(derived)

    def _check_resolution(self):
        """Each Hertz semi-axis spans at least MIN_ELEMENTS_PER_RADIUS elements (BEM only: MDR has no grid)."""
        if self.solver.fidelity != "bem":
            return
        (sx, sy), (dx, dy) = self.semi_axes, self.spacing
        key_y = "dy" if self.grid.dy is not None else "dx"
        for key, semi, h, axis in (("dx", sx, dx, "x"), (key_y, sy, dy, "y")):
            if semi / h < MIN_ELEMENTS_PER_RADIUS:
                what = "contact radius a" if sx == sy else f"contact semi-axis along {axis}"
                raise SceneError(
                    f"[grid] {key} = {h!r} mm: the Hertz {what} = {semi:.4g} mm spans {semi / h:.2g} elements; "
                    f"allowed range is 0 < {key} <= {semi / MIN_ELEMENTS_PER_RADIUS:.4g} mm for this scene (at "
                    f"least {MIN_ELEMENTS_PER_RADIUS} elements per semi-axis; leave grid.dx out for the "
                    f"recommended a/{RESOLUTION_PER_RADIUS})")

    def _check_steps(self):
        """The load path has at most MAX_STEPS steps (mirrors solver.stepping.build_path)."""
        ld, mo = self.load, self.motion
        n_load = 1 + ld.ramp_steps * ((1 if self.Ft > 0 else 0) + len(ld.levels))
        if n_load > MAX_STEPS:
            raise SceneError(f"[load] ramp_steps = {ld.ramp_steps} with {len(ld.levels)} levels: {n_load} loading "
                             f"steps exceed the limit of {MAX_STEPS} steps per run; allowed range is ramp_steps "
                             f"<= {(MAX_STEPS - 1) // (1 + len(ld.levels))}")
        W = self.amplitude
        if not (W > 0 and mo.periods > 0):
            return
        ratio = W / mo.dW
        given = "" if mo.W is not None else f" (= w a, a = {self.contact_radius:.4g} mm)"
        if not math.isfinite(ratio):  # W / dW overflowed: math.ceil would raise
            raise SceneError(f"[motion] W = {W:.5g} mm{given} with dW = {mo.dW!r} mm needs {ratio:.3g} steps "
                             f"per quarter period; allowed range is W <= {MAX_STEPS * mo.dW / 4:.4g} mm at this "
                             f"dW (at most {MAX_STEPS} steps per run)")
        per_quarter = math.ceil(ratio - 1e-9)
        n = n_load + 4 * per_quarter * mo.periods
        if n <= MAX_STEPS:
            return
        ranges = []
        most_per_quarter = (MAX_STEPS - n_load) // (4 * mo.periods)
        if most_per_quarter >= 1:
            ranges.append(f"dW >= {W / most_per_quarter:.4g} mm at these periods")
        most_periods = (MAX_STEPS - n_load) // (4 * per_quarter)
        if most_periods >= 1:
            ranges.append(f"periods <= {most_periods} at this dW")
        raise SceneError(
            f"[motion] dW = {mo.dW!r} mm, periods = {mo.periods}: {n} steps ({mo.periods} periods x 4 x "
            f"ceil(W/dW) = {per_quarter} with W = {W:.5g} mm{given}, plus {n_load} loading steps) exceed the "
            f"limit of {MAX_STEPS} steps per run; allowed range is " + (", or ".join(ranges) or "a larger dW"))

    # --- derived quantities ----------------------------------------------------------------------
    @property
    def material_pair(self) -> MaterialPair:
        m = self.materials
        return MaterialPair.from_moduli(m.E1, m.nu1, m.E2, m.nu2)

    @property
    def radii(self) -> tuple[float, float]:
        g = self.geometry
        return (g.R, g.R) if g.R is not None else (g.Rx, g.Ry)

    @property
    def equivalent_radius(self) -> float:
        """sqrt(Rx Ry) (mm): the radius of the sphere with the same Gaussian curvature."""
        rx, ry = self.radii
        return math.sqrt(rx) * math.sqrt(ry)  # not sqrt(rx ry): that overflows from rx ry > 1e308

    @property
    def contact_radius(self) -> float:
        """Hertz contact radius a of the equivalent sphere (mm), the unit of w."""
        return (3.0 * self.load.Fn * self.equivalent_radius / (4.0 * self.material_pair.E_star)) ** (1 / 3)

    @property
    def semi_axes(self) -> tuple[float, float]:
        """Hertz semi-axes (mm) along x and y: exact for a sphere, c (Rx/Ry)^(+-1/3) for an ellipse."""
        rx, ry = self.radii
        c = self.contact_radius
        return (c, c) if rx == ry else (c * (rx / ry) ** (1 / 3), c * (ry / rx) ** (1 / 3))

    @property
    def f_t(self) -> float:
        ld = self.load
        if ld.Ft is not None:
            return ld.Ft / (ld.mu * ld.Fn)
        return 0.0 if ld.ft is None else ld.ft

    @property
    def Ft(self) -> float:
        """Tangential force magnitude (N)."""
        return self.f_t * self.load.mu * self.load.Fn

    @property
    def amplitude(self) -> float:
        """Rolling amplitude W (mm)."""
        mo = self.motion
        if mo.W is not None:
            return mo.W
        return 0.0 if mo.w is None else mo.w * self.contact_radius

    @property
    def rolling_step(self) -> float:
        """Step actually used, W/ceil(W/dW) (mm), so that the reversal points are hit exactly."""
        W = self.amplitude
        return W / math.ceil(W / self.motion.dW - 1e-9) if W > 0 else 0.0

    @property
    def load_direction(self) -> tuple[float, float]:
        t = math.radians(self.load.load_angle)
        return (math.cos(t), math.sin(t))

    @property
    def rolling_direction(self) -> tuple[float, float]:
        t = math.radians(self.load.load_angle + self.motion.angle)
        return (math.cos(t), math.sin(t))

    @property
    def spacing(self) -> tuple[float, float]:
        return self.grid.dx, (self.grid.dy if self.grid.dy is not None else self.grid.dx)

    def replace(self, **sections) -> "Scene":
        return replace(self, **sections)


def _check(sec, f, value):
    """Validate one key against its field spec; return the (possibly converted) value."""
    meta, key = f.metadata, f"[{sec}] {f.name}"
    unit = f" {meta['unit']}" if meta.get("unit") else ""
    if meta.get("choices"):
        if value not in meta["choices"]:
            raise SceneError(f"{key} = {value!r}: allowed values are {list(meta['choices'])}")
        return value
    if f.name == "levels":
        if not isinstance(value, list) or not all(_is_number(v) for v in value):
            raise SceneError(f"{key} = {value!r}: expected a list of f_t values in [-1, 1]")
        for v in value:
            _range(key, float(v), meta, unit)
        return [float(v) for v in value]
    want_int = f.type in ("int",)
    if want_int:
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            else:
                raise SceneError(f"{key} = {value!r}: expected an integer")
    elif not _is_number(value):
        raise SceneError(f"{key} = {value!r}: expected a number{unit and ' in' + unit}")
    else:
        value = float(value)
    if isinstance(value, float) and math.isnan(value):
        raise SceneError(f"{key} = nan: expected a number")
    _range(key, value, meta, unit)
    return value


def _range(key, value, meta, unit):
    lo, hi = meta.get("lo"), meta.get("hi")
    bad_lo = lo is not None and (value <= lo if meta["lo_open"] else value < lo)
    bad_hi = hi is not None and (value >= hi if meta["hi_open"] else value > hi)
    if bad_lo or bad_hi:
        left = "(" if meta["lo_open"] else "["
        right = ")" if meta["hi_open"] else "]"
        raise SceneError(f"{key} = {value!r}{unit}: allowed range is {left}{lo}, {hi}{right}{unit}")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _parse_value(raw: str):
    """A --set value: TOML, else a number as Python writes it (.5, 1., 1e3: not TOML), else the text."""
    try:
        return tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        pass
    try:
        return float(raw)  # a NaN is refused with the key by the field check, like TOML's nan
    except ValueError:
        return raw


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return str(v)


def key_unit(key: str) -> str:
    """Unit of a scene key 'section.name' as written in HDF5 `units` attributes ('-': dimensionless or
    not a quantity; also for a key that is not a scene key)."""
    sec, _, name = key.partition(".")
    for f in fields(SECTIONS[sec]) if sec in SECTIONS else ():
        if f.name == name:
            return f.metadata.get("unit") or "-"
    return "-"


DEFAULT_SCENE_FILE = "paper_perpendicular.toml"


def shipped_scene_path(name: str) -> Path:
    """Path of a scene file shipped in the `cases` package."""
    return Path(str(resources.files("cases").joinpath(name)))


def default_scene() -> Scene:
    """The embedded default: the seed paper's Table 1 (perpendicular setting, f_t = 0.46, w = 0.23)."""
    return Scene.from_toml(shipped_scene_path(DEFAULT_SCENE_FILE))
