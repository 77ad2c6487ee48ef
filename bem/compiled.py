"""Compiled element loops: numba kernels, built once per machine ahead of time and then loaded without numba.

rollcontact's element loops (the stick/slip division, the CG updates, the spectral scaling, ...) are numba functions.
Loading them through numba's JIT cache costs every process numba's import and its compiler's start-up, a large part
of a run's start-up time and resident memory (benchmarks/README.md, "Lean runs"), although nothing is compiled. So the
kernels of each layer (`rollcontact.bem`, `rollcontact.solver`) are compiled once, ahead of time, into one extension
module in the cache (`numba.pycc`; ROLLCONTACT_KERNEL_CACHE, else ROLLCONTACT_CACHE/kernels, default
~/.cache/rollcontact/kernels), named by a digest of the kernel sources, numba's, llvmlite's and Python's versions and
the processor; a process then imports that module (a millisecond) and never imports numba.

A kernel module imports this module's decorators:

    @kernel("void(f8[:, ::1], f8[:, ::1])")   an element loop called from Python, with its one numba signature
    @inline                                   a helper that kernels inline (numba's inline="always")
    @internal                                 a function that only kernels call (compiled into them)

and calls its kernels with exactly the signature's types (float64 arrays of the given dimensions and layout, int8
regions, Python floats and ints for f8 and i8 scalars): an ahead-of-time kernel checks only the item size of its
arrays. ROLLCONTACT_KERNEL_CHECKS=1 wraps every kernel in a check of each argument against its signature (the test
suite sets it).

The first call of a kernel whose library is not built yet builds it: a child process (`python -m
rollcontact.bem.compiled LAYER FILE`) imports the layer's kernel modules with numba's JIT and compiles them with
numba.pycc (a C compiler is needed; tens of seconds for the solver's kernels), under a file lock, so that concurrent
processes build it once. If the build fails (no C compiler, numba without pycc), the layer's kernels fall back to
numba's JIT with its on-disk cache (cache=True), the behaviour without this module, and the failure is recorded
beside the library (<name>.failed, read by later processes) and warned about once. ROLLCONTACT_KERNELS=jit selects
the JIT throughout (no build). Both routes compile the same Python with the same LLVM and flags (no fast-math): their
results are identical (tests/bem/test_compiled.py).
"""
from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import os
import platform
import subprocess
import sys
import threading
import warnings
from dataclasses import dataclass
from pathlib import Path

#: the modules whose kernels a layer's library holds are the .py files of its package that contain this text
MARKER = b"from rollcontact.bem.compiled import"
#: numba options of every kernel (as the JIT used them); an ahead-of-time build has no fast-math either
JIT_OPTIONS = dict(cache=True, nogil=True)
#: libraries kept per layer in the cache (the newest by modification time; a library is touched when loaded)
KEEP = 6
#: version of the build recipe (`build_library`), part of the digest: raise it when the recipe changes
BUILD = 1

_mode = os.environ.get("ROLLCONTACT_KERNELS", "aot")
_checks = os.environ.get("ROLLCONTACT_KERNEL_CHECKS", "") not in ("", "0")
_lock = threading.RLock()
_entries: dict[str, list] = {}       # layer -> [_Entry] of its kernels and inline helpers, in declaration order
_libraries: dict[str, object] = {}   # layer -> loaded library module, or None when the layer uses the JIT


@dataclass
class _Entry:
    layer: str
    module: str
    name: str
    fn: object
    signature: str | None    # None: an inline helper or an internal function
    inline: bool
    options: dict
    pending: object = None   # its _Pending stand-in, if one was handed out

    @property
    def export(self) -> str:
        """The kernel's name in the layer's library: its module path below the layer and its name."""
        return (self.module[len(self.layer) + 1:] + "." + self.name).replace(".", "__")


def kernel(signature: str, **options):
    """Declare an element loop with its numba signature (types of the arguments and the result); options: extra numba
    options of the JIT route. Returns the library's compiled function, or a stand-in that resolves on first call."""
    def declare(fn):
        entry = _register(fn, signature, options, False)
        if _mode == "jit":
            return _jit(entry)
        library = _library_if_built(entry.layer)
        if library is not None and hasattr(library, entry.export):
            return _checked(entry, getattr(library, entry.export))
        entry.pending = _Pending(entry)
        return entry.pending
    return declare


def inline(fn):
    """Declare a helper that kernels inline (numba inline='always'); the plain function when the library is used."""
    entry = _register(fn, None, {}, True)
    return _jit(entry) if _mode == "jit" else fn


