"""Settings every test shares.

Every compiled kernel checks its arguments against its signature (ROLLCONTACT_KERNEL_CHECKS, rollcontact.bem.compiled),
so that a call with another dtype, dimension or layout fails here rather than reading memory wrongly in a run.

Under pytest-xdist each worker process gets its own FFTW wisdom file (ROLLCONTACT_CACHE, bem.wisdom): FFTW_MEASURE
chooses its algorithms by timing, so two processes planning the same transform at once may choose differently and
give results that differ in the last bit; with the workers sharing one file, the wisdom a test's run processes
load could change between them (a restarted run compared bit for bit with an uninterrupted one). The compiled kernels
stay in the shared cache (ROLLCONTACT_KERNEL_CACHE): they are built once, under a lock, and are the same for all.
"""
import os
from pathlib import Path

os.environ.setdefault("ROLLCONTACT_KERNEL_CHECKS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")      # as the rollcontact command runs (cases.cli.main)


def pytest_configure(config):
    worker = os.environ.get("PYTEST_XDIST_WORKER")
    if worker and "ROLLCONTACT_CACHE" not in os.environ:
        base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "rollcontact"
        os.environ["ROLLCONTACT_CACHE"] = str(base / f"pytest-{worker}")
        os.environ.setdefault("ROLLCONTACT_KERNEL_CACHE", str(base / "kernels"))
