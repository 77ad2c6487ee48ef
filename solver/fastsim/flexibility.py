"""The flexibilities of Kalker's simplified theory and of the strip theory, calibrated on Kalker's creep coefficients
C11, C22, C23 (solver.creep.kalker; docs/theory.md §7.3, §12.4; derivations in docs/creep_fidelity.md).

Simplified theory (Kalker 1982, "A fast algorithm for the simplified theory of rolling contact", Vehicle System
Dynamics 11:1-13): the surface displacement difference is u = L tau. Integrating the stick condition du/dx = w from
the leading edge of an ellipse with semi-axes a (rolling direction) and b gives the linear forces 8 a^2 b xi / (3 L)
(longitudinal), 8 a^2 b eta / (3 L) (lateral) and pi a^3 b phi / (4 L) (lateral, from spin); equal to Kalker's
G c^2 C11 xi, G c^2 C22 eta and G c^3 C23 phi (c = sqrt(a b)) they give

    L1 = 8 a / (3 G C11),   L2 = 8 a / (3 G C22),   L3 = pi a sqrt(a / b) / (4 G C23)        (mm^3/N = mm/MPa)

and the one flexibility of a combined creepage, weighted by the creepages (Kalker 1982):

    L = (|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 + c^2 phi^2).

Strip theory (Kalker 1967, strip theory for rolling with slip and spin): each strip y = const of half-length l is a
two-dimensional rolling contact whose displacement gradient is du/dx = -K H[tau] (H the finite Hilbert transform).
Calibrated so that full adhesion gives Kalker's coefficients over the ellipse (FaStrip's amendment, Sichani, Enblom &
Berg 2016, Vehicle System Dynamics 54:748-764):

    K_x = pi^2 / (2 G C11),   K_y = pi^2 / (2 G C22),   K_phi = 2 pi sqrt(a / b) / (3 G C23)    (1/MPa)

Units: mm, MPa; G Kalker's combined shear modulus, nu his combined Poisson ratio (bem.materials.MaterialPair).
"""
from dataclasses import dataclass
import math

from rollcontact.bem.errors import InputError
from rollcontact.solver.creep.kalker import kalker_coefficients


@dataclass(frozen=True)
class Flexibilities:
    """The contact ellipse a (rolling direction), b (mm), Kalker's combined shear modulus G (MPa) and his
    coefficients (C11, C22, C23) at its a/b and Poisson ratio; the flexibilities and strip stiffnesses they give."""
    a: float
    b: float
    G: float
    coefficients: tuple

    @property
    def c(self) -> float:
        """sqrt(a b) (mm)."""
        return math.sqrt(self.a * self.b)

    @property
    def L1(self) -> float:
        """Longitudinal flexibility 8 a / (3 G C11) (mm/MPa)."""
        return 8.0 * self.a / (3.0 * self.G * self.coefficients[0])

    @property
    def L2(self) -> float:
        """Lateral flexibility 8 a / (3 G C22) (mm/MPa)."""
        return 8.0 * self.a / (3.0 * self.G * self.coefficients[1])

    @property
    def L3(self) -> float:
        """Spin flexibility pi a sqrt(a / b) / (4 G C23) (mm/MPa)."""
        return math.pi * self.a * math.sqrt(self.a / self.b) / (4.0 * self.G * self.coefficients[2])

    def weighted(self, xi: float, eta: float, phi: float) -> float:
        """Kalker's one flexibility L (mm/MPa) for the creepages (xi, eta dimensionless, phi in 1/mm); L1 without
        creepage."""
        c = self.c
        norm = math.sqrt(xi * xi + eta * eta + c * c * phi * phi)
        if norm == 0.0:
            return self.L1
        return (abs(xi) * self.L1 + abs(eta) * self.L2 + c * abs(phi) * self.L3) / norm

    def strip_stiffnesses(self) -> tuple[float, float, float]:
        """(1/K_x, 1/K_y, 1/K_phi) (MPa) of the strip theory calibrated on Kalker's coefficients (module
        docstring): 2 G C11 / pi^2, 2 G C22 / pi^2, 3 G C23 / (2 pi sqrt(a / b))."""
        c11, c22, c23 = self.coefficients
        return (2.0 * self.G * c11 / math.pi ** 2, 2.0 * self.G * c22 / math.pi ** 2,
                3.0 * self.G * c23 / (2.0 * math.pi * math.sqrt(self.a / self.b)))


def kalker_flexibilities(a: float, b: float, G: float, nu: float) -> Flexibilities:
    """The flexibilities of the ellipse with semi-axes a (rolling direction) and b (mm), the combined shear modulus G
    (MPa) and Poisson ratio nu (clipped to Kalker's table, 0 <= nu <= 0.5)."""
    if not (a > 0 and b > 0 and math.isfinite(a) and math.isfinite(b)):
        raise InputError(f"semi-axes a = {a!r}, b = {b!r} mm: must be positive and finite")
    if not (G > 0 and math.isfinite(G)):
        raise InputError(f"G = {G!r} MPa: must be positive and finite")
    return Flexibilities(float(a), float(b), float(G), kalker_coefficients(a / b, min(max(nu, 0.0), 0.5)))
