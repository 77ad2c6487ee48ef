"""The checks of a scene's keys against each other (`SceneChecks`, a mixin of `cases.scene.Scene`, called by
`Scene.from_dict`): a [rolling] scene without [motion] or a tangential load, one spelling of each quantity, an
oscillating load that never slides, and moduli, geometry and load whose contact has a finite positive size. Each
raises SceneError naming the keys and what is allowed. Units: mm, N, MPa, degrees.
"""
from __future__ import annotations

from dataclasses import fields
import math

import numpy as np

from rollcontact.bem.errors import SceneError
from rollcontact.cases.scene.geometry import resolve_shape
from rollcontact.cases.scene.keys import FAST_FIDELITIES
from rollcontact.cases.scene.limits import MAX_STEPS


class SceneChecks:
    """Consistency checks of `cases.scene.Scene` (a mixin without fields)."""

    def _check_rolling(self, data: dict):
        """A [rolling] scene has no [motion], no tangential load, and a model of rolling with creepage."""
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
        for key, unit in (("distance", " mm"), ("step", " mm"), ("initial", ""), ("grid", "")):
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
        self._check_fast_rolling()

    def _check_fast_rolling(self):
        """The models of a [rolling] scene: 'bem', the fast models of solver.fastsim (steady creepages; FaStrip steady
        only), 'auto'; and the fast models' traction bound (docs/creep_fidelity.md)."""
        so, ro = self.solver, self.rolling
        if so.fidelity == "mdr":
            raise SceneError("[solver] fidelity = 'mdr' with [rolling]: the 1-D MDR model has no creepage; allowed "
                             "values are ['bem', 'fastsim', 'fastrip', 'auto']")
        if so.fidelity in FAST_FIDELITIES:
            if self.prescribed_forces is not None:
                raise SceneError(f"[rolling] Fx, Fy with [solver] fidelity = {so.fidelity!r}: the fast models take "
                                 "the creepages xi, eta; give those, or use fidelity = 'bem'")
            if so.coupling == "on":
                raise SceneError(f"[solver] coupling = 'on' with fidelity = {so.fidelity!r}: the fast models have no "
                                 "normal-tangential coupling; use fidelity = 'bem', or coupling = 'auto' / 'off'")
            if so.fidelity == "fastrip" and ro.mode == "transient":
                raise SceneError("[solver] fidelity = 'fastrip' with [rolling] mode = 'transient': FaStrip (strip "
                                 "theory) is a steady-state theory; use fidelity = 'fastsim' or 'bem', or mode = "
                                 "'steady'")
        if so.traction_bound in (None, "scene"):
            return
        if so.fidelity not in FAST_FIDELITIES:
            raise SceneError(f"[solver] traction_bound = {so.traction_bound!r} with fidelity = {so.fidelity!r}: the "
                             "bound is chosen for the fast models only; set fidelity = 'fastsim' or 'fastrip', or "
                             "remove solver.traction_bound")
        if so.fidelity == "fastrip" and so.traction_bound == "parabolic":
            raise SceneError("[solver] traction_bound = 'parabolic' with fidelity = 'fastrip': the parabolic bound is "
                             "FASTSIM's; FaStrip's strips carry the semi-ellipsoid ('ellipsoid' or 'scene')")
        (sa, sb), turned = self.semi_axes, ro.direction % 180.0
        if self.shape not in ("sphere", "ellipsoid") or (sa != sb and turned not in (0.0, 90.0)):
            raise SceneError(f"[solver] traction_bound = {so.traction_bound!r}: Hertz's contact ellipse is known for a "
                             "sphere or an ellipsoid rolling along one of its axes ([rolling] direction 0 or 90 deg); "
                             "use traction_bound = 'scene' (the pressure of the normal problem)")

    def _check_fidelity(self):
        """The fast models are for [rolling] scenes; solver.accuracy goes with fidelity = 'auto'."""
        so = self.solver
        if so.fidelity in FAST_FIDELITIES and not self.rolling_on:
            raise SceneError(f"[solver] fidelity = {so.fidelity!r}: a model of rolling with creepage, for scenes with a "
                             "[rolling] section; allowed values here are ['bem', 'mdr', 'auto']")
        if so.traction_bound is not None and not self.rolling_on:
            raise SceneError(f"[solver] traction_bound = {so.traction_bound!r}: applies to the fast models of [rolling] "
                             "scenes only; remove solver.traction_bound")
        if so.accuracy is not None and so.fidelity != "auto":
            raise SceneError(f"[solver] accuracy = {so.accuracy!r} with fidelity = {so.fidelity!r}: the accuracy is "
                             "what fidelity = 'auto' chooses a model for; set fidelity = 'auto', or remove "
                             "solver.accuracy")

    def _check_transient_grid(self):
        """[rolling] grid = 'contact' needs a step of whole elements (the grid moves by whole cells) and elastic
        bodies with Coulomb's friction and no [thermal] (a viscoelastic body's element states, a friction law's memory
        and the temperatures stay with the material, on the world-fixed grid)."""
        ro = self.rolling
        if ro.mode != "transient" or ro.grid != "contact":
            return
        if not self._whole_steps():
            raise SceneError(f"[rolling] grid = 'contact' with step = {ro.step!r} mm = {ro.step / self.spacing[0]:.6g} "
                             f"elements of dx = {self.spacing[0]!r} mm: the grid that moves with the contact needs a "
                             "whole number of elements per step; set step = k dx, or grid = 'world'")
        if self.solver.fidelity == "fastsim":
            raise SceneError("[rolling] grid = 'contact' with [solver] fidelity = 'fastsim': FASTSIM's transient "
                             "steps the world-fixed grid (its strips carry their state along the material); set "
                             "grid = 'world' or leave grid out")
        if self.viscoelastic:
            keys = [f"materials.visco{i}" for i in (1, 2) if getattr(self.materials, f"visco{i}") == "sls"]
            raise SceneError(f"[rolling] grid = 'contact' with {', '.join(keys)} = 'sls': a viscoelastic body's "
                             "element states stay with its material, which the grid moving with the contact leaves "
                             "behind; set grid = 'world' (the default for viscoelastic bodies)")
        if self.friction_on or self.thermal_on:
            section = "[friction] law" if self.friction_on else "[thermal]"
            raise SceneError(f"[rolling] grid = 'contact' with a {section}: the friction memory and temperatures stay "
                             "with the material, which the grid moving with the contact leaves behind; set grid = "
                             "'world' (the default with [friction] or [thermal])")

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

    def _check_visco(self):
        """A viscoelastic body (materials.visco<i> = 'sls', docs/viscoelastic.md) has a finite glassy modulus E<i>, a
        relaxed modulus below it and a relaxation time, and its scene a speed and the boundary elements; an elastic
        body takes no relaxed modulus or relaxation time. Refused with the key named, before any work."""
        m = self.materials
        for i in (1, 2):
            visco, E = getattr(m, f"visco{i}"), getattr(m, f"E{i}")
            relaxed, tau = getattr(m, f"E{i}_relaxed"), getattr(m, f"tau{i}")
            if visco != "sls":
                for key, value in ((f"E{i}_relaxed", relaxed), (f"tau{i}", tau)):
                    if value is not None:
                        raise SceneError(f"[materials] {key} = {value!r} for an elastic body (visco{i} left out or "
                                         f"'none'): a relaxed modulus and a relaxation time belong to a viscoelastic "
                                         f"body; set materials.visco{i} = 'sls' or remove materials.{key}")
                continue
            for key, value, unit in ((f"E{i}_relaxed", relaxed, "MPa"), (f"tau{i}", tau, "s")):
                if value is None:
                    raise SceneError(f"[materials] visco{i} = 'sls' needs materials.{key} ({unit}): the standard linear "
                                     f"solid's {'relaxed modulus' if unit == 'MPa' else 'creep relaxation time'}")
            if math.isinf(E):
                raise SceneError(f"[materials] E{i} = inf with visco{i} = 'sls': a rigid body cannot be viscoelastic; "
                                 f"give the glassy (instantaneous) modulus as E{i} (MPa)")
            if not relaxed < E:
                raise SceneError(f"[materials] E{i}_relaxed = {relaxed!r} MPa with E{i} = {E!r} MPa: allowed range is "
                                 f"(0, {E!r}) MPa (the relaxed modulus below the glassy one, E{i})")
        if not self.viscoelastic:
            return
        keys = [f"materials.visco{i}" for i in (1, 2) if getattr(m, f"visco{i}") == "sls"]
        if self.speed is None:
            where = "[rolling] speed" if self.rolling_on else "[motion] speed"
            raise SceneError(f"{', '.join(keys)} = 'sls' without a speed: a viscoelastic body needs the rolling speed "
                             f"(mm/s, > 0) that gives its steps their time; set {where.replace('[', '').replace('] ', '.')}")
        if self.solver.fidelity != "bem":
            raise SceneError(f"[solver] fidelity = {self.solver.fidelity!r} with {', '.join(keys)} = 'sls': the MDR "
                             "model and the fast models (and the maps of 'auto') have no viscoelastic bodies; allowed "
                             "value is 'bem'")

    def _check_friction_models(self, data: dict):
        """[friction] laws and [thermal] (docs/friction.md) with the other models: a wheel-rail scene takes neither
        (its patches use load.mu); viscoelastic bodies take neither (the slip-velocity iteration and the contact
        temperatures are of elastic half-spaces: [load] mu there); [thermal] needs the boundary elements (the fast models have no
        slip-velocity field to heat with). A law other than 'coulomb' with another fidelity is refused by
        cases.scene.friction.check_friction; 'coulomb' gives load.mu to any model."""
        given = [f"[{sec}]" for sec in ("friction", "thermal") if data.get(sec)]
        if not given:
            return
        if "wheelrail" in data or self.wheelrail_on:
            raise SceneError(f"{' and '.join(given)} with [wheelrail]: friction laws and surface temperatures are not "
                             "supported in wheel-rail scenes (each patch takes load.mu); remove "
                             f"{' and '.join(given)}")
        if self.viscoelastic:
            keys = [f"materials.visco{i}" for i in (1, 2) if getattr(self.materials, f"visco{i}") == "sls"]
            raise SceneError(f"{' and '.join(given)} with {', '.join(keys)} = 'sls': friction laws and surface "
                             "temperatures are for elastic bodies; remove the viscoelastic keys, or give the "
                             f"coefficient as [load] mu and remove {' and '.join(given)}")
        if data.get("thermal") and self.solver.fidelity != "bem":
            raise SceneError(f"[thermal] with [solver] fidelity = {self.solver.fidelity!r}: the surface temperatures "
                             "are computed from the boundary elements' slip velocities; allowed value is 'bem'")

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

    def _check_oscillation(self):
        """Refuse a load schedule that lifts the sphere off or slides (docs/theory.md §11.2-11.3), before any work.

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
