"""Shakedown-limit search of the 3D model (`rollcontact limit-search`; seed Eqs. 18-19, docs/theory.md §8.4).

For each combination of the varied keys: bisection in f_t (or in w when load.ft is varied) on the state of the
run, shakedown below, ratcheting above, to a stated tolerance, from a bracket around the kappa = 3/2 closed form.
Probes are ordinary sweep run files (cases.sweep.runner), so a rerun resumes; results in OUTDIR/limits.{csv,h5}
(cases.sweep.table). Units: f_t = Ft/(mu Fn), w = W/a (seed Eq. 9).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
import sys
import time

import numpy as np

from rollcontact.bem.errors import InputError, OutputWriteError, RollcontactError, SceneError
from rollcontact.solver.rolling.shakedown import geometric_decay

from rollcontact.cases.arguments import arg, on_command_line
from rollcontact.cases.scene.scene import Scene
from rollcontact.cases.results.hdf5 import stored_history, stored_summary
from rollcontact.cases.sweep.runner import claimed_table, execute_run, is_done, stopped_sweep, wait_for_claimed
from rollcontact.cases.sweep.plan import (
    RANGE_DIGITS, PlannedRun, describe, build_scene, parse_vary, plan_sweep, run_file_name)
from rollcontact.cases.sweep.table import write_summary
from rollcontact.cases.results.outputs import output_folder
from rollcontact.cases.sweep.workers import make_pool, raise_if_interrupted, completed, default_jobs, require_dask


LIMIT_KAPPAS = (1.0, 1.1, 1.5)
"""Closed-form MDR limits reported beside each 3D bracket: seed fits parallel (1) and perpendicular (1.1),
pure MDR (1.5); seed Eqs. 18-19 and docs/theory.md §8.4."""

LIMIT_COLUMNS = ("index", "searched", "lower", "upper", "midpoint", "width", "status", "probes",
                 "undecided", "mdr_kappa=1", "mdr_kappa=1.1", "mdr_kappa=1.5", "f_t", "w", "error")
"""Columns of limits.csv / limits.h5 after the varied keys.

