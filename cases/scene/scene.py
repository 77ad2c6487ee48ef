"""Scenes: a TOML file <-> a `Scene` dataclass, validated key by key.

Units: mm, N, MPa, degrees, s (mm/s for speeds). Sections and keys (public contract, see README):

    [materials] E1, nu1 (sphere; E1 = inf for a rigid sphere), E2, nu2 (substrate)
    [geometry]  R, or Rx and Ry (radii of the profile h = x^2/2Rx + y^2/2Ry), or shape with its keys:
                cone (slope), power (n, R), flat_rounded (b, R) (cases.scene.geometry)
    [load]      Fn; mu; ft (= Ft/(mu Fn)) or Ft; load_angle (direction of Ft from the x axis);
                ramp_steps (increments from 0 to Ft); levels (further f_t levels, each reached in
                ramp_steps increments: unloading and reversal); ft_amplitude, fn_amplitude, phase,
                cycles_per_period (loads oscillating within each period, docs/oscillating_loads.md)
    [motion]    w (= W/a) or W; angle (rolling direction relative to Ft); periods; dW; steps_per_period; speed (mm/s)
    [rolling]   mode ("steady", "transient"), xi, eta (or Fx, Fy in N), phi (1/mm), direction; distance, step
                (mm) and initial ("rest", "cattaneo") of a transient; speed (mm/s): rolling on with creepage and
                spin, in place of [motion] and a tangential load (Kalker's convention, solver.creep)
    [friction]  law and its keys: a friction law in place of load.mu (cases.scene.friction, docs/friction.md)
    [thermal]   conductivity1/2, density1/2, heat_capacity1/2, T_bulk1/2: surface temperatures ([rolling] scenes)
    [grid]      dx, dy, margin
    [solver]    tol, max_iter, fidelity ("bem" or "mdr"), threads, coupling, shakedown_tol
    [output]    fields ("reversals", "all", "last", "none")

A key left out takes its default (the field specs of `cases.scene.keys`): the seed paper's materials, Fn, mu
and rolling angle, but no tangential load and no motion; only [geometry] is required. So a scene file states
only what its scene needs (the README's scene-key table lists the defaults). Unknown keys, wrong types and
out-of-range values raise `SceneError` naming the key, the value and the allowed range; so do, for a new
run, a grid coarser than MIN_ELEMENTS_PER_RADIUS elements per Hertz semi-axis and a path of more than
MAX_STEPS steps.

The sections and the check of one key are in `cases.scene.keys`, the limits of a new run and the
default resolution in `cases.scene.limits`; their public names are importable from here too.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
import math
from pathlib import Path
import tomllib
from importlib import resources

from rollcontact.bem.errors import SceneError
from rollcontact.bem.materials import MaterialPair
from rollcontact.cases.scene.geometry import (
    SHAPE_KEYS, check_file_coverage, checked_file_geometry, cylinder_semi_axes, normal_reference, resolve_shape, shape_profile, tangential_reference)
from rollcontact.cases.scene.friction import check_friction, friction_on, thermal_on
from rollcontact.cases.scene.keys import (
    SECTIONS, Friction, GridSpec, Geometry, Load, Materials, Motion, Output, Rolling, SolverSpec, SECTION_ATTR, Thermal,
    check_key)
# re-exported: the names other modules import from cases.scene
from rollcontact.cases.scene.keys import INF, key_unit  # noqa: F401
from rollcontact.cases.scene.limits import MAX_STEPS, MIN_ELEMENTS_PER_RADIUS, RESOLUTION_PER_RADIUS, SceneLimits  # noqa: F401

#: keys of one section that are alternative spellings of one quantity: a scene gives one of each pair
ALTERNATIVE_KEYS = (("ft", "Ft"), ("w", "W"), ("R", "Rx"), ("R", "Ry"), ("xi", "Fx"), ("eta", "Fy"))


def other_spellings(key: str) -> set:
    """The alternative spellings of section.key: 'load.ft' -> {'load.Ft'}, 'geometry.R' -> {'geometry.Rx',
    'geometry.Ry'}; empty for a key without one."""
    sec, _, name = key.partition(".")
    return {f"{sec}.{b if name == a else a}" for a, b in ALTERNATIVE_KEYS if name in (a, b)}


@dataclass
class Scene(SceneLimits):
    """A complete, validated scene. Build it with `Scene.from_toml`, `Scene.from_dict` or `default_scene`."""

    materials: Materials = field(default_factory=Materials)
    geometry: Geometry = field(default_factory=Geometry)
    load: Load = field(default_factory=Load)
    motion: Motion = field(default_factory=Motion)
    rolling: Rolling = field(default_factory=Rolling)
    friction: Friction = field(default_factory=Friction)
    thermal: Thermal = field(default_factory=Thermal)
    grid: GridSpec = field(default_factory=GridSpec)
    solver: SolverSpec = field(default_factory=SolverSpec)
    output: Output = field(default_factory=Output)
    name: str = "scene"
    #: keys filled in by `_resolve_resolution` ("grid.dx", "motion.dW"); `with_overrides` re-derives them
    derived: frozenset = field(default=frozenset(), repr=False, compare=False)

    # --- construction ----------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, name: str = "scene", run_limits: bool = True) -> "Scene":
        """run_limits=False skips the checks that only a new run needs (grid resolution, number of steps, a file
        profile's file and checksum), for reading the scene stored in a run file (written before those checks
        existed, or whose profile file is elsewhere now)."""
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
            kwargs = {k: check_key(sec, names[k], v) for k, v in values.items()}
            parts[sec] = klass(**kwargs)
        scene = cls(**parts, name=name)
        scene._check_rolling(data)
        check_friction(scene, data)      # a friction law puts its static coefficient in load.mu
        scene._check_consistency()
        if scene.shape == "file" and run_limits:   # a stored scene is readable without its profile file
            scene.geometry, filled = checked_file_geometry(scene.geometry)
            scene.derived = frozenset({"geometry.sha256"} if filled else ())
        scene._resolve_resolution()
        if scene.shape == "file" and run_limits:
            check_file_coverage(scene)
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
        return cls.from_toml_text(text, name=path.stem, base=path.parent)

    @classmethod
    def from_toml_text(cls, text: str, name: str = "scene", run_limits: bool = True, base=None) -> "Scene":
        """base: the folder a relative [geometry] path is relative to (the scene file's; default the current one)."""
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError(f"scene {name}: not valid TOML ({exc})") from None
        geometry = data.get("geometry")
        if base is not None and isinstance(geometry, dict) and isinstance(geometry.get("path"), str):
            geometry["path"] = str(Path(base) / Path(geometry["path"]).expanduser())
        return cls.from_dict(data, name=name, run_limits=run_limits)

    def to_dict(self, include_none: bool = False) -> dict:
        """The scene as {section: {key: value}}; [rolling] only in a rolling scene, which has no [motion];
        [friction] and [thermal] only when given (and then no load.mu: the law gives it)."""
        out = {}
        for sec in SECTIONS:
            if sec == ("motion" if self.rolling_on else "rolling"):
                continue
            if (sec == "friction" and not self.friction_on) or (sec == "thermal" and not self.thermal_on):
                continue
            obj = getattr(self, SECTION_ATTR[sec])
            vals = {f.name: getattr(obj, f.name) for f in fields(obj)}
            out[sec] = {k: v for k, v in vals.items() if include_none or v is not None}
        if self.friction_on:
            out["load"].pop("mu", None)
        return out

    def to_toml(self) -> str:
        """The full scene as TOML text (every key, None-valued alternatives left out)."""
        lines = [f"# rollcontact scene '{self.name}' (units: mm, N, MPa, degrees)"]
        for sec, vals in self.to_dict().items():
            lines.append(f"\n[{sec}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in vals.items()]
        return "\n".join(lines) + "\n"

    @staticmethod
    def assignments(overrides) -> list[str]:
        """`section.key=value` strings (as `--set` takes them) from {"section.key": value}; a list of such strings
        passes through. Values are written as TOML, so that they parse back to the same value."""
        if isinstance(overrides, dict):
            return [f"{key}={_toml_value(value)}" for key, value in overrides.items()]
        if isinstance(overrides, str):
            return [overrides]
        return list(overrides)

    def with_overrides(self, assignments) -> "Scene":
        """A new scene with overrides applied: `section.key=value` strings (values parsed as TOML, else as strings),
        or a dict {"section.key": value}."""
        assignments = self.assignments(assignments)
        data = self.to_dict()
        for key in self.derived:  # re-derived from the overridden scene unless set explicitly
            sec, name = key.split(".")
            data.get(sec, {}).pop(name, None)    # [motion] is left out of a rolling scene's dict
        given = {}  # section.key -> the --set item that gave it
        for item in assignments:
            if "=" not in item or "." not in item.split("=", 1)[0]:
                raise SceneError(f"--set {item!r}: expected section.key=value, e.g. load.ft=0.5")
            key, raw = item.split("=", 1)
            sec, name = key.strip().split(".", 1)
            if sec not in SECTIONS:
                raise SceneError(f"--set {item!r}: unknown section {sec!r}; allowed: {list(SECTIONS)}")
            value = _parse_value(raw.strip())
            section = data.setdefault(sec, {})
            for other in sorted(other_spellings(f"{sec}.{name}")):
                if other in given:
                    raise SceneError(f"--set {given[other]!r} and --set {item!r}: give either {other} or "
                                     f"{sec}.{name}, not both")
                section.pop(other.partition(".")[2], None)
            section[name] = value
            given[f"{sec}.{name}"] = item
        if not self.friction_on and any(key.startswith("friction.") for key in given) and "load.mu" not in given:
            data["load"].pop("mu", None)   # a law set from the command line takes the place of load.mu
        if "geometry.shape" in given:  # a new shape: the old shape's keys that it does not take are dropped
            keep = SHAPE_KEYS.get(data["geometry"]["shape"], ())
            for name in list(data["geometry"]):
                if name != "shape" and name not in keep and f"geometry.{name}" not in given:
                    del data["geometry"][name]
        return Scene.from_dict(data, name=self.name)

    @property
    def friction_on(self) -> bool:
        """True for a scene with a [friction] law (cases.scene.friction)."""
        return friction_on(self)

    @property
    def thermal_on(self) -> bool:
        """True for a scene with a [thermal] section (surface temperatures)."""
        return thermal_on(self)

    @property
    def rolling_on(self) -> bool:
        """True for a scene that rolls on with creepages ([rolling] mode other than 'none')."""
        return self.rolling.mode != "none"

    @property
    def creepages(self) -> tuple[float, float, float]:
        """[rolling] (xi, eta, phi) with an omitted creepage as 0 (phi in 1/mm)."""
        ro = self.rolling
        return (ro.xi or 0.0, ro.eta or 0.0, ro.phi)

    @property
    def prescribed_forces(self) -> tuple[float, float] | None:
        """[rolling] (Fx, Fy) in N when the forces are prescribed, else None."""
        ro = self.rolling
        return None if ro.Fx is None else (ro.Fx, ro.Fy)

    @property
    def rolling_half_length(self) -> float:
        """Half-length (mm) of the Hertz contact along the [rolling] direction (an ellipse's extent along it)."""
        (sa, sb), t = self.semi_axes, math.radians(self.rolling.direction)
        return math.hypot(sa * math.cos(t), sb * math.sin(t))

    def _check_rolling(self, data: dict):
        """A [rolling] scene has no [motion], no tangential load and the BEM model."""
        if not self.rolling_on:
            if set(data.get("rolling", {})) - {"mode"}:
                raise SceneError("[rolling] mode = 'none' with other [rolling] keys: set mode = 'steady' to roll "
                                 "with creepages, or leave the [rolling] section out")
            return
        if "motion" in data:
            raise SceneError("[rolling] and [motion] exclude each other: a [rolling] scene rolls on steadily with "
                             "creepages xi, eta, phi; remove the [motion] section (oscillating rolling)")
        ld = self.load
        for key, value in (("ft", ld.ft), ("Ft", ld.Ft)):
            if value is not None:
                raise SceneError(f"[load] {key} = {value!r} with [rolling]: the tangential force of a rolling "
                                 "scene follows from its creepages [rolling] xi, eta, phi; remove load." + key)
        if ld.levels:
            raise SceneError("[load] levels with [rolling]: a rolling scene has no tangential load path; remove "
                             "load.levels")
        ro = self.rolling
        for creep, force in (("xi", "Fx"), ("eta", "Fy")):
            if getattr(ro, creep) is not None and getattr(ro, force) is not None:
                raise SceneError(f"[rolling] give either {creep} (creepage) or {force} (N), not both")
        if (ro.Fx is None) != (ro.Fy is None):
            raise SceneError("[rolling] Fx and Fy (N) are prescribed together (both creepages are then solved for); "
                             "give both, or the creepages xi and eta")
        for key, unit in (("distance", " mm"), ("step", " mm"), ("initial", "")):
            if getattr(ro, key) is not None and ro.mode != "transient":
                raise SceneError(f"[rolling] {key} = {getattr(ro, key)!r}{unit} with mode = {ro.mode!r}: {key} "
                                 "applies to mode = 'transient' only")
        if ro.step is not None:
            half = self.rolling_half_length
            if ro.step > half:
                raise SceneError(f"[rolling] step = {ro.step!r} mm: allowed range is 0 < step <= {half:.6g} mm (the "
                                 "contact's half-length a along the rolling direction; a longer step skips material)")
            distance = ro.distance if ro.distance is not None else 8.0 * half
            if distance / ro.step > MAX_STEPS:
                raise SceneError(f"[rolling] distance / step = {distance:.6g} / {ro.step!r} mm: more than "
                                 f"{MAX_STEPS} steps; use a larger step or a shorter distance")
        if self.solver.fidelity != "bem":
            raise SceneError(f"[solver] fidelity = {self.solver.fidelity!r} with [rolling]: creep rolling needs the "
                             "boundary elements; allowed value is 'bem'")

    def _check_consistency(self):
        ld, mo = self.load, self.motion
        resolve_shape(self.geometry)
        if ld.ft is not None and ld.Ft is not None:
            raise SceneError("[load] give either ft (= Ft/(mu Fn)) or Ft (N), not both")
        if ld.Ft is not None and ld.Ft > ld.mu * ld.Fn * (1 + 1e-12):
            raise SceneError(f"[load] Ft = {ld.Ft} N exceeds mu*Fn = {ld.mu * ld.Fn:.6g} N: gross sliding, "
                             "no static state exists (allowed range 0 <= Ft <= mu*Fn)")
        if mo.w is not None and mo.W is not None:
            raise SceneError("[motion] give either w (= W/a) or W (mm), not both")
        self._check_oscillation()

    @property
    def oscillating(self) -> bool:
        """True when a load oscillates within each period (load.ft_amplitude or load.fn_amplitude > 0)."""
        return self.load.ft_amplitude > 0 or self.load.fn_amplitude > 0

    def _check_oscillation(self):
        """Refuse a load schedule that lifts the sphere off or slides (theory §11.2-11.3), before any work.

        The schedule f_t = ft + A sin(psi), Fn = Fn (1 + B sin(psi)) (A = ft_amplitude, B = fn_amplitude) is
        checked over the whole cycle, not only at the steps: |Ft|/(mu Fn) = |ft + A s|/(1 + B s) with s = sin psi
        in [-1, 1] is monotone in s on either side of its zero, so its maximum is at s = +1 or s = -1, and
        |Ft| < mu Fn holds at every phase iff |ft + A| < 1 + B and |ft - A| < 1 - B, i.e. (ft, A >= 0)
        ft + B - 1 < A < min(1 + B - ft, 1 - B + ft).
        """
        ld = self.load
        if not self.oscillating:
            return
        if ld.levels:
            raise SceneError(f"[load] levels = {ld.levels!r} cannot be combined with oscillating loads "
                             "(ft_amplitude, fn_amplitude): give one or the other")
        if ld.fn_amplitude > 0 and self.shape not in ("sphere", "ellipsoid"):
            raise SceneError(f"[load] fn_amplitude = {ld.fn_amplitude!r} with [geometry] shape = {self.shape!r}: an "
                             "oscillating normal load is supported for shape = 'sphere' or 'ellipsoid' only (the grid "
                             "is sized by Hertz's a ~ Fn^(1/3) at the largest Fn); set fn_amplitude = 0")
        A, B, ft = ld.ft_amplitude, ld.fn_amplitude, self.f_t
        use = max(abs(ft + A) / (1.0 + B), abs(ft - A) / (1.0 - B))
        if use >= 1.0:
            lower, upper = ft + B - 1.0, min(1.0 + B - ft, 1.0 - B + ft)
            allowed = (f"ft_amplitude < {upper:.6g}" if lower < 0 else
                       f"{lower:.6g} < ft_amplitude < {upper:.6g}" if lower < upper else
                       "none: lower load.ft below 1")
            raise SceneError(
                f"[load] ft_amplitude = {A!r} with ft = {ft:.6g}, fn_amplitude = {B!r}: |Ft| reaches {use:.4g} "
                f"mu Fn during the cycle (gross sliding; at the smallest Fn, Fn (1 - fn_amplitude), when ft is "
                f"large); allowed range is {allowed} at this ft and fn_amplitude (|Ft| < mu Fn at every phase)")

    # --- derived quantities ----------------------------------------------------------------------
    @property
    def material_pair(self) -> MaterialPair:
        m = self.materials
        return MaterialPair.from_moduli(m.E1, m.nu1, m.E2, m.nu2)

    @property
    def shape(self) -> str:
        """The geometry's shape ('sphere', 'ellipsoid', 'cone', 'power', 'flat_rounded'; cases.scene.geometry)."""
        return resolve_shape(self.geometry)

    @property
    def profile(self):
        """The undeformed profile h(X, Y, centre) (mm) that the solvers take."""
        return shape_profile(self.geometry, self.shape)

    @property
    def normal_reference(self):
        """Closed-form normal contact under Fn (a, approach, p0): Hertz, or the exact MDR solution of the shape."""
        return normal_reference(self.geometry, self.shape, self.material_pair.E_star, self.load.Fn)

    @property
    def tangential_reference(self):
        """Closed-form Cattaneo-type loading of `normal_reference` (U0, stick_radius, shift)."""
        return tangential_reference(self.normal_reference, self.load.mu, self.material_pair.G_star)

    @property
    def radii(self) -> tuple[float, float]:
        """(Rx, Ry) of a sphere or an ellipsoid (mm); SceneError for the other shapes."""
        g = self.geometry
        if self.shape not in ("sphere", "ellipsoid"):
            raise SceneError(f"[geometry] shape = {g.shape!r} has no radii Rx, Ry")
        return (g.R, g.R) if g.R is not None else (g.Rx, g.Ry)

    @property
    def equivalent_radius(self) -> float:
        """sqrt(Rx Ry) (mm): the radius of the sphere with the same Gaussian curvature (sphere and ellipsoid)."""
        rx, ry = self.radii
        return math.sqrt(rx) * math.sqrt(ry)  # not sqrt(rx ry): that overflows from rx ry > 1e308

    @property
    def contact_radius(self) -> float:
        """Contact radius a (mm), the unit of w: Hertz's of the equivalent sphere for a sphere or an ellipsoid, the
        MDR's exact radius of the profile under Fn for the other (axisymmetric) shapes."""
        if self.shape not in ("sphere", "ellipsoid"):
            return self.normal_reference.a        # the MDR's a; the cylinder's half-width under Fn/length
        return (3.0 * self.load.Fn * self.equivalent_radius / (4.0 * self.material_pair.E_star)) ** (1 / 3)

    @property
    def semi_axes(self) -> tuple[float, float]:
        """Contact semi-axes (mm) along x and y: exact for a sphere and the axisymmetric shapes (a, a),
        Hertz's estimate c (Rx/Ry)^(+-1/3) for an ellipse, an estimate for the cylinder (cylinder_semi_axes)."""
        if self.shape == "cylinder":
            return cylinder_semi_axes(self.geometry, self.material_pair.E_star, self.load.Fn)
        if self.shape not in ("sphere", "ellipsoid"):
            a = self.contact_radius
            return (a, a)
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
    def speed(self) -> float | None:
        """Rolling speed V (mm/s): [rolling] speed in a [rolling] scene, else [motion] speed; None without one
        (the scene is time-independent)."""
        return self.rolling.speed if self.rolling_on else self.motion.speed

    @property
    def step_time(self) -> float | None:
        """Duration dt (s) of every step of a stepped run, None without a speed or in steady rolling (which has no
        steps: the slip velocity is V times the slip per unit rolled distance).

        A step's time is its displacement over the speed, as the reference program's dq / V: the rolling step
        actually used, W/ceil(W/dW), in an oscillating scene; motion.dW (default dx) in a scene without rolling
        (w = 0: shifts and loads at rest); [rolling] step (default dx) in a transient [rolling] scene. Every step
        of the path takes dt, the loading steps included: step n ends at time n dt, step 0 (the normal load from
        the unloaded state) at t = 0."""
        V = self.speed
        if V is None:
            return None
        if self.rolling_on:
            if self.rolling.mode != "transient":
                return None
            return (self.rolling.step if self.rolling.step is not None else self.spacing[0]) / V
        moving = self.amplitude > 0 and self.motion.periods > 0
        return (self.rolling_step if moving else self.motion.dW) / V

    @property
    def load_direction(self) -> tuple[float, float]:
        """Unit vector along Ft (load.load_angle from +x)."""
        t = math.radians(self.load.load_angle)
        return (math.cos(t), math.sin(t))

    @property
    def transverse_direction(self) -> tuple[float, float]:
        """Unit vector across Ft: the load direction turned by +90 deg (the direction of U_perp)."""
        ex, ey = self.load_direction
        return (-ey, ex)

    @property
    def rolling_direction(self) -> tuple[float, float]:
        t = math.radians(self.load.load_angle + self.motion.angle)
        return (math.cos(t), math.sin(t))

    @property
    def spacing(self) -> tuple[float, float]:
        return self.grid.dx, (self.grid.dy if self.grid.dy is not None else self.grid.dx)

    def replace(self, **sections) -> "Scene":
        return replace(self, **sections)


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


DEFAULT_SCENE_FILE = "paper_perpendicular.toml"


def shipped_scene_path(name: str) -> Path:
    """Path of a scene file shipped in the `rollcontact.cases` package (cases/*.toml)."""
    return Path(str(resources.files("rollcontact.cases").joinpath(name)))


def default_scene() -> Scene:
    """The embedded default: the seed paper's Table 1 (perpendicular setting, f_t = 0.46, w = 0.23)."""
    return Scene.from_toml(shipped_scene_path(DEFAULT_SCENE_FILE))
