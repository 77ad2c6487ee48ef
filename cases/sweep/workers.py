"""Where sweep runs execute: local worker processes ('forkserver', one BLAS thread each, exiting with the
sweep), this process (jobs = 1), or a Dask distributed scheduler (optional extra); and the interrupt flag the
CLI's SIGTERM handler sets (cases.sweep.runner, cases.sweep.limit_search).

All three pools have the same small interface: submit(fn, *args) -> future, as_completed(futures), stop()
(cancel and terminate: the unfinished runs are redone on resume), close().
"""
import os
import re
import signal
import sys
import threading
import time

from rollcontact.bem.wisdom import process_exists
from rollcontact.bem.errors import InputError
from rollcontact.cases.arguments import arg

def _worker_init(sweep_pid: int):
    """Worker set-up: one BLAS thread, and exit if the sweep process dies (e.g. SIGKILL).

    numba's thread settings are left alone: the kernels are serial (no parallel=True), and changing
    NUMBA_NUM_THREADS after numba is imported (the fork server preloads it) makes every later compilation in
    the worker fail ("Cannot set NUMBA_NUM_THREADS to a different value once the threads have been
    launched") - which a worker meets whenever numba's on-disk cache misses, e.g. on a fresh install.
    With 'forkserver' the worker's parent is the fork server, which outlives a killed sweep, so the sweep's
    own pid is watched (twice a second) besides the parent's."""
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    signal.signal(signal.SIGINT, signal.SIG_IGN)    # Ctrl-C is handled by the parent, which stops us
    parent = os.getppid()

    def watch():
        while True:
            time.sleep(0.5)
            if os.getppid() != parent or not process_exists(sweep_pid):
                os._exit(1)
    threading.Thread(target=watch, daemon=True).start()


#: Set by the CLI's SIGTERM handler (`cases.cli.sweep_cmd`), which also raises KeyboardInterrupt. An exception raised
#: by a signal handler while Python runs a weakref callback or a finaliser is only printed ("Exception ignored
#: in ...") and the sweep went on to finish with exit code 0 (the kill-and-resume test failed 2 times in 12 on a
#: loaded machine); the loops of the sweep and the limit search, and `_LocalPool.as_completed`, raise it again at
#: their next check (`raise_if_interrupted`).
interrupt_requested = threading.Event()


def raise_if_interrupted():
    if interrupt_requested.is_set():
        raise KeyboardInterrupt


class _LocalPool:
    """ProcessPoolExecutor with the 'forkserver' context (solver modules preloaded once) or 'spawn'."""

    def __init__(self, jobs):
        from concurrent.futures import ProcessPoolExecutor
        import multiprocessing
        methods = multiprocessing.get_all_start_methods()
        ctx = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        if ctx.get_start_method() == "forkserver":
            ctx.set_forkserver_preload(["rollcontact.cases.run.scene_run", "rollcontact.cases.run.bem_run",
                                        "rollcontact.cases.sweep.runner", "rollcontact.cases.sweep.limit_search"])
        self.executor = ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_worker_init,
                                            initargs=(os.getpid(),))

    def submit(self, fn, *args):
        return self.executor.submit(fn, *args)

    def as_completed(self, futures):
        """The futures as they complete, checking `interrupt_requested` at least every 0.5 s."""
        from concurrent.futures import FIRST_COMPLETED, wait
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
            raise_if_interrupted()
            yield from done

    def stop(self):
        """Cancel what has not started and terminate running workers (their runs are redone on resume)."""
        procs = list(getattr(self.executor, "_processes", {}).values())
        self.executor.shutdown(wait=False, cancel_futures=True)
        for p in procs:
            if p.is_alive():
                p.terminate()
        for p in procs:
            p.join(timeout=5)

    def close(self):
        self.executor.shutdown(wait=True)


