"""Which model runs a scene ([solver] fidelity), and for fidelity = "auto" the cheapest model whose measured error
is within [solver] accuracy (docs/creep_fidelity.md).

[rolling] scenes: FASTSIM, then FaStrip (steady only), then the boundary elements (Kalker's exact theory, the
reference), by cost; a fast model is taken when its error predicted by the measured map (solver.fastsim.error_map:
|F - F_exact| / |F_exact| over a/b, nu and the creepages in saturation units) is within the accuracy. Shakedown
scenes: the 1-D MDR model when its error in u_sd predicted by its measured map (solver.mdr.error_map, over w and
f_t per alignment) is within the accuracy, else the 3-D solver. A scene outside a map's measured domain (another
shape, coupled materials, prescribed forces, a/b or nu or w outside the map, oscillating loads, ...) runs on the
boundary elements, and the reason says so. The choice is written to stderr as one line and recorded in the run's
summary (fidelity_used, predicted_error, accuracy, fidelity_reason).
"""
from __future__ import annotations

from dataclasses import dataclass
import math
import sys

from rollcontact.cases.scene.keys import DEFAULT_ACCURACY
from rollcontact.cases.scene.scene import Scene

#: The fast models in the order of their cost (solver.fastsim.error_map's seconds_per_case).
FAST_BY_COST = ("fastsim", "fastrip")
NAMES = {"fastsim": "FASTSIM", "fastrip": "FaStrip", "bem": "the boundary elements", "mdr": "the 1-D MDR model"}


@dataclass
class FidelityChoice:
    """The model that runs ("bem", "mdr", "fastsim", "fastrip"), what the scene asked for, and for 'auto' the
    accuracy requested, the chosen model's predicted error (0 for the boundary elements: the maps' reference) and
    why it was chosen."""
    model: str
    requested: str
    accuracy: float | None = None
    predicted_error: float | None = None
    reason: str = ""

    @property
    def automatic(self) -> bool:
        return self.requested == "auto"

    def summary(self) -> dict:
        """The run summary's fidelity values."""
        out = dict(fidelity=self.model, fidelity_used=self.model)
        if self.automatic:
            out.update(accuracy=self.accuracy, predicted_error=self.predicted_error, fidelity_reason=self.reason)
        return out

    def message(self) -> str:
        return (f"solver.fidelity = 'auto' (accuracy {self.accuracy:g}): {NAMES[self.model]} ('{self.model}', "
                f"predicted error {self.predicted_error:.3g}); {self.reason}")

    def announce(self, stream=None):
        """Write the choice to stderr (or `stream`) when it was made automatically."""
        if self.automatic:
            print(f"rollcontact: {self.message()}", file=stream or sys.stderr, flush=True)


def choose_fidelity(scene: Scene) -> FidelityChoice:
    """The model for `scene` (module docstring)."""
    requested = scene.solver.fidelity
    if requested != "auto":
        return FidelityChoice(requested, requested)
    accuracy = scene.solver.accuracy if scene.solver.accuracy is not None else DEFAULT_ACCURACY
    if scene.rolling_on:
        model, error, reason = _rolling_choice(scene, accuracy)
    else:
        model, error, reason = _shakedown_choice(scene, accuracy)
    return FidelityChoice(model, requested, accuracy, error, reason)


def _rolling_choice(scene: Scene, accuracy: float):
    from rollcontact.bem.operator import COUPLING_THRESHOLD
    from rollcontact.cases.run.rolling_frame import rolling_semi_axes
    from rollcontact.solver.fastsim.error_map import load_error_map, normalised_creepages
    pair = scene.material_pair
    if scene.prescribed_forces is not None:
        return "bem", 0.0, "prescribed forces Fx, Fy: the map is over creepages (the fast models take creepages)"
    coupling = scene.solver.coupling
    if coupling == "on" or (coupling == "auto" and abs(pair.beta) > COUPLING_THRESHOLD):
        return "bem", 0.0, (f"coupled materials (Dundurs beta = {pair.beta:.3g}): the fast models have no "
                            "normal-tangential coupling and the map none either")
    axes = rolling_semi_axes(scene)
    if scene.shape not in ("sphere", "ellipsoid") or axes is None:
        return "bem", 0.0, (f"shape {scene.shape!r} rolling at {scene.rolling.direction:g} deg: the map holds Hertzian "
                            "ellipses rolling along an axis")
    a, b = axes
    nu = min(max(pair.nu, 0.0), 0.5)
    hat = normalised_creepages(*scene.creepages, a, b, pair.G, nu, scene.load.mu, scene.load.Fn)
    emap = load_error_map()
    where = (f"a/b = {a / b:.3g}, nu = {nu:.3g}, creepages / saturation (xi, eta, phi) = "
             f"({hat[0]:.3g}, {hat[1]:.3g}, {hat[2]:.3g})")
    predictions = []
    for model in FAST_BY_COST:
        if model == "fastrip" and scene.rolling.mode == "transient":
            predictions.append("FaStrip is steady only")
            continue
        error = emap.predict(model, a / b, nu, *hat)
        if error is None:
            return "bem", 0.0, f"{where} lies outside the measured map (a/b 0.2-5, nu 0-0.5)"
        if error <= accuracy:
            cheaper = f" ({'; '.join(predictions)})" if predictions else ""
            return model, error, (f"the cheapest model within the accuracy at {where}{cheaper}; measured map, "
                                  f"largest error at the corners of its cell")
        predictions.append(f"{NAMES[model]} {error:.3g}")
    return "bem", 0.0, (f"the fast models' predicted errors at {where} exceed {accuracy:g} ({'; '.join(predictions)})"
                        "; the exact theory")


def _shakedown_choice(scene: Scene, accuracy: float):
    from rollcontact.solver.mdr.error_map import load_mdr_map
    mdr_map = load_mdr_map()
    why = mdr_map.outside(scene_point(scene))
    if why:
        return "bem", 0.0, f"{why}: the 3-D solver"
    point = scene_point(scene)
    error = mdr_map.predict(point)
    where = f"w = {point['w']:.3g}, f_t = {point['f_t']:.3g}, rolling angle {point['angle']:g} deg"
    if error is not None and error <= accuracy:
        return "mdr", error, f"the MDR model's measured u_sd error at {where} is within the accuracy"
    shown = "unknown" if error is None else ("inf (it ratchets or the 3-D run does)" if math.isinf(error)
                                             else f"{error:.3g}")
    return "bem", 0.0, f"the MDR model's predicted u_sd error at {where} is {shown}, above {accuracy:g}: the 3-D solver"


def scene_point(scene: Scene) -> dict:
    """The shakedown scene's coordinates in the MDR map, with what decides whether the map applies."""
    pair = scene.material_pair
    return dict(w=scene.amplitude / scene.contact_radius, f_t=scene.f_t, angle=scene.motion.angle % 180.0,
                nu=pair.nu, beta=pair.beta, shape=scene.shape, oscillating=scene.oscillating,
                levels=bool(scene.load.levels), periods=scene.motion.periods)
