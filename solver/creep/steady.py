"""Steady rolling with creepage and spin, solved directly in contact-fixed coordinates (docs/theory.md §11.5, §7.3).

Kalker's sign convention (see `solver.creep.kalker`): body 1 rolls in +x over body 2; xi, eta (dimensionless)
and phi (1/mm) are the rigid slip of body 1 relative to body 2 per unit rolling distance; `traction` is the
traction ON BODY 1 (MPa; the opposite of the project's substrate traction of docs/theory.md §0) and the forces
Fx, Fy (N) and moment Mz (N mm, about the grid origin) are those on body 1. With u = A traction the displacement
difference u1 - u2 (mm), the slip per unit rolling distance of body 1 relative to body 2 at cell I is

    s_I = (xi - phi y_I, eta + phi x_I) + (u_I - u_{I+1}) / dx

(the upwind difference of u along the rolling direction: the material at I was at the upstream cell I + 1 a
step dx earlier; CONTACT's steady "T=3" discretisation; the spin term is taken at x_I + dx/6, SPIN_OFFSET).
Coulomb: |tau_I| <= mu p_I, stick s_I = 0 where |tau_I| < mu p_I, and tau_I = -mu p_I s_I/|s_I| in slip.

Solved by Kalker's element Gauss-Seidel (SteadyGS) in the traction differences dp_I = tau_I - tau_{I+1}, for
which the slip is s = w + A dp / dx with the symmetric positive definite A (`_sweep` explains why): the 2x2
problem per element with the projection on the Coulomb disc, each row from the trailing edge to the leading
edge, the rows in increasing y; the displacements A dp are kept exact element by element (in-row sums, 1-D FFTs
to the rows ahead, `bem.rows`, one 2-D product per sweep by the operator's FFTW plans). Stops when a sweep changes no traction by more than
tol times the largest bound (SteadyParams); the forces are then converged to about 1e-8 relative (measured).
The pressure is given (the normal problem is solved before; with identical or uncoupled materials it does not
depend on the traction); the displacement caused by the pressure through Kalker's K is added to the rigid slip.
"""
from dataclasses import dataclass, field
import math

import numpy as np

from rollcontact.bem.errors import ContactEdgeError, ConvergenceError, InputError
from rollcontact.bem.grid import Grid
from rollcontact.bem.influence import influence_coefficients
from rollcontact.bem.materials import MaterialPair
from rollcontact.bem.operator import HalfSpaceOperator
from rollcontact.bem.rows import RowInfluence
from rollcontact.solver.creep import _sweep


#: The spin's rigid slip eta + phi x is evaluated at x + SPIN_OFFSET dx, as CONTACT does (its `facphi` = 1/6,
#: "offset 1/6 dq used in rolling problems"). Measured on the circle, nu = 0.25, n = 21 / 41 / 61 / 81 elements
#: across, C23 with the contact-area error divided out (c^3 -> (cells in contact dA / pi)^1.5): -3.4 / -2.2 /
#: -1.3 / -1.05 % at offset 0 (first order from below), +0.6 / +0.2 / +0.1 / -0.0 % at 1/6, +3 % at 1/2.
SPIN_OFFSET = 1.0 / 6.0
#: Sweeps over which `stalled` compares the traction changes.
STALL_WINDOW = 20


@dataclass(frozen=True)
class SteadyParams:
    """Stop when no traction changes by more than tol * (largest bound, or largest traction without friction
    limit) in a sweep; at most max_sweeps sweeps, then ConvergenceError. omega: relaxation of the stick elements
    (CONTACT's OMEGAH; 1 is plain Gauss-Seidel: over-relaxation measured 1.6-5 x slower, benchmarks/README.md)."""
    tol: float = 1e-6
    max_sweeps: int = 3000
    omega: float = 1.0

    def __post_init__(self):
        if not (0.0 < self.tol < 1.0):
            raise InputError(f"steady tol = {self.tol!r}: allowed range 0 < tol < 1")
        if int(self.max_sweeps) != self.max_sweeps or self.max_sweeps < 1:
            raise InputError(f"steady max_sweeps = {self.max_sweeps!r}: must be an integer >= 1")
        if not (0.0 < self.omega < 2.0):
            raise InputError(f"steady omega = {self.omega!r}: allowed range 0 < omega < 2")


