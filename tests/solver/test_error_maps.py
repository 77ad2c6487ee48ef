"""The measured error maps of the fidelity ladder (solver/accuracy_map.py, solver/fastsim/error_map.py,
solver/mdr/error_map.py): the symmetries the creep map folds its creepages by, the conservative corner-max
prediction, and the map builder (benchmarks/creep_error_map.py) on a tiny configuration, read back as the map."""
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from rollcontact.bem import MaterialPair
from rollcontact.solver.accuracy_map import Axis, ErrorTable
from rollcontact.solver.creep import SteadyRolling, ellipse_grid, hertz_pressure, solve_steady
from rollcontact.solver.fastsim import kalker_flexibilities, solve_fastrip, solve_fastsim
from rollcontact.solver.fastsim.error_map import RESOLUTION_MARGIN, creep_coordinates, load_error_map, map_from_json
from rollcontact.solver.mdr.error_map import load_mdr_map

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


@pytest.mark.parametrize("mirror", [(1, -1, -1), (-1, 1, 1), (-1, -1, -1)])
def test_force_errors_are_unchanged_by_the_maps_symmetries(mirror):
    """Mirroring y maps (xi, eta, phi) to (xi, -eta, -phi) and (Fx, Fy) to (Fx, -Fy); reversing every creepage
    reverses every traction (Coulomb's law and elasticity are odd): the exact solver and both fast models keep |F|
    and |F - F_exact| under these maps (to the solvers' tolerance), so the map folds its creepages onto |xi|,
    eta >= 0 and sees the same point (creep_coordinates)."""
    nu, mu = 0.28, 0.3
    grid = ellipse_grid(1.2, 0.8, 21)
    pressure = hertz_pressure(grid, 1.2, 0.8, 1.0)
    pair = MaterialPair.from_moduli(2 * (1 + nu), nu, 2 * (1 + nu), nu)
    flex = kalker_flexibilities(1.2, 0.8, 1.0, nu)
    base = np.array([0.02, 0.015, 0.04])
    forces = {}
    for tag, creep in (("base", base), ("mirror", base * mirror)):
        exact = np.array(solve_steady(SteadyRolling(grid, pair), pressure, mu, *creep).force)
        forces[tag] = {"exact": exact}
        for name, solve in (("fastsim", solve_fastsim), ("fastrip", solve_fastrip)):
            forces[tag][name] = np.array(solve(grid, pressure, mu, *creep, flexibilities=flex).force)
    for name in ("fastsim", "fastrip"):
        err = [np.hypot(*(f[name] - f["exact"])) / np.hypot(*f["exact"]) for f in forces.values()]
        assert err[0] == pytest.approx(err[1], rel=1e-4, abs=1e-6)
    assert creep_coordinates(*base) == pytest.approx(creep_coordinates(*(base * mirror)))


def test_corner_max_bounds_the_prediction_from_the_cells_nodes():
    """Inside a cell the prediction is the largest of its 2^d corners (not an interpolation); at a node, the node's
    value; outside a bounded axis none; a clamped axis takes its end nodes; a failed node (inf) stays inf."""
    axes = (Axis("x", (0.0, 1.0, 2.0)), Axis("t", (0.1, 1.0), clamped=True))
    errors = np.array([[0.01, 0.03], [0.05, 0.02], [0.04, np.inf]])
    table = ErrorTable(axes, {"m": errors})
    assert table.predict("m", dict(x=0.5, t=0.5)) == 0.05
    assert table.predict("m", dict(x=1.0, t=1.0)) == 0.02
    assert table.predict("m", dict(x=2.5, t=0.5)) is None
    assert table.predict("m", dict(x=0.0, t=10.0)) == 0.03
    assert table.predict("m", dict(x=1.5, t=0.2)) == math.inf


def test_map_builder_writes_what_the_loader_reads(tmp_path):
    """benchmarks/creep_error_map.py on a tiny configuration: the map's errors are finite and the loader predicts
    the measured value at a node, plus the margin for the cells' placement (this map has no resolution margin)."""
    sys.path.insert(0, str(BENCHMARKS))
    try:
        import creep_error_map as builder
    finally:
        sys.path.remove(str(BENCHMARKS))
    config = dict(nu=(0.28,), ratio=(0.5, 2.0), theta=(0, 90), alpha=(0, 90), t=(0.2, 2.0), held_out=2)
    errors, exact, seconds = builder.build_map(config, 15, log=lambda *a: None)
    data = dict(axes={k: list(config[k]) for k in ("nu", "ratio", "theta", "alpha", "t")}, models=list(errors),
                errors={m: e.tolist() for m, e in errors.items()}, seconds_per_case=seconds)
    emap = map_from_json(json.loads(json.dumps(data)))
    assert all(np.isfinite(e).all() for e in errors.values()) and seconds["fastsim"] < seconds["bem"]
    hat = (0.0, 2.0, 0.0)            # theta 90, alpha 90, t 2 at a/b = 2
    assert emap.predict("fastsim", 2.0, 0.28, *hat) == pytest.approx(errors["fastsim"][0, 1, 1, 1, 1]
                                                                     + RESOLUTION_MARGIN)


def test_packaged_maps_cover_the_issues_ranges():
    """The packaged maps: a/b 0.2-5 and nu 0-0.5 with FASTSIM cheaper than FaStrip cheaper than the exact solver;
    the MDR map over the seed's w 0.1-0.4 and f_t 0.1-0.9 at both alignments, MDR cheaper than 3-D."""
    emap = load_error_map()
    axes = {a.name: a.nodes for a in emap.table.axes}
    assert axes["ratio"][0] == 0.2 and axes["ratio"][-1] == 5.0 and axes["nu"] == (0.0, 0.28, 0.5)
    s = emap.seconds_per_case
    assert s["fastsim"] < s["fastrip"] < s["bem"]
    mdr = load_mdr_map()
    assert {a.name: a.nodes for a in mdr.table.axes}["angle"] == (0.0, 90.0)
    assert mdr.seconds_per_run["mdr"] < mdr.seconds_per_run["bem"]