def internal(fn):
    """Declare a function that only kernels call (a numba function of its own, not inlined); the plain function when
    the library is used (the library holds it compiled into the kernels)."""
    entry = _register(fn, None, {}, False)
    return _jit(entry) if _mode == "jit" else fn


def ready(layer: str) -> bool | None:
    """True when `layer`'s kernels are compiled (its library built for these sources and this machine), False when
    the first kernel call will build it, None when the layer uses numba's JIT (ROLLCONTACT_KERNELS=jit or a failed
    build: numba's own cache decides)."""
    if _mode == "jit":
        return None
    path = _library_path(layer)
    if path.exists():
        return True
    return None if path.with_suffix(".failed").exists() else False


def cache_dir() -> Path:
    """ROLLCONTACT_KERNEL_CACHE, else ROLLCONTACT_CACHE/kernels (default ~/.cache/rollcontact/kernels)."""
    if os.environ.get("ROLLCONTACT_KERNEL_CACHE"):
        return Path(os.environ["ROLLCONTACT_KERNEL_CACHE"])
    root = os.environ.get("ROLLCONTACT_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "rollcontact")
    return Path(root) / "kernels"


# --- declaration ------------------------------------------------------------------------------------------------
def _register(fn, signature, options, inline_) -> _Entry:
    module = fn.__module__
    parts = module.split(".")
    if parts[0] != "rollcontact" or len(parts) < 3:
        raise ValueError(f"{module}.{fn.__name__}: kernels live in a layer of rollcontact (rollcontact.bem, ...)")
    entry = _Entry(".".join(parts[:2]), module, fn.__name__, fn, signature, inline_, options)
    with _lock:
        _entries.setdefault(entry.layer, []).append(entry)
    return entry


def _jit(entry: _Entry):
    import numba
    if entry.inline:
        return numba.njit(cache=True, inline="always")(entry.fn)
    return numba.njit(**JIT_OPTIONS, **entry.options)(entry.fn)


class _Pending:
    """Stand-in for a kernel whose library is not loaded yet: the first call builds or loads the layer's library (or
    falls back to the JIT), puts the kernel in its module's namespace and calls it."""

    def __init__(self, entry):
        self._entry = entry
        self._fn = None
        self.__name__ = entry.name
        self.__doc__ = entry.fn.__doc__
        self.py_func = entry.fn

    def __call__(self, *args):
        fn = self._fn
        if fn is None:
            fn = self._fn = _resolve(self._entry)
        return fn(*args)


def _resolve(entry: _Entry):
    """The compiled kernel of `entry`: from its layer's library (built if needed), else numba's JIT."""
    with _lock:
        library = _libraries.get(entry.layer, False)
        if library is False:
            library = _libraries[entry.layer] = _load_or_build(entry.layer)
            if library is None:
                _use_jit(entry.layer)
        if entry.pending is not None and entry.pending._fn is not None:
            return entry.pending._fn
        if library is not None and hasattr(library, entry.export):
            fn = _checked(entry, getattr(library, entry.export))
        else:
            fn = _jit(entry)
        _bind(entry, fn)
        return fn


def _bind(entry: _Entry, fn):
    """Put the compiled `fn` of `entry` in its module's namespace, in place of its stand-in or plain function."""
    module = sys.modules[entry.module]
    if getattr(module, entry.name, None) in (entry.pending, entry.fn):
        setattr(module, entry.name, fn)
    if entry.pending is not None:
        entry.pending._fn = fn


def _use_jit(layer: str):
    """Put numba functions for every kernel and inline helper of `layer` in their modules (the JIT compiles a kernel
    from the globals of its module: the helpers it inlines and the kernels it calls must be numba functions)."""
    for entry in _entries.get(layer, ()):
        if entry.pending is None or entry.pending._fn is None:
            _bind(entry, _jit(entry))


# --- the library ------------------------------------------------------------------------------------------------
_digests: dict[str, str] = {}


def _root(layer: str) -> Path:
    """The folder of the layer's package (found without importing it)."""
    module = sys.modules.get(layer)
    if module is not None:
        return Path(module.__path__[0])
    return Path(importlib.util.find_spec(layer).submodule_search_locations[0])


def _kernel_files(layer: str) -> list[Path]:
    """The .py files of `layer`'s package that declare kernels (contain MARKER), sorted."""
    root = _root(layer)
    here = Path(__file__).resolve()
    return sorted(p for p in root.rglob("*.py") if p.resolve() != here and MARKER in p.read_bytes())


def _digest(layer: str) -> str:
    """Digest of what the layer's library is compiled from: its kernel files, the build recipe (BUILD), numba's,
    llvmlite's and Python's versions, and the processor (the library is built for it)."""
    if layer not in _digests:
        h = hashlib.sha256(f"{BUILD}".encode())
        root = _root(layer)
        for path in _kernel_files(layer):
            h.update(str(path.relative_to(root)).encode())
            h.update(path.read_bytes())
        for package in ("numba", "llvmlite"):
            spec = importlib.util.find_spec(package)
            version = Path(spec.origin).with_name("_version.py") if spec and spec.origin else None
            h.update(version.read_bytes() if version is not None and version.exists() else b"?")
        h.update(f"{sys.version}|{sys.implementation.cache_tag}|{platform.machine()}|{_processor()}".encode())
        _digests[layer] = h.hexdigest()[:16]
    return _digests[layer]


def _processor() -> str:
    """The processor's model and features (the library is compiled for the host processor)."""
    try:
        with open("/proc/cpuinfo") as fh:
            lines = []
            for line in fh:
                if not line.strip():
                    break
                if line.startswith(("vendor_id", "model name", "flags", "cpu family", "model\t")):
                    lines.append(line.strip())
            return "|".join(lines)
    except OSError:
        return platform.processor()


def _module_name(layer: str) -> str:
    return f"{layer.replace('.', '_')}_kernels_{_digest(layer)}"


def _library_path(layer: str) -> Path:
    return cache_dir() / (_module_name(layer) + importlib.machinery.EXTENSION_SUFFIXES[0])


def _library_if_built(layer: str):
    """The layer's library if it is loaded or built (loaded now), else None."""
    with _lock:
        library = _libraries.get(layer, False)
        if library is False:
            path = _library_path(layer)
            library = _import_library(layer, path) if path.exists() else False
            if library is not False:
                _libraries[layer] = library
        return library or None


def _import_library(layer: str, path: Path):
    """Import the extension module at `path`; None if that fails (a damaged file)."""
    try:
        spec = importlib.util.spec_from_file_location(_module_name(layer), path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    except Exception:   # an unreadable or truncated library: rebuild
        return None
    try:
        os.utime(path)   # the newest are kept (`_prune`)
    except OSError:
        pass
    return module


def _load_or_build(layer: str):
    """The layer's library, built now if it is missing; None (the JIT) if it cannot be built."""
    path = _library_path(layer)
    failed = path.with_suffix(".failed")
    if failed.exists():
        return None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with _FileLock(path.with_suffix(".lock")):
            if not path.exists():
                _build(layer, path)
    except (OSError, RuntimeError) as exc:
        try:
            failed.write_text(f"{exc}\n")
        except OSError:
            pass
        warnings.warn(f"rollcontact: the compiled kernels of {layer} could not be built ({exc}); numba's JIT is used "
                      f"instead (start-up about 0.5 s longer). To retry, delete {failed}.", RuntimeWarning,
                      stacklevel=4)
        return None
    library = _import_library(layer, path)
    _prune(layer)
    return library


def _build(layer: str, path: Path):
    """Compile the layer's library into `path` in a child process (numba imported there only)."""
    env = dict(os.environ, ROLLCONTACT_KERNELS="jit", ROLLCONTACT_KERNEL_CHECKS="0")
    tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    try:
        proc = subprocess.run([sys.executable, "-m", "rollcontact.bem.compiled", layer, str(tmp)], env=env,
                              capture_output=True, text=True)
        if proc.returncode != 0 or not tmp.exists():
            tail = " ".join((proc.stderr or proc.stdout).strip().splitlines()[-3:])
            raise RuntimeError(f"the build process failed: {tail or f'exit status {proc.returncode}'}")
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def _prune(layer: str):
    """Remove the layer's oldest libraries beyond KEEP (other sources or versions)."""
    prefix = f"{layer.replace('.', '_')}_kernels_"
    try:
        found = sorted((p for p in cache_dir().glob(prefix + "*") if p.suffix in (".so", ".pyd", ".failed")),
                       key=lambda p: p.stat().st_mtime, reverse=True)
        for old in found[KEEP:]:
            old.unlink(missing_ok=True)
            if old.suffix != ".failed":
                old.with_suffix(".lock").unlink(missing_ok=True)
    except OSError:
        pass


class _FileLock:
    """An exclusive lock on a file (fcntl.flock where available; no lock elsewhere)."""

    def __init__(self, path):
        self._path = path
        self._fh = None

    def __enter__(self):
        try:
            import fcntl
        except ImportError:
            return self
        self._fh = open(self._path, "a")
        fcntl.flock(self._fh, fcntl.LOCK_EX)
        return self

    def __exit__(self, *exc):
        if self._fh is not None:
            self._fh.close()


# --- argument checks (ROLLCONTACT_KERNEL_CHECKS=1) ------------------------------------------------------------------
def _checked(entry: _Entry, fn):
    """fn, or with ROLLCONTACT_KERNEL_CHECKS a wrapper that checks every argument against the signature (TypeError)."""
    if not _checks:
        return fn
    import numpy as np
    specs = _argument_specs(entry.signature)

    def call(*values):
        if len(values) != len(specs):
            raise TypeError(f"{entry.module}.{entry.name}: {len(values)} arguments, the signature has {len(specs)}")
        for k, (value, (kind, dtype, ndim, contiguous)) in enumerate(zip(values, specs)):
            if ndim:
                ok = (isinstance(value, np.ndarray) and value.dtype == dtype and value.ndim == ndim
                      and (value.flags.c_contiguous or not contiguous))
            elif kind == "b":
                ok = isinstance(value, (bool, np.bool_))
            elif kind == "i":
                ok = isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))
            else:
                ok = isinstance(value, (float, int, np.floating, np.integer)) and not isinstance(value, (bool, np.bool_))
            if not ok:
                got = (f"{value.dtype} array of {value.ndim} dimensions (C-contiguous: {value.flags.c_contiguous})"
                       if isinstance(value, np.ndarray) else type(value).__name__)
                raise TypeError(f"{entry.module}.{entry.name}: argument {k} is a {got}; the signature "
                                f"{entry.signature!r} wants {'an array' if ndim else 'a scalar'} of its type")
        return fn(*values)
    call.__name__ = entry.name
    return call


