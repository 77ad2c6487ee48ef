"""Limits of a new run and the default resolution of a scene: each Hertz semi-axis spans at least
MIN_ELEMENTS_PER_RADIUS grid elements, the load path has at most MAX_STEPS steps, and an omitted grid.dx (and
motion.dW) takes RESOLUTION_PER_RADIUS elements per contact radius.

`SceneLimits` holds these checks as methods of `cases.scene.Scene` (a mixin without fields: they read the
scene's sections and its derived quantities semi_axes, spacing, Ft, amplitude and contact_radius). Units: mm,
N, MPa; the limits raise `SceneError` naming the key, the value and the allowed range.
"""
from dataclasses import replace
import math

from rollcontact.bem.errors import SceneError

#: Elements per contact radius when a scene leaves grid.dx out (motion.dW then defaults to dx). The
#: cheapest resolution whose shakedown displacement u_sd stays within 1 % of the converged value over the
#: seed's Fig. 8 family (its 32 shaken-down runs, both alignments: worst 0.20 %); a/dx = 6 is within 1 % at
#: the paper's point but 1.37 % off at f_t = 0.1 (benchmarks/default_resolution.py, benchmarks/README.md).
RESOLUTION_PER_RADIUS = 12

#: Elements across the slip annulus of a tangential load oscillating at constant Fn without rolling (motion.w = 0,
#: load.fn_amplitude = 0), when grid.dx is left out: the annulus a [1 - (1 - A)^(1/3)] of an amplitude A = load.ft_amplitude (in mu Fn; the reverse-slip
#: annulus of a swing of 2 A, Cattaneo-Mindlin, theory §11.2) spans at least this many elements, so that the work
#: dissipated per cycle is within 1 % of Mindlin-Deresiewicz's (at a/12 the annulus of A = 0.3 is 1.3 elements
#: and the work 4.4 % low; with 4 elements and more, a scan of a/dx = 24-42 at A = 0.3 stayed within 0.5 %).
RESOLUTION_PER_ANNULUS = 4

#: The finest default: a/dx at most this many however thin the annulus (A < 0.22 would ask for more); a
#: scene that needs the work of smaller amplitudes to 1 % sets grid.dx itself (docs/oscillating_loads.md).
MAX_RESOLUTION_PER_RADIUS = 48


#: Fewest elements per Hertz contact semi-axis a grid may have ([grid] dx, dy <= a/3). a/dx = 3 is the coarsest
#: resolution benchmarks/stability.py verifies (Hertz + Cattaneo converge, approach within 0.1 %); on coarser
#: grids the discrete contact (a few elements) is not a useful approximation of the Hertz ellipse, and with
#: dx > a the grid sized for the contact is so small that the run stops at once with ContactEdgeError,
#: whose advice (a larger grid.margin) misses the cause.
MIN_ELEMENTS_PER_RADIUS = 3

#: Most steps (loading + rolling) one run may take. Generous: the seed's runs take ~250 steps, and a step
#: costs at least a few ms on the smallest grids (~10 ms on the paper's 55 x 65), so 1e6 steps are hours of
#: computing, while the load path and the history of 1e6 steps need only ~200 MB. Beyond it a typo such as
#: dW = 1e-9 would only show up as a MemoryError (tens of GiB) while the path is built.
MAX_STEPS = 1_000_000


def _round_sig(x: float, digits: int) -> float:
    return float(f"{x:.{digits}g}")


