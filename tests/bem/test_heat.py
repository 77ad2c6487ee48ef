"""The moving heat source (bem.heat; docs/friction.md, "Temperatures"): the element response against an independent
quadrature of Rosenthal's point source and against Boussinesq's element integral (no motion); the grid operator
against the classical solution of a uniform flux on a square moving over a half-space (Jaeger 1942) at Peclet
numbers 0.1, 1, 10, 100, and that solution against its two closed-form limits."""
import math

import numpy as np
import pytest
from scipy import integrate

from rollcontact.bem import Grid
from rollcontact.bem.heat import MovingHeatSource, ThermalBody, element_response
from rollcontact.bem.influence import influence_coefficients


def rosenthal(X, Y, hx, hy, c):
    """The element integral of exp(-c (R + xi)) / (2 pi R) (xi = X - x' ahead) by adaptive quadrature: over y' with
    y' - Y = |xi| sinh(t) (which takes the 1/R and the thin wake behind the source), then over x'."""
    def inner(xi):
        a = abs(xi)
        t0, t1 = math.asinh((Y - hy) / a), math.asinh((Y + hy) / a)
        w = 1.0 / math.sqrt(max(c * a, 1e-30))
        points = [q for q in ((-3 * w, -w, 0.0, w, 3 * w) if xi < 0 else (0.0,)) if t0 < q < t1]
        return integrate.quad(lambda t: math.exp(-c * (a * math.cosh(t) + xi)), t0, t1, points=points or None,
                              limit=200, epsrel=1e-12, epsabs=0)[0]
    edges = [X - hx] + ([0.0] if X - hx < 0 < X + hx else []) + [X + hx]
    return sum(integrate.quad(inner, lo, hi, limit=200, epsrel=1e-11, epsabs=0)[0]
               for lo, hi in zip(edges[:-1], edges[1:])) / (2 * math.pi)


OFFSETS = [(0.0, 0.0), (-0.2, 0.0), (0.2, 0.0), (-0.6, 0.2), (0.6, 0.0), (-2.2, 0.0), (-2.2, 0.6), (0.0, 3.0)]


@pytest.mark.parametrize("c", [0.05, 20.0, 5000.0])
def test_element_response_is_rosenthals_point_source_integrated_over_the_element(c):
    """c = V/(2 kappa) from 0.05 to 5000 /mm on a 0.2 mm element: c dx = 0.01 ... 1000 (the thermal wake behind the
    element is then far narrower than the element). Agreement to 1e-8 of the element's own response."""
    own = float(element_response(0.0, 0.0, 0.1, 0.1, c))
    for X, Y in OFFSETS:
        assert float(element_response(X, Y, 0.1, 0.1, c)) == pytest.approx(rosenthal(X, Y, 0.1, 0.1, c), abs=1e-8 * own)


def test_without_motion_the_response_is_boussinesqs_element_integral():
    X, Y = np.meshgrid(np.arange(-12, 13) * 0.2, np.arange(-6, 7) * 0.3)
    zz = influence_coefficients(X, Y, 0.2, 0.3, 1.0, 0.5, 0.0, components=("zz",))["zz"]   # (1 - nu)/(pi G) = 1/(2 pi)
    assert element_response(X, Y, 0.1, 0.15, 0.0) == pytest.approx(zz, rel=1e-12, abs=1e-14)


def square_exact(pe, n=64):
    """Max and mean temperature rise (units q a / k) of a uniform flux on the square |x|, |y| <= a = 1 moving at
    c = Pe / a: the element response of the whole square (Jaeger's time integral), its maximum along y = 0 and its
    mean by Gauss-Legendre in x (x = a - 2 a t^2 takes the square root at the leading edge) and y."""
    from scipy.optimize import minimize_scalar
    res = minimize_scalar(lambda x: -float(element_response(x, 0.0, 1.0, 1.0, pe)), bounds=(-1 + 1e-9, 1 - 1e-9),
                          method="bounded", options={"xatol": 1e-10})
    t, w = np.polynomial.legendre.leggauss(n)
    t, w = 0.5 * (t + 1), 0.5 * w
    x, wx = 1 - 2 * t ** 2, 4 * t * w
    y, wy = np.polynomial.legendre.leggauss(n)
    mean = float(np.sum(wy[:, None] * wx[None, :] * element_response(x[None, :], y[:, None], 1.0, 1.0, pe))) / 4
    return -res.fun, mean


