"""How messages name the arguments a user gave: the Python API's keywords (`output`, `overrides`, `overwrite=True`)
or, inside a `rollcontact` command, its options (`-o`, `--set`, `--overwrite`).

The API (cases.api) and everything below it build their messages with `arg` and `flag`; the command line
(cases.cli.main) runs each command inside `command_line()`, so that the same error reads in the words of whoever
called. Outside that block (Python, tests, the workers of a sweep) the API's names are used.
"""
from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar

#: API keyword -> the command-line option that gives it
OPTIONS = {
    "output": "-o", "overwrite": "--overwrite", "overrides": "--set", "vary": "--vary", "step": "--step",
    "steps": "--step", "depths": "--depths", "restart": "--restart", "stresses": "--stresses", "tol": "--tol",
    "jobs": "--jobs", "scheduler": "--scheduler", "of": "--of", "points": "--points", "max_ratio": "--max",
    "w": "--w", "ft": "--ft", "angle": "--angle", "kappa": "--kappa", "scene": "SCENE", "target": "TARGET",
}
#: the API's spelling of an option that is a value of an argument there (--all-steps is steps="all")
VALUES = {"all_steps": ("--all-steps", 'steps="all"')}

_command_line = ContextVar("rollcontact_command_line", default=False)


@contextmanager
def command_line():
    """Messages raised inside name the command line's options."""
    token = _command_line.set(True)
    try:
        yield
    finally:
        _command_line.reset(token)


def on_command_line() -> bool:
    """True inside `command_line()`."""
    return _command_line.get()


def arg(name: str) -> str:
    """How a message names the argument `name` (an API keyword): '-o' on the command line, 'output' in Python."""
    if name in VALUES:
        return VALUES[name][0 if on_command_line() else 1]
    return OPTIONS.get(name, name) if on_command_line() else name


def flag(name: str) -> str:
    """How a message asks for a switch: '--overwrite' on the command line, 'overwrite=True' in Python."""
    return OPTIONS.get(name, name) if on_command_line() else f"{name}=True"


def restart_hint(path, stresses: bool = False, depths=None) -> str:
    """How to continue the run stored (incomplete) in `path` in its own file: the command, or the API call (with the
    stresses computed as the run goes, at the given depths in mm, as before)."""
    z = None if depths is None else ",".join(f"{float(v):.17g}" for v in depths)
    if on_command_line():
        return (f"rollcontact run --restart {path}" + (" --stresses" if stresses else "")
                + (f" --depths {z}" if stresses and z else ""))
    return (f"rollcontact.restart({str(path)!r}, output={str(path)!r}" + (", stresses=True" if stresses else "")
            + (f", depths=[{z}]" if stresses and z else "") + ")")


def restart_step_hint(path, step: int) -> str:
    """How to continue the run stored in `path` from its stored `step` into a new file."""
    if on_command_line():
        return f"rollcontact run --restart {path} --step {step} -o OUT.h5"
    return f"rollcontact.restart({str(path)!r}, step={step}, output='OUT.h5')"
