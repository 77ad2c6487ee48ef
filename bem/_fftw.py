"""The pyfftw module, imported without the parts rollcontact does not use (bem.operator, bem.wisdom)."""
import sys


def import_pyfftw():
    """pyfftw, imported without the parts rollcontact does not use. Its package imports pyfftw.interfaces, which
    imports scipy.fftpack and, when Dask is installed, dask.array for its wrappers of those interfaces: 0.55 s of
    a 0.57 s import, paid by every run (benchmarks/startup.py). rollcontact plans FFTW objects
    directly, so those two are hidden from that import (a None entry in sys.modules makes an import fail) and
    restored at once; pyfftw.interfaces is complete but for its scipy and Dask wrappers, which a later import of
    pyfftw.interfaces.scipy_fft (or .dask_fft) still loads."""
    if "pyfftw" in sys.modules:
        return sys.modules["pyfftw"]
    hidden = [name for name in ("scipy.fftpack", "dask.array.fft") if name not in sys.modules]
    for name in hidden:
        sys.modules[name] = None
    try:
        import pyfftw
    finally:
        for name in hidden:
            if sys.modules.get(name, 0) is None:
                del sys.modules[name]
    return pyfftw


pyfftw = import_pyfftw()