searched: 'f_t' (limit f_t,lim(w), when w is varied) or 'w' (limit w_lim(f_t), when f_t is varied);
lower: largest searched value found to shake down; upper: smallest found to ratchet (or slide);
midpoint, width = upper - lower; status: 'ok' (width <= tol), 'widened' (a probe stayed undecided after
MAX_PERIODS_FACTOR times the scene's periods: the bracket is the neighbourhood around it), 'failed' (error says
why);
probes: runs made (or reused); undecided: searched values that stayed undecided (';'-separated);
mdr_kappa=K: closed-form limit for kappa = K (seed Eqs. 18-19, or its inverse w_lim); f_t, w: the other,
fixed, normalised coordinate of the search (f_t = Ft/(mu Fn), w = W/a)."""

_FT_KEYS = ("load.ft", "load.Ft")
_W_KEYS = ("motion.w", "motion.W")
_SEARCH_RANGE = {"load.ft": (0.01, 0.99), "motion.w": (0.02, 0.98)}
_BRACKET_MARGIN = 0.05          # first outward step when a side of the first bracket is not yet found
_FIRST_HALF_WIDTH = 0.02        # the first bracket: the kappa = 3/2 closed form +- max(this, tol)
MAX_PERIODS_FACTOR = 16         # an undecided probe is continued up to 16x the scene's periods (160 for the paper's)


def _side(state: str) -> int:
    """-1 below the limit (shakedown/cyclic slip/static: U settles), +1 above (ratcheting/gross sliding), 0 undecided."""
    return {"shakedown": -1, "cyclic_slip": -1, "static": -1, "ratcheting": 1, "gross_sliding": 1}.get(state, 0)


class _LimitSearch:
    """Bisection of one combination: probes are ordinary run files in `runs_dir` (so a rerun resumes)."""

    def __init__(self, base, overrides, values, searched, tol, runs_dir, outdir, log):
        self.base, self.overrides, self.values = base, list(overrides), dict(values)
        self.searched, self.tol, self.runs_dir, self.outdir, self.log = searched, tol, runs_dir, outdir, log
        scene = build_scene(base, overrides, values, (searched,))
        self.periods = scene.motion.periods
        self.probes, self.undecided = 0, []
        self.range = _SEARCH_RANGE[searched]
        if searched == "load.ft" and scene.oscillating:
            # oscillating loads slide (and are refused, cases.scene.Scene._check_oscillation) from
            # f_t = min(1 + B - A, 1 - B + A) on (A = ft_amplitude, B = fn_amplitude)
            A, B = scene.load.ft_amplitude, scene.load.fn_amplitude
            # f_t = min(1 + B - A, 1 - B + A) on, and below A + B - 1 (|ft - A| >= 1 - B at the smallest Fn)
            self.range = (max(self.range[0], A + B - 1.0 + 0.005),
                          min(self.range[1], 1.0 + B - A - 0.005, 1.0 - B + A - 0.005))

    def run(self, x, periods, extend_from=None) -> tuple[str, Path]:
        """State and run file of the probe at `x` with `periods` periods (extend_from: a shorter run of it)."""
        values = dict(self.values)
        values[self.searched] = float(f"{x:.{RANGE_DIGITS}g}")
        extra = [] if periods == self.periods else [f"motion.periods={periods}"]
        name_values = dict(values, **({"motion.periods": periods} if extra else {}))
        scene = build_scene(self.base, self.overrides + extra, values, (self.searched,))
        toml = scene.to_toml()
        run = PlannedRun(self.probes, name_values, toml, self.runs_dir / run_file_name(name_values, toml),
                         scene.name)
        self.probes += 1
        if is_done(run):
            summary = stored_summary(run.path)["summary"]
        else:
            raise_if_interrupted()    # an interrupt swallowed during the previous probe (jobs = 1: in this process)
            result = execute_run(toml, scene.name, str(run.path), None if extend_from is None else str(extend_from))
            if result["status"] == "claimed":       # another limit search on the folder computes this probe
                result = wait_for_claimed(run)
            if result.get("write_error"):
                raise OutputWriteError(result["error"])
            if result["status"] != "complete":
                raise RollcontactError(f"probe {describe(name_values)} failed: {result['error']}")
            summary = result["summary"]
        state = summary.get("state") or ""
        if self.log:
            print(f"limit-search {describe(self.values)}: {self.searched}={x:.6g} periods={periods} -> {state}",
                  file=sys.stderr, flush=True)
        return state, run.path

    def classify(self, x) -> int:
        """-1 below the limit (shakedown), +1 above (ratcheting, gross sliding), 0 undecided. Near the limit the
        increments decay slowly (50-100 periods at w = 0.23, f_t = 0.66): an undecided probe is continued from its
        last step (not run again) for the periods its geometric decay still needs to reach the shakedown
        tolerance (solver.rolling.shakedown.geometric_decay), or as many again when the decay is not yet steady,
        up to MAX_PERIODS_FACTOR times the scene's periods; still undecided then, it is left undecided."""
        periods, previous = self.periods, None
        cap = self.periods * MAX_PERIODS_FACTOR
        while True:
            state, path = self.run(x, periods, previous)
            side = _side(state)
            if side != 0 or periods >= cap:
                break
            decay = self.decay(path)
            more = decay.periods_to_tol + 2 if decay is not None and decay.geometric else periods
            if self.log and decay is not None:
                print(f"limit-search {describe(self.values)}: {self.searched}={x:.6g} undecided after {periods} "
                      f"periods, {decay.describe()}", file=sys.stderr, flush=True)
            periods, previous = min(cap, periods + max(more, 2)), path
        if side == 0:
            self.undecided.append(x)
        return side

    def decay(self, path):
        """geometric_decay of a probe's increments (U along Ft at the period ends, in U0)."""
        stored = stored_summary(path)
        scene = Scene.from_toml_text(stored["scene"], run_limits=False)
        h = stored_history(path, ("U_x", "U_y", "period"))
        e_f = scene.load_direction
        U = h["U_x"] * e_f[0] + h["U_y"] * e_f[1]
        period = np.asarray(h["period"])
        ends = [int(np.flatnonzero(period == k)[-1]) for k in range(int(period.max()) + 1)]
        return geometric_decay(np.diff(U[ends]) / stored["summary"]["U0"], tol=scene.solver.shakedown_tol)

    def bracket(self, guess_lo, guess_hi):
        """Find lo (below the limit) and hi (above it), starting from the closed-form guesses."""
        xmin, xmax = self.range
        lo, hi = min(max(xmin, guess_lo), xmax), min(xmax, guess_hi)
        step = _BRACKET_MARGIN
        while True:
            s = self.classify(lo)
            if s == -1:
                break
            if s == 1:
                hi = min(hi, lo)
            if lo <= xmin:
                raise RollcontactError(f"{self.searched} = {xmin}: still no shakedown at the lower end of the "
                                       f"search range [{xmin}, {xmax}]")
            lo, step = max(xmin, lo - step), 2 * step
        if lo >= xmax:
            raise RollcontactError(f"{self.searched} = {xmax:.6g}: still no ratcheting at the upper end of the "
                                   f"search range [{xmin}, {xmax:.6g}]")
        step = _BRACKET_MARGIN
        while hi <= lo:
            hi = min(xmax, lo + step)
        while True:
            s = self.classify(hi)
            if s == 1:
                break
            if s == -1:
                lo = max(lo, hi)
            if hi >= xmax:
                raise RollcontactError(f"{self.searched} = {xmax}: still no ratcheting at the upper end of the "
                                       f"search range [{xmin}, {xmax}]")
            hi, step = min(xmax, hi + step), 2 * step
        return lo, hi

    def bisect(self, lo, hi):
        """Halve [lo, hi] until hi - lo <= tol; an undecided midpoint ends it with a widened bracket."""
        while hi - lo > self.tol * (1 + 1e-9):
            m = 0.5 * (lo + hi)
            s = self.classify(m)
            if s == -1:
                lo = m
            elif s == 1:
                hi = m
            else:
                return self.widen(m, lo, hi) + ("widened",)
        return lo, hi, "ok"

    def widen(self, m, lo, hi):
        """Around an undecided m: step outwards by tol/2, tol, 2 tol, ... until each side is decided."""
        h, lo_found, hi_found = 0.5 * self.tol, False, False
        while not (lo_found and hi_found):
            if not lo_found:
                a = m - h
                if a <= lo:
                    lo_found = True
                elif self.classify(a) == -1:
                    lo, lo_found = a, True
            if not hi_found:
                b = m + h
                if b >= hi:
                    hi_found = True
                elif self.classify(b) == 1:
                    hi, hi_found = b, True
            h *= 2
        return lo, hi


