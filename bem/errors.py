"""The project's exceptions, in one place.

They live in `bem` (which imports nothing of ours) so that every layer can raise and catch them.
Messages name the parameter, the value, and what is allowed.
"""


class RollcontactError(Exception):
    """Base class of every error rollcontact raises on purpose."""


class InputError(RollcontactError, ValueError):
    """A parameter is out of its allowed range or inconsistent with another one."""


class SceneError(InputError):
    """A scene file or a `--set` override is malformed: unknown key, wrong type, out of range."""


class ConvergenceError(RollcontactError, RuntimeError):
    """An iterative solver did not reach its stated tolerance within its iteration budget.

    Attributes: `solver` (name), `iterations`, `residual`, `tol`, and `regime` (a short description of
    the physical situation, e.g. 'f_t = 0.999, stick zone 2 elements'), all optional.
    """

    def __init__(self, message, *, solver=None, iterations=None, residual=None, tol=None, regime=None):
        parts = [message]
        if solver is not None:
            parts.append(f"solver={solver}")
        if iterations is not None:
            parts.append(f"iterations={iterations}")
        if residual is not None and tol is not None:
            parts.append(f"residual={residual:.3e} > tol={tol:.1e}")
        if regime:
            parts.append(f"regime: {regime}")
        super().__init__("; ".join(parts))
        self.solver, self.iterations, self.residual, self.tol, self.regime = (
            solver, iterations, residual, tol, regime)


class GrossSlidingError(RollcontactError, RuntimeError):
    """The tangential load exceeds the friction capacity mu*Fn: no static equilibrium exists."""


class ContactEdgeError(RollcontactError, RuntimeError):
    """The contact area reached the edge of the computational grid: the grid is too small."""


class OutputExistsError(InputError):
    """An output file exists and was not to be replaced (the message names the file and --overwrite)."""


class OutputInUseError(InputError):
    """Another process is writing the same output (the message names the process and its host)."""


class OutputWriteError(RollcontactError):
    """A file could not be written: a full disk, a folder that vanished, a read-only file system. The message names
    the file and the failure; nothing partial is left under the file's name (cases.results.writing).

    Attributes: `path` (the file), `errno` (the operating system's error number), and, set by the code that knows
    them, `result` (the RunResult still in memory, when a run's final write failed) and `restart` (the file a
    `--restart` continues from: the run's last good checkpoint, when one is kept)."""

    def __init__(self, message, *, path=None, errno=None):
        super().__init__(message)
        self.path, self.errno = path, errno
        self.result = None
        self.restart = None
