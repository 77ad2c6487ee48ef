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
#: annulus of a swing of 2 A, Cattaneo-Mindlin, docs/theory.md §11.2) spans at least this many elements, so that the
# work
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


#: How a load oscillating within each period (load.ft_amplitude, load.fn_amplitude) must be sampled by the steps:
#: at least MIN_STEPS_PER_LOAD_CYCLE steps per load cycle (steps per period / load.cycles_per_period), and every
#: peak and trough of the load reached by a step to within PEAK_MISS of the amplitude.
#:
#: Why the peaks: Coulomb friction is rate-independent, so the frictional work of a cycle follows its extreme loads,
#: not the path between them. With the sampled phase a distance d from a peak, the largest load falls short by
#: 1 - cos(d) of the amplitude. Measured on Mindlin-Deresiewicz (w = 0, ft = 0, ft_amplitude x = 0.3 / 0.6 / 0.9,
#: dx = 0.4 mm, paper materials; benchmarks/load_cycle_sampling.py, docs/robustness.md): with the peaks on steps the
#: work per cycle is within 0.3 % of its 192-step value from 4 steps per cycle on; with the peaks half a step off it
#: is 3.1 / 3.5 / 4.8 % low at 24 steps (peak 0.86 % short), 12-17 % at 12, 25-34 % at 8, and at 4 steps (phase 45
#: deg, peak 29 % short) 72-79 %; 6 steps miss the peaks by 13 % at any phase (40-51 % low). PEAK_MISS =
#: 1 - cos(pi/24) = 0.86 % is the worst case of 24 steps per cycle, the default of a period without rolling: every
#: scene sampled as finely as the default passes at any phase, a coarser one only when its steps fall on (or within
#: 7.5 deg of) the peaks.
#: Why at least 4 steps: a cycle's rise and fall each need a step between its extremes; Nyquist's 2 steps would
#: alternate between the two extremes, and at fewer the cycles alias (1000 cycles in 24 steps "shake down" at
#: loads the steps never visit).
MIN_STEPS_PER_LOAD_CYCLE = 4
PEAK_MISS = 1.0 - math.cos(math.pi / 24)


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

    def steps_per_period(self) -> int | None:
        """Steps of one period of the path: 4 ceil(W/dW) when the sphere rolls, motion.steps_per_period without
        rolling (w = 0); None when the path has no period (no rolling and no oscillating load, or periods = 0)."""
        mo = self.motion
        if mo.periods == 0:
            return None
        W = self.amplitude
        if W > 0:
            ratio = W / mo.dW
            return 4 * math.ceil(ratio - 1e-9) if math.isfinite(ratio) else None
        return mo.steps_per_period if self.oscillating else None

    def load_peak_miss(self) -> tuple[float, float] | None:
        """(steps per load cycle, largest shortfall of a sampled peak or trough of the load cycle, as a fraction of
        the amplitude: 1 - cos(d), d the phase distance from the extreme to its nearest step) of an oscillating
        load; None without one. Steps k = 1..N of a period have the load phase m 2 pi k/N + phase (solver.rolling
        .schedule); the extremes are at pi/2 + j pi."""
        n = self.steps_per_period() if self.oscillating else None
        if n is None:
            return None
        m = self.load.cycles_per_period
        spacing = 2.0 * math.pi * m / n                     # load phase between two steps
        start = math.radians(self.load.phase)
        worst = 0.0
        for j in range(2 * m):                             # the m peaks and m troughs of a period
            r = (math.pi / 2 + j * math.pi - start) % spacing
            worst = max(worst, min(r, spacing - r))
        return n / m, 1.0 - math.cos(min(worst, math.pi))

    def _check_load_cycles(self):
        """An oscillating load is sampled by at least MIN_STEPS_PER_LOAD_CYCLE steps per load cycle, with every
        extreme reached to within PEAK_MISS of its amplitude."""
        sampled = self.load_peak_miss()
        if sampled is None:
            return
        per_cycle, miss = sampled
        if per_cycle >= MIN_STEPS_PER_LOAD_CYCLE and miss <= PEAK_MISS * (1 + 1e-9):
            return
        n, m = self.steps_per_period(), self.load.cycles_per_period
        need = 24 * m                                       # enough at any phase (PEAK_MISS)
        if self.amplitude > 0:
            W = self.amplitude
            how = (f"motion.dW <= {W / (need / 4):.4g} mm (a period of W = {W:.4g} mm has 4 ceil(W/dW) = {n} steps at "
                   f"dW = {self.motion.dW!r} mm)")
        else:
            how = f"motion.steps_per_period >= {need} (it is {n})"
        why = (f"{per_cycle:.3g} steps per load cycle" if per_cycle < MIN_STEPS_PER_LOAD_CYCLE else
               f"{per_cycle:.3g} steps per load cycle at phase {self.load.phase!r} deg miss a peak of the load by "
               f"{100 * miss:.2g} % of its amplitude")
        raise SceneError(
            f"[load] cycles_per_period = {m} with {n} steps per period: {why}; allowed is at least "
            f"{MIN_STEPS_PER_LOAD_CYCLE} steps per load cycle, every peak reached within {100 * PEAK_MISS:.2g} % (the "
            f"worst case of 24 steps per cycle: the work per cycle then stays within 5 %; docs/robustness.md); "
            f"use {how}, or a phase that puts the peaks on steps")

    def _check_rolling_run(self):
        """A [rolling] scene: prescribed forces below full sliding, |(Fx, Fy)| < mu Fn, and the grid of a transient
        within the element limit (bem.grid.MAX_ELEMENTS): the world-fixed grid over the distance rolled, or the grid
        that moves with the contact."""
        if not self.rolling_on:
            return
        from rollcontact.bem.errors import InputError
        from rollcontact.bem.grid import MAX_ELEMENTS
        from rollcontact.cases.scene.extent import rolling_frame_box, rolling_frame_grid
        from rollcontact.solver.creep.world import rolling_steps
        ro, ld = self.rolling, self.load
        if ro.Fx is not None:
            F, mu_fn = math.hypot(ro.Fx, ro.Fy), ld.mu * ld.Fn
            if not F < mu_fn:
                raise SceneError(f"[rolling] Fx = {ro.Fx!r}, Fy = {ro.Fy!r} N: |F| = {F:.6g} N reaches mu Fn = "
                                 f"{mu_fn:.6g} N (full sliding: no creepage gives that force); allowed range is "
                                 f"|(Fx, Fy)| < mu Fn = {mu_fn:.6g} N")
        if ro.mode != "transient":
            return
        step = ro.step if ro.step is not None else self.spacing[0]
        distance = ro.distance if ro.distance is not None else 8.0 * self.rolling_half_length
        if self.transient_grid == "contact":           # the grid moves with the contact: the distance adds steps only
            rolling_frame_grid(self, trail=step)
            if rolling_steps(distance, step) > MAX_STEPS:
                raise SceneError(f"[rolling] distance = {distance:.6g} mm in steps of {step:.6g} mm: more than "
                                 f"{MAX_STEPS} steps per run; allowed range is distance <= {MAX_STEPS * step:.6g} mm "
                                 "at this step")
            return
        try:
            rolling_frame_grid(self, travel=rolling_steps(distance, step) * step)
        except InputError as exc:
            # the longest travel, whole steps, whose grid keeps within the limit: its last cell centre
            # (i0 + nx - 1) dx with nx = MAX_ELEMENTS // ny must cover xmax - dx/2 (bem.grid.Grid.covering)
            at_rest = rolling_frame_grid(self)
            dx = self.spacing[0]
            xmax = (at_rest.i0 + MAX_ELEMENTS // at_rest.ny - 0.5) * dx
            longest = math.floor((xmax - rolling_frame_box(self)[1]) / step * (1 - 1e-12)) * step
            allowed = (f"distance <= {longest:.6g} mm at grid.dx = {dx!r} mm" if longest > 0 else
                       "none at this grid: use a larger grid.dx")
            raise SceneError(f"[rolling] distance = {distance:.6g} mm: the world-fixed grid of the transient would "
                             f"exceed the element limit ({exc}); allowed range is {allowed}") from None
