"""The README's commands run as written in a fresh clone after its set-up command (no activated venv): they are
checked for form, then run (the walkthrough shortened, the main job and the Python example as written)."""
from pathlib import Path
import re
import shlex
import subprocess
import sys
import tomllib

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()


def test_every_command_calls_the_console_script_inside_the_venv():
    lines = [ln.strip() for ln in README.splitlines() if ln.startswith("    ")]
    calls = [ln for ln in lines if re.search(r"(^|\s|/)rollcontact\s", ln)]
    assert calls
    for ln in calls:
        assert ln.startswith((".venv/bin/rollcontact ", "python3 -m venv .venv && ")), ln
    setup = [ln for ln in lines if ln.startswith("python3 -m venv .venv")]
    assert len(setup) == 2                                     # the two set-up commands at the top
    prose = "\n".join(ln for ln in README.splitlines() if not ln.startswith("    "))
    spans = re.findall(r"`([^`]*)`", prose)
    inline = [c for c in spans if re.search(r"rollcontact (run|plot|sweep|compare|limits|limit-search|COMMAND)", c)]
    assert inline
    assert all(c.startswith(".venv/bin/rollcontact") for c in inline), inline


def test_no_link_outside_the_repository_and_every_extra_mentioned_is_defined():
    assert "../" not in README
    extras = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"])
    mentioned = set(re.findall(r"`(\w+)` extra", README)) | set(re.findall(r"\.\[(\w+)\]", README))
    assert mentioned and mentioned <= extras, mentioned - extras


# ------------------------------------------------------------------------------------------- run as written
BIN = Path(sys.executable).parent
#: appended to the runs of the walkthrough so that the whole README runs in about a minute: a coarse grid
#: (a/dx = 8, above the 3 the scenes require), 3 periods; limit searches to a bracket of 0.1
SHORT = {"run": ["--set", "grid.dx=0.6", "--set", "motion.dW=0.6", "--set", "motion.periods=3"],
         "sweep": ["--set", "grid.dx=0.6", "--set", "motion.dW=0.6", "--set", "motion.periods=3"],
         "limit-search": ["--set", "grid.dx=0.6", "--set", "motion.dW=0.6", "--tol", "0.1"]}


def _walkthrough_commands() -> list[str]:
    """The indented `.venv/bin/rollcontact ...` lines of the README in order (continuations joined, comments
    dropped), without the synopsis lines of "Command line" (placeholders in brackets or capitals)."""
    lines, joined = README.splitlines(), []
    i = 0
    while i < len(lines):
        ln = lines[i]
        if ln.startswith("    .venv/bin/rollcontact "):
            cmd = ln.strip()
            while cmd.endswith("\\"):
                i += 1
                cmd = cmd[:-1].rstrip() + " " + lines[i].strip()
            cmd = re.sub(r"\s+#.*$", "", cmd)
            # the Dask example needs its scheduler and workers: test_no_result_lost starts them as shown and runs a
            # sweep on them
            if not re.search(r"[\[|]|\b[A-Z]{3,}\b|--scheduler", cmd):
                joined.append(cmd)
        i += 1
    return joined


def test_the_readme_commands_run(tmp_path):
    """Every walkthrough command in order, in a temporary folder (so results/ and plots/ land there), with the
    shortening above; each exits 0, and the files they name exist afterwards."""
    commands = _walkthrough_commands()
    assert len(commands) >= 8
    for cmd in commands:
        args = shlex.split(cmd)
        args[0] = str(BIN / "rollcontact")
        rolling = any(a.startswith("cases/creep") for a in args)      # a [rolling] scene has no [motion] to shorten
        args = [str(ROOT / a) if a.startswith("cases/") else a for a in args]
        args += [] if rolling else SHORT.get(args[1], [])
        proc = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, (cmd, proc.stderr[-2000:])
    for name in ("results/perp.h5", "results/par.h5", "results/perp_rat.h5", "results/sweep/summary.csv",
                 "results/sweep/limits.csv", "results/md.h5", "results/creep.h5"):
        assert (tmp_path / name).exists(), name
    assert list((tmp_path / "results/sweep/plots").glob("*_usd.png"))
    assert list((tmp_path / "results/plots").glob("compare_par_vs_perp_*.png"))
    assert list((tmp_path / "results/creep").glob("*_creep_xi.csv"))
    # nothing but results/ in the working folder: the walkthrough writes where git ignores it
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results"]


def test_the_main_job_runs_as_the_first_command_says(tmp_path):
    """The first set-up command ends in `.venv/bin/rollcontact run`: the embedded default scene, written to
    results/paper_perpendicular.h5, and the path is printed."""
    first = next(ln for ln in README.splitlines() if ln.startswith("    python3 -m venv"))
    assert first.rstrip().endswith("&& .venv/bin/rollcontact run")
    proc = subprocess.run([str(BIN / "rollcontact"), "run", "-q"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=600)
    out = tmp_path / "results" / "paper_perpendicular.h5"
    assert proc.returncode == 0 and out.exists() and f"results written to {out.resolve()}" in proc.stdout


def test_the_python_api_example_runs_as_written(tmp_path, monkeypatch):
    block = re.search(r"## Python API.*?```python\n(.*?)```", README, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(block, "README.md (Python API)", "exec"), namespace)
    result = namespace["result"]
    expected = re.search(r"# shakedown ([0-9.]+)", block).group(1)      # the value the README prints
    assert result.state == "shakedown" and f"{result.summary['u_sd']:.5f}" == expected
    assert namespace["p"].shape == (len(result.y), len(result.x)) and namespace["U"].ndim == 1


def test_the_readme_is_a_short_guide_whose_links_resolve():
    """At most 250 lines; the two set-up commands come first; every relative link names a file of the repository,
    and the guide, the references, the studies, the theory and the benchmarks are linked."""
    lines = README.splitlines()
    assert len(lines) <= 250
    first = [ln for ln in lines if ln.startswith("    ")][:2]
    assert all(ln.startswith("    python3 -m venv .venv && ") for ln in first)
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README)
    assert all((ROOT / link).exists() for link in links if "://" not in link), links
    for page in ("docs/user_guide.md", "docs/scene_reference.md", "docs/hdf5_schema.md", "docs/theory.md",
                 "benchmarks/README.md", "docs/alignment.md", "docs/oscillating_loads.md", "docs/shapes.md",
                 "docs/subsurface.md", "docs/creep_rolling.md"):
        assert f"]({page})" in README, page


def test_the_commands_on_the_docs_pages_call_the_venv():
    """Every indented command line of docs/*.md that calls rollcontact or python does so inside the venv, as the
    README's set-up command leaves it (no activated environment)."""
    for page in sorted((ROOT / "docs").glob("*.md")):
        for ln in page.read_text().splitlines():
            cmd = ln.strip()
            if ln.startswith("    ") and re.match(r"(rollcontact|python3?|pip) [\w./-]+(\s|$)", cmd):
                raise AssertionError(f"{page.name}: {cmd!r} does not call .venv/bin/...")