def _limit_task(base_toml, base_name, overrides, values, searched, tol, runs_dir, outdir, log) -> dict:
    """Worker entry of one limit search (picklable in and out); never raises a RollcontactError."""
    from rollcontact.solver.mdr import limits as lim
    base = Scene.from_toml_text(base_toml, name=base_name)
    search = _LimitSearch(base, overrides, values, searched, tol, Path(runs_dir), Path(outdir), log)
    scene = build_scene(base, overrides, values, (searched,))
    row = dict(values)
    kappas = {k: f"mdr_kappa={k:g}" for k in LIMIT_KAPPAS}
    if searched == "load.ft":
        w = scene.amplitude / scene.contact_radius
        row.update(searched="f_t", w=w, f_t=None)
        closed = {k: lim.f_t_lim(min(w, 1.0), k) for k in LIMIT_KAPPAS}
    else:
        f = scene.f_t
        row.update(searched="w", f_t=f, w=None)
        closed = {k: lim.w_lim(f, k) for k in LIMIT_KAPPAS}
    for k, label in kappas.items():
        row[label] = closed[k]
    # the 3-D limits of the paper's sphere lie on the kappa = 3/2 closed form at both settings and every alignment
    # measured (docs/alignment.md), so the search starts there and widens outwards when it has to
    half = max(_FIRST_HALF_WIDTH, tol)
    lo_guess, hi_guess = closed[1.5] - half, closed[1.5] + half
    try:
        lo, hi = search.bracket(lo_guess, hi_guess)
        lo, hi, status = search.bisect(lo, hi)
        row.update(lower=lo, upper=hi, midpoint=0.5 * (lo + hi), width=hi - lo, status=status, error="")
    except OutputWriteError as exc:        # the search stops (search_limits)
        row.update(status="failed", error=str(exc), write_error=True)
    except RollcontactError as exc:
        row.update(status="failed", error=f"{type(exc).__name__}: {exc}")
    row.update(probes=search.probes, undecided=";".join(f"{x:.6g}" for x in search.undecided))
    return row