def test_the_square_source_tends_to_its_stationary_and_high_speed_limits():
    """Pe -> 0: the centre of the square 4 ln(1 + sqrt 2)/pi = 1.1222 q a/k (Carslaw & Jaeger); Pe -> inf: conduction
    into the depth only, max 2/sqrt(pi Pe) and mean 4/(3 sqrt(pi Pe)) q a/k (Jaeger's 1-D solution)."""
    assert float(element_response(0.0, 0.0, 1.0, 1.0, 0.0)) == pytest.approx(4 * math.log(1 + math.sqrt(2)) / math.pi,
                                                                            rel=1e-12)
    peak, mean = square_exact(1000.0, n=32)  # the mean's lateral losses fall as Pe^(-1/2): 0.7 % at Pe = 1000
    assert peak == pytest.approx(2 / math.sqrt(math.pi * 1000.0), rel=1e-3)
    assert mean == pytest.approx(4 / (3 * math.sqrt(math.pi * 1000.0)), rel=1e-2)


@pytest.mark.parametrize("pe", [0.1, 1.0, 10.0, 100.0])
def test_grid_temperatures_of_a_moving_square_are_jaegers_within_2_percent(pe):
    """21 x 21 elements across the square (the issue's bound 2 %; measured 0.01-0.74 % max, 0.13-0.46 % mean)."""
    n = 21
    dx = 2.0 / n
    grid = Grid(n + 12, n + 12, dx, dx, -(n + 11) // 2, -(n + 11) // 2)
    X, Y = grid.mesh()
    inside = (np.abs(X) < 1 - dx / 4) & (np.abs(Y) < 1 - dx / 4)
    assert inside.sum() == n * n
    source = MovingHeatSource(grid, ThermalBody(conductivity=1.0, diffusivity=1.0), speed=2.0 * pe)   # c = V/(2k)
    T = source.temperature(np.where(inside, 1.0, 0.0))
    peak, mean = square_exact(pe)
    assert T[inside].max() == pytest.approx(peak, rel=0.02)
    assert T[inside].mean() == pytest.approx(mean, rel=0.02)


def test_the_convolution_is_linear_not_periodic():
    """A flux at the grid's first column heats the last column by the kernel at that offset only (no wrap-around)."""
    grid = Grid(30, 10, 0.2, 0.2)
    source = MovingHeatSource(grid, ThermalBody(0.05, 14.0), speed=100.0)
    flux = np.zeros(grid.shape)
    flux[5, 0] = 1.0
    T = source.temperature(flux)
    ox = np.arange(-(grid.nx - 1), grid.nx) * grid.dx
    expected = element_response(ox[grid.nx - 1 + 29], 0.0, 0.1, 0.1, 100.0 / 28.0) / 0.05
    assert T[5, 29] == pytest.approx(float(expected), rel=1e-10)


@pytest.mark.parametrize("c, h", [(0.0, 0.05), (0.05, 0.05), (10.0, 0.05), (1060.0, 0.125), (1e5, 0.1)])
def test_the_grid_rule_is_the_element_response_at_every_grid_offset(c, h):
    """MovingHeatSource builds its coefficients with `grid_response` (one rule in u for all offsets, a matrix
    product); it must be the element response at every offset of the grid, from no motion to c dx = 2e4."""
    from rollcontact.bem.heat import grid_response
    n, m = (31, 17) if c < 1e4 else (11, 5)
    x, y = np.arange(-(n - 1), n) * 2 * h, np.arange(0, m) * 2 * h
    exact = element_response(x[None, :], y[:, None], h, h, c)
    assert grid_response(x, y, h, h, c) == pytest.approx(exact, abs=1e-8 * exact[0, n - 1])
