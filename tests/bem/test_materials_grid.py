"""Material constants (docs/theory.md §1) and the world-fixed grid."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid, contact_box
from rollcontact.bem.materials import Material, MaterialPair

SCENE = MaterialPair.from_moduli(206e3, 0.3, 4.35, 0.5)


def test_seed_constants_match_theory_values():
    # docs/theory.md §1 lists the scene's constants to 5-6 digits.
    assert SCENE.E_star == pytest.approx(5.79985, rel=1e-5)
    assert SCENE.G_star == pytest.approx(3.86659, rel=1e-5)
    assert SCENE.G == pytest.approx(2.89995, rel=1e-5)
    assert SCENE.nu == pytest.approx(0.499996, abs=1e-6)
    assert SCENE.K == pytest.approx(3.66e-6, rel=1e-2)
    assert SCENE.beta == pytest.approx(7.32e-6, rel=1e-2)


def test_seed_table1_contact_radius_and_approach_need_the_usual_E_star():
    # docs/theory.md P1: Table 1 gives a = 4.8 mm, d = 0.57 mm; the seed's printed Eq. 2 would give a = 6.03 mm.
    Fn, R = 21.19, 40.0
    a = (3 * Fn * R / (4 * SCENE.E_star)) ** (1 / 3)
    assert a == pytest.approx(4.8, abs=0.02)
    assert a * a / R == pytest.approx(0.57, abs=0.005)


def test_rigid_on_incompressible_is_uncoupled_and_identical_bodies_too():
    rigid = MaterialPair(Material(math.inf, 0.3), Material(4.35, 0.5))
    assert rigid.beta == 0.0
    assert rigid.E_star / rigid.G_star == pytest.approx(1.5, rel=1e-14)
    same = MaterialPair.from_moduli(210e3, 0.3, 210e3, 0.3)
    assert abs(same.beta) < 1e-15  # docs/theory.md P6: K is a difference


def test_dundurs_beta_steel_on_aluminium():
    # Johnson (1985) Table: beta for steel/aluminium is about -0.1 (sign: body 1 stiffer).
    pair = MaterialPair.from_moduli(210e3, 0.3, 70e3, 0.33)
    expected = 0.5 * ((1 - 2 * 0.3) / (210e3 / 2.6) - (1 - 2 * 0.33) / (70e3 / 2.66)) / (
        (1 - 0.3) / (210e3 / 2.6) + (1 - 0.33) / (70e3 / 2.66))
    assert pair.beta == pytest.approx(expected, rel=1e-12)
    assert -0.15 < pair.beta < -0.05


@pytest.mark.parametrize("E, nu", [(-1.0, 0.3), (0.0, 0.3), (1.0, 0.6), (1.0, -1.0)])
def test_bad_material_is_refused_with_the_parameter_named(E, nu):
    with pytest.raises(InputError, match="Young's modulus|Poisson ratio"):
        Material(E, nu)


def test_two_rigid_bodies_are_refused():
    with pytest.raises(InputError, match="rigid"):
        MaterialPair(Material(math.inf, 0.3), Material(math.inf, 0.3))


def test_grid_covers_box_with_centres_on_multiples_of_the_spacing():
    g = Grid.covering(-1.05, 1.05, -0.5, 0.9, 0.2, 0.1)
    assert g.x[0] <= -1.05 + 0.1 and g.x[-1] >= 1.05 - 0.1
    assert np.allclose(g.x / 0.2, np.round(g.x / 0.2))
    assert 0.0 in np.round(g.x, 12) and 0.0 in np.round(g.y, 12)
    assert g.shape == (len(g.y), len(g.x))
    X, Y = g.mesh()
    assert X.shape == g.shape


def test_grid_for_the_paper_scene_is_in_the_seed_element_range():
    # seed: 3050-4200 elements at 0.2 mm for W = 1.2-3.4 mm... our box: contact a = 4.786, W = 1.1 along y
    box = contact_box(4.786, 4.786, [(0, -1.1), (0, 1.1)], 0.6)
    g = Grid.covering(*box, 0.2, 0.2)
    assert 3000 < g.size < 4200


def test_grid_too_large_is_refused():
    with pytest.raises(InputError, match="exceeds the limit"):
        Grid.covering(-100, 100, -100, 100, 0.01, 0.01)
