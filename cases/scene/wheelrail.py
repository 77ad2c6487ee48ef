"""The [wheelrail] section of a scene: a wheel on its rail (solver.wheelrail; docs/wheelrail.md). Its checks, the
geometry it describes, and the estimates a scene derives from it. Units: mm, N, MPa, rad, s.

A [wheelrail] scene has no [geometry] or [motion] and no tangential or normal load in [load] (only mu): the contact
follows from the profiles, the wheelset's position and the load Fz; the creepages from its motion. Its [rolling]
takes only mode ("steady", the default, or "transient": each patch then rolls from an initial state, solver.wheelrail.
transient) and a transient's distance, step and initial. It
needs the materials of both bodies ([materials] E1, nu1: the wheel; E2, nu2: the rail; their defaults are the seed
paper's rubber substrate) and the BEM model with a patch solver of solver.wheelrail.PATCH_SOLVERS ([solver]
fidelity). Normal and tangential problems are solved uncoupled: dissimilar materials (Kalker's K != 0) need
[solver] coupling = "off", which says so.

Checked when the scene is read for a new run (run_limits): the profile files (cases.scene.wheelrail_profiles; their
checksums filled in as wheelrail.wheel_sha256, rail_sha256, or checked when given), the placement of the rail (its
gauge point), and that both profiles cover the contact the scene's position and load give (the interpenetration at
twice a Hertz estimate of the approach). The contact's semi-axes for the default grid (grid.dx = the smaller / 12)
are Hertz's at the first touch, with the wheel's radius along x and the profiles' relative curvature across.
"""
from __future__ import annotations

from dataclasses import astuple, replace
import math
from pathlib import Path

from rollcontact.bem.errors import InputError, SceneError
from rollcontact.cases.scene.wheelrail_profiles import read_profile
from rollcontact.solver.wheelrail import ContactSearch, Profile, WheelPlacement, place_rail
from rollcontact.solver.wheelrail.patch import omega_per_speed as _omega_per_speed

#: keys a [wheelrail] scene must give
REQUIRED = ("wheel_profile", "rail_profile", "wheel_radius", "rail_inclination", "side", "flange_back", "Fz")
#: sections a [wheelrail] scene may not have, and why
EXCLUDED = {"geometry": "the contact's geometry follows from the wheel and rail profiles",
            "motion": "the wheelset rolls steadily; its motion is [wheelrail] speed, xi or omega"}
#: the [rolling] keys a [wheelrail] scene takes
ROLLING_KEYS = ("mode", "distance", "step", "initial")
#: the only [load] key a [wheelrail] scene takes
LOAD_KEYS = ("mu",)

_ESTIMATES: dict = {}


def check_sections(data: dict):
    """SceneError for what a [wheelrail] scene may not hold (module docstring), from the raw scene tables."""
    for sec, why in EXCLUDED.items():
        if sec in data:
            raise SceneError(f"[wheelrail] and [{sec}] exclude each other: {why}; remove the [{sec}] section")
    extra = sorted(set(data.get("load", {})) - set(LOAD_KEYS))
    if extra:
        hint = " (the vertical load is [wheelrail] Fz)" if "Fn" in extra else ""
        raise SceneError(f"[load] {', '.join(extra)} with [wheelrail]: a wheel-rail scene takes only load.mu from "
                         f"[load]{hint}; remove {', '.join('load.' + k for k in extra)}")
    rolling = data.get("rolling", {})
    extra = sorted(set(rolling) - set(ROLLING_KEYS))
    if extra:
        raise SceneError(f"[rolling] {', '.join(extra)} with [wheelrail]: the creepages follow from the wheelset's "
                         "motion ([wheelrail] xi or omega, yaw); [rolling] takes only mode = \"transient\" with "
                         "distance, step and initial")
    if rolling.get("mode", "steady") == "none":
        raise SceneError("[rolling] mode = 'none' with [wheelrail]: a wheel-rail scene rolls; allowed values are "
                         "'steady' (the default) and 'transient'")
    for key in ("distance", "step", "initial"):
        if key in rolling and rolling.get("mode") != "transient":
            raise SceneError(f"[rolling] {key} with mode = {rolling.get('mode', 'steady')!r}: {key} applies to "
                             "mode = 'transient' only")
    if "margin" in data.get("grid", {}):
        raise SceneError("[grid] margin with [wheelrail]: the patch grids cover each patch's interpenetration region "
                         "(which holds its contact) and one cell more; remove grid.margin")
    materials = data.get("materials", {})
    missing = [k for k in ("E1", "nu1", "E2", "nu2") if k not in materials]
    if missing:
        raise SceneError(f"[wheelrail] needs both materials: give [materials] {', '.join(missing)} (E1, nu1 the "
                         "wheel's, E2, nu2 the rail's; e.g. steel E = 210000.0 MPa, nu = 0.28; the defaults are the "
                         "seed paper's rubber)")