def fixed_range(searched: str) -> tuple[float, float]:
    """The open range of the fixed coordinate of a search in `searched` (the other one, w or f_t) in which the pure-MDR
    limit (kappa = 3/2, where the 3-D limits lie: README) falls inside the searched range _SEARCH_RANGE: w in
    (0.00667, 0.917) for a search in f_t, f_t in (0.000596, 0.970) for a search in w. Outside it the search has no
    bracket to find (w = 1.5 shakes down at no load: `rollcontact limits` refuses w > 1)."""
    from rollcontact.solver.mdr import limits as lim
    lo, hi = _SEARCH_RANGE[searched]
    if searched == "load.ft":
        return lim.w_lim(hi, 1.5), lim.w_lim(lo, 1.5)
    return lim.f_t_lim(hi, 1.5), lim.f_t_lim(lo, 1.5)


def _check_fixed_coordinate(plan, searched: str):
    """Every combination's fixed coordinate (w of a search in f_t, f_t of one in w) lies in `fixed_range`, checked
    before any probe runs (SceneError naming the varied value and the range)."""
    lo, hi = fixed_range(searched)
    name, key = ("w = W/a", "motion.w") if searched == "load.ft" else ("f_t = Ft/(mu Fn)", "load.ft")
    for run in plan:
        scene = Scene.from_toml_text(run.scene_toml, run_limits=False)
        x = scene.amplitude / scene.contact_radius if searched == "load.ft" else scene.f_t
        if not lo < x < hi:
            raise SceneError(f"{arg('vary')} {describe(run.values)}: {name} = {x:.6g}; a limit search in "
                             f"{searched.split('.')[1]} needs {lo:.4g} < {key.split('.')[1]} < {hi:.4g} (there the "
                             f"pure-MDR limit lies inside the searched range {list(_SEARCH_RANGE[searched])}); "
                             "nothing was run")


@dataclass
class LimitReport:
    """Rows of limits.csv (one per combination of the varied keys) and where they were written."""

    outdir: Path
    keys: list
    searched: str
    rows: list = field(default_factory=list)
    wall_time: float = 0.0

    @property
    def limits_csv(self) -> Path:
        return self.outdir / "limits.csv"

    def report(self) -> str:
        """The lines `rollcontact limit-search` prints: each combination's 3-D bracket and the MDR closed forms."""
        name = "f_t,lim" if self.searched == "load.ft" else "w_lim"
        lines = []
        for r in self.rows:
            fixed = " ".join(f"{k}={r[k]}" for k in self.keys)
            if r["status"] == "failed":
                lines.append(f"{fixed}: failed: {r['error']}")
                continue
            closed = ", ".join(f"{c.split('=')[1]}: {r[c]:.4f}" for c in ("mdr_kappa=1", "mdr_kappa=1.1",
                                                                           "mdr_kappa=1.5"))
            lines.append(f"{fixed}: 3D {name} in [{r['lower']:.4f}, {r['upper']:.4f}] (mid {r['midpoint']:.4f}, "
                         f"{r['status']}, {r['probes']} probes); MDR kappa {closed}")
        lines.append(f"limits: {self.limits_csv}")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"LimitReport({len(self.rows)} combination(s), searched={self.searched!r}, outdir={str(self.outdir)!r})"


