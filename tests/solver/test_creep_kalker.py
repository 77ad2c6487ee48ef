"""Kalker's creep coefficient table and its interpolation (docs/theory.md §7.3, solver/creep/kalker.py)."""
import math

import pytest

from rollcontact.bem.errors import InputError
from rollcontact.solver.creep import kalker_coefficients, linear_creep_forces


@pytest.mark.parametrize("ratio, nu, expected", [
    (1.0, 0.5, (5.20, 3.98, 1.63)),      # the scene's circle (docs/theory.md §7.3)
    (0.5, 0.25, (3.62, 3.01, 0.929)),
    (2.0, 0.0, (4.37, 4.37, 2.35)),      # b/a = 0.5 row
    (0.1, 0.5, (4.85, 2.53, 0.731)),
    (10.0, 0.25, (11.7, 12.8, 14.6)),    # b/a = 0.1 row
])
def test_table_nodes_are_reproduced_exactly(ratio, nu, expected):
    assert kalker_coefficients(ratio, nu) == pytest.approx(expected, rel=1e-12)


def test_between_rows_linear_in_g_and_between_columns_quadratic_in_one_over_c():
    # a/b = 0.75: halfway between the 0.7 and 0.8 rows at nu = 0
    assert kalker_coefficients(0.75, 0.0)[0] == pytest.approx(0.5 * (3.09 + 3.19), rel=1e-12)
    # b/a = 0.75 (a/b = 4/3): halfway between the b/a = 0.7 and 0.8 rows
    assert kalker_coefficients(4 / 3, 0.0)[0] == pytest.approx(0.5 * (3.82 + 3.65), rel=1e-12)
    # nu = 0.125 on the circle: the Lagrange interpolant of 1/C at its midpoint (3/8, 3/4, -1/8 weights)
    inv = 3 / 8 / 3.40 + 3 / 4 / 4.12 - 1 / 8 / 5.20
    assert kalker_coefficients(1.0, 0.125)[0] == pytest.approx(1 / inv, rel=1e-12)


def test_symmetry_nu_zero_gives_c11_equal_c22():
    for ratio in (0.1, 0.35, 1.0, 1.7, 9.0):
        c11, c22, _ = kalker_coefficients(ratio, 0.0)
        assert c11 == pytest.approx(c22, rel=1e-12)


def test_asymptotes_join_the_table_at_g_01():
    """Below g = 0.1 the slender-ellipse asymptotes (CONTACT's) take over. At g = 0.1 they are not continuous with
    the table (measured largest jumps: a << b 2.5 % for C11, C22, the plane-strain limits pi^2/(4(1-nu)),
    pi^2/4, and 6.0 % for C23; a >> b 4.3 % for C11, C22 and 0.9 % for C23). Checked with 1/2 % above those: a
    check of the transcribed formulas (a wrong factor is off by far more), not of their precision."""
    for nu in (0.0, 0.25, 0.5):
        for ratio, rel, rel23 in ((0.1, 0.03, 0.065), (10.0, 0.048, 0.015)):
            table = kalker_coefficients(ratio, nu)
            near = kalker_coefficients(ratio * (1 - 1e-9) if ratio < 1 else ratio * (1 + 1e-9), nu)
            assert near[:2] == pytest.approx(table[:2], rel=rel)
            assert near[2] == pytest.approx(table[2], rel=rel23)


def test_linear_forces_oppose_the_creepages():
    fx, fy, mz = linear_creep_forces(2.0, 1.0, 80e3, 0.25, xi=1e-3, eta=-1e-3, phi=0.0, C33=1.0)
    assert fx < 0 < fy
    c = math.sqrt(2.0)
    assert fx == pytest.approx(-80e3 * c * c * kalker_coefficients(2.0, 0.25)[0] * 1e-3)
    assert mz == pytest.approx(80e3 * c ** 3 * kalker_coefficients(2.0, 0.25)[2] * -1e-3)


@pytest.mark.parametrize("ratio, nu", [(0.0, 0.25), (-1.0, 0.25), (math.inf, 0.25), (1.0, 0.6), (1.0, -0.1)])
def test_out_of_range_is_refused(ratio, nu):
    with pytest.raises(InputError):
        kalker_coefficients(ratio, nu)