def check_keys(scene):
    """SceneError for missing or inconsistent [wheelrail] keys and for a [solver] it cannot use."""
    wr = scene.wheelrail
    missing = [k for k in REQUIRED if getattr(wr, k) is None]
    if missing:
        raise SceneError(f"[wheelrail] needs {', '.join(missing)} (keys: wheel_profile, rail_profile (files), "
                         "wheel_radius (mm), rail_inclination (rad, 0.025 for 1:40), side ('left' or 'right'), "
                         "flange_back (mm, -70 for the published S1002), Fz (N))")
    if wr.xi is not None and wr.omega is not None:
        raise SceneError("[wheelrail] give either xi (the longitudinal creepage at the nominal rolling radius) or omega "
                         "(rad/s, with speed), not both")
    if wr.omega is not None and wr.speed is None:
        raise SceneError(f"[wheelrail] omega = {wr.omega!r} rad/s needs the forward speed: give [wheelrail] speed "
                         "(mm/s), or the creepage xi instead of omega")
    from rollcontact.bem.operator import COUPLING_THRESHOLD
    from rollcontact.solver.wheelrail.solve import PATCH_SOLVERS
    if scene.solver.fidelity not in PATCH_SOLVERS:
        raise SceneError(f"[solver] fidelity = {scene.solver.fidelity!r} with [wheelrail]: allowed values are "
                         f"{sorted(PATCH_SOLVERS)} (the patches' tangential solver)")
    pair = scene.material_pair
    if abs(pair.beta) > COUPLING_THRESHOLD and scene.solver.coupling != "off":
        raise SceneError(f"[wheelrail] with dissimilar materials (Dundurs' beta = {pair.beta:.3g}): the patches are "
                         "solved with the normal and tangential problems uncoupled; set [solver] coupling = \"off\" to "
                         "accept that approximation")


def checked_files(wr):
    """The section with its profile paths made absolute and their checksums filled in (or checked: SceneError when a
    file changed), and the checksum keys filled in (derived keys)."""
    filled, changes = set(), {}
    for key, sum_key in (("wheel_profile", "wheel_sha256"), ("rail_profile", "rail_sha256")):
        path = str(Path(getattr(wr, key)).expanduser().resolve())
        digest = read_profile(path, key)[2]
        given = getattr(wr, sum_key)
        if given is not None and given != digest:
            raise SceneError(f"[wheelrail] {sum_key} = {given!r} does not match the file {path!r} (sha256 {digest}): "
                             "the file changed since the scene was written; restore it, or leave the checksum out to "
                             "accept it")
        if given is None:
            filled.add(f"wheelrail.{sum_key}")
        changes[key], changes[sum_key] = path, digest
    return replace(wr, **changes), filled


def geometry(wr):
    """(RailPlacement, WheelPlacement) of a checked section; SceneError naming the key for a profile the placement
    cannot use."""
    y, z, _ = read_profile(wr.rail_profile, "rail_profile")
    try:
        rail = place_rail(Profile(y, z, "rail profile"), wr.rail_inclination, wr.gauge, wr.gauge_height)
    except InputError as exc:
        raise SceneError(f"[wheelrail] rail_profile = {wr.rail_profile!r}: {exc}") from None
    y, z, _ = read_profile(wr.wheel_profile, "wheel_profile")
    try:
        wheel = WheelPlacement.on_wheelset(Profile(y, z, "wheel profile"), wr.wheel_radius, wr.back_to_back,
                                           wr.flange_back)
    except InputError as exc:
        raise SceneError(f"[wheelrail] wheel_profile = {wr.wheel_profile!r}: {exc}") from None
    return rail, wheel


def side_sign(wr) -> float:
    """+1 for the left wheel, -1 for the right: the track's y (to the left) over the side frame's (to the field)."""
    return 1.0 if wr.side == "left" else -1.0


def search(wr):
    """The contact search (solver.wheelrail.ContactSearch) of a checked section at its position."""
    rail, wheel = geometry(wr)
    s = side_sign(wr)
    try:
        return ContactSearch(rail, wheel, wr.y, s * wr.yaw, s * wr.roll)
    except InputError as exc:
        raise SceneError(f"[wheelrail] y = {wr.y!r} mm: {exc}") from None


def estimate(scene) -> tuple[float, float, float]:
    """(a, b, approach) (mm): Hertz's semi-axes along x and across, and approach, at the first touch under Fz (module
    docstring); cached per section and materials."""
    from rollcontact.solver.analytic import HertzEllipse
    wr = scene.wheelrail
    key = (astuple(wr), astuple(scene.materials))
    if key not in _ESTIMATES:
        found = search(wr)
        k = max(found.curvature_estimate(), 1.0 / (50.0 * wr.wheel_radius))
        hertz = HertzEllipse(wr.wheel_radius, 1.0 / k, scene.material_pair.E_star, wr.Fz)
        _ESTIMATES[key] = (hertz.a, hertz.b, hertz.approach)
    return _ESTIMATES[key]


def check_coverage(scene):
    """SceneError unless both profiles cover the interpenetration at twice the estimated approach."""
    approach = estimate(scene)[2]
    try:
        search(scene.wheelrail).regions(2.0 * approach)
    except InputError as exc:
        raise SceneError(f"[wheelrail] {exc}") from None


def omega_per_speed(wr) -> float:
    """The wheelset's omega / V (rad/mm): from omega and speed, or from xi (default 0) at the nominal radius."""
    if wr.omega is not None:
        return wr.omega / wr.speed
    return _omega_per_speed(wr.wheel_radius, 0.0 if wr.xi is None else wr.xi)


def nominal_xi(wr) -> float:
    """The longitudinal creepage at the nominal rolling radius, xi = (V - omega r0) / ((V + omega r0) / 2)."""
    k = omega_per_speed(wr) * wr.wheel_radius
    return 2.0 * (1.0 - k) / (1.0 + k) if math.isfinite(k) else math.nan
