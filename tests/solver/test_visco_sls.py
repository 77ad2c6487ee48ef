"""The Standard Linear Solid's element states (solver.visco.sls, solver.visco.memory): the exact step update against
the creep compliance, the dissipated work against a fine time integration, the effective modulus at its limits."""
import math

import numpy as np
import pytest

from rollcontact.bem.errors import InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.materials import Material, MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.solver.visco.memory import ViscoMemory
from rollcontact.solver.visco.sls import StandardLinearSolid, effective_pair, step_coefficients

SLS = StandardLinearSolid(E_glassy=30.0, E_relaxed=5.0, tau=0.4, nu=0.45)
GRID = Grid(7, 6, 0.3, 0.35, -3, -2)
RIGID = Material(math.inf, 0.3)


def unit_product(t):
    """(u_z, u_x, u_y) of the tractions t by the body's unit-compliance operator (E = 1), with coupling."""
    op = HalfSpaceOperator(GRID, MaterialPair(RIGID, Material(1.0, SLS.nu)), coupling=True)
    return np.stack([op.normal(t[0]) + op.normal_from_tangential(t[1], t[2]),
                     *(op.tangential(t[1], t[2]) + op.tangential_from_pressure(t[0]))])


@pytest.mark.parametrize("dt", [0.01, 0.4, 5.0])
def test_a_load_ramped_over_one_step_then_held_creeps_as_the_compliance_says(dt):
    """Tractions ramped linearly over step 0 and held: the displacement of step n is A_1 t times the creep compliance
    averaged over the ramp, (1/dt) int_{t_n}^{t_n + dt} C(s) ds, exactly (1e-12), normal and tangential parts."""
    op = HalfSpaceOperator(GRID, effective_pair(RIGID, SLS, dt), coupling=True)
    memory = ViscoMemory(op, {2: SLS}, dt)
    rng = np.random.default_rng(3)
    t = rng.random((3,) + GRID.shape)
    base = unit_product(t)
    Cg, Cr, tau = SLS.C_glassy, SLS.C_relaxed, SLS.tau
    for n in range(6):
        extra_n, extra_t = memory.terms()
        u_z = op.normal(t[0]) + op.normal_from_tangential(t[1], t[2]) + extra_n
        own = op.tangential(t[1], t[2]) + op.tangential_from_pressure(t[0])
        u_t = memory.advance(t[0], t[1:], own)
        tn = n * dt
        mean_c = Cg + (Cr - Cg) * (1.0 - tau * math.exp(-tn / tau) * -math.expm1(-dt / tau) / dt)
        scale = np.abs(base).max() * mean_c
        assert np.abs(u_z - mean_c * base[0]).max() <= 1e-12 * scale
        assert np.abs(u_t - mean_c * base[1:]).max() <= 1e-12 * scale
        if n == 0:
            assert np.abs(extra_t).max() == 0.0


def test_the_work_dissipated_in_a_step_equals_the_time_integral_of_the_dashpot_power():
    """Three steps of random tractions: each step's dissipated work (exact step integrals) against the midpoint
    rule over 4000 sub-intervals of (1/tau) q(t) . A_h q(t) dA with q(t) = e^(-t/tau) q_0 + (tau/dt)(1 - e^(-t/tau))
    (t_n - t_{n-1}) (within 1e-6); positive."""
    dt = 0.3
    op = HalfSpaceOperator(GRID, effective_pair(RIGID, SLS, dt), coupling=True)
    memory = ViscoMemory(op, {2: SLS}, dt)
    rng = np.random.default_rng(5)
    q = np.zeros((3,) + GRID.shape)
    previous = np.zeros_like(q)
    hmod = 1.0 / (SLS.C_relaxed - SLS.C_glassy)
    for _ in range(3):
        t = rng.random((3,) + GRID.shape) - 0.3
        memory.terms()
        memory.advance(t[0], t[1:], np.zeros((2,) + GRID.shape))
        jump = t - previous
        s = (np.arange(4000) + 0.5) * dt / 4000
        Aq0, Aj = unit_product(q) / hmod, unit_product(jump) / hmod
        a = np.exp(-s / SLS.tau)
        c = SLS.tau / dt * (1.0 - a)
        power = (a * a * np.vdot(q, Aq0) + 2 * a * c * np.vdot(q, Aj) + c * c * np.vdot(jump, Aj)) / SLS.tau
        work = power.mean() * dt * GRID.cell_area
        assert memory.dissipation == pytest.approx(work, rel=1e-6)
        assert memory.dissipation > 0
        st = step_coefficients(dt, SLS.tau)
        q = st.decay * q + st.ramp * jump
        previous = t


def test_the_effective_modulus_is_glassy_for_short_steps_and_relaxed_for_long_ones():
    """E_eff(dt) = 1/(C_r - (C_r - C_g)(tau/dt)(1 - e^(-dt/tau))): E_g as dt -> 0, E_r as dt -> inf, monotone."""
    assert SLS.effective_modulus(1e-12) == pytest.approx(SLS.E_glassy, rel=1e-9)
    assert SLS.effective_modulus(1e12) == pytest.approx(SLS.E_relaxed, rel=1e-9)
    moduli = [SLS.effective_modulus(dt) for dt in np.geomspace(1e-3, 1e3, 25)]
    assert all(b < a for a, b in zip(moduli, moduli[1:]))
    st = step_coefficients(1e-9, 1.0)        # the series of the step integrals where they cancel
    assert st.I_cc == pytest.approx(1e-9 / 3.0, rel=1e-6) and st.ramp == pytest.approx(1.0, abs=1e-9)
    assert step_coefficients(0.5 - 1e-12, 1.0).I_cc == pytest.approx(step_coefficients(0.5, 1.0).I_cc, rel=1e-9)


@pytest.mark.parametrize("kwargs, match", [
    (dict(E_glassy=5.0, E_relaxed=5.0, tau=1.0, nu=0.3), "E_r < E_g"),
    (dict(E_glassy=5.0, E_relaxed=6.0, tau=1.0, nu=0.3), "E_r < E_g"),
    (dict(E_glassy=5.0, E_relaxed=1.0, tau=0.0, nu=0.3), "tau"),
    (dict(E_glassy=math.inf, E_relaxed=1.0, tau=1.0, nu=0.3), "E_r < E_g < inf"),
    (dict(E_glassy=5.0, E_relaxed=1.0, tau=1.0, nu=0.6), "nu")])
def test_a_standard_linear_solid_refuses_impossible_constants(kwargs, match):
    with pytest.raises(InputError, match=match):
        StandardLinearSolid(**kwargs)