def search_limits(base: Scene, axes, outdir, *, overrides=(), tol=0.01, jobs=None, scheduler=None,
                  overwrite=False, progress=sys.stderr) -> LimitReport:
    """Shakedown limit of the 3D model for every combination of the axes, by bisection on the run state.

    Varying motion.w (or motion.W) searches f_t,lim(w); varying load.ft (or load.Ft) searches w_lim(f_t);
    other varied keys (e.g. motion.angle) are carried along. Bisection to `tol` (in f_t or w units) from a
    bracket of +- max(0.02, tol) around the closed-form limit for kappa = 3/2, widened outwards as needed; an
    undecided probe is continued for the periods its geometric decay still needs (`_LimitSearch.classify`), up to
    MAX_PERIODS_FACTOR times the scene's periods, else the bracket is widened around it (status 'widened'). Probe
    runs are files in OUTDIR/runs (named like sweep runs, so a rerun reuses them, and claimed through their locks,
    so that searches started on one folder share the probes); results in OUTDIR/limits.{csv,h5} (columns:
    LIMIT_COLUMNS), rewritten after each finished combination; the limits table of another search is not replaced
    unless `overwrite`. Combinations run in parallel.
    """
    t0 = time.perf_counter()
    axes = [parse_vary(a) if isinstance(a, str) else a for a in axes]
    keys = [a.key for a in axes]
    has_ft = [k for k in keys if k in _FT_KEYS]
    has_w = [k for k in keys if k in _W_KEYS]
    if has_ft and has_w:
        raise SceneError(f"limit-search: vary either the amplitude (motion.w) or the load (load.ft), not both "
                         f"(got {has_w + has_ft}); the other one is searched")
    if not (has_ft or has_w):
        raise SceneError("limit-search: vary motion.w (to find f_t,lim(w)) or load.ft (to find w_lim(f_t)), "
                         f"e.g. {arg('vary')} " + ("motion.w=0.1,0.23,0.4" if on_command_line() else
                                                   "{'motion.w': [0.1, 0.23, 0.4]}"))
    if not tol > 0 or not tol < 0.5:
        raise InputError(f"{arg('tol')} = {tol!r}: allowed range is 0 < tol < 0.5 (in units of f_t or w)")
    searched = "motion.w" if has_ft else "load.ft"
    lo_x = _SEARCH_RANGE[searched][0]
    for item in overrides:
        key = item.split("=", 1)[0].strip()
        if key in (_W_KEYS if searched == "motion.w" else _FT_KEYS):
            raise SceneError(f"{arg('overrides')} {item!r}: the limit search searches {searched}, so it sets it in "
                             f"every probe; drop the {arg('overrides')}")
    if scheduler:
        require_dask(scheduler)
    outdir = Path(outdir).absolute()     # the workers (Dask's among them) may run in other folders
    plan = plan_sweep(base, axes, outdir, list(overrides) + [f"{searched}={lo_x}"], replaces=(searched,))
    _check_fixed_coordinate(plan, searched)
    outdir = output_folder(outdir)
    runs_dir = outdir / "runs"
    jobs = default_jobs() if jobs is None else int(jobs)
    if jobs < 1:
        raise InputError(f"{arg('jobs')} = {jobs!r}: allowed range is jobs >= 1")
    attrs = {"base_scene": base.to_toml(), "overrides": list(overrides) or [""], "tol": float(tol),
             "searched": searched}
    with claimed_table(outdir / "limits.h5", keys, attrs, overwrite):
        write_summary(outdir, keys, [], stem="limits", columns=LIMIT_COLUMNS, attrs=attrs)
    if progress is not None:
        print(f"limit-search: {len(plan)} combination(s), searching {searched} to tol = {tol:g}; probe runs in "
              f"{runs_dir}", file=progress, flush=True)
    pool = make_pool(min(jobs, len(plan)), scheduler)
    rows = {}
    try:
        tasks = [(run, _limit_task, (base.to_toml(), base.name, list(overrides), run.values, searched, float(tol),
                                     str(runs_dir), str(outdir), progress is not None)) for run in plan]
        for run, row, failure in completed(pool, tasks):
            if failure:
                row = dict(run.values, status="failed", error=failure)
            if row.pop("write_error", False):
                raise OutputWriteError(row["error"])
            row["index"] = run.index
            rows[run.index] = row
            write_summary(outdir, keys, rows.values(), stem="limits", columns=LIMIT_COLUMNS, attrs=attrs)
            if progress is not None:
                what = (f"{row['searched']} in [{row['lower']:.4f}, {row['upper']:.4f}] ({row['status']})"
                        if row["status"] != "failed" else f"FAILED ({row['error']})")
                print(f"limit-search [{len(rows)}/{len(plan)}] {describe(run.values)}: {what}",
                      file=progress, flush=True)
        pool.close()
        raise_if_interrupted()
    except OutputWriteError as exc:
        pool.stop()
        raise stopped_sweep(exc, outdir, "limits", len(rows), len(plan)) from None
    except KeyboardInterrupt:
        pool.stop()
        write_summary(outdir, keys, rows.values(), stem="limits", columns=LIMIT_COLUMNS, attrs=attrs)
        if progress is not None:
            print(f"limit-search: interrupted; {len(rows)} of {len(plan)} search(es) finished are in "
                  f"{outdir}/limits.csv; rerun the same command to resume (finished probe runs in {runs_dir} are "
                  "reused)", file=progress, flush=True)
        raise
    return LimitReport(outdir, keys, searched, [rows[i] for i in sorted(rows)], time.perf_counter() - t0)
