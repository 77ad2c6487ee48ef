"""The [friction] and [thermal] sections of a scene: which keys each friction law takes, what needs a rolling speed,
and the solver objects they make (docs/friction.md). Units: mm, s, mm/s, degC; [thermal] in W/(m K), kg/m^3,
J/(kg K).

Rules (each refused with a SceneError naming the key, before any work):

* [friction] given means a friction law: `law` is required, and [load] mu is refused beside it (the law's static
  coefficient mu(0) takes its place: f_t = Ft/(mu_static Fn) and u = U/U0 use it);
* each law takes its own keys and no others: coulomb mu; linear, rational, exponential mu_kin, mu_1, s_1 and
  optionally mu_2, s_2 (s_2 with mu_2 > 0), memory_distance, memory_s0 (memory_s0 with memory_distance > 0);
  temperature mu_ref, T_ref, dmu_heat, dT_heat (with mu_ref + dmu_heat > 0) and a [thermal] section;
* the slip-velocity laws need a speed (motion.speed, or rolling.speed in a [rolling] scene), and so does [thermal];
* [thermal] applies to [rolling] scenes (the heat source moving steadily over both bodies at rolling.speed); the
  oscillating and shift scenes, which move back and forth, are refused;
* a law other than coulomb needs the boundary elements (solver.fidelity = "bem") and creepages, not prescribed
  forces (rolling.Fx, Fy: a falling creep curve has two creepages below its peak and none above).
"""
from __future__ import annotations

from dataclasses import fields

from rollcontact.bem.errors import SceneError

#: law -> (required keys, optional keys)
LAW_KEYS = {
    "coulomb": (("mu",), ()),
    "linear": (("mu_kin", "mu_1", "s_1"), ("mu_2", "s_2", "memory_distance", "memory_s0")),
    "rational": (("mu_kin", "mu_1", "s_1"), ("mu_2", "s_2", "memory_distance", "memory_s0")),
    "exponential": (("mu_kin", "mu_1", "s_1"), ("mu_2", "s_2", "memory_distance", "memory_s0")),
    "temperature": (("mu_ref", "T_ref", "dmu_heat", "dT_heat"), ()),
}
THERMAL_REQUIRED = ("conductivity1", "density1", "heat_capacity1", "conductivity2", "density2", "heat_capacity2")


def friction_on(scene) -> bool:
    """True when the scene has a [friction] law."""
    return scene.friction.law is not None


def thermal_on(scene) -> bool:
    """True when the scene has a [thermal] section (its conductivities given)."""
    return scene.thermal.conductivity1 is not None


