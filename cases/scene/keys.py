"""The keys of a scene: its sections as dataclasses whose fields carry the default, the allowed range and the
unit of each key, and the validation of one key against its field spec (used by `cases.scene.Scene.from_dict`).

Units: mm, N, MPa, degrees, mm/s, degC and the SI units of the [thermal] keys (each field's `unit`; none for
dimensionless keys). A value of the wrong type, out of
its range or not among its choices raises `SceneError` naming the key, the value and the allowed range or values.
Each field also says which kinds of run it applies to (`modes`, default: its section's, SECTION_MODES; the kinds:
MODES). docs/scene_reference.md is generated from these fields (docs/scripts/reference.py).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields
import math

from rollcontact.bem.errors import SceneError

INF = math.inf

#: The models a scene can ask for ([solver] fidelity).
FIDELITIES = ("bem", "mdr", "fastsim", "fastrip", "auto")
#: The fast models of [rolling] scenes (solver.fastsim).
FAST_FIDELITIES = ("fastsim", "fastrip")
#: [solver] accuracy when fidelity = "auto" leaves it out.
DEFAULT_ACCURACY = 0.02


#: The kinds of run a key can apply to (docs/scene_reference.md).
MODES = {
    "oscillating": "the sphere (or another profile) rolled back and forth under a tangential load, [load] and [motion] "
                   "(the seed paper's scene), on the 3-D boundary elements",
    "mdr": "the same with solver.fidelity = \"mdr\": the 1-D spring model of the MDR (docs/theory.md §8.2)",
    "steady": "[rolling] mode = \"steady\": steady rolling with creepage and spin (docs/theory.md §11.5)",
    "transient": "[rolling] mode = \"transient\": rolling on the world-fixed grid from an initial state",
    "wheelrail": "[wheelrail]: a wheel on a rail with measured profiles, the contact patches found by search "
                 "(docs/wheelrail.md)",
}
ALL_MODES = tuple(MODES)
#: The modes of each section's keys, unless a key says otherwise (its `modes`); a section not listed: all.
SECTION_MODES = {
    "load": ("oscillating", "mdr"),
    "motion": ("oscillating", "mdr"),
    "rolling": ("steady", "transient"),
    "friction": ("oscillating", "steady", "transient"),
    "thermal": ("steady", "transient"),
    "wheelrail": ("wheelrail",),
    "grid": ("oscillating", "steady", "transient"),
    "solver": ("oscillating", "steady", "transient"),
    "output": ("oscillating", "steady", "transient"),
}
#: One line on what each section holds (docs/scene_reference.md).
SECTION_DOCS = {
    "materials": "the elastic constants of the two bodies: body 1 the sphere (or profile), body 2 the substrate",
    "geometry": "the undeformed profile of body 1 over the flat substrate (the only required section)",
    "load": "the normal force, the friction coefficient and the tangential load path",
    "motion": "the oscillating rolling: amplitude, direction relative to Ft, periods, step",
    "rolling": "rolling on with creepage and spin, steady or transient (excludes [motion] and a tangential load)",
    "friction": "a friction law in place of [load] mu: falling with the slip velocity, with memory, or with the "
                "surface temperature (docs/friction.md); the boundary elements only (law 'coulomb' also with the "
                "fast models; neither with viscoelastic bodies nor [wheelrail])",
    "thermal": "surface temperatures of both bodies heated by the frictional power, in [rolling] scenes with "
               "rolling.speed (docs/friction.md)",
    "wheelrail": "a wheel on a rail: the profiles, the track, the wheelset's position, load and motion",
    "grid": "the boundary-element grid: element size and margin around the swept contact",
    "solver": "tolerances, budgets, model fidelity, threads and the normal-tangential coupling",
    "output": "which steps' surface fields the run file keeps",
}


def _spec(default, lo=None, hi=None, *, lo_open=False, hi_open=False, choices=None, unit="", doc="", modes=None):
    """Field with its allowed range kept in the metadata, so validation and docs share one table; `modes`: the
    kinds of run (MODES) it applies to, when not those of its section (SECTION_MODES)."""
    meta = dict(lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, choices=choices, unit=unit, doc=doc, modes=modes)
    if isinstance(default, list):
        return field(default_factory=lambda: list(default), metadata=meta)
    return field(default=default, metadata=meta)


@dataclass
class Materials:
    E1: float = _spec(206e3, 0, INF, lo_open=True, unit="MPa", doc="sphere Young's modulus (inf: rigid)")
    nu1: float = _spec(0.3, -1, 0.5, lo_open=True, doc="sphere Poisson ratio")
    E2: float = _spec(4.35, 0, INF, lo_open=True, hi_open=True, unit="MPa", doc="substrate Young's modulus")
    nu2: float = _spec(0.5, -1, 0.5, lo_open=True, doc="substrate Poisson ratio")
    # viscoelastic bodies (docs/viscoelastic.md): a Standard Linear Solid with E<i> its glassy (instantaneous) modulus,
    # creep compliance C(t) = 1/E<i> + (1/E<i>_relaxed - 1/E<i>)(1 - exp(-t/tau<i>)), nu<i> constant; left out (the
    # default) or "none": elastic
    visco1: str | None = _spec(None, choices=("none", "sls"),
                               doc="sphere material model: 'none' (or left out) elastic, 'sls' standard linear solid "
                                   "(E1 glassy, E1_relaxed, tau1; needs a speed)")
    E1_relaxed: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="MPa",
                                     doc="sphere's relaxed (long-time) modulus of visco1 = 'sls', below E1")
    tau1: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="s",
                               doc="sphere's creep relaxation time of visco1 = 'sls'")
    visco2: str | None = _spec(None, choices=("none", "sls"),
                               doc="substrate material model: 'none' (or left out) elastic, 'sls' standard linear solid "
                                   "(E2 glassy, E2_relaxed, tau2; needs a speed)")
    E2_relaxed: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="MPa",
                                     doc="substrate's relaxed (long-time) modulus of visco2 = 'sls', below E2")
    tau2: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="s",
                               doc="substrate's creep relaxation time of visco2 = 'sls'")


@dataclass
class Geometry:
    # shape left out: "sphere" with R, "ellipsoid" with Rx and Ry (the keys each shape takes:
    # cases.scene.geometry.SHAPE_KEYS)
    shape: str | None = _spec(None, choices=("sphere", "ellipsoid", "cone", "power", "flat_rounded", "cylinder",
                                             "file"),
                              doc="profile shape (default: sphere with R, ellipsoid with Rx, Ry)")
    R: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                            doc="sphere radius; power law R; edge radius of flat_rounded; cylinder radius")
    Rx: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="radius in x")
    Ry: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="radius in y")
    slope: float | None = _spec(None, 0, 90, lo_open=True, hi_open=True, unit="deg",
                                doc="cone flank angle against the undeformed surface")
    n: float | None = _spec(None, 1, 20, doc="exponent of the power law h = r^n/(n R^(n-1))")
    b: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm", doc="flat radius of flat_rounded")
    length: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                                 doc="length of the cylinder's straight part")
    edge_R: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                                 doc="radius of the cylinder's rounded ends")
    axis: str | None = _spec(None, choices=("x", "y"), doc="direction of the cylinder's axis (default x)")
    path: str | None = _spec(None, doc="profile file of shape = 'file' (.npz x, y, h; .npy or .csv rows x, y, h)")
    sha256: str | None = _spec(None, doc="SHA-256 of the profile file (filled in when left out, checked when given)")


@dataclass
class Load:
    Fn: float = _spec(21.19, 0, INF, lo_open=True, hi_open=True, unit="N", doc="normal force", modes=ALL_MODES)
    # from 1e-6: the tangential problem scales with mu, but squared tractions underflow far below it (mu = 1e-200
    # gave u_stat 1.6 % off, silently)
    mu: float = _spec(0.93, 1e-6, 10, doc="friction coefficient", modes=ALL_MODES)
    ft: float | None = _spec(None, 0, 1, doc="tangential force / (mu Fn)")
    Ft: float | None = _spec(None, 0, INF, hi_open=True, unit="N", doc="tangential force")
    load_angle: float = _spec(0.0, -360, 360, unit="deg", doc="direction of Ft from the x axis")
    ramp_steps: int = _spec(1, 1, 10000, doc="increments from 0 to Ft")
    levels: list = _spec([], -1, 1, doc="further f_t levels after the ramp (unloading, reversal)")
    # loads oscillating within each period (docs/theory.md §11.2-11.3, cases.scene.scene.Scene._check_oscillation):
    # f_t(theta) = ft + ft_amplitude sin(m theta + phase), Fn(theta) = Fn (1 + fn_amplitude sin(m theta + phase))
    ft_amplitude: float = _spec(0.0, 0, 1, doc="amplitude of f_t around its mean ft, in units of mu Fn")
    fn_amplitude: float = _spec(0.0, 0, 1, hi_open=True,
                                doc="relative amplitude of Fn around Fn (1 would lift the sphere off)")
    phase: float = _spec(0.0, -360, 360, unit="deg", doc="phase of the load oscillation relative to the rolling")
    cycles_per_period: int = _spec(1, 1, 1000, doc="load cycles per period")


@dataclass
class Motion:
    # no upper bound, as for W (w = 2 rolls two radii each way; the MDR limits of the seed hold for w <= 1)
    w: float | None = _spec(None, 0, INF, hi_open=True, doc="amplitude / contact radius a")
    W: float | None = _spec(None, 0, INF, hi_open=True, unit="mm", doc="amplitude of the centre")
    angle: float = _spec(90.0, -360, 360, unit="deg", doc="rolling direction relative to Ft")
    periods: int = _spec(10, 0, 100000, doc="oscillation periods")
    dW: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                             doc="largest rolling step (default: the element size dx)")
    steps_per_period: int = _spec(24, 4, 100000, doc="steps of a period of oscillating loads without rolling (w = 0)")
    speed: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm/s",
                                doc="rolling speed; gives each step the time dt = dW_used / speed (at rest, w = 0: "
                                    "dW / speed), loading steps included (default: none, time-independent)")


@dataclass
class Rolling:
    """Rolling on with prescribed creepages (solver.creep; docs/theory.md §7.3, §11.5), in Kalker's convention: body 1
    (the sphere) rolls along `direction` over body 2; xi, eta are the longitudinal and lateral rigid slip of body 1
    relative to body 2 per unit rolling distance, phi the spin (1/mm); the forces reported are those on body 1."""
    mode: str = _spec("none", choices=("none", "steady", "transient"),
                      doc="'steady': the steady state in contact-fixed coordinates; 'transient': stepped from the "
                          "`initial` state over `distance` in steps of `step` on the grid `grid`; 'none': no "
                          "[rolling]")
    xi: float | None = _spec(None, -1, 1, doc="longitudinal creepage (0 unless Fx, Fy are given)")
    eta: float | None = _spec(None, -1, 1, doc="lateral creepage (0 unless Fx, Fy are given)")
    phi: float = _spec(0.0, -INF, INF, lo_open=True, hi_open=True, unit="1/mm", doc="spin creepage")
    direction: float = _spec(0.0, -360, 360, unit="deg", doc="rolling direction from the x axis")
    Fx: float | None = _spec(None, -INF, INF, lo_open=True, hi_open=True, unit="N",
                             doc="prescribed longitudinal force on the sphere (with Fy; xi, eta solved for: steady, "
                                 "or per step of a transient run)")
    Fy: float | None = _spec(None, -INF, INF, lo_open=True, hi_open=True, unit="N",
                             doc="prescribed lateral force on the sphere (with Fx)")
    distance: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                                   doc="transient: distance rolled from the initial state (default: 4 contact "
                                       "lengths, 8 a; rounded up to whole steps)", modes=("transient",))
    # the upper bound (the contact's half-length a along the rolling direction) is checked by Scene._check_rolling
    step: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                               doc="transient: rolling step (default: the element size dx; "
                                   "at most the contact's half-length a along the rolling direction)",
                               modes=("transient",))
    grid: str | None = _spec(None, choices=("contact", "world"),
                             doc="transient: the grid the steps are solved on, 'contact' (moves with the contact, "
                                 "x from its centre; the previous step's tractions carried by the step, which must "
                                 "be a whole number of elements dx) or 'world' (fixed to the substrate, covering the "
                                 "distance rolled; any step); default 'contact' when the step is whole elements "
                                 "and nothing stays with the material (no viscoelastic body, friction law, "
                                 "[thermal] or FASTSIM), else 'world' (docs/creep_rolling.md)",
                             modes=("transient",))
    initial: str | None = _spec(None, choices=("rest", "cattaneo"),
                                doc="transient: initial state, 'rest' (Fn alone, zero tangential force; the default) "
                                    "or 'cattaneo' (then the tangential load of one step at rest)",
                                modes=("transient",))
    speed: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm/s",
                                doc="rolling speed V; transient: each step takes dt = step / V; steady: slip velocity "
                                    "= V x slip per unit rolled distance (default: none, time-independent)")


@dataclass
class Friction:
    """A friction law in place of [load] mu (solver.friction; docs/friction.md): the section given at all means a law,
    and load.mu is refused beside it. The keys that do not belong to the chosen law are refused
    (cases.scene.friction)."""
    law: str | None = _spec(None, choices=("coulomb", "linear", "rational", "exponential", "temperature"),
                            doc="friction law: 'coulomb' (mu), 'linear' | 'rational' | 'exponential' (mu_kin, mu_1, "
                                "s_1, mu_2, s_2: mu falls with the slip velocity), 'temperature' (mu_ref, T_ref, "
                                "dmu_heat, dT_heat; needs [thermal])")
    mu: float | None = _spec(None, 1e-6, 10, doc="coulomb: the friction coefficient")
    mu_kin: float | None = _spec(None, 0, 10, lo_open=True,
                                 doc="slip-velocity laws: the coefficient at high slip velocity")
    mu_1: float | None = _spec(None, 0, 10, doc="slip-velocity laws: size of the first term at s = 0")
    s_1: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm/s",
                              doc="slip-velocity laws: slip velocity halving the first term (linear: where it ends)")
    mu_2: float | None = _spec(None, 0, 10, doc="slip-velocity laws: size of the second term at s = 0 (default 0)")
    s_2: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm/s",
                              doc="slip-velocity laws: slip velocity halving the second term (with mu_2 > 0)")
    memory_distance: float | None = _spec(None, 0, INF, hi_open=True, unit="mm",
                                          doc="slip-velocity laws: sliding distance d_c over which the local "
                                              "coefficient relaxes to the law's (default 0: instantaneous)")
    memory_s0: float | None = _spec(None, 0, INF, hi_open=True, unit="mm/s",
                                    doc="with memory_distance > 0: the least rate max(s, s0) of the relaxation, so that "
                                        "it goes on where nothing slips (default 0)")
    mu_ref: float | None = _spec(None, 0, 10, lo_open=True, doc="temperature law: the coefficient below T_ref")
    T_ref: float | None = _spec(None, -273.15, INF, lo_open=True, hi_open=True, unit="degC",
                                doc="temperature law: the temperature where mu starts to change")
    dmu_heat: float | None = _spec(None, -10, 10, doc="temperature law: change of mu from T_ref to T_ref + dT_heat "
                                                      "(mu_ref + dmu_heat > 0)")
    dT_heat: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="degC",
                                  doc="temperature law: the temperature range of the change")


@dataclass
class Thermal:
    """Surface temperatures of the two bodies (bem.heat, solver.friction.thermal; docs/friction.md): body 1 the
    sphere (the rolling body), body 2 the substrate. For [rolling] scenes with rolling.speed."""
    conductivity1: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="W/(m K)",
                                        doc="thermal conductivity of body 1")
    density1: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="kg/m^3", doc="density of body 1")
    heat_capacity1: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="J/(kg K)",
                                         doc="specific heat capacity of body 1")
    T_bulk1: float = _spec(20.0, -273.15, INF, lo_open=True, hi_open=True, unit="degC",
                           doc="bulk temperature of body 1")
    conductivity2: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="W/(m K)",
                                        doc="thermal conductivity of body 2")
    density2: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="kg/m^3", doc="density of body 2")
    heat_capacity2: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="J/(kg K)",
                                         doc="specific heat capacity of body 2")
    T_bulk2: float = _spec(20.0, -273.15, INF, lo_open=True, hi_open=True, unit="degC",
                           doc="bulk temperature of body 2")


@dataclass
class WheelRail:
    """A wheel on its rail (solver.wheelrail; docs/wheelrail.md): two lateral profiles, the track and the wheelset,
    the wheelset's position, load and motion. Profiles: y positive towards the field side, z upwards (mm). Track
    frame for yaw and roll: x along the direction of travel, y to the left, z up (right-hand rule)."""
    wheel_profile: str | None = _spec(None, doc="wheel profile file: two columns y, z (mm; CSV or white space), or "
                                                "SIMPACK .prw (required)")
    rail_profile: str | None = _spec(None, doc="rail profile file: two columns y, z (mm), or SIMPACK .prr (required)")
    wheel_sha256: str | None = _spec(None, doc="SHA-256 of the wheel profile file (filled in when left out, checked "
                                               "when given)")
    rail_sha256: str | None = _spec(None, doc="SHA-256 of the rail profile file (filled in when left out, checked "
                                              "when given)")
    wheel_radius: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm",
                                       doc="nominal rolling radius at the wheel profile's reference point y = 0 "
                                           "(required)")
    rail_inclination: float | None = _spec(None, -0.2, 0.2, unit="rad",
                                           doc="inclination of the rail towards the track centre (0.025 for 1:40; 0 "
                                               "for a profile drawn inclined, as the Manchester benchmark's; "
                                               "required)")
    side: str | None = _spec(None, choices=("left", "right"), doc="which wheel and rail of the track (required)")
    gauge: float = _spec(1435.0, 0, INF, lo_open=True, hi_open=True, unit="mm",
                         doc="track gauge: distance of the rails' inner faces at gauge_height below their top")
    gauge_height: float = _spec(14.0, 0, INF, hi_open=True, unit="mm",
                                doc="depth below the top of the rail where the gauge is measured (0: no gauge point, "
                                    "the rail profile's origin at gauge / 2 from the track centre)")
    back_to_back: float = _spec(1360.0, 0, INF, lo_open=True, hi_open=True, unit="mm",
                                doc="distance of the wheels' flange backs")
    flange_back: float | None = _spec(None, -INF, INF, lo_open=True, hi_open=True, unit="mm",
                                      doc="y of the flange back in the wheel profile's coordinates (-70 for the "
                                          "published S1002; required)")
    y: float = _spec(0.0, -100, 100, unit="mm", doc="lateral displacement of the wheelset from its centred position, "
                                                    "positive towards the field side of this rail")
    yaw: float = _spec(0.0, -0.2, 0.2, unit="rad", doc="wheelset yaw angle (about the track's upward z)")
    roll: float = _spec(0.0, -0.2, 0.2, unit="rad", doc="wheelset roll angle (about the track's forward x)")
    Fz: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="N",
                             doc="vertical load on this wheel; the wheelset's height is solved for it (required)")
    speed: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="mm/s",
                                doc="forward speed of the wheelset (needed with omega)")
    xi: float | None = _spec(None, -1, 1, doc="longitudinal creepage at the nominal rolling radius, (V - omega r0) / "
                                              "((V + omega r0) / 2) (default 0 without omega)")
    omega: float | None = _spec(None, 0, INF, lo_open=True, hi_open=True, unit="rad/s",
                                doc="angular velocity of the wheelset about its axle, positive rolling forward "
                                    "(with speed; instead of xi)")


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
    fidelity: str = _spec("bem", choices=FIDELITIES,
                          doc="the model: 'bem' 3D boundary elements (Kalker's exact theory); 'mdr' the 1D MDR model "
                              "(shakedown scenes); 'fastsim', 'fastrip' Kalker's simplified theory and FaStrip "
                              "([rolling] scenes, docs/creep_fidelity.md); 'auto' the cheapest model whose measured "
                              "error is within solver.accuracy",
                          modes=("oscillating", "mdr", "steady", "transient", "wheelrail"))
    accuracy: float | None = _spec(None, 0, 1, lo_open=True, hi_open=True,
                                   doc="with fidelity = 'auto': the relative error allowed, of the tangential forces "
                                       "([rolling]) or of u_sd (shakedown scenes), against the exact 3D model "
                                       f"(default {DEFAULT_ACCURACY} with 'auto')",
                                   modes=("oscillating", "steady", "transient"))
    traction_bound: str | None = _spec(None, choices=("scene", "ellipsoid", "parabolic"),
                                       doc="traction bound mu p of fidelity 'fastsim' / 'fastrip': 'scene' (the "
                                           "default) the pressure of the scene's normal problem; 'ellipsoid' Hertz's "
                                           "semi-ellipsoid, 'parabolic' Kalker's 1982 parabola (FASTSIM only) over "
                                           "the Hertz contact ellipse", modes=("steady", "transient"))
    threads: int = _spec(1, 1, 256, doc="FFTW threads")
    coupling: str = _spec("auto", choices=("auto", "on", "off"), doc="normal-tangential coupling")
    shakedown_tol: float = _spec(1e-4, 0, 1, lo_open=True, doc="per-period increment |dU|/U0 taken as shakedown",
                                 modes=("oscillating", "mdr"))


@dataclass
class Output:
    fields: str = _spec("reversals", choices=("reversals", "all", "last", "none"),
                        doc="steps whose fields are stored")


SECTIONS = {"materials": Materials, "geometry": Geometry, "load": Load, "motion": Motion, "rolling": Rolling,
            "friction": Friction, "thermal": Thermal, "wheelrail": WheelRail, "grid": GridSpec, "solver": SolverSpec,
            "output": Output}
SECTION_ATTR = {"materials": "materials", "geometry": "geometry", "load": "load", "motion": "motion",
                "rolling": "rolling", "friction": "friction", "thermal": "thermal", "wheelrail": "wheelrail",
                "grid": "grid", "solver": "solver", "output": "output"}


def check_key(sec, f, value):
    """Validate one key against its field spec; return the (possibly converted) value."""
    meta, key = f.metadata, f"[{sec}] {f.name}"
    unit = f" {meta['unit']}" if meta.get("unit") else ""
    if meta.get("choices"):
        if value not in meta["choices"]:
            raise SceneError(f"{key} = {value!r}: allowed values are {list(meta['choices'])}")
        return value
    if f.type == "str | None":   # text keys without choices (geometry.path, geometry.sha256)
        if not isinstance(value, str) or not value:
            raise SceneError(f"{key} = {value!r}: expected a non-empty string")
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


def key_unit(key: str) -> str:
    """Unit of a scene key 'section.name' as written in HDF5 `units` attributes ('-': dimensionless or
    not a quantity; also for a key that is not a scene key)."""
    sec, _, name = key.partition(".")
    for f in fields(SECTIONS[sec]) if sec in SECTIONS else ():
        if f.name == name:
            return f.metadata.get("unit") or "-"
    return "-"


def key_modes(section: str, f) -> tuple:
    """The kinds of run (MODES) the key `f` (a dataclass field) of `section` applies to."""
    return f.metadata.get("modes") or SECTION_MODES.get(section, ALL_MODES)
