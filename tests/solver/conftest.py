"""Fixtures of the tangential solver tests (test_tangential_*.py): the seed's Hertz contact on the 0.2 mm grid
(`scene`, 55^2 elements) and on the 0.1 mm grid (`fine_scene`, 109^2), with the Coulomb bound g = mu p in MPa
(see tangential_helpers.py). Units mm, N, MPa.
"""
import pytest

from tangential_helpers import Scene


@pytest.fixture(scope="module")
def scene():
    return Scene(0.2)


@pytest.fixture(scope="module")
def fine_scene():
    return Scene(0.1)
