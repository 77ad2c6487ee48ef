"""Scenes: a TOML file <-> a `Scene` dataclass, validated key by key.

Units: mm, N, MPa, degrees, s (mm/s for speeds). Sections and keys (public contract, see README):

    [materials] E1, nu1 (sphere; E1 = inf for a rigid sphere), E2, nu2 (substrate); visco1, visco2 ("none", "sls"),
                E1_relaxed, E2_relaxed, tau1, tau2 (s): Standard Linear Solid bodies, E<i> their glassy modulus
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
    [wheelrail] a wheel on its rail from two profile files, in place of [geometry], [motion], [rolling] and the loads of
                [load] (cases.scene.wheelrail, docs/wheelrail.md)
    [grid]      dx, dy, margin
    [solver]    tol, max_iter, fidelity ("bem", "mdr", "fastsim", "fastrip" or "auto"), accuracy (with "auto"),
                traction_bound (of "fastsim", "fastrip"), threads, coupling, shakedown_tol
    [output]    fields ("reversals", "all", "last", "none")

A key left out takes its default (the field specs of `cases.scene.keys`): the seed paper's materials, Fn, mu
and rolling angle, but no tangential load and no motion; only [geometry] is required. So a scene file states
only what its scene needs (docs/scene_reference.md lists the defaults). Unknown keys, wrong types and
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


from rollcontact.bem.errors import SceneError
from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.cases.arguments import arg
from rollcontact.cases.scene.geometry import (
    check_file_coverage, checked_file_geometry, cylinder_semi_axes, normal_reference, resolve_shape, shape_profile, tangential_reference)
from rollcontact.cases.scene.friction import check_friction, friction_on, thermal_on
from rollcontact.cases.scene.keys import (
    SECTIONS, Friction, GridSpec, Geometry, Load, Materials, Motion, Output, Rolling, SolverSpec, SECTION_ATTR, Thermal,
    WheelRail, check_key)
# re-exported: the names other modules import from cases.scene
from rollcontact.cases.scene.keys import INF, key_unit  # noqa: F401
from rollcontact.cases.scene.limits import MAX_STEPS, MIN_ELEMENTS_PER_RADIUS, RESOLUTION_PER_RADIUS, SceneLimits  # noqa: F401
from rollcontact.cases.scene.checks import SceneChecks
from rollcontact.solver.visco.sls import StandardLinearSolid
from rollcontact.cases.scene.overrides import (  # noqa: F401  (ALTERNATIVE_KEYS, SPELLINGS, other_spellings re-exported)
    ALTERNATIVE_KEYS, SPELLINGS, assignments_of, other_spellings, toml_value, with_overrides)


def stored_name(toml_text: str) -> str | None:
    """The scene name a stored scene's first line states (`Scene.to_toml`: "# rollcontact scene 'NAME' (units: ..."),
    or None."""
    first = toml_text.split("\n", 1)[0] if isinstance(toml_text, str) else ""
    match = re.match(r"# rollcontact scene '(.*)' \(units:", first)
    return match.group(1) if match else None


@dataclass
class Scene(SceneChecks, SceneLimits):
    """A complete, validated scene. Build it with `Scene.from_toml`, `Scene.from_dict` or `default_scene`."""

    materials: Materials = field(default_factory=Materials)
    geometry: Geometry = field(default_factory=Geometry)
    load: Load = field(default_factory=Load)
    motion: Motion = field(default_factory=Motion)
    rolling: Rolling = field(default_factory=Rolling)
    friction: Friction = field(default_factory=Friction)
    thermal: Thermal = field(default_factory=Thermal)
    wheelrail: WheelRail = field(default_factory=WheelRail)
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
        if scene.viscoelastic and ("wheelrail" in data or scene.wheelrail_on):
            raise SceneError("[materials] visco1 / visco2 = 'sls' with [wheelrail]: viscoelastic bodies are not "
                             "supported in wheel-rail scenes; remove the viscoelastic keys or the [wheelrail] section")
        scene._check_friction_models(data)
        if "wheelrail" in data or scene.wheelrail_on:
            return scene._wheelrail_checked(data, run_limits)
        scene._check_rolling(data)
        check_friction(scene, data)      # a friction law puts its static coefficient in load.mu
        scene._check_fidelity()
        scene._check_consistency()
        scene._check_visco()
        if scene.shape == "file" and run_limits:   # a stored scene is readable without its profile file
            scene.geometry, filled = checked_file_geometry(scene.geometry)
            scene.derived = frozenset({"geometry.sha256"} if filled else ())
        if scene.shape != "file" or run_limits:    # a file profile's size needs its file
            scene._check_finite()
        scene._resolve_resolution()
        scene._check_transient_grid()
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
        for sec, key in (("geometry", "path"), ("wheelrail", "wheel_profile"), ("wheelrail", "rail_profile")):
            table = data.get(sec)
            if base is not None and isinstance(table, dict) and isinstance(table.get(key), str):
                table[key] = str(Path(base) / Path(table[key]).expanduser())
        return cls.from_dict(data, name=name, run_limits=run_limits)

    def to_dict(self, include_none: bool = False) -> dict:
        """The scene as {section: {key: value}}; [rolling] only in a rolling scene, which has no [motion]; a
        [wheelrail] scene has no [motion] or [geometry] and only load.mu and grid.dx, dy; [friction] and [thermal]
        only when given (and then no load.mu: the law gives it)."""
        out = {}
        skip = ("geometry", "motion") + (() if self.rolling_on else ("rolling",)) if self.wheelrail_on else \
            ("wheelrail", "motion" if self.rolling_on else "rolling")
        for sec in SECTIONS:
            if sec in skip:
                continue
            if (sec == "friction" and not self.friction_on) or (sec == "thermal" and not self.thermal_on):
                continue
            obj = getattr(self, SECTION_ATTR[sec])
            vals = {f.name: getattr(obj, f.name) for f in fields(obj)}
            if self.wheelrail_on and sec in ("load", "grid", "rolling"):
                vals = {k: v for k, v in vals.items() if k in ("mu", "dx", "dy", "mode", "distance", "step", "initial")}
            out[sec] = {k: v for k, v in vals.items() if include_none or v is not None}
        if self.friction_on:
            out["load"].pop("mu", None)
        return out

    def to_toml(self) -> str:
        """The full scene as TOML text (every key, None-valued alternatives left out)."""
        lines = [f"# rollcontact scene '{self.name}' (units: mm, N, MPa, degrees)"]
        for sec, vals in self.to_dict().items():
            lines.append(f"\n[{sec}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in vals.items()]
        return "\n".join(lines) + "\n"

    @property
    def wheelrail_on(self) -> bool:
        """True for a wheel-rail scene ([wheelrail], cases.scene.wheelrail)."""
        return self.wheelrail != WheelRail()

    def _wheelrail_checked(self, data: dict, run_limits: bool) -> "Scene":
        """The checks of a [wheelrail] scene (cases.scene.wheelrail), its files' checksums and default grid (not the
        grid's least resolution: a flange root's contact is narrow by nature; the run reports each patch's cells)."""
        from rollcontact.cases.scene import wheelrail
        wheelrail.check_sections(data)
        wheelrail.check_keys(self)
        if run_limits:
            self.wheelrail, filled = wheelrail.checked_files(self.wheelrail)
            self.derived = frozenset(filled)
            self._resolve_resolution()
            wheelrail.check_coverage(self)
        return self

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

    @property
    def transient_grid(self) -> str | None:
        """The grid of a [rolling] transient: [rolling] grid, by default 'contact' (moving with the contact) when the
        step (default dx) is a whole number of elements dx, the bodies are elastic, friction is Coulomb's and there
        is no [thermal] and the model is not FASTSIM, else 'world' (a viscoelastic body's element states, a friction
        law's memory, the temperatures and FASTSIM's strips stay with the material, on the world grid); None outside a
        transient."""
        ro = self.rolling
        if ro.mode != "transient":
            return None
        if ro.grid is not None:
            return ro.grid
        material_state = self.viscoelastic or self.friction_on or self.thermal_on or self.solver.fidelity == "fastsim"
        return "contact" if self._whole_steps() and not material_state else "world"

    def _whole_steps(self) -> bool:
        """True when the transient's step is k >= 1 whole elements dx along the rolling direction (within 1e-9, as
        solver.creep.moving.whole_cells, which the grid moving with the contact needs)."""
        dx = self.spacing[0]
        step = self.rolling.step if self.rolling.step is not None else dx
        k = round(step / dx)
        return k >= 1 and abs(step / dx - k) <= 1e-9 * max(1.0, step / dx)

    @property
    def traction_bound(self) -> str:
        """The fast models' traction bound ([solver] traction_bound; 'scene' when left out)."""
        return self.solver.traction_bound or "scene"

    @staticmethod
    def assignments(overrides) -> list[str]:
        """`section.key=value` strings (as `--set` takes them) from {"section.key": value} (cases.scene.overrides)."""
        return assignments_of(overrides)

    def with_overrides(self, assignments, replaces=()) -> "Scene":
        """A new scene with overrides applied: `section.key=value` strings, or a dict {"section.key": value} (a text
        value read as --set reads it). An override in the other spelling of a quantity the scene gives (load.Ft where
        it gives load.ft, motion.W for motion.w, forces for creepages) is refused unless its key is in `replaces` (a
        limit search sets the load.ft or motion.w it searches). SceneError names the key (cases.scene.overrides)."""
        return with_overrides(self, assignments, replaces)

    @property
    def oscillating(self) -> bool:
        """True when a load oscillates within each period (load.ft_amplitude or load.fn_amplitude > 0)."""
        return self.load.ft_amplitude > 0 or self.load.fn_amplitude > 0

    # --- derived quantities ----------------------------------------------------------------------
    @property
    def viscoelastic(self) -> bool:
        """True when a body is a Standard Linear Solid (materials.visco1 or visco2 = 'sls')."""
        return "sls" in (self.materials.visco1, self.materials.visco2)

    @property
    def bodies(self) -> tuple:
        """(sphere, substrate): each a bem Material, or a solver.visco StandardLinearSolid for visco<i> = 'sls'."""
        m = self.materials
        out = []
        for i in (1, 2):
            E, nu = getattr(m, f"E{i}"), getattr(m, f"nu{i}")
            if getattr(m, f"visco{i}") == "sls":
                out.append(StandardLinearSolid(E, getattr(m, f"E{i}_relaxed"), getattr(m, f"tau{i}"), nu))
            else:
                out.append(Material(E, nu))
        return tuple(out)

    @property
    def sls_bodies(self) -> dict:
        """{body index: StandardLinearSolid} of the viscoelastic bodies (empty for an elastic scene)."""
        return {i: b for i, b in enumerate(self.bodies, start=1) if isinstance(b, StandardLinearSolid)}

    @property
    def material_pair(self) -> MaterialPair:
        """The elastic pair; a viscoelastic body with its relaxed modulus (the long-time, quasi-static limit: the
        normalisations a, d, p0, U0, the default grid and the grid's extent, which covers the largest contact, follow
        it). The solvers get the effective pair of the step time (solver.visco.sls.effective_pair)."""
        m = self.materials
        E1 = m.E1_relaxed if m.visco1 == "sls" else m.E1
        E2 = m.E2_relaxed if m.visco2 == "sls" else m.E2
        return MaterialPair.from_moduli(E1, m.nu1, E2, m.nu2)

    @property
    def shape(self) -> str:
        """The geometry's shape ('sphere', 'ellipsoid', 'cone', 'power', 'flat_rounded'; cases.scene.geometry), or
        'wheelrail'."""
        return "wheelrail" if self.wheelrail_on else resolve_shape(self.geometry)

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
        Hertz's estimate c (Rx/Ry)^(+-1/3) for an ellipse, an estimate for the cylinder (cylinder_semi_axes), Hertz's
        at the first touch for [wheelrail] (cases.scene.wheelrail.estimate)."""
        if self.wheelrail_on:
            from rollcontact.cases.scene.wheelrail import estimate
            return estimate(self)[:2]
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
        if self.wheelrail_on:
            return self.wheelrail.speed
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
        if V is None or self.wheelrail_on:
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


DEFAULT_SCENE_FILE = "paper_perpendicular.toml"


def shipped_scene_path(name: str) -> Path:
    """Path of a scene file shipped in the `rollcontact.cases` package (cases/*.toml)."""
    return Path(str(resources.files("rollcontact.cases").joinpath(name)))


def default_scene() -> Scene:
    """The embedded default: the seed paper's Table 1 (perpendicular setting, f_t = 0.46, w = 0.23)."""
    return Scene.from_toml(shipped_scene_path(DEFAULT_SCENE_FILE))