@dataclass
class SteadyResult:
    """Steady rolling state on the contact-fixed grid (Kalker's convention, module docstring).

    traction (2, ny, nx) MPa on body 1; slip (2, ny, nx) per unit rolling distance (dimensionless), zero
    outside the contact; contact, stick (ny, nx) bool; force (Fx, Fy) N and moment Mz (N mm) on body 1;
    sweeps done, the last sweep's largest traction change (MPa) and the largest slip left in the stick cells.
    """
    traction: np.ndarray
    slip: np.ndarray
    contact: np.ndarray
    stick: np.ndarray
    force: tuple
    moment: float
    sweeps: int
    change: float
    stick_slip: float
    creepages: tuple = field(default=(0.0, 0.0, 0.0))
    friction: object = None     # with a friction law: its solver.friction.FrictionState (solve_steady_friction)


class SteadyRolling:
    """The per-grid set-up of the steady solver: dense Toeplitz tangential kernels of `materials` on `grid`
    (3 arrays of (2 ny - 1) x (2 nx - 1) floats), built once and shared by every solve on that grid, and the
    operator whose FFTW plans apply them to a whole field (`operator`: a bem HalfSpaceOperator of the same grid and
    materials to share, else one of its own). coupled: include the tangential displacement of the pressure
    (Kalker's K; default: when K != 0). with_flow: each row is swept from the leading edge (True: for operators with
    memory, solver.visco) or from the trailing edge (False, Kalker's order: 33 against 42 sweeps on a Hertz contact at
    a/dx = 12). A solve that starts with the flow goes on under-relaxed or in Kalker's order when it stalls
    (`sweep_stages`)."""

    with_flow = False

    def __init__(self, grid: Grid, materials: MaterialPair, coupled: bool | None = None,
                 operator: HalfSpaceOperator | None = None):
        self.grid, self.materials = grid, materials
        ny, nx = grid.shape
        X, Y = np.meshgrid(np.arange(-(nx - 1), nx) * grid.dx, np.arange(-(ny - 1), ny) * grid.dy)
        k = influence_coefficients(X, Y, grid.dx, grid.dy, materials.G, materials.nu, materials.K,
                                   components=("xx", "xy", "yy", "xz", "yz"))
        self.kernels = tuple(np.ascontiguousarray(k[c]) for c in ("xx", "xy", "yy"))
        self.rows = (np.ascontiguousarray(k["xx"][ny - 1]), np.ascontiguousarray(k["yy"][ny - 1]))
        self.row_influence = RowInfluence(*self.kernels)
        coupled = materials.K != 0.0 if coupled is None else bool(coupled)
        self._coupling = (k["xz"], k["yz"]) if coupled and materials.K != 0.0 else None
        if operator is None:
            operator = HalfSpaceOperator(grid, materials, coupling=False)
        elif operator.grid != grid or operator.materials != materials:
            raise InputError("SteadyRolling: the operator must be built on the same grid and materials")
        self._operator = operator

    def displacement(self, traction, out=None):
        """u1 - u2 (mm), shape (2, ny, nx), from the traction on body 1 (MPa): the Toeplitz product by the
        operator's FFTs (padded: no wrap onto the grid), into `out` if given."""
        return self._operator.tangential(traction[0], traction[1], out)

    def pressure_displacement(self, pressure):
        """u1 - u2 (mm) caused by the pressure through Kalker's K (zero when K = 0). The coupling coefficients
        are those of the substrate traction convention (docs/theory.md §2.2); u1 - u2 is minus that displacement."""
        if self._coupling is None:
            return np.zeros((2,) + self.grid.shape)
        return -np.stack([_convolve(self._coupling[0], pressure), _convolve(self._coupling[1], pressure)])

    def rigid_slip(self, xi, eta, phi, pressure=None):
        """(xi - phi y, eta + phi x) on the grid (+ the upwind difference of the pressure's displacement)."""
        X, Y = self.grid.mesh()
        rigid = np.stack([xi - phi * Y, eta + phi * (X + SPIN_OFFSET * self.grid.dx)])
        if pressure is not None and self._coupling is not None:
            up = self.pressure_displacement(pressure)
            rigid[:, :, :-1] += (up[:, :, :-1] - up[:, :, 1:]) / self.grid.dx
        return rigid