_DTYPES = {"f8": "float64", "i8": "int64", "i1": "int8", "b1": "bool", "c16": "complex128"}


def _argument_specs(signature: str) -> list:
    """(kind, dtype, ndim, C-contiguous) of each argument of a numba signature string written with the codes of
    _DTYPES, e.g. "void(f8[:, ::1], i8)" -> [('f', 'float64', 2, True), ('i', 'int64', 0, False)]."""
    depth, start = 0, None
    for k in range(len(signature) - 1, -1, -1):          # the argument list: the last top-level parentheses
        depth += {")": 1, "(": -1}.get(signature[k], 0)
        if depth == 0:
            start = k
            break
    args, depth, part = [], 0, ""
    for ch in signature[start + 1:-1] + ",":
        if ch == "," and depth == 0:
            args.append(part.strip())
            part = ""
            continue
        depth += {"[": 1, "]": -1}.get(ch, 0)
        part += ch
    specs = []
    for arg in args:
        code, _, dims = arg.partition("[")
        ndim = dims.count(":") - dims.count("::") if dims else 0
        specs.append((code[0], _DTYPES[code], ndim, dims.rstrip("]").endswith("::1")))
    return specs


# --- the build process ------------------------------------------------------------------------------------------
def build_library(layer: str, out: Path):
    """Compile every kernel of `layer` into the extension module `out` (numba.pycc, for the host processor). Runs in
    the child process of `_build`, with ROLLCONTACT_KERNELS=jit (so the inline helpers are numba functions)."""
    import importlib
    import tempfile
    importlib.import_module(layer)
    root = _root(layer)
    for path in _kernel_files(layer):
        rel = path.relative_to(root).with_suffix("")
        importlib.import_module(".".join((layer, *rel.parts)).removesuffix(".__init__"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from numba.pycc import CC
    name = _module_name(layer)
    cc = CC(name)
    cc.target_cpu = "host"
    with tempfile.TemporaryDirectory(prefix="rollcontact-kernels-") as tmp:
        cc.output_dir = tmp
        for entry in _entries.get(layer, ()):
            if entry.signature is not None:
                cc.export(entry.export, entry.signature)(entry.fn)
        cc.compile()
        built = Path(tmp) / cc.output_file
        os.replace(built, out) if built.parent == out.parent else out.write_bytes(built.read_bytes())


if __name__ == "__main__":
    from rollcontact.bem import compiled as _module   # the registry is the imported module's, not __main__'s
    _module.build_library(sys.argv[1], Path(sys.argv[2]))