class _DaskPool:
    """Runs submitted to a Dask distributed scheduler at `address` (optional dependency)."""

    def __init__(self, address):
        distributed = require_dask()
        self._distributed = distributed
        try:
            self.client = distributed.Client(address, timeout=30)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"{arg('scheduler')} {address!r}: cannot connect to the Dask scheduler ({exc})") from None

    def submit(self, fn, *args):
        return self.client.submit(fn, *args, pure=False)

    def as_completed(self, futures):
        """The futures as they complete; a worker that leaves the scheduler meanwhile (it died, or was stopped) is
        reported on stderr: the scheduler runs its unfinished runs again on the other workers (each run claims its
        file's lock anew, which the dead worker's process no longer holds, and starts from the beginning)."""
        known = self._workers()
        for future in self._distributed.as_completed(futures):
            now = self._workers()
            for address in sorted(known - now):
                print(f"sweep: Dask worker {address} left the scheduler (it died or was stopped); the scheduler runs "
                      "its unfinished runs again on the other workers", file=sys.stderr, flush=True)
            known = now
            yield future

    def _workers(self) -> set:
        try:
            return set(self.client.scheduler_info()["workers"])
        except Exception:            # a scheduler that does not answer: no report, the futures still complete
            return set()

    def stop(self):
        self.client.close()

    def close(self):
        self.client.close()


class _SerialPool:
    """In-process execution (jobs = 1): futures that have already run."""

    class _Done:
        def __init__(self, fn, args):
            self._fn, self._args = fn, args

        def result(self):
            return self._fn(*self._args)

    def submit(self, fn, *args):
        return self._Done(fn, args)

    def as_completed(self, futures):
        return iter(futures)

    def stop(self):
        pass

    def close(self):
        pass


def require_dask(address=None):
    """The dask.distributed module, or InputError saying how to install it or that `address` is not a scheduler
    address (checked before a sweep writes anything)."""
    if address is not None and not re.fullmatch(r"([a-z]+://)?(\[[0-9A-Fa-f:.]+\]|[^\s:/\[\]]+):\d+", str(address)):
        raise InputError(f"{arg('scheduler')} {address!r}: expected HOST:PORT or tcp://HOST:PORT (an IPv6 host in brackets), "
                         "e.g. tcp://127.0.0.1:8786")
    try:
        import distributed
    except ImportError:
        raise InputError(f"{arg('scheduler')} needs the optional dependency dask.distributed: "
                         "pip install 'rollcontact[dask]'") from None
    return distributed


def make_pool(jobs, scheduler):
    if scheduler:
        return _DaskPool(scheduler)
    if jobs == 1:
        return _SerialPool()
    return _LocalPool(jobs)



def completed(pool, tasks):
    """Submit tasks = [(item, fn, args), ...] to the pool and yield (item, result, failure) as they complete.

    failure is None, or 'ExceptionType: message' when the task raised (a worker that died, BrokenProcessPool,
    or a bug outside the RollcontactErrors that the tasks turn into results themselves); result is then None.
    KeyboardInterrupt passes through, and `interrupt_requested` is checked after the caller has handled each
    item (its summary written), so an interrupt loses no finished result."""
    futures = {}
    for item, fn, args in tasks:
        futures[pool.submit(fn, *args)] = item
    for f in pool.as_completed(list(futures)):
        try:
            result, failure = f.result(), None
        except KeyboardInterrupt:
            raise
        except Exception as exc:
            result, failure = None, f"{type(exc).__name__}: {exc}"
        yield futures[f], result, failure
        raise_if_interrupted()


def default_jobs() -> int:
    """Number of usable cores (the default of --jobs)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:                  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


def sigterm_as_interrupt(flag=True):
    """Make SIGTERM behave like Ctrl-C (SIGINT) in the CLI, so that a run writes its finished steps and a sweep
    stops its workers and writes its summary. With `flag` both signals also set `interrupt_requested`, which makes
    a sweep raise the interrupt again if the exception was swallowed (it is never cleared: one command per
    process)."""

    def handler(signum, frame):
        if flag:
            interrupt_requested.set()
        raise KeyboardInterrupt
    try:
        signal.signal(signal.SIGTERM, handler)
        signal.signal(signal.SIGINT, handler)  # Ctrl-C: the same, so that a swallowed one is raised again too
    except ValueError:                      # not the main thread (e.g. called from a test thread)
        return
    if flag and not getattr(sys.unraisablehook, "quiet_interrupts", False):
        sys.unraisablehook = _quiet_interrupts(sys.unraisablehook)


def _quiet_interrupts(previous):
    """An unraisable hook that drops the report of a KeyboardInterrupt swallowed where Python cannot raise it (a
    signal landing in a weakref callback or __del__ prints 'Exception ignored in ...' and a traceback) once
    `interrupt_requested` is set: the interrupt is raised again at the next check, so the report is noise."""
    def hook(unraisable):
        if issubclass(unraisable.exc_type, KeyboardInterrupt) and interrupt_requested.is_set():
            return
        previous(unraisable)
    hook.quiet_interrupts = True
    return hook
