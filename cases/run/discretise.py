"""A scene made discrete: its load path (`scene_path`), the world-fixed grid just large enough for it
(`scene_grid`), the half-space operator on a grid (`scene_operator`) and the steps whose fields are stored
(`field_steps`). Units: mm, N, MPa."""
from __future__ import annotations

import math

import numpy as np

from rollcontact.bem.errors import InputError, SceneError
from rollcontact.bem.grid import MAX_ELEMENTS, Grid, contact_box
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.cases.run.viscoelastic import step_pair
from rollcontact.cases.scene.extent import contact_extent, estimated  # noqa: F401  (re-exported)
from rollcontact.cases.scene.scene import Scene
from rollcontact.solver.rolling.schedule import LoadOscillation
from rollcontact.solver.rolling.stepping import LoadPath, build_path


def scene_path(scene: Scene) -> LoadPath:
    """The scene's loading phase and oscillation as a LoadPath (solver.rolling.stepping.build_path)."""
    e_f = np.array(scene.load_direction)
    ld = scene.load
    mu_fn = ld.mu * ld.Fn
    oscillation = None
    if scene.oscillating:   # docs/theory.md §11.2-11.3; the defaults leave the path as it was (normal_forces None)
        oscillation = LoadOscillation(force_amplitude=tuple(ld.ft_amplitude * mu_fn * e_f),
                                      normal_amplitude=ld.fn_amplitude * ld.Fn, phase=ld.phase,
                                      cycles_per_period=ld.cycles_per_period,
                                      steps_per_period=scene.motion.steps_per_period)
    return build_path(force=scene.Ft * e_f, ramp_steps=ld.ramp_steps,
                      levels=[lv * mu_fn * e_f for lv in ld.levels],
                      rolling_direction=scene.rolling_direction, amplitude=scene.amplitude,
                      max_step=scene.motion.dW, periods=scene.motion.periods, normal_force=ld.Fn,
                      oscillation=oscillation, step_time=scene.step_time)


def scene_operator(scene: Scene, grid: Grid) -> HalfSpaceOperator:
    """The scene's half-space operator on `grid` ([solver] threads and coupling); with viscoelastic bodies that of the
    effective pair of its step time (cases.run.viscoelastic.step_pair)."""
    pair = step_pair(scene) if scene.viscoelastic else scene.material_pair
    return HalfSpaceOperator(grid, pair, threads=scene.solver.threads,
                             coupling={"auto": "auto", "on": True, "off": False}[scene.solver.coupling])


def scene_grid(scene: Scene, path: LoadPath | None = None) -> Grid:
    """Grid just large enough for every contact the path can produce, plus the scene's margin.

    The Hertz semi-axes of an ellipse are estimated from the equivalent sphere, c (Rx/Ry)^(+-1/3), with
    a 10 % allowance, as are the cylinder's (cases.scene.geometry.cylinder_semi_axes); the sphere's and the other
    axisymmetric shapes' contact radius is exact (Hertz, MDR); the run stops with ContactEdgeError if a contact still reaches the edge. The margin is
    at least one element (max(dx, dy)). Without a path, the centres are the extremes of the scene's
    oscillation (0 and +-W along the rolling direction), so an over-large scene is refused (SceneError,
    bem.grid.MAX_ELEMENTS) before its path is built.
    """
    semi_x, semi_y = contact_extent(scene)
    if scene.load.fn_amplitude > 0:   # the largest Fn of an oscillating normal load: a ~ Fn^(1/3)
        grow = (1.0 + scene.load.fn_amplitude) ** (1.0 / 3.0)
        semi_x, semi_y = grow * semi_x, grow * semi_y
    dx, dy = scene.spacing
    if path is not None:
        centres = path.centres
    elif scene.amplitude > 0 and scene.motion.periods > 0:
        reach = scene.amplitude * np.array(scene.rolling_direction)
        centres = np.array([(0.0, 0.0), reach, -reach])
    else:
        centres = np.zeros((1, 2))
    # at least one element of margin: with half an element the discrete contact, slightly wider than Hertz's,
    # touched the grid's edge at step 0 (ContactEdgeError) on the paper scene
    margin = max(scene.grid.margin, dx, dy)
    try:
        return Grid.covering(*contact_box(semi_x, semi_y, centres, margin), dx, dy)
    except InputError as exc:  # too many elements: name the keys that set the size
        x0, x1, y0, y1 = contact_box(semi_x, semi_y, centres, 0.0)
        w0, h0 = x1 - x0, y1 - y0
        # largest margin m with (w0 + 2m)(h0 + 2m) <= MAX_ELEMENTS dx dy
        m_max = (math.sqrt((w0 - h0) ** 2 + 4.0 * MAX_ELEMENTS * dx * dy) - (w0 + h0)) / 4.0
        hint = (f"the allowed range at this dx, dy and amplitude is [grid] margin <= {m_max:.4g} mm"
                if m_max >= max(dx, dy) else "even without a margin the swept contact needs more elements: use a "
                "larger [grid] dx or a smaller [motion] W or w")
        raise SceneError(f"{exc} ([grid] margin = {scene.grid.margin!r} mm, [motion] W = "
                         f"{scene.amplitude:.4g} mm); {hint}") from None


def field_steps(scene: Scene, path: LoadPath) -> np.ndarray:
    """Steps whose fields are stored ([output] fields)."""
    n = path.n_steps
    mode = scene.output.fields
    if mode == "all":
        return np.arange(n)
    if mode == "none":
        return np.zeros(0, dtype=int)
    if mode == "last":
        return np.array([n - 1])
    keep = path.reversal.copy()
    keep[np.flatnonzero(path.period == 0)[-1]] = True
    keep[-1] = True
    return np.flatnonzero(keep)
