"""What a run with a [friction] law or [thermal] adds to its summary, history and fields (names and units:
cases.results.run_result, FRICTION_*). Units: W, degC, mm/s."""
from __future__ import annotations

import numpy as np


def friction_summary(scene, history: dict, state=None) -> dict:
    """mu_static and friction_law; frictional_power (W) of the last step (history/frictional_power) or of `state`
    (a solver.friction.FrictionState: the steady state's), friction_feedback (the uniqueness indicator: its, or the
    largest of the steps') and, with temperatures, T1_max, T2_max (degC)."""
    from rollcontact.cases.scene.friction import friction_law
    law = friction_law(scene)
    out = dict(mu_static=scene.load.mu, friction_law=law.describe() if law else f"coulomb mu = {scene.load.mu:.6g}")
    power = history.get("frictional_power")
    if state is not None:
        out.update(frictional_power=state.power, friction_feedback=state.feedback)
    elif power is not None and len(power):
        out["frictional_power"] = float(np.asarray(power)[-1])
        out["friction_feedback"] = float(np.max(history["friction_feedback"]))
    out.update(temperature_summary(state))
    return out


def temperature_summary(state) -> dict:
    """T1_max, T2_max (degC) of a FrictionState with temperatures (empty otherwise)."""
    temps = None if state is None else state.temperatures
    if temps is None:
        return {}
    return dict(T1_max=float(np.max(temps.T1)), T2_max=float(np.max(temps.T2)))


def friction_fields(state) -> dict:
    """The fields of a FrictionState: mu, slip_velocity and, with temperatures, T1, T2 (each (ny, nx))."""
    if state is None:
        return {}
    out = {"mu": state.mu, "slip_velocity": state.slip_velocity}
    if state.temperatures is not None:
        out.update(T1=state.temperatures.T1, T2=state.temperatures.T2)
    return out


def friction_lines(summary: dict) -> list[str]:
    """The lines `rollcontact run` prints for a run with a friction law or temperatures (none otherwise)."""
    if "friction_law" not in summary:
        return []
    lines = [f"friction: {summary['friction_law']} (mu_static = {summary['mu_static']:.6g}: the mu of f_t and u)"
             + (f"; frictional power {summary['frictional_power']:.6g} W" if "frictional_power" in summary else "")]
    if "T1_max" in summary:
        lines.append(f"surface temperatures: T1_max = {summary['T1_max']:.5g} degC (body 1), T2_max = "
                     f"{summary['T2_max']:.5g} degC (body 2)")
    feedback = summary.get("friction_feedback")
    if feedback is not None and feedback >= 1.0:
        lines.append(f"note: falling friction steeper than the elements' own stiffness (feedback {feedback:.3g} >= 1): "
                     "the quasi-static problem may have several solutions and this is one of them; compare with "
                     "friction memory (memory_distance) or the transient (docs/friction.md)")
    return lines
