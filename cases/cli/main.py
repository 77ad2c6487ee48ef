"""Command line: `rollcontact run | limits | ...` (see the README walkthrough).

Exit codes: 0 success, 1 the run failed (its partial results are still written), 2 bad input.
"""
from __future__ import annotations

import argparse
import os
from pathlib import Path
import sys

from rollcontact.bem.errors import InputError, RollcontactError, SceneError



def _add_run(sub):
    p = sub.add_parser("run", help="run one scene (default: the seed paper's perpendicular scene)",
                       description="Run one scene and write its results to HDF5, as it goes (checkpoints at every "
                                   "period end; a killed run continues with --restart). Units: mm, N, MPa.")
    p.add_argument("scene", nargs="?", help="scene TOML file (default: the embedded paper scene)")
    p.add_argument("-o", "--output", help="output HDF5 file, not replaced if it exists unless --overwrite (default: "
                   "results/<scene name>.h5; with --set or --restart, results/<scene name>[__from_step<N>]__"
                   "<key=value>....h5; -2, -3, ... added to a default name that exists; --restart of an incomplete "
                   "run: the run's own file)")
    p.add_argument("--overwrite", action="store_true", help="replace the -o file if it exists")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override a scene key, e.g. --set load.ft=0.77 (repeatable)")
    p.add_argument("--restart", metavar="RUN.h5",
                   help="continue a stored run from its last stored step (or --step); a run killed while running "
                        "continues from its last checkpoint")
    p.add_argument("--step", type=int, help="with --restart: the stored step to continue from")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress lines")
    p.add_argument("--stresses", action="store_true",
                   help="also compute the subsurface stresses of each stored step when it is stored, kept if the run "
                        "stops (RUN.h5.subsurface/) and added to its file (as `rollcontact stresses RUN.h5 "
                        "--all-steps`); a restart takes those computed before")
    from rollcontact.cases.cli.stresses_cmd import add_depth_options
    add_depth_options(p)
    p.set_defaults(func=_run)


def _run(args) -> int:
    from rollcontact.cases import api
    from rollcontact.cases.run.summary import format_summary
    from rollcontact.cases.sweep.workers import sigterm_as_interrupt
    if args.step is not None and not args.restart:
        raise InputError(f"--step {args.step}: applies only with --restart RUN.h5 (the stored step to continue "
                         "from); to run a scene from the start, leave --step out")
    if args.restart and args.scene:
        raise SceneError("give either a scene file or --restart, not both")
    progress = not args.quiet
    depths = _stress_depths(args)
    if args.restart:
        out = args.output or _restart_output(args, progress)
        run = lambda: api.restart(args.restart, step=args.step, overrides=args.overrides,  # noqa: E731
                                  output=out, overwrite=args.overwrite, progress=progress, stresses=args.stresses,
                                  depths=depths)
    else:
        scene = api.load_scene(args.scene, args.overrides)
        out = args.output or _free_default(scene.name, args.overrides, None, progress)
        run = lambda: api.run(scene, out, overwrite=args.overwrite, progress=progress,  # noqa: E731
                              stresses=args.stresses, depths=depths)
    sigterm_as_interrupt(flag=False)
    try:
        result = run()
    except api.RunInterrupted as exc:
        print(_interrupted_message(exc.result), file=sys.stderr)
        return 130
    except KeyboardInterrupt:       # before the first step, or a second interrupt while the run was being written
        print(_interrupted_early_message(out), file=sys.stderr)
        return 130
    if Path(result.path) != Path(out):
        print(f"the run did not complete: written to {result.path}, beside the complete run in {out}, "
              "which is kept", file=sys.stderr)
    print(format_summary(result))
    if args.stresses and result.path is not None:
        _report_stresses(result)
    elif not args.stresses:
        _note_unused_stresses(args.restart, result.path)
    return 0 if result.status == "complete" else 1


def _note_unused_stresses(*run_files):
    """A run without --stresses beside step files of an earlier `run --stresses` (killed) says they are there."""
    from rollcontact.cases.run.step_stresses import folder_of
    for run_file in {Path(f) for f in run_files if f}:
        folder = folder_of(run_file)
        steps = list(folder.glob("step_*.h5")) if folder.is_dir() else []
        if steps:
            print(f"note: {folder} holds the subsurface stresses of {len(steps)} stored step(s) of an earlier "
                  "`run --stresses` that stopped; this run (without --stresses) did not use them: restart with "
                  "--stresses to take them, or remove the folder", file=sys.stderr)


def _report_stresses(result):
    """`run --stresses`: what the run added to its file (the stresses of its stored steps, computed as it went)."""
    if not len(result.field_steps):
        print("--stresses: the run stored no field snapshots (output.fields = 'none', or the MDR model); no "
              "subsurface stresses computed", file=sys.stderr)
    elif result.subsurface.get("steps"):
        from rollcontact.cases.cli.stresses_cmd import report
        print(report(result.subsurface, result.path))


def _stress_depths(args):
    """--depths parsed before any work (None: the default depths); refused without --stresses."""
    if args.depths is None:
        return None
    if not args.stresses:
        raise InputError("--depths applies only with --stresses (the subsurface stresses of the stored steps)")
    from rollcontact.cases.run.stresses import parse_depths
    return parse_depths(args.depths)


