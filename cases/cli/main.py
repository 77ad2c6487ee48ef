"""Command line: `rollcontact run | limits | sweep | limit-search | plot | compare | stresses | creep-curve |
import-contact` (see the README walkthrough).

Every command is a thin layer over one function of the Python API (rollcontact.cases.api, `import rollcontact`): it
parses its arguments, calls the API, and prints what the API returns (a result's `report()`); the modules of this
package import nothing of rollcontact but the API (tests/cases/test_api.py checks it). The API's messages name its
own arguments (`output`, `overrides`); inside a command (cases.arguments.command_line, set in `main`) the same
messages name the options (-o, --set).

Adding a command (e.g. `import-contact`):
  1. the work, in the module of its idea (for a new family, a new subpackage of cases/), raising RollcontactError
     subclasses whose messages name arguments through cases.arguments.arg (add the option's spelling to
     cases.arguments.OPTIONS);
  2. an API function in cases/api.py (or re-exported there), keyword arguments named as the options, returning a
     result object with a `report()` (the text the command prints); add its name to `__all__` and to
     rollcontact/__init__.py's _API;
  3. a module cases/cli/<name>_cmd.py with `register(subparsers)` that adds the parser and a handler
     `handler(args) -> int` calling the API function and printing `result.report()`; register it in
     `build_parser` below. Bad input raises InputError (exit 2), a failure another RollcontactError (exit 1).

Exit codes: 0 success, 1 a run failed (its partial results are still written) or a file could not be written,
2 bad input, 130 interrupted (Ctrl-C, SIGTERM).
"""
from __future__ import annotations

import argparse
import os
from pathlib import Path
import sys

from rollcontact.bem.errors import InputError, RollcontactError, SceneError
from rollcontact.cases.arguments import command_line


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
    if args.step is not None and not args.restart:
        raise InputError(f"--step {args.step}: applies only with --restart RUN.h5 (the stored step to continue "
                         "from); to run a scene from the start, leave --step out")
    if args.restart and args.scene:
        raise SceneError("give either a scene file or --restart, not both")
    progress = not args.quiet
    depths = _stress_depths(args)
    if args.restart:
        out = args.output or api.default_output(restart=args.restart, step=args.step, overrides=args.overrides)
        run = lambda: api.restart(args.restart, step=args.step, overrides=args.overrides,  # noqa: E731
                                  output=out, overwrite=args.overwrite, new_name=not args.output, progress=progress,
                                  stresses=args.stresses, depths=depths)
    else:
        scene = api.load_scene(args.scene, args.overrides)
        out = args.output or api.default_output(scene, overrides=args.overrides)
        run = lambda: api.run(scene, out, overwrite=args.overwrite, new_name=not args.output,  # noqa: E731
                              progress=progress, stresses=args.stresses, depths=depths)
    if progress and not args.output and (args.overrides or args.restart) and str(out) != str(args.restart):
        print(f"no -o given: writing to {out} (named after the scene, the restart step and the --set overrides; "
              "no file is replaced without -o ... --overwrite)", file=sys.stderr, flush=True)
    api.stop_on_sigterm()
    try:
        result = run()
    except api.RunInterrupted as exc:
        print(f"rollcontact run: {exc}", file=sys.stderr)
        return 130
    if result.path is not None and result.path.name.startswith(f"{Path(out).stem}.partial"):
        print(f"the run did not complete: written to {result.path}, beside the complete run in {out}, "
              "which is kept", file=sys.stderr)
    print(result.report())
    if args.stresses:
        _report_stresses(result)
    else:
        note = api.unused_stresses_note(result.path, args.restart)
        if note:
            print(note, file=sys.stderr)
    return 0 if result.status == "complete" else 1


def _report_stresses(result):
    """`run --stresses`: what the run added to its file (the stresses of its stored steps, computed as it went)."""
    if not len(result.field_steps):
        print("--stresses: the run stored no field snapshots (output.fields = 'none', or the MDR model); no "
              "subsurface stresses computed", file=sys.stderr)
    elif result.subsurface:
        print(result.subsurface.report())


def _stress_depths(args):
    """--depths parsed before any work (None: the default depths); refused without --stresses."""
    if args.depths is None:
        return None
    if not args.stresses:
        raise InputError("--depths applies only with --stresses (the subsurface stresses of the stored steps)")
    from rollcontact.cases import api
    return api.parse_depths(args.depths)


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
    from rollcontact.cases.cli import import_cmd; import_cmd.register(sub)  # noqa: E702
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
        with command_line():           # messages name the options (-o, --set), not the API's keywords
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
    clients, plots) exit normally.

    BLAS runs on one thread unless the environment says otherwise (OPENBLAS_NUM_THREADS, set before numpy loads): the
    dense products of rollcontact are small (the FFTs carry the work, on `[solver] threads`), and OpenBLAS's thread
    pool costs a process 0.08 s of CPU at numpy's import and spins a second core in small products."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
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
