"""Influence coefficients of a uniformly loaded rectangular element (docs/theory.md §2)."""
import numpy as np
import pytest
from scipy import integrate

from rollcontact.bem.influence import influence_coefficients

G, NU, DX, DY = 1.0, 0.3, 0.2, 0.3
GS = G / 2  # one elastic body on a rigid one: Kalker's combined G is twice the body's modulus
K = 0.25 * (-(1 - 2 * NU) / GS) * G  # rigid sphere: K/G = -(1 - 2 nu2)/(4 G2)


def point_kernel(comp, X, Y):
    """Boussinesq / Cerruti point-load displacements of one half-space (docs/theory.md §2.1)."""
    r = np.hypot(X, Y)
    c = 1 / (2 * np.pi * GS)
    return {"zz": lambda: c * (1 - NU) / r,
            "xx": lambda: c * ((1 - NU) / r + NU * X ** 2 / r ** 3),
            "yy": lambda: c * ((1 - NU) / r + NU * Y ** 2 / r ** 3),
            "xy": lambda: c * NU * X * Y / r ** 3,
            "xz": lambda: -(1 - 2 * NU) * X / (4 * np.pi * GS * r ** 2),
            "yz": lambda: -(1 - 2 * NU) * Y / (4 * np.pi * GS * r ** 2)}[comp]()


COMPONENTS = ("zz", "xx", "yy", "xy", "xz", "yz")


@pytest.mark.parametrize("point", [(0.5, 0.7), (-1.3, 0.4), (0.15, 0.2), (2.0, -3.0), (-0.3, -0.25)])
def test_coefficients_equal_numerical_integration_of_point_kernels(point):
    # Closed-form corner functions vs adaptive quadrature of the point kernels over the element:
    # both are exact up to quadrature round-off (1e-11 requested), so agree to ~1e-12 relative.
    x, y = point
    A = influence_coefficients(x, y, DX, DY, G, NU, K)
    for comp in COMPONENTS:
        ref, _ = integrate.dblquad(lambda eta, xi: point_kernel(comp, x - xi, y - eta),
                                   -DX / 2, DX / 2, -DY / 2, DY / 2, epsabs=1e-14, epsrel=1e-12)
        assert float(A[comp]) == pytest.approx(ref, rel=1e-10, abs=1e-16), comp


@pytest.mark.parametrize("r", [2.0, 20.0])
def test_far_field_approaches_point_load_with_second_order_error(r):
    # A(r) / (kernel(r) dA) - 1 = O((h/r)^2) (docs/theory.md §2.2): bound with constant 1 on (h/r)^2.
    angles = np.linspace(0.1, 2 * np.pi, 7)
    X, Y = r * np.cos(angles), r * np.sin(angles)
    A = influence_coefficients(X, Y, DX, DY, G, NU, K)
    for comp in ("zz", "xx", "yy"):
        ratio = A[comp] / (point_kernel(comp, X, Y) * DX * DY)
        assert np.max(np.abs(ratio - 1)) < (max(DX, DY) / r) ** 2, comp


def test_self_coefficients_of_a_square_element_match_closed_form():
    h = 0.2
    A = influence_coefficients(0.0, 0.0, h, h, G, NU, K)
    ln = 4 * h * np.log(1 + np.sqrt(2))
    assert float(A["zz"]) == pytest.approx((1 - NU) / (2 * np.pi * GS) * ln, rel=1e-14)
    assert float(A["xx"]) == pytest.approx((1 - NU / 2) / (2 * np.pi * GS) * ln, rel=1e-14)
    assert float(A["yy"]) == pytest.approx(float(A["xx"]), rel=1e-14)
    assert float(A["xy"]) == 0.0 and float(A["xz"]) == 0.0


def test_symmetries_and_betti_reciprocity():
    X, Y = np.meshgrid(np.arange(-5, 6) * DX, np.arange(-4, 5) * DY)
    A = influence_coefficients(X, Y, DX, DY, G, NU, K)
    flip = influence_coefficients(-X, Y, DX, DY, G, NU, K)
    for comp in ("zz", "xx", "yy"):
        np.testing.assert_allclose(A[comp], flip[comp], rtol=1e-13, atol=0)
    np.testing.assert_allclose(A["xy"], -flip["xy"], rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(A["xz"], -flip["xz"], rtol=1e-13, atol=1e-15)


def test_mirror_symmetry_survives_far_offsets():
    # The ln(X + r) rewrite for X < 0 keeps even kernels even far away (docs/theory.md §2.2a: without it the
    # symmetry degrades to 7e-7 at 1000 cells).
    X = np.array([1000.0, -1000.0]) * 0.2
    A = influence_coefficients(X, np.array([0.0, 0.0]), 0.2, 0.2, G, NU, K)
    assert abs(A["zz"][0] - A["zz"][1]) / A["zz"][0] < 1e-13


def test_coupling_vanishes_when_K_is_zero():
    A = influence_coefficients(0.5, 0.7, DX, DY, G, NU, 0.0)
    assert float(A["xz"]) == 0.0 and float(A["yz"]) == 0.0
