"""The Standard Linear Solid (SLS) of one body and what one time step of it does (docs/theory.md §12.3).

Creep compliance (1/MPa) at constant Poisson ratio nu:

    C(t) = C_g + (C_r - C_g) (1 - exp(-t / tau)),     C_g = 1/E_g (glassy, instantaneous), C_r = 1/E_r (relaxed),

tau the creep relaxation time (s). With nu constant every influence coefficient of the body is its compliance times
a fixed function of the geometry, so the body's surface displacement (mm) under the traction history t(s) = (p, tau_x,
tau_y)(s) (MPa) is the unit-compliance elastic operator A_1 applied to

    C_r t(t) - (C_r - C_g) q(t),      q(t) = int_{-inf}^{t} exp(-(t - s)/tau) dt(s),

one exponentially fading state q per element and traction component (dq/dt = dt/dt - q/tau; no history storage).
Over a step of length dt with the traction linear in time from t_{n-1} to t_n, the update is exact:

    q_n = e q_{n-1} + b (t_n - t_{n-1}),      e = exp(-dt/tau),  b = (tau/dt)(1 - e)        (`StepCoefficients`)

so u_n = C_eff A_1 t_n + H_n with the step's effective compliance C_eff = C_r - (C_r - C_g) b (an elastic operator
with the modulus 1/C_eff) and the history displacement H_n = -A_h (e q_{n-1} - b t_{n-1}), A_h = (C_r - C_g) A_1 the
body's "history operator" (`history_pair`). dt -> inf gives C_eff = C_r and H = 0 (relaxed), dt -> 0 gives
C_eff = C_g and q = t (glassy).

Dissipation: the SLS is a glassy spring in series with a Kelvin-Voigt unit whose dashpot carries q; the power it
dissipates (N mm/s) is (1/tau) q . A_h q dA, summed over the elements (the quadratic form of the body's own,
symmetric influence matrix). Over one step q(t) = a(t) q_{n-1} + c(t) (t_n - t_{n-1}) with a = exp(-t/tau) and
c = (tau/dt)(1 - exp(-t/tau)), so the work dissipated in the step is exactly

    (1/tau) [I_aa q.A_h q + 2 I_ac q.A_h dt + I_cc dt.A_h dt] dA        (`StepCoefficients.I_aa`, ...)

with I_xy the integrals of the products of a and c over the step (s). Units: MPa, mm, s.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

from rollcontact.bem.errors import InputError
from rollcontact.bem.materials import Material, MaterialPair


@dataclass(frozen=True)
class StepCoefficients:
    """What a step of length dt (s) does to an SLS of relaxation time tau (s): decay e = exp(-dt/tau), ramp weight
    b = (tau/dt)(1 - e) of the step's traction increment, and the step integrals I_aa, I_ac, I_cc (s) of the
    dissipated work (module docstring)."""
    decay: float
    ramp: float
    I_aa: float
    I_ac: float
    I_cc: float


def _phi(x: float) -> float:
    """x - 3/2 + 2 exp(-x) - exp(-2x)/2 = sum_{n>=3} (-1)^n (2 - 2^(n-1)) x^n / n!, without cancellation for small x."""
    if x >= 0.5:
        return x - 1.5 + 2.0 * math.exp(-x) - 0.5 * math.exp(-2.0 * x)
    total, term = 0.0, x * x / 2.0          # x^n / n! for n = 2
    for n in range(3, 40):
        term *= x / n
        c = (2.0 - 2.0 ** (n - 1)) * (-1.0) ** n
        total += c * term
        if abs(c * term) < 1e-18 * abs(total):
            break
    return total


def step_coefficients(dt: float, tau: float) -> StepCoefficients:
    """The exact step coefficients of an SLS state over dt seconds (tau: its creep relaxation time, s)."""
    if not (dt > 0 and math.isfinite(dt)) or not (tau > 0 and math.isfinite(tau)):
        raise InputError(f"SLS step: dt = {dt!r} s and tau = {tau!r} s must be finite and > 0")
    x = dt / tau
    s = -math.expm1(-x)                      # 1 - e, accurate for small x
    ramp = s / x
    I_aa = 0.5 * tau * -math.expm1(-2.0 * x)
    I_ac = 0.5 * tau * s * s / x
    I_cc = tau * _phi(x) / (x * x)
    return StepCoefficients(math.exp(-x), ramp, I_aa, I_ac, I_cc)


@dataclass(frozen=True)
class StandardLinearSolid:
    """One viscoelastic body: glassy modulus E_glassy > relaxed modulus E_relaxed > 0 (MPa), creep relaxation time
    tau > 0 (s), Poisson ratio nu constant in time."""
    E_glassy: float
    E_relaxed: float
    tau: float
    nu: float

    def __post_init__(self):
        if not (0 < self.E_relaxed < self.E_glassy < math.inf):
            raise InputError(f"SLS moduli E_g = {self.E_glassy!r}, E_r = {self.E_relaxed!r} MPa: need 0 < E_r < E_g < inf "
                             "(the relaxed modulus below the glassy one)")
        if not (0 < self.tau < math.inf):
            raise InputError(f"SLS relaxation time tau = {self.tau!r} s: must be finite and > 0")
        Material(self.E_glassy, self.nu)     # checks nu

    @property
    def C_glassy(self) -> float:
        """Glassy compliance 1/E_g (1/MPa)."""
        return 1.0 / self.E_glassy

    @property
    def C_relaxed(self) -> float:
        """Relaxed compliance 1/E_r (1/MPa)."""
        return 1.0 / self.E_relaxed

    @property
    def creep_ratio(self) -> float:
        """f = C_r/C_g - 1 = E_g/E_r - 1 (CONTACT's FG)."""
        return self.E_glassy / self.E_relaxed - 1.0

    def creep(self, t: float) -> float:
        """Creep compliance C(t) (1/MPa) at t >= 0 s."""
        return self.C_glassy + (self.C_relaxed - self.C_glassy) * -math.expm1(-t / self.tau)

    def step(self, dt: float) -> StepCoefficients:
        """The exact coefficients of a step of dt seconds (`step_coefficients`)."""
        return step_coefficients(dt, self.tau)

    def effective_modulus(self, dt: float) -> float:
        """1/C_eff (MPa): the elastic modulus that carries the traction of a step of dt seconds,
        C_eff = C_r - (C_r - C_g) b."""
        b = self.step(dt).ramp
        return 1.0 / (self.C_relaxed - (self.C_relaxed - self.C_glassy) * b)

    @property
    def history_modulus(self) -> float:
        """1/(C_r - C_g) (MPa): the modulus of the history operator A_h = (C_r - C_g) A_1."""
        return 1.0 / (self.C_relaxed - self.C_glassy)


def effective_pair(body1, body2, dt: float) -> MaterialPair:
    """The elastic pair a step of dt seconds sees: each body a `Material`, or a `StandardLinearSolid` replaced by its
    effective modulus (`StandardLinearSolid.effective_modulus`)."""
    def one(b):
        return Material(b.effective_modulus(dt), b.nu) if isinstance(b, StandardLinearSolid) else b
    return MaterialPair(one(body1), one(body2))


def history_pair(body: StandardLinearSolid, index: int) -> MaterialPair:
    """The pair whose combined operator is body `index`'s (1 or 2) history operator A_h = (C_r - C_g) A_1: that body
    with the history modulus against a rigid partner (Kalker's combined G, nu, K then carry that body alone, with the
    sign its K has in the pair)."""
    own = Material(body.history_modulus, body.nu)
    rigid = Material(math.inf, 0.3)
    if index == 1:
        return MaterialPair(own, rigid)
    if index == 2:
        return MaterialPair(rigid, own)
    raise InputError(f"SLS body index {index!r}: must be 1 (sphere) or 2 (substrate)")