def check_friction(scene, data: dict):
    """Refuse what the module docstring lists; with a law, put its static coefficient in scene.load.mu."""
    given = data.get("friction", {})
    thermal_given = data.get("thermal", {})
    fr = scene.friction
    if given and fr.law is None:
        raise SceneError(f"[friction] {sorted(given)} without law: give law = 'coulomb', 'linear', 'rational', "
                         "'exponential' or 'temperature'")
    if thermal_given:
        missing = [k for k in THERMAL_REQUIRED if k not in thermal_given]
        if missing:
            raise SceneError(f"[thermal] needs {', '.join(missing)} (W/(m K), kg/m^3, J/(kg K) of both bodies); "
                             f"given: {sorted(thermal_given)}")
        if not scene.rolling_on:
            raise SceneError("[thermal] applies to [rolling] scenes (mode 'steady' or 'transient', with "
                             "rolling.speed): the temperatures are those of a heat source moving steadily over both "
                             "bodies; an oscillating or shift scene moves back and forth; remove [thermal]")
        if scene.speed is None:
            raise SceneError("[thermal] needs rolling.speed (mm/s): the bodies' material passes through the heat "
                             "source at the rolling speed")
    if fr.law is None:
        return
    if "mu" in data.get("load", {}):
        raise SceneError(f"[load] mu = {data['load']['mu']!r} together with [friction]: the friction law gives the "
                         "coefficient; remove load.mu (its static value mu(0) is used for f_t and u)")
    required, optional = LAW_KEYS[fr.law]
    allowed = set(required) | set(optional) | {"law"}
    for f in fields(fr):
        if f.name not in allowed and getattr(fr, f.name) is not None:
            raise SceneError(f"[friction] {f.name} = {getattr(fr, f.name)!r} does not apply to law = {fr.law!r}; "
                             f"its keys are {', '.join(required + optional)}")
    missing = [k for k in required if getattr(fr, k) is None]
    if missing:
        raise SceneError(f"[friction] law = {fr.law!r} needs {', '.join(missing)}")
    if fr.mu_2 and fr.s_2 is None:
        raise SceneError(f"[friction] mu_2 = {fr.mu_2!r} needs s_2 (mm/s, > 0)")
    if fr.s_2 is not None and not fr.mu_2:
        raise SceneError(f"[friction] s_2 = {fr.s_2!r} mm/s without mu_2 > 0: give mu_2 or remove s_2")
    if fr.memory_s0 is not None and not fr.memory_distance:
        raise SceneError(f"[friction] memory_s0 = {fr.memory_s0!r} mm/s applies with memory_distance > 0 only")
    if fr.law == "temperature":
        if fr.mu_ref + fr.dmu_heat <= 0:
            raise SceneError(f"[friction] dmu_heat = {fr.dmu_heat!r}: mu_ref + dmu_heat must be > 0 (mu_ref = "
                             f"{fr.mu_ref!r}); allowed range dmu_heat > {-fr.mu_ref!r}")
        if not thermal_given:
            raise SceneError("[friction] law = 'temperature' needs the surface temperatures: give a [thermal] section")
    if fr.law in ("linear", "rational", "exponential") and scene.speed is None:
        key = "rolling.speed" if scene.rolling_on else "motion.speed"
        raise SceneError(f"[friction] law = {fr.law!r} needs the rolling speed {key} (mm/s): the slip velocity is the "
                         "slip per step over the step's time (or the speed times the slip per unit rolled distance)")
    if fr.law != "coulomb":
        if scene.solver.fidelity != "bem":
            raise SceneError(f"[solver] fidelity = {scene.solver.fidelity!r} with [friction] law = {fr.law!r}: the "
                             "friction laws need the boundary elements; allowed value is 'bem'")
        if scene.rolling_on and scene.rolling.Fx is not None:
            raise SceneError(f"[rolling] Fx, Fy with [friction] law = {fr.law!r}: with falling friction a force below "
                             "the creep curve's peak has two creepages and one above it none; give the creepages "
                             "xi, eta")
    scene.load.mu = friction_law(scene).mu_static


def friction_law(scene):
    """The scene's solver.friction.FrictionLaw (None without [friction])."""
    from rollcontact.solver.friction import FrictionLaw
    fr = scene.friction
    if fr.law is None:
        return None
    values = {f.name: getattr(fr, f.name) for f in fields(fr) if f.name not in ("law", "memory_distance", "memory_s0")}
    return FrictionLaw(fr.law, **{k: float(v) for k, v in values.items() if v is not None})


def local_friction(scene, grid=None):
    """The scene's solver.friction.LocalFriction (None without [friction] and [thermal]): its law (with [thermal]
    alone, Coulomb's with load.mu), memory and speed, the iteration's tolerance and budget [solver] tol and max_iter,
    and on `grid` (the run's: x along the rolling direction) the contact temperatures of [thermal]."""
    from rollcontact.solver.friction import FrictionLaw, FrictionMemory, FrictionParams, LocalFriction
    law = friction_law(scene)
    if law is None and not thermal_on(scene):
        return None
    law = law or FrictionLaw("coulomb", mu=scene.load.mu)
    fr = scene.friction
    memory = FrictionMemory(fr.memory_distance or 0.0, fr.memory_s0 or 0.0)
    thermal = contact_temperature(scene, grid) if grid is not None and thermal_on(scene) else None
    params = FrictionParams(tol=scene.solver.tol, max_iter=scene.solver.max_iter)
    return LocalFriction(law, memory, scene.speed, params, thermal)


def thermal_bodies(scene):
    """(body 1, body 2) as bem.heat.ThermalBody (conductivity W/(mm K), diffusivity mm^2/s)."""
    from rollcontact.bem.heat import ThermalBody
    th = scene.thermal
    return (ThermalBody.from_si(th.conductivity1, th.density1, th.heat_capacity1),
            ThermalBody.from_si(th.conductivity2, th.density2, th.heat_capacity2))


def contact_temperature(scene, grid):
    """The solver.friction.ContactTemperature of [thermal] on `grid` at the rolling speed (None without [thermal])."""
    from rollcontact.solver.friction import ContactTemperature
    if not thermal_on(scene):
        return None
    body1, body2 = thermal_bodies(scene)
    return ContactTemperature(grid, body1, body2, scene.speed, scene.thermal.T_bulk1, scene.thermal.T_bulk2)
