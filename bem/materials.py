"""Elastic constants of a pair of bodies (docs/theory.md §1).

Body 1 is the sphere (upper body), body 2 the substrate (half-space below z = 0). Moduli in MPa.
A rigid body has E = inf.

Two families of combined constants are used:
* Kalker's (CONTACT's) G, nu, K for the influence coefficients (docs/theory.md §2.2):
      1/G = (1/G1 + 1/G2)/2,  nu/G = (nu1/G1 + nu2/G2)/2,  K/G = ((1-2nu1)/G1 - (1-2nu2)/G2)/4
  (K is a difference: identical materials are uncoupled, docs/theory.md P6);
* the Hertz/MDR constants E*, G* (Popov & Hess):
      E* = [(1-nu1^2)/E1 + (1-nu2^2)/E2]^-1,   G* = [(2-nu1)/(4G1) + (2-nu2)/(4G2)]^-1.
  The seed's Eq. 2 prints E* with (1-nu)/G, which is half the usual value (docs/theory.md P1); the usual
  E* reproduces Table 1 (a = 4.8 mm, d = 0.57 mm).
Dundurs' beta = K/(1-nu) measures the normal-tangential coupling; beta = 0 decouples them.
"""
from dataclasses import dataclass
import math

from rollcontact.bem.errors import InputError


@dataclass(frozen=True)
class Material:
    """One isotropic linear-elastic body: Young's modulus E (MPa, inf for rigid), Poisson ratio nu."""

    E: float
    nu: float

    def __post_init__(self):
        if not (self.E > 0):
            raise InputError(f"Young's modulus E = {self.E!r} MPa: must be > 0 (inf for a rigid body)")
        if not (-1.0 < self.nu <= 0.5):
            raise InputError(f"Poisson ratio nu = {self.nu!r}: allowed range is -1 < nu <= 0.5")

    @property
    def rigid(self) -> bool:
        return math.isinf(self.E)

    @property
    def compliance(self) -> float:
        """1/G in 1/MPa (0 for a rigid body)."""
        return 0.0 if self.rigid else 2.0 * (1.0 + self.nu) / self.E


@dataclass(frozen=True)
class MaterialPair:
    """Sphere (body 1) on substrate (body 2): every combined constant derives from the four inputs."""

    body1: Material
    body2: Material

    def __post_init__(self):
        if self.body1.rigid and self.body2.rigid:
            raise InputError("materials: both bodies rigid (E1 = E2 = inf); at least one must be elastic")

    @classmethod
    def from_moduli(cls, E1, nu1, E2, nu2) -> "MaterialPair":
        return cls(Material(float(E1), float(nu1)), Material(float(E2), float(nu2)))

    # --- Kalker's combined constants -----------------------------------------------------------
    @property
    def G(self) -> float:
        """Combined shear modulus G (MPa): 1/G = (1/G1 + 1/G2)/2."""
        return 2.0 / (self.body1.compliance + self.body2.compliance)

    @property
    def nu(self) -> float:
        """Combined Poisson ratio: nu/G = (nu1/G1 + nu2/G2)/2."""
        c1, c2 = self.body1.compliance, self.body2.compliance
        return 0.5 * (self.body1.nu * c1 + self.body2.nu * c2) * self.G

    @property
    def K(self) -> float:
        """Kalker's coupling constant K (dimensionless): K/G = ((1-2nu1)/G1 - (1-2nu2)/G2)/4."""
        c1, c2 = self.body1.compliance, self.body2.compliance
        return 0.25 * ((1 - 2 * self.body1.nu) * c1 - (1 - 2 * self.body2.nu) * c2) * self.G

    @property
    def beta(self) -> float:
        """Dundurs' second constant beta = K/(1-nu) (Johnson 1985, §5.4)."""
        return self.K / (1.0 - self.nu)

    # --- Hertz / MDR constants -------------------------------------------------------------------
    @property
    def E_star(self) -> float:
        """Contact modulus E* (MPa) = [(1-nu1)/(2G1) + (1-nu2)/(2G2)]^-1."""
        b1, b2 = self.body1, self.body2
        return 1.0 / (0.5 * (1 - b1.nu) * b1.compliance + 0.5 * (1 - b2.nu) * b2.compliance)

    @property
    def G_star(self) -> float:
        """Tangential contact modulus G* (MPa) = [(2-nu1)/(4G1) + (2-nu2)/(4G2)]^-1."""
        b1, b2 = self.body1, self.body2
        return 1.0 / (0.25 * (2 - b1.nu) * b1.compliance + 0.25 * (2 - b2.nu) * b2.compliance)
