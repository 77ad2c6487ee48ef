"""docs/friction.md's command in its quick form (docs/friction/make_friction.py --quick): it runs and reproduces the
page's checks against the reference program's printed figures and the classical moving heat source."""
import csv
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "docs" / "friction" / "make_friction.py"


@pytest.mark.slow
def test_the_friction_page_command_runs_and_reproduces_its_checks(tmp_path):
    subprocess.run([sys.executable, str(SCRIPT), "--quick", "-o", str(tmp_path / "out"), "--runs",
                    str(tmp_path / "runs")], check=True, timeout=1800)
    out = tmp_path / "out"
    for name in ("laws.png", "falling_creep_curve.png", "veldep_transient.png", "study_limits.png", "limits.csv"):
        assert (out / name).stat().st_size > 0, name
    rows = {(r["example"], r["case"]): r for r in csv.DictReader(open(out / "contact_examples.csv"))}
    assert float(rows[("ertz_temperature", "2")]["T_max_contact"]) == pytest.approx(75.0, abs=1e-6)
    assert float(rows[("ertz_temperature", "1")]["p_max"]) == pytest.approx(770.6, abs=0.05)
    assert float(rows[("ertz_temperature", "1")]["T_max_1d_own_twice"]) == pytest.approx(166.8, abs=0.05)
    assert float(rows[("veldep_fric", "steady")]["Fx_over_muFn"]) == pytest.approx(0.5941, abs=5e-5)
    for r in csv.DictReader(open(out / "jaeger_square.csv")):
        assert abs(float(r["grid_max_error"])) < 0.02 and abs(float(r["grid_mean_error"])) < 0.02
    for r in csv.DictReader(open(out / "steady_transient.csv")):
        assert abs(float(r["relative_difference"])) < 5e-3, r["case"]
