"""What a command imports before it works: `rollcontact --version`/`--help` and `import rollcontact` load none of
the numerical stack (their time is measured in benchmarks/startup.py; here the modules they load are checked,
which does not depend on the machine's load), and the pyfftw import leaves Dask and scipy.fftpack importable.
The layering of the package (bem -> solver -> cases, no private module of another package) is checked on the
source. Run as fresh processes."""
import ast
from pathlib import Path
import subprocess
import sys

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "scipy", "numba", "pyfftw", "h5py", "matplotlib", "dask")


def _loaded_after(code: str) -> set:
    probe = code + "\nimport sys\nprint(' '.join(sorted(m.split('.')[0] for m in sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120, check=True)
    return set(out.stdout.split())


@pytest.mark.parametrize("code", ["import rollcontact",
                                  "from rollcontact.cases.cli.main import build_parser; build_parser()",
                                  "import rollcontact.bem.errors"])
def test_start_up_loads_none_of_the_numerical_stack(code):
    assert not _loaded_after(code) & set(HEAVY)


def test_the_api_names_resolve_on_first_use():
    loaded = _loaded_after("import rollcontact; rollcontact.load_scene; rollcontact.RunResult")
    assert "numpy" in loaded and "matplotlib" not in loaded and "pyfftw" not in loaded


def test_importing_the_operator_leaves_dask_and_scipy_fftpack_importable():
    code = ("import rollcontact.bem.operator, sys; assert 'dask' not in sys.modules; "
            "import dask.array.fft, scipy.fftpack, pyfftw.interfaces.scipy_fft; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr[-2000:]


LAYERS = {"bem": set(), "solver": {"bem"}, "cases": {"bem", "solver", "cases"}}


def _imports(path: Path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            yield node.module, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, []


@pytest.mark.parametrize("layer", list(LAYERS))
def test_imports_go_one_way_and_never_into_another_packages_private_module(layer):
    """A private module (_name) is imported only inside its own package, and a private name only from a private
    module of the same package (or the package itself): what another module needs is public."""
    bad = []
    for path in sorted((ROOT / layer).rglob("*.py")):
        package = ".".join(("rollcontact",) + path.relative_to(ROOT).parent.parts)
        for module, names in _imports(path):
            parts = module.split(".")
            if parts[0] in ("bem", "solver", "cases"):
                bad.append(f"{path.name}: bare import {module} (use rollcontact.{module})")
            if parts[0] != "rollcontact" or len(parts) < 2:
                continue
            if parts[1] not in LAYERS[layer] | {layer}:
                bad.append(f"{path.relative_to(ROOT)}: imports {module} (layer {layer} may import {LAYERS[layer]})")
            head, _, leaf = module.rpartition(".")
            private_module = leaf.startswith("_")
            if private_module and head != package:
                bad.append(f"{path.relative_to(ROOT)}: imports {module}, a private module of another package")
            private_names = [n for n in names if n.startswith("_") and not n.startswith("__")]
            if private_names and not (private_module and head == package) and module != package:
                bad.append(f"{path.relative_to(ROOT)}: imports private {private_names} from {module}")
    assert not bad, "\n".join(bad)


def test_every_function_the_readme_names_as_api_is_there():
    """The README's "Python API" and the user guide's name rollcontact.<name>(...) calls; each must exist."""
    import re
    import rollcontact
    root = Path(__file__).resolve().parents[1]
    readme = (root / "README.md").read_text() + (root / "docs" / "user_guide.md").read_text()
    names = set(re.findall(r"rollcontact\.([a-z_]+)\(", readme))
    assert {"load_scene", "run", "read_run", "restart", "sweep", "limit_search"} <= names
    assert all(callable(getattr(rollcontact, n)) for n in names), sorted(n for n in names if not hasattr(rollcontact, n))
