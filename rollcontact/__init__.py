"""rollcontact: quasi-static rolling contact with Coulomb friction on an elastic half-space (boundary elements,
FFT). Units: mm, N, MPa, degrees.

The Python API (the `rollcontact` command is a thin layer over it; see README, "Python API"):

    load_scene(path=None, overrides=None)   a scene from a TOML file or the embedded default, with overrides
    run(scene, output=None)                  run it (BEM or the 1-D MDR model); a RunResult, HDF5 if output given
    read_run(path)                           a stored run file as the same RunResult
    restart(path, step=None, overrides=None) continue a stored run (more periods, after a kill), as `run --restart`
    stresses(path, steps=None, depths=None)  add the subsurface stresses of stored steps to a run file
    sweep(scene, vary, output, ...)          a parameter sweep, as `rollcontact sweep`
    limit_search(scene, vary, output, ...)   the shakedown-limit search, as `rollcontact limit-search`
    creep_curve(scene, of, fidelity=...)     creep-force curves of a [rolling] scene, as `rollcontact creep-curve`

Subpackages, in the order data flows: `rollcontact.cases` (scenes, runs, results, sweeps, plots, CLI) ->
`rollcontact.bem` (half-space: materials, grid, influence coefficients, FFT operator) -> `rollcontact.solver`
(normal and tangential solvers, rolling, MDR model).
"""
_API = ("load_scene", "run", "read_run", "restart", "stresses", "sweep", "limit_search", "creep_curve", "RunResult",
        "Scene", "RollcontactError", "InputError", "SceneError", "ConvergenceError", "RunInterrupted")
__all__ = ["__version__", *_API]


def __getattr__(name):
    """The API (and __version__, from the package metadata) is looked up on first use, so that `import rollcontact`
    and `rollcontact --help` stay fast."""
    if name == "__version__":
        from importlib import metadata
        try:
            return metadata.version("rollcontact")
        except metadata.PackageNotFoundError:  # pragma: no cover - a source tree that is not installed
            return "unknown"
    if name in _API:
        from rollcontact.cases import api
        return getattr(api, name)
    raise AttributeError(f"module 'rollcontact' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_API))