class SceneLimits:
    """The resolution default and the run-limit checks of `cases.scene.Scene`, called by `Scene.from_dict`."""

    def _resolve_resolution(self):
        """Fill an omitted grid.dx and motion.dW with the recommended resolution (RESOLUTION_PER_RADIUS, finer for
        the slip annulus of a tangential load oscillating without rolling: `default_elements_per_radius`)."""
        derived = set(self.derived)            # keys derived before (geometry.sha256 of a file profile)
        if self.grid.dx is None:
            per_radius = self.default_elements_per_radius()
            self.grid = replace(self.grid, dx=_round_sig(min(self.semi_axes) / per_radius, 2))
            derived.add("grid.dx")
        if self.motion.dW is None:
            self.motion = replace(self.motion, dW=self.grid.dx)
            derived.add("motion.dW")
        self.derived = frozenset(derived)

    def default_elements_per_radius(self) -> float:
        """Elements per (smaller) Hertz semi-axis of the default grid.dx: RESOLUTION_PER_RADIUS, or for a tangential
        load oscillating at constant Fn without rolling (the Mindlin-Deresiewicz setting) RESOLUTION_PER_ANNULUS
        across its slip annulus, up to MAX_RESOLUTION_PER_RADIUS."""
        amplitude = self.load.ft_amplitude
        if self.amplitude > 0 or not amplitude > 0 or self.load.fn_amplitude > 0:
            return RESOLUTION_PER_RADIUS
        annulus = 1.0 - (1.0 - min(amplitude, 1.0)) ** (1.0 / 3.0)     # in contact radii
        return min(max(RESOLUTION_PER_RADIUS, RESOLUTION_PER_ANNULUS / annulus), MAX_RESOLUTION_PER_RADIUS)

    def _check_resolution(self):
        """Each Hertz semi-axis spans at least MIN_ELEMENTS_PER_RADIUS elements (every model on a grid: not the MDR)."""
        if self.solver.fidelity == "mdr":
            return
        (sx, sy), (dx, dy) = self.semi_axes, self.spacing
        key_y = "dy" if self.grid.dy is not None else "dx"
        for key, semi, h, axis in (("dx", sx, dx, "x"), (key_y, sy, dy, "y")):
            if semi / h < MIN_ELEMENTS_PER_RADIUS:
                what = "contact radius a" if sx == sy else f"contact semi-axis along {axis}"
                raise SceneError(
                    f"[grid] {key} = {h!r} mm: the Hertz {what} = {semi:.4g} mm spans {semi / h:.2g} elements; "
                    f"allowed range is 0 < {key} <= {semi / MIN_ELEMENTS_PER_RADIUS:.4g} mm for this scene (at "
                    f"least {MIN_ELEMENTS_PER_RADIUS} elements per semi-axis; leave grid.dx out for the "
                    f"recommended a/{RESOLUTION_PER_RADIUS})")

    def _check_steps(self):
        """The load path has at most MAX_STEPS steps (mirrors solver.rolling.stepping.build_path)."""
        ld, mo = self.load, self.motion
        n_load = 1 + ld.ramp_steps * ((1 if self.Ft > 0 else 0) + len(ld.levels))
        if n_load > MAX_STEPS:
            raise SceneError(f"[load] ramp_steps = {ld.ramp_steps} with {len(ld.levels)} levels: {n_load} loading "
                             f"steps exceed the limit of {MAX_STEPS} steps per run; allowed range is ramp_steps "
                             f"<= {(MAX_STEPS - 1) // (1 + len(ld.levels))}")
        W = self.amplitude
        if W == 0 and self.oscillating and n_load + mo.periods * mo.steps_per_period > MAX_STEPS:
            raise SceneError(f"[motion] periods = {mo.periods} x steps_per_period = {mo.steps_per_period} steps (loads "
                             f"oscillating without rolling) exceed the limit of {MAX_STEPS} steps per run; allowed "
                             f"range is periods <= {(MAX_STEPS - n_load) // mo.steps_per_period}")
        if not (W > 0 and mo.periods > 0):
            return
        ratio = W / mo.dW
        given = "" if mo.W is not None else f" (= w a, a = {self.contact_radius:.4g} mm)"
        if not math.isfinite(ratio):  # W / dW overflowed: math.ceil would raise
            raise SceneError(f"[motion] W = {W:.5g} mm{given} with dW = {mo.dW!r} mm needs {ratio:.3g} steps "
                             f"per quarter period; allowed range is W <= {MAX_STEPS * mo.dW / 4:.4g} mm at this "
                             f"dW (at most {MAX_STEPS} steps per run)")
        per_quarter = math.ceil(ratio - 1e-9)
        n = n_load + 4 * per_quarter * mo.periods
        if n <= MAX_STEPS:
            return
        ranges = []
        most_per_quarter = (MAX_STEPS - n_load) // (4 * mo.periods)
        if most_per_quarter >= 1:
            ranges.append(f"dW >= {W / most_per_quarter:.4g} mm at these periods")
        most_periods = (MAX_STEPS - n_load) // (4 * per_quarter)
        if most_periods >= 1:
            ranges.append(f"periods <= {most_periods} at this dW")
        raise SceneError(
            f"[motion] dW = {mo.dW!r} mm, periods = {mo.periods}: {n} steps ({mo.periods} periods x 4 x "
            f"ceil(W/dW) = {per_quarter} with W = {W:.5g} mm{given}, plus {n_load} loading steps) exceed the "
            f"limit of {MAX_STEPS} steps per run; allowed range is " + (", or ".join(ranges) or "a larger dW"))
