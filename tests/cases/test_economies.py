"""Model no more than a scene needs: the qualitative economies (benchmarks/economies.py measures them).

Asserted: the grid covers the swept contact and no more (inside the seed's element range for W = 1.2 mm,
well below a naive square grid for large amplitudes); no coupling spectra unless beta != 0 or forced;
field snapshots only where asked ('reversals' files are a fraction of 'all'); the MDR fidelity stores no
2-D fields. Not timings. Units mm, N, MPa.
"""
import math

import pytest

from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.cases.run.discretise import scene_grid, scene_path
from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene

SEED_ELEMENTS = (3050, 4200)     # seed: 3050-4200 elements for W = 1.2-3.4 mm at dx = 0.2 mm (docs/theory.md P14)


def naive_square(scene):
    W, a, m, dx = scene.amplitude, scene.contact_radius, scene.grid.margin, scene.grid.dx
    return math.ceil(2 * (a + W + m) / dx) ** 2


@pytest.mark.parametrize("angle", [90, 0])
def test_grid_of_seed_amplitude_lies_in_seed_element_range(angle):
    scene = default_scene().with_overrides(["motion.W=1.2", f"motion.angle={angle}"], replaces=("motion.W",))
    grid = scene_grid(scene, scene_path(scene))
    assert SEED_ELEMENTS[0] <= grid.size <= SEED_ELEMENTS[1]


@pytest.mark.parametrize("W", [1.2, 2.0, 3.4])
def test_grid_covers_swept_strip_not_a_square(W):
    scene = default_scene().with_overrides([f"motion.W={W}"], replaces=("motion.W",))
    grid = scene_grid(scene, scene_path(scene))
    a, m = scene.contact_radius, scene.grid.margin
    # long side along the rolling direction (y, perpendicular), short side = the contact + margin
    assert grid.ny * grid.dy >= 2 * (a + W) and grid.nx * grid.dx <= 2 * (a + m) + 2 * grid.dx
    assert grid.size < naive_square(scene) * (0.9 if W < 2 else 0.8)


def test_uncoupled_operator_holds_no_coupling_spectra():
    scene = default_scene()
    assert abs(scene.material_pair.beta) < 1e-4          # incompressible substrate: beta ~ 0
    grid = scene_grid(scene, scene_path(scene))
    auto = HalfSpaceOperator(grid, scene.material_pair)
    forced = HalfSpaceOperator(grid, scene.material_pair, coupling=True)
    assert not auto.coupled and not {"xz", "yz"} & set(auto.spectra)
    assert forced.coupled and {"xz", "yz"} <= set(forced.spectra)


def test_compressible_pair_switches_coupling_on():
    from rollcontact.bem import MaterialPair
    pair = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.3)
    scene = default_scene()
    op = HalfSpaceOperator(scene_grid(scene, scene_path(scene)), pair)
    assert op.coupled and {"xz", "yz"} <= set(op.spectra)


def test_field_snapshots_only_where_asked(tmp_path):
    sizes, snaps = {}, {}
    for mode in ("none", "reversals", "all"):
        scene = default_scene().with_overrides(["grid.dx=0.4", "grid.dy=0.4", "motion.dW=0.4", "motion.periods=2",
                                                f"output.fields={mode}"])
        out = run_scene(scene, tmp_path / f"{mode}.h5")
        sizes[mode] = (tmp_path / f"{mode}.h5").stat().st_size
        snaps[mode] = len(out.field_steps)
    assert snaps["none"] == 0 and snaps["all"] == out.summary["steps"]
    assert 0 < snaps["reversals"] < snaps["all"] / 2
    assert sizes["none"] < sizes["reversals"] < sizes["all"] / 2


def test_mdr_fidelity_stores_no_fields(tmp_path):
    out = run_scene(default_scene().with_overrides(["solver.fidelity=mdr"]), tmp_path / "mdr.h5")
    assert len(out.field_steps) == 0 and out.summary["state"] == "shakedown"