def solve_steady(problem: SteadyRolling, pressure, mu, xi=0.0, eta=0.0, phi=0.0, *, initial=None,
                 params: SteadyParams = SteadyParams(), bound_update=None) -> SteadyResult:
    """Steady rolling tractions for the creepages xi, eta (dimensionless) and spin phi (1/mm) under the
    pressure field (MPa, (ny, nx); the contact is where it is > 0) with friction coefficient mu (math.inf:
    no friction limit, the linear theory; or a local coefficient per cell, (ny, nx), solver.friction). `initial`: a traction (2, ny, nx) to start from (a warm start).
    Kalker's sign convention (module docstring). Raises ContactEdgeError if the contact touches the grid's
    leading column (the upwind difference needs one cell ahead), ConvergenceError after max_sweeps.
    bound_update(slip, traction, stick): called after each sweep with the slip per unit rolled distance (2, ny, nx)
    and the traction of the sweep and the stick cells; returns None when the bound is consistent with them, else the
    new bound (MPa, (ny, nx)) for the next sweep (a friction law, solver.friction.steady); the solve stops when a
    sweep changes no traction beyond tol and the bound is consistent."""
    grid = problem.grid
    pressure = np.asarray(pressure, dtype=float)
    if pressure.shape != grid.shape or not np.all(np.isfinite(pressure)) or np.any(pressure < 0):
        raise InputError(f"pressure: must be a finite, non-negative array of the grid's shape {grid.shape}")
    local = np.ndim(mu) > 0           # a local coefficient per cell (solver.friction)
    if not local and not (mu > 0):
        raise InputError(f"mu = {mu!r}: must be > 0 (math.inf for no friction limit)")
    for name, v in (("xi", xi), ("eta", eta), ("phi", phi)):
        if not math.isfinite(v):
            raise InputError(f"{name} = {v!r}: must be finite")
    contact = pressure > 0
    if not contact.any():
        raise InputError("pressure: no cell in contact")
    if contact[:, -1].any() or contact[:, 0].any():
        raise ContactEdgeError("the contact reaches the grid's first or last column: the steady upwind "
                               "difference needs one free cell ahead of and behind the contact in every row")
    if local:
        mu = np.asarray(mu, dtype=float)
        if mu.shape != grid.shape or not np.all(np.isfinite(mu[contact]) & (mu[contact] > 0)):
            raise InputError(f"mu: a local coefficient must be finite and > 0 on the contact, of shape {grid.shape}")
        bound = np.where(contact, mu * pressure, 0.0)
    else:
        bound = np.where(contact, mu * pressure if math.isfinite(mu) else np.inf, 0.0)
    rigid = problem.rigid_slip(xi, eta, phi, pressure)
    tau = np.zeros((2,) + grid.shape) if initial is None else np.array(initial, dtype=float)
    if tau.shape != (2,) + grid.shape or not np.all(np.isfinite(tau)):
        raise InputError(f"initial traction: must be a finite array of shape {(2,) + grid.shape}")
    tau[:, ~contact] = 0.0
    norm = np.hypot(tau[0], tau[1])
    over = norm > bound
    tau[:, over] *= bound[over] / norm[over]
    status = np.where(contact, np.where(over | (norm >= bound), _sweep.SLIP, _sweep.STICK),
                      _sweep.EXTERIOR).astype(np.int8)
    dp = tau.copy()
    dp[:, :, :-1] -= tau[:, :, 1:]
    lo, hi = _row_ranges(contact)
    disp = problem.displacement(dp)
    inv_dx = 1.0 / grid.dx
    scale = float(np.max(bound[contact])) if local or math.isfinite(mu) else None
    change = math.inf
    stages = sweep_stages(problem.with_flow, params.omega)
    stage, changes = 0, []
    for sweeps in range(1, params.max_sweeps + 1):
        with_flow, omega = stages[stage]
        change = _sweep_rows(problem, rigid, tau, dp, status, bound, disp, lo, hi, omega, with_flow)
        ref = scale if scale is not None else max(float(np.max(np.hypot(tau[0], tau[1]))), 1e-300)
        if bound_update is not None:   # the slip of this sweep is rigid + A dp / dx (module docstring)
            new_bound = bound_update(rigid + disp * inv_dx, tau, status == _sweep.STICK)
            if new_bound is not None:
                bound[...] = new_bound
                continue
        if change <= params.tol * ref:
            break
        changes.append(change / ref)
        if stage + 1 < len(stages) and stalled(changes):
            stage, changes = stage + 1, []       # the next order / relaxation (`sweep_stages`)
    else:
        raise ConvergenceError("steady rolling Gauss-Seidel did not converge", solver="solve_steady",
                               iterations=params.max_sweeps, residual=change / ref, tol=params.tol,
                               regime=f"xi = {xi}, eta = {eta}, phi = {phi}, mu = "
                                      + (f"{mu.min():.6g} to {mu.max():.6g} (local)" if local else f"{mu}"))
    return _result(problem, tau, rigid, contact, bound, sweeps, change, (xi, eta, phi))


