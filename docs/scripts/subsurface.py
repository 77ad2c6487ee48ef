"""The tables of docs/subsurface.md: where the stresses below a sliding Hertz sphere peak.

    .venv/bin/python docs/scripts/subsurface.py [-o results/subsurface] [--quick]

Runs `python benchmarks/hamilton_sliding.py -o OUT` (Hamilton's closed form for the sliding sphere, nu = 0.3, and the
grid's stresses at a/dx = 12 for mu = 0 ... 0.5) and writes its tables: the Hertz axis check, the maxima for each mu,
the friction coefficients at which the maxima reach the surface. --quick: mu = 0.3 only.
"""
from __future__ import annotations

import json
from pathlib import Path
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _study import SKIPPED, Study  # noqa: E402

MUS = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]


def place(x):
    """x in units of a, the edges written as a and -a."""
    return "a" if abs(x - 1) < 1e-9 else "-a" if abs(x + 1) < 1e-9 else f"{x:.3f}"


def main(argv=None) -> int:
    study = Study.from_command_line("subsurface", __doc__, argv)
    study.python("benchmarks/hamilton_sliding.py", *(["--quick"] if study.quick else []), "-o", study.out)
    data = json.loads((study.out / "hamilton_sliding.json").read_text())
    h = data["hertz_axis"]
    study.table("hertz", ["grid", "σ_r, σ_z on the axis: largest error", "max shear on the axis (depth)",
                          "von Mises on the axis"],
                [["a/dx = 12, ν = 0.3", f"{100 * h['axis_error']:.2f} % of p0",
                  f"{h['tresca_max']:.3f} p0 ({h['tresca_depth']:.2f} a)", f"{h['von_mises_max']:.3f} p0"]])
    rows = {r["mu"]: r for r in data["rows"]}
    out = []
    for mu in MUS:
        r = rows.get(mu)
        if r is None:
            out.append([f"{mu:g}", *[SKIPPED] * 4])
            continue
        vm, tr, g = r["von_mises"], r["tresca"], r["grid"]["von_mises_grid"]
        below = vm["below"]["z"] > 1e-6
        out.append([f"{mu:g}",
                    f"{vm['below']['value']:.3f} ({vm['below']['x']:.3f}, {vm['below']['z']:.3f})" if below
                    else "(none below)",
                    f"{vm['surface']['value']:.3f} ({place(vm['surface']['x'])})",
                    (f"{tr['below']['value']:.3f}" if tr["below"]["z"] > 1e-6 else "(none below)")
                    + f" / {tr['surface']['value']:.3f} ({place(tr['surface']['x'])})",
                    f"{g['value']:.3f} ({g['x']:.3f}, {g['z']:.2f})"])
    study.table("maxima", ["μ", "von Mises below (x, z)", "von Mises on the surface (x)",
                           "max shear below / surface (x)", "grid von Mises max (x, z)"], out)
    s = data["switch_mu"]
    study.table("switch", ["maximum", "μ at which it reaches the surface"],
                [["von Mises", f"{s['von_mises']:.4f}"], ["max shear (σ1 − σ3)/2", f"{s['tresca']:.4f}"]])
    return study.finish()


if __name__ == "__main__":
    sys.exit(main())
