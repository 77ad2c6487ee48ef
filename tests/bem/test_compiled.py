"""The compiled kernels (bem/compiled.py): a run loads the layers' libraries built ahead of time and never imports
numba; the JIT route (ROLLCONTACT_KERNELS=jit, or a library that could not be built) compiles the same Python with the
same LLVM and no fast-math, so both give bit-for-bit the same results; the argument checks the suite runs with refuse
what an ahead-of-time kernel cannot check itself; a failed build is recorded and warned about, not retried."""
import json
import os
import shutil
import subprocess
import sys
import warnings

import numpy as np
import pytest

from rollcontact.bem import compiled
from rollcontact.bem import _spectral, wisdom

#: one period of the paper's perpendicular scene in a fresh process: its forces, shifts and iteration counts
RUN = """
import json, sys
from rollcontact.cases.api import load_scene, run
result = run(load_scene(None, ["motion.periods=1", "load.ft=0.77"]))
h = result.history
print(json.dumps({"numba": "numba" in sys.modules, "U_x": h["U_x"].tolist(), "F_x": h["F_x"].tolist(),
                  "iterations": h["iterations"].tolist(), "p": result.fields["p"][-1].ravel().tolist()[::7]}))
"""


def run_process(env=None, prelude=""):
    """RUN in a fresh process with `env` added; a ROLLCONTACT_CACHE given there holds its kernels too."""
    base = {k: v for k, v in os.environ.items() if not (env and "ROLLCONTACT_CACHE" in env
                                                        and k == "ROLLCONTACT_KERNEL_CACHE")}
    proc = subprocess.run([sys.executable, "-c", prelude + RUN], capture_output=True, text=True, timeout=900,
                          env=dict(base, **(env or {})))
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_a_run_process_uses_the_built_libraries_without_numba():
    out = run_process(env={"ROLLCONTACT_KERNEL_CHECKS": "0"})
    assert out["numba"] is False
    assert compiled.ready("rollcontact.solver") and compiled.ready("rollcontact.bem")


@pytest.mark.slow
def test_the_jit_route_and_a_failed_build_give_the_libraries_results_bit_for_bit(tmp_path):
    """Three processes on one period of the paper scene: the libraries, numba's JIT throughout (ROLLCONTACT_KERNELS=jit),
    and the fallback of a layer whose build failed (a .failed marker in an empty cache): the same shifts, forces,
    iteration counts and pressures, bit for bit. The empty cache gets the FFTW wisdom the other two used (FFTW_MEASURE
    chooses its plans by timing, and another plan changes the products at round-off)."""
    aot = run_process()
    jit = run_process(env={"ROLLCONTACT_KERNELS": "jit"})
    mark = ("import rollcontact.bem, rollcontact.solver\nfrom rollcontact.bem import compiled\n"
            "for layer in ('rollcontact.bem', 'rollcontact.solver'):\n"
            "    path = compiled._library_path(layer)\n"
            "    path.parent.mkdir(parents=True, exist_ok=True)\n"
            "    path.with_suffix('.failed').write_text('test')\n")
    if wisdom.wisdom_file().exists():
        shutil.copy(wisdom.wisdom_file(), tmp_path / wisdom.wisdom_file().name)
    fallback = run_process(env={"ROLLCONTACT_CACHE": str(tmp_path)}, prelude=mark)
    assert jit["numba"] and fallback["numba"] and not aot["numba"]
    for name, other in (("jit", jit), ("fallback", fallback)):
        assert {k: v for k, v in other.items() if k != "numba"} == {k: v for k, v in aot.items() if k != "numba"}, name


def test_argument_checks_refuse_what_a_compiled_kernel_cannot_check():
    """With ROLLCONTACT_KERNEL_CHECKS (set by the suite's conftest) a kernel refuses another dtype, a missing dimension
    or a strided view, naming the kernel and the argument; the right arguments pass."""
    py, pxh = 6, 4
    spec, out, sym = np.ones((1, py, 2 * pxh)), np.empty((1, py, 2 * pxh)), np.full((py, pxh), 2.0)
    _spectral.scale_1(spec, sym, out)
    assert np.array_equal(out, 2.0 * spec)
    for bad, k in ((spec.astype(np.float32), 0), (spec[0], 0), (np.ones((1, py, 4 * pxh))[:, :, ::2], 0),
                   (sym.astype(np.int64), 1)):
        args = [spec, sym, out]
        args[k] = bad
        with pytest.raises(TypeError, match=rf"_spectral\.scale_1: argument {k} is a"):
            _spectral.scale_1(*args)


@pytest.mark.parametrize("signature, specs", [
    ("void(f8[:, :, ::1], i1[:, ::1], f8, i8, b1)",
     [("f", "float64", 3, True), ("i", "int8", 2, True), ("f", "float64", 0, False), ("i", "int64", 0, False),
      ("b", "bool", 0, False)]),
    ("Tuple((f8, i8))(c16[::1], i8[:, :])", [("c", "complex128", 1, True), ("i", "int64", 2, False)]),
])
def test_signatures_are_read_argument_by_argument(signature, specs):
    assert compiled._argument_specs(signature) == specs


def test_a_build_that_fails_is_recorded_warned_about_once_and_not_retried(tmp_path, monkeypatch):
    monkeypatch.setenv("ROLLCONTACT_CACHE", str(tmp_path))
    monkeypatch.delenv("ROLLCONTACT_KERNEL_CACHE", raising=False)
    calls = []

    def failing(layer, path):
        calls.append(layer)
        raise RuntimeError("no C compiler")
    monkeypatch.setattr(compiled, "_build", failing)
    with pytest.warns(RuntimeWarning, match=r"rollcontact.bem could not be built \(no C compiler\); numba's JIT"):
        assert compiled._load_or_build("rollcontact.bem") is None
    marker = compiled._library_path("rollcontact.bem").with_suffix(".failed")
    assert marker.read_text() == "no C compiler\n"
    assert compiled.ready("rollcontact.bem") is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert compiled._load_or_build("rollcontact.bem") is None
    assert calls == ["rollcontact.bem"]
