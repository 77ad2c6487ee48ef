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
import re
import tomllib
from importlib import resources

import numpy as np

from rollcontact.bem.errors import SceneError
from rollcontact.bem.materials import MaterialPair
from rollcontact.cases.arguments import arg
from rollcontact.cases.scene.geometry import (
    SHAPE_KEYS, check_file_coverage, checked_file_geometry, cylinder_semi_axes, normal_reference, resolve_shape, shape_profile, tangential_reference)
from rollcontact.cases.scene.keys import (
    SECTIONS, GridSpec, Geometry, Load, Materials, Motion, Output, Rolling, SolverSpec, SECTION_ATTR, check_key)
# re-exported: the names other modules import from cases.scene
from rollcontact.cases.scene.keys import INF, key_unit  # noqa: F401
from rollcontact.cases.scene.limits import MAX_STEPS, MIN_ELEMENTS_PER_RADIUS, RESOLUTION_PER_RADIUS, SceneLimits  # noqa: F401

#: keys of one section that are alternative spellings of one quantity: a scene gives one of each pair
ALTERNATIVE_KEYS = (("ft", "Ft"), ("w", "W"), ("R", "Rx"), ("R", "Ry"), ("xi", "Fx"), ("eta", "Fy"))
#: pairs of ALTERNATIVE_KEYS that an override may not switch from the scene's spelling to the other (the scene's
#: value would be dropped unannounced): the tangential load as f_t or in N, the amplitude as w or in mm, creepages or
#: forces. R and Rx, Ry switch the shape (sphere, ellipsoid), as geometry.shape does, and may be switched.
SPELLINGS = {("load", "ft"): "Ft", ("load", "Ft"): "ft", ("motion", "w"): "W", ("motion", "W"): "w",
             ("rolling", "xi"): "Fx", ("rolling", "Fx"): "xi", ("rolling", "eta"): "Fy", ("rolling", "Fy"): "eta"}


