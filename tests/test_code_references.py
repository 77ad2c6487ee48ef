"""Every module, object and repository path that a docstring or a comment names exists.

Scanned: the docstrings (module, class, function) and the comments of every Python file of the package, the tests,
the benchmarks and docs/. Three kinds of reference are checked:

* dotted names of the package (`rollcontact.solver.memo`, `bem.operator`, `cases.plots.common.RunView.u`): the
  longest prefix must import as a module of `rollcontact` and the rest resolve as attributes (a dataclass field
  counts); `solver.tol` and the other keys of the scene's [solver] section are scene keys, not modules;
* repository paths starting with a top-level folder (`bem/`, `solver/`, `cases/`, `rollcontact/`, `tests/`,
  `benchmarks/`, `docs/`, `.ci/`): the file or folder must exist (a glob must match; `{a,b}` is expanded;
  placeholders such as `<name>` or `$OUT` are not checked);
* names in backticks that contain an underscore (`_moves`, `run_figures`, `op.tangential_inverse`): the last
  part must be defined somewhere in the repository (a module, a function, a class, an attribute, an argument or
  a string constant), which catches names of modules and functions that were renamed or removed.
"""
from __future__ import annotations

import ast
import dataclasses
import importlib
import io
from pathlib import Path
import re
import tokenize

ROOT = Path(__file__).resolve().parents[1]
SCANNED = ("bem", "solver", "cases", "rollcontact", "tests", "benchmarks", "docs")
TOP = ("bem", "solver", "cases", "rollcontact", "tests", "benchmarks", "docs", r"\.ci")
ID = r"[A-Za-z_]\w*"
DOTTED = re.compile(r"(?<![\w./])(?:rollcontact\.)?(?:bem|solver|cases)(?:\.(?:" + ID + r"(?:\{[\w,]+\})?|\{[\w,]+\}))+")
PATH = re.compile(r"(?<![\w./-])(?:" + "|".join(TOP) + r")/(?:[\w./*<>$-]|\{[\w.,]+\})*(?:[\w*>]|\{[\w.,]+\})")
BACKTICKED = re.compile(r"`(" + ID + r"(?:\." + ID + r")*)(?:\(|`)")


def _files():
    return [p for d in SCANNED for p in sorted((ROOT / d).rglob("*.py")) if ".venv" not in p.parts]


def _docstring_nodes(tree):
    return [n for n in ast.walk(tree) if isinstance(n, (ast.Module, ast.ClassDef, ast.FunctionDef,
                                                        ast.AsyncFunctionDef))]


def _texts(path: Path):
    """(line, text) of every docstring and comment of a Python file."""
    src = path.read_text()
    for node in _docstring_nodes(ast.parse(src)):
        doc = ast.get_docstring(node, clean=False)
        if doc:
            yield node.body[0].lineno, doc
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        if tok.type == tokenize.COMMENT:
            yield tok.start[0], tok.string


def _expand(text: str) -> list[str]:
    """'a{b,c}d' -> ['abd', 'acd'] (brace expansion, as the shell does)."""
    m = re.search(r"\{([\w.,]+)\}", text)
    if not m:
        return [text]
    return [x for alt in m.group(1).split(",") for x in _expand(text[:m.start()] + alt + text[m.end():])]


def _scene_keys() -> set[str]:
    from rollcontact.cases.scene import keys
    return {f"solver.{f.name}" for f in dataclasses.fields(keys.SolverSpec)}


def _resolves(name: str, scene_keys) -> bool:
    parts = name.split(".")
    if parts[0] == "rollcontact":
        parts = parts[1:]
    elif name in scene_keys:
        return True
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module("rollcontact." + ".".join(parts[:k]))
            break
        except ModuleNotFoundError:
            continue
    else:
        return False
    for attr in parts[k:]:
        if obj is not None and hasattr(obj, attr):
            obj = getattr(obj, attr)
        elif obj is not None and (attr in getattr(obj, "__annotations__", {}) or (
                dataclasses.is_dataclass(obj) and attr in {f.name for f in dataclasses.fields(obj)})):
            obj = None          # a field without a class-level default: nothing further to resolve
        else:
            return False
    return True


def _path_exists(path: str) -> bool:
    return any(ROOT.glob(path)) if "*" in path else (ROOT / path).exists()


def _defined_names(files) -> set[str]:
    """Every name the repository defines or uses in code: modules, functions, classes, attributes, arguments,
    keywords, imports, and the identifiers inside string constants other than docstrings."""
    names = set()
    for f in files:
        if f == Path(__file__).resolve():
            continue            # its own test strings name stale references on purpose
        names.add(f.stem)
        tree = ast.parse(f.read_text())
        docs = {id(n.body[0].value) for n in _docstring_nodes(tree) if ast.get_docstring(n, clean=False)}
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names.add(node.name)
            elif isinstance(node, ast.Name):
                names.add(node.id)
            elif isinstance(node, ast.Attribute):
                names.add(node.attr)
            elif isinstance(node, ast.arg):
                names.add(node.arg)
            elif isinstance(node, ast.keyword) and node.arg:
                names.add(node.arg)
            elif isinstance(node, ast.alias):
                names.add(node.asname or node.name.split(".")[-1])
            elif isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
                names.update(re.findall(ID, node.value))
    return names


def _stale_references():
    files = _files()
    scene_keys = _scene_keys()
    defined = _defined_names(files)
    bad = []
    for f in files:
        where = f.relative_to(ROOT)
        for line, text in _texts(f):
            for m in DOTTED.finditer(text):
                for name in _expand(m.group(0)):
                    if not _resolves(name, scene_keys):
                        bad.append(f"{where}:{line}: module or object {name!r} does not exist")
            for m in PATH.finditer(text):
                if any(c in m.group(0) for c in "<>$"):
                    continue
                for path in _expand(m.group(0).rstrip(".")):
                    if not _path_exists(path):
                        bad.append(f"{where}:{line}: path {path!r} is not in the repository")
            for m in BACKTICKED.finditer(text):
                last = m.group(1).split(".")[-1]
                if "_" in last.strip("_") and last not in defined:
                    bad.append(f"{where}:{line}: `{m.group(1)}` is defined nowhere in the repository")
    return bad


def test_every_module_object_and_path_named_in_docstrings_and_comments_exists():
    bad = _stale_references()
    assert not bad, "stale references in docstrings or comments:\n" + "\n".join(bad)


def test_the_reference_check_finds_stale_names(tmp_path):
    """The patterns catch the forms used in the code (dotted, braced, paths, backticks)."""
    text = ("see solver._tangential_{division,cg}, cases/plots.py, `plots_run`, rollcontact.cases.plots.common "
            "and docs/scripts/shapes.py")
    dotted = [n for m in DOTTED.finditer(text) for n in _expand(m.group(0))]
    assert dotted == ["solver._tangential_division", "solver._tangential_cg", "rollcontact.cases.plots.common"]
    assert not any(_resolves(n, set()) for n in dotted[:2]) and _resolves(dotted[2], set())
    paths = [m.group(0) for m in PATH.finditer(text)]
    assert paths == ["cases/plots.py", "docs/scripts/shapes.py"]
    assert not _path_exists(paths[0]) and _path_exists(paths[1])
    assert [m.group(1) for m in BACKTICKED.finditer(text)] == ["plots_run"]