def _interrupted_early_message(out) -> str:
    from rollcontact.cases.results.hdf5 import stored_summary
    stored = stored_summary(out) if Path(out).is_file() else None
    if stored is None:
        return "rollcontact run: interrupted before the first step; nothing written"
    more = "" if stored["status"] == "complete" else f"; continue with: rollcontact run --restart {out}"
    return f"rollcontact run: interrupted; {out} is left with status '{stored['status']}'{more}"


def _restart_output(args, progress) -> Path:
    """Without -o, a restart of a run that did not complete (a checkpoint, a failed run) from its last step continues
    in its own file; any other goes to a new file named after it and the step."""
    from rollcontact.cases.run.restart import load_restart
    source = load_restart(args.restart, args.step)
    if source.data.status != "complete" and source.step == int(source.data.history["step"][-1]):
        return Path(args.restart)
    return _free_default(source.scene.name, args.overrides, source.step, progress)


def _free_default(scene_name, overrides, restart_step, progress) -> Path:
    """The default output (cases.results.outputs.default_output), with -2, -3, ... added while that name exists:
    a run without -o never replaces a file."""
    from rollcontact.cases.results.outputs import default_output, free_name
    base = default_output(scene_name, overrides, restart_step)
    out = free_name(base)
    if progress and (overrides or restart_step is not None or out != base):
        why = f"{base} exists" if out != base else "named after the scene, the restart step and the --set overrides"
        print(f"no -o given: writing to {out} ({why}; no file is replaced without -o ... --overwrite)",
              file=sys.stderr, flush=True)
    return out


def _interrupted_message(result) -> str:
    n = len(result.history["step"])
    text = f"rollcontact run: interrupted after {n} step(s); they are in {result.path} (status 'failed')"
    if len(result.field_steps):
        step = int(result.field_steps[-1])
        text += f"; continue with: rollcontact run --restart {result.path} --step {step} -o OUT.h5"
    return text


class _Version(argparse.Action):
    """--version, read from the package metadata only when asked for (importlib.metadata costs 0.04 s)."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        from rollcontact import __version__
        print(f"rollcontact {__version__}")
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="rollcontact", description=(
        "Quasi-static rolling contact with Coulomb friction on an elastic half-space "
        "(boundary elements, FFT). Units: mm, N, MPa, degrees."))
    parser.add_argument("--version", action=_Version, help="print the version and exit")
    sub = parser.add_subparsers(dest="command", required=True)
    _add_run(sub)
    try:
        from rollcontact.cases.cli import limits_cmd
    except ImportError:  # pragma: no cover - optional while the module is being written
        limits_cmd = None
    if limits_cmd is not None:
        limits_cmd.register(sub)
    from rollcontact.cases.cli import sweep_cmd; sweep_cmd.register(sub)  # noqa: E702
    from rollcontact.cases.cli import plot_cmd; plot_cmd.register(sub)  # noqa: E702  plot, compare
    from rollcontact.cases.cli import stresses_cmd; stresses_cmd.register(sub)  # noqa: E702
    from rollcontact.cases.cli import creep_cmd; creep_cmd.register(sub)  # noqa: E702
    return parser


class _ClosedPipeSafe:
    """stdout that survives its reader going away (`rollcontact limits | head -4`): the first BrokenPipeError points
    the descriptor at /dev/null, so the command finishes its work (a sweep its runs and summary) silently instead of
    dying with a traceback."""

    def __init__(self, stream):
        self._stream = stream

    def _to_devnull(self):
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, self._stream.fileno())
        os.close(fd)

    def write(self, text):
        try:
            return self._stream.write(text)
        except BrokenPipeError:
            self._to_devnull()
            return len(text)

    def flush(self):
        try:
            self._stream.flush()
        except BrokenPipeError:
            self._to_devnull()

    def __getattr__(self, name):
        return getattr(self._stream, name)


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    real = sys.stdout is sys.__stdout__ and sys.stdout is not None
    if real:
        sys.stdout = _ClosedPipeSafe(sys.stdout)
    try:
        return args.func(args)
    except RollcontactError as exc:
        print(f"rollcontact {args.command}: error: {exc}", file=sys.stderr)
        return 2 if isinstance(exc, ValueError) else 1
    finally:
        if real:
            sys.stdout.flush()
            sys.stdout = sys.__stdout__


def console_main():
    """The `rollcontact` command (pyproject's entry point): `main`, then, after `run`, an exit that skips the
    interpreter's teardown. Tearing down numba's compiler and the module graph takes 0.23-0.35 s after a run
    (benchmarks/startup.py), 10-15 % of a paper scene's process, with nothing
    left to do: the run file is closed and renamed into place, stdout and stderr are flushed here, and `run` starts
    no other process or thread that needs a clean-up. The other commands (sweeps with their worker pools and Dask
    clients, plots) exit normally."""
    code = main()
    if sys.argv[1:2] == ["run"]:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        finally:
            os._exit(code)
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(console_main())