def stored_name(toml_text: str) -> str | None:
    """The scene name a stored scene's first line states (`Scene.to_toml`: "# rollcontact scene 'NAME' (units: ..."),
    or None."""
    first = toml_text.split("\n", 1)[0] if isinstance(toml_text, str) else ""
    match = re.match(r"# rollcontact scene '(.*)' \(units:", first)
    return match.group(1) if match else None


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
        scene._check_consistency()
        if scene.shape == "file" and run_limits:   # a stored scene is readable without its profile file
            scene.geometry, filled = checked_file_geometry(scene.geometry)
            scene.derived = frozenset({"geometry.sha256"} if filled else ())
        if scene.shape != "file" or run_limits:    # a file profile's size needs its file
            scene._check_finite()
        scene._resolve_resolution()
        if scene.shape == "file" and run_limits:
            check_file_coverage(scene)
        if run_limits:
            scene._check_resolution()
            scene._check_steps()
            scene._check_load_cycles()
            scene._check_rolling_run()
        return scene

    @classmethod
    def from_toml(cls, path) -> "Scene":
        path = Path(path)
        try:
            raw = path.read_bytes()
        except OSError as exc:
            raise SceneError(f"scene file {path}: {exc.strerror}") from None
        if raw.startswith(b"\x89HDF\r\n\x1a\n"):
            raise SceneError(f"scene file {path}: is an HDF5 file (a run file?), not a scene (TOML text); to continue "
                             f"a run give it to {arg('restart')}, to read it use rollcontact.read_run or rollcontact plot")
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise SceneError(f"scene file {path}: not a text file (byte {exc.start} is not UTF-8); expected a scene "
                             "in TOML") from None
        return cls.from_toml_text(text, name=path.stem, base=path.parent)

    @classmethod
    def from_toml_text(cls, text: str, name: str | None = None, run_limits: bool = True, base=None) -> "Scene":
        """The scene of a TOML text. name: its name (default: the name a stored scene states in its first line,
        `to_toml`, else 'scene'); base: the folder a relative [geometry] path is relative to (the scene file's;
        default the current one)."""
        if name is None:
            name = stored_name(text) or "scene"
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError(f"scene {name}: not valid TOML ({exc})") from None
        geometry = data.get("geometry")
        if base is not None and isinstance(geometry, dict) and isinstance(geometry.get("path"), str):
            geometry["path"] = str(Path(base) / Path(geometry["path"]).expanduser())
        return cls.from_dict(data, name=name, run_limits=run_limits)

    def to_dict(self, include_none: bool = False) -> dict:
        """The scene as {section: {key: value}}; [rolling] only in a rolling scene, which has no [motion]."""
        out = {}
        for sec in SECTIONS:
            if sec == ("motion" if self.rolling_on else "rolling"):
                continue
            obj = getattr(self, SECTION_ATTR[sec])
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

    @staticmethod
    def assignments(overrides) -> list[str]:
        """`section.key=value` strings (as `--set` takes them) from {"section.key": value}; a list of such strings
        passes through. Values are written as TOML, so that they parse back to the same value; a text value is
        taken as --set takes its text ({"load.ft": "0.3"} is --set load.ft=0.3). SceneError naming `overrides`
        (--set) for anything else."""
        if isinstance(overrides, dict):
            out = []
            for key, value in overrides.items():
                if not isinstance(key, str):
                    raise SceneError(f"{arg('overrides')}: key {key!r} is not a 'section.key' string")
                out.append(f"{key}={value if isinstance(value, str) else _toml_value(value)}")
            return out
        if isinstance(overrides, str):
            return [overrides]
        try:
            items = list(overrides)
        except TypeError:
            raise SceneError(f"{arg('overrides')} = {overrides!r}: expected {{'section.key': value}} or a list of "
                             "'section.key=value' strings") from None
        bad = [item for item in items if not isinstance(item, str)]
        if bad:
            raise SceneError(f"{arg('overrides')} {bad[0]!r}: expected a 'section.key=value' string")
        return items

    def with_overrides(self, assignments, replaces=()) -> "Scene":
        """A new scene with overrides applied: `section.key=value` strings (values parsed as TOML, else as a number,
        else as text, as --set takes them), or a dict {"section.key": value} (a text value is parsed the same way).

        An override in the other spelling of a quantity the scene gives (load.Ft where the scene gives load.ft,
        motion.W for motion.w, forces rolling.Fx, Fy for the creepages xi, eta, and the reverse) is refused, naming
        the scene's value and its equivalent, unless its key is in `replaces` (a limit search sets the load.ft or
        motion.w it searches). SceneError names the key."""
        assignments = self.assignments(assignments)
        data = self.to_dict()
        for key in self.derived:  # re-derived from the overridden scene unless set explicitly
            sec, name = key.split(".")
            data.get(sec, {}).pop(name, None)    # [motion] is left out of a rolling scene's dict
        given = {}  # section.key -> the --set item that gave it
        for item in assignments:
            if "=" not in item or "." not in item.split("=", 1)[0]:
                raise SceneError(f"{arg('overrides')} {item!r}: expected section.key=value, e.g. load.ft=0.5")
            key, raw = item.split("=", 1)
            sec, name = key.strip().split(".", 1)
            if sec not in SECTIONS:
                raise SceneError(f"{arg('overrides')} {item!r}: unknown section {sec!r}; allowed: {list(SECTIONS)}")
            value = _parse_value(raw.strip(), text=_is_text_key(sec, name))
            section = data.setdefault(sec, {})
            for other in sorted(other_spellings(f"{sec}.{name}")):
                if other in given:
                    raise SceneError(f"{arg('overrides')} {given[other]!r} and {arg('overrides')} {item!r}: give "
                                     f"either {other} or {sec}.{name}, not both")
                o_name = other.partition(".")[2]
                if (o_name in section and SPELLINGS.get((sec, name)) == o_name
                        and f"{sec}.{name}" not in replaces):
                    raise SceneError(self._spelling_refusal(item, sec, name, o_name, section[o_name], value))
                section.pop(o_name, None)
            section[name] = value
            given[f"{sec}.{name}"] = item
        if "geometry.shape" in given:  # a new shape: the old shape's keys that it does not take are dropped
            keep = SHAPE_KEYS.get(data["geometry"]["shape"], ())
            for name in list(data["geometry"]):
                if name != "shape" and name not in keep and f"geometry.{name}" not in given:
                    del data["geometry"][name]
        return Scene.from_dict(data, name=self.name)

    def _spelling_refusal(self, item, sec, name, other, stored, value) -> str:
        """The message refusing `item` (section.name=value) where the scene gives section.other = stored."""
        head = f"{arg('overrides')} {item!r}: the scene gives {sec}.{other} = {stored!r}"
        if sec == "rolling":
            given, wanted = (("forces", "creepages") if name in ("Fx", "Fy") else ("creepages", "forces"))
            return (f"{head}: prescribed forces (rolling.Fx, rolling.Fy) and creepages (rolling.xi, rolling.eta) "
                    f"exclude each other, and the scene prescribes the {wanted}; override the {wanted}, or write "
                    f"a scene file with the {given} in their place")
        equivalent = ""
        if _is_number(value):
            ld = self.load
            if name == "Ft":
                equivalent = f" ({sec}.ft = {value / (ld.mu * ld.Fn):.6g} is Ft = {value} N here)"
            elif name == "ft":
                equivalent = f" ({sec}.Ft = {value * ld.mu * ld.Fn:.6g} N is ft = {value} here)"
            elif name == "W":
                equivalent = f" ({sec}.w = {value / self.contact_radius:.6g} is W = {value} mm here)"
            elif name == "w":
                equivalent = f" ({sec}.W = {value * self.contact_radius:.6g} mm is w = {value} here)"
        return (f"{head}, the same quantity in its other spelling: give {sec}.{other}{equivalent}, or a scene file "
                f"with {sec}.{name} in place of {sec}.{other}")

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

    def _check_finite(self):
        """The combined moduli and the contact size that the keys give are finite and positive: keys each within their
        range can still over- or underflow together (E1 = 5e-324 MPa gives E* = 0; R = 1e300 mm an infinite
        contact). SceneError naming the keys."""
        m = self.materials
        with np.errstate(all="ignore"):
            pair = self.material_pair
            moduli = (("E*", pair.E_star), ("G*", pair.G_star))
        for name, value in moduli:
            if not (math.isfinite(value) and value > 0):
                raise SceneError(f"[materials] E1 = {m.E1!r}, nu1 = {m.nu1!r}, E2 = {m.E2!r}, nu2 = {m.nu2!r} MPa: the "
                                 f"combined modulus {name} = {value!r} MPa is not a positive finite number (the moduli "
                                 "over- or underflow); allowed are moduli whose combination is, e.g. 1e-100 < E < 1e100")
        try:
            with np.errstate(over="raise", divide="raise", invalid="raise"):
                a = self.contact_radius
                axes = self.semi_axes
        except (ArithmeticError, ValueError, FloatingPointError):
            a, axes = math.nan, (math.nan,)
        if not (math.isfinite(a) and a > 0 and all(math.isfinite(v) and v > 0 for v in axes)):
            raise SceneError(f"[geometry] {self._geometry_text()} with [load] Fn = {self.load.Fn!r} N and E* = "
                             f"{pair.E_star:.6g} MPa: the contact size a = {a!r} mm is not a positive finite length "
                             "(the keys over- or underflow together); give a geometry, load and moduli whose Hertz "
                             "contact radius is")

    def _geometry_text(self) -> str:
        g = self.geometry
        return ", ".join(f"{f.name} = {getattr(g, f.name)!r}" for f in fields(g) if getattr(g, f.name) is not None)

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


def _is_text_key(sec: str, name: str) -> bool:
    """True for a key whose values are text (a choice such as solver.fidelity, or geometry.path)."""
    for f in fields(SECTIONS[sec]):
        if f.name == name:
            return bool(f.metadata.get("choices")) or f.type == "str | None"
    return False


def _parse_value(raw: str, text: bool = False):
    """A --set value: TOML, else a number as Python writes it (.5, 1., 1e3: not TOML), else the text. For a text
    key (`text`) the text itself unless it is a TOML string (geometry.path=1.5 is the file '1.5')."""
    try:
        parsed = tomllib.loads(f"v = {raw}")
    except tomllib.TOMLDecodeError:
        parsed = None
    if parsed is not None and list(parsed) == ["v"]:         # one value, not a value and further TOML lines
        value = parsed["v"]
        return value if not text or isinstance(value, str) else raw
    if text:
        return raw
    try:
        return float(raw)  # a NaN is refused with the key by the field check, like TOML's nan
    except ValueError:
        return raw


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


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