def sweep_stages(with_flow: bool, omega: float) -> list:
    """The (with_flow, omega) of the sweeps a solve goes through, each taken when the one before `stalled`: Kalker's
    order alone for an elastic operator; for one with memory (with_flow) the flow's order, then with its stick
    elements under-relaxed (0.7, 0.5 of omega), then Kalker's order (omega, 0.5 omega). Measured on viscoelastic
    contacts (docs/viscoelastic.md): the flow's order converges in 21-55 sweeps where Kalker's diverges (a sphere or an
    ellipse on a substrate with E_g/E_r = 10 at V tau/a <= 0.3), cycles on a one-row strip (which Kalker's order
    solves) and, for an elastic sphere of other Poisson ratio on the substrate, converges under-relaxed."""
    if not with_flow:
        return [(False, omega)]
    return [(True, omega), (True, 0.7 * omega), (True, 0.5 * omega), (False, omega), (False, 0.5 * omega)]


def stalled(changes, window=STALL_WINDOW) -> bool:
    """True when the largest traction change of the last `window` sweeps has not fallen below half of that of the
    `window` sweeps before (checked every `window` sweeps): a sweep order that cycles instead of converging."""
    n = len(changes)
    return n >= 2 * window and n % window == 0 and min(changes[-window:]) >= 0.5 * min(changes[-2 * window:-window])


def _sweep_rows(problem, rigid, tau, dp, status, bound, disp, lo, hi, omega, with_flow=False):
    """One Gauss-Seidel sweep over the contact rows (`_sweep.row_sweep`), in increasing y. Each row's change of dp
    is carried to the rows still to come in this sweep (1-D FFTs, `bem.rows`), so that every element sees the
    latest state: an exact element Gauss-Seidel. The rows already done get it at the end of the sweep, when
    disp = A dp is recomputed by one 2-D FFT product (half the 1-D transforms of carrying it to every row)."""
    rows = np.nonzero(hi > lo)[0]
    last = int(rows[-1])
    row_xx, row_yy = problem.rows
    inv_dx = 1.0 / problem.grid.dx
    change = 0.0
    for j in rows:
        start = dp[:, j].copy()
        change = max(change, _sweep.row_sweep(j, rigid, tau, dp, status, bound, disp, row_xx, row_yy, inv_dx,
                                               lo[j], hi[j], start, omega, with_flow))
        if j < last:
            problem.row_influence.add(disp, j, dp[:, j] - start, slice(int(j) + 1, last + 1))
    problem.displacement(dp, out=disp)
    return change


def _row_ranges(contact):
    """Per row, the cells [lo, hi) where the traction difference dp can be non-zero: from the free cell behind
    the contact to its leading cell (lo = hi = 0 in a row without contact)."""
    ny = contact.shape[0]
    lo = np.zeros(ny, dtype=np.intp)
    hi = np.zeros(ny, dtype=np.intp)
    for j in range(ny):
        cols = np.nonzero(contact[j])[0]
        if cols.size:
            lo[j], hi[j] = cols[0] - 1, cols[-1] + 1
    return lo, hi


def _result(problem, tau, rigid, contact, bound, sweeps, change, creepages):
    """Slip from a fresh product (no drift of the running updates), stick cells, forces and moment."""
    grid = problem.grid
    disp = problem.displacement(tau)
    slip = rigid.copy()
    slip[:, :, :-1] += (disp[:, :, :-1] - disp[:, :, 1:]) / grid.dx
    slip[:, ~contact] = 0.0
    norm = np.hypot(tau[0], tau[1])
    stick = contact & (norm < bound * (1.0 - 1e-9))
    speed = np.hypot(slip[0], slip[1])
    scale = max(float(np.max(np.hypot(rigid[0], rigid[1])[contact])), 1e-300)
    stick_slip = float(np.max(speed[stick]) / scale) if stick.any() else 0.0
    X, Y = grid.mesh()
    dA = grid.cell_area
    force = (float(tau[0].sum() * dA), float(tau[1].sum() * dA))
    moment = float(((X * tau[1] - Y * tau[0]).sum()) * dA)
    return SteadyResult(tau, slip, contact, stick, force, moment, sweeps, change, stick_slip, creepages)


def _convolve(kernel, field):
    """sum_J kernel[I - J] field[J] on the grid (aperiodic), kernel of shape (2 ny - 1, 2 nx - 1) centred."""
    ny, nx = field.shape
    shape = (2 * ny - 1 + ny, 2 * nx - 1 + nx)
    prod = np.fft.irfft2(np.fft.rfft2(kernel, shape) * np.fft.rfft2(field, shape), shape)
    return prod[ny - 1:2 * ny - 1, nx - 1:2 * nx - 1]
