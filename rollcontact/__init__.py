"""rollcontact: quasi-static rolling contact with Coulomb friction on an elastic half-space (boundary elements,
FFT). Units: mm, N, MPa, degrees.

The Python API (every `rollcontact` command is a thin layer over one of these; see docs/python_api.md):

    load_scene(path=None, overrides=None)    a scene from a TOML file or the embedded default, with overrides
    run(scene, output=None, ...)             run it (BEM or the 1-D MDR model); a RunResult, HDF5 if output given
    read_run(path)                           a stored run file as the same RunResult (results compare with ==)
    restart(path, step=None, ...)            continue a stored run (more periods, after a kill), as `run --restart`
    stresses(run, steps=None, depths=None)   the subsurface stresses of a run file or a RunResult
    sweep(scene, vary, output, ...)          a parameter sweep, as `rollcontact sweep`
    limit_search(scene, vary, output, ...)   the shakedown-limit search, as `rollcontact limit-search`
    limits(w=None, ft=None, ...)             the closed-form limits, as `rollcontact limits`
    plot(target, ...), compare(a, b, ...)    figures of a run, a sweep folder, two runs
    creep_curve(scene, of="xi", ...)         the creep-force curve of a [rolling] scene, as `rollcontact creep-curve`
    default_output(scene, ...)               where `rollcontact run` writes without -o
    import_contact(deck, output=None)        a CONTACT input deck as scenes and a report, as `import-contact`

Errors are RollcontactError: SceneError, InputError, OutputExistsError, OutputInUseError, OutputWriteError,
ConvergenceError (rollcontact.cases.api).

Subpackages, in the order data flows: `rollcontact.cases` (scenes, runs, results, sweeps, plots, CLI) ->
`rollcontact.bem` (half-space: materials, grid, influence coefficients, FFT operator) -> `rollcontact.solver`
(normal and tangential solvers, rolling, MDR model).
"""
_API = ("load_scene", "run", "read_run", "restart", "stresses", "sweep", "limit_search", "limits", "plot", "compare",
        "creep_curve", "default_output", "import_contact", "RunResult", "Scene", "RollcontactError", "InputError",
        "SceneError", "ConvergenceError", "OutputExistsError", "OutputInUseError", "OutputWriteError", "RunInterrupted")
__all__ = ["__version__", *_API]


def __getattr__(name):
    """The API (and __version__, from the package metadata) is looked up on first use, so that `import rollcontact`
    and `rollcontact --help` stay fast."""
    if name == "__version__":
        return _installed_version()
    if name in _API:
        from rollcontact.cases import api
        return getattr(api, name)
    raise AttributeError(f"module 'rollcontact' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_API))


def _installed_version() -> str:
    """The installed distribution's version: the Version line of its METADATA, found on sys.path as
    importlib.metadata would find it (which itself costs a run tens of milliseconds to import); importlib.metadata
    where the file is not found that way."""
    import os
    import sys
    for entry in sys.path:
        try:
            names = [n for n in os.listdir(entry or ".") if n.startswith("rollcontact-") and n.endswith(".dist-info")]
        except OSError:
            continue
        for name in names:
            try:
                with open(os.path.join(entry or ".", name, "METADATA"), encoding="utf-8") as fh:
                    for line in fh:
                        if line.startswith("Version:"):
                            return line.split(":", 1)[1].strip()
                        if not line.strip():
                            break
            except OSError:
                continue
    from importlib import metadata
    try:
        return metadata.version("rollcontact")
    except metadata.PackageNotFoundError:  # pragma: no cover - a source tree that is not installed
        return "unknown"
