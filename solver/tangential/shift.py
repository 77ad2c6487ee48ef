"""Kalker's quasi-static transient ("shift") problem on the world-fixed grid (docs/theory.md §5).

One step n -> n+1. Known: the previous traction tau' (2, ny, nx) in MPa, the traction bound
g = mu p (ny, nx) in MPa (zero outside the contact). Unknown: the traction tau (zero where g = 0) and the
rigid-shift increment dU (2,) in mm. With the slip of the step

    s = A (tau - tau') + e - dU                                   (e = extra_slip, e.g. A^tz (p - p'))

Coulomb's law holds per element: stick |tau| <= g with s = 0, slip tau = -g s/|s|, and the total force
sum tau dA = F (N). Signs (docs/theory.md §0): tau acts on the substrate; U is the sphere's rigid shift relative
to the substrate far field, U.F > 0 under a steady load (Cattaneo: U_x > 0 for F along +x).

Method: active-set Newton-CG with deflation ("projected TangCG")
-------------------------------------------------------------------
The step is the convex program  min 1/2 (tau - tau')^T A (tau - tau') + e.tau  over the discs
|tau_I| <= g_I with sum tau = F/dA (dU is the multiplier of the force constraint), solved by one nonlinear
preconditioned conjugate-gradient loop in the spirit of TangCG (Zhao, Vollebregt & Oosterlee 2015, theory
§5.4), with three choices that matter for speed:

* Exact Newton linearisation of the slip area. In a slip element the unknown is the direction of
  tau = g n; the linearised operator is t^T A t plus the curvature kappa = |s|/g (rotating a traction of
  fixed length changes its direction). The stick/slip operator K = P (A + kappa) P (P = identity in stick,
  t t^T in slip) is symmetric positive definite, so CG applies without change inside a fixed division.
* The force constraint by deflation, as in NormCG (docs/theory.md §4.3, §5.2 alternative): every direction is
  projected onto sum v = 0 in the free directions, so a CG step keeps the force (the renormalisation of the
  slip tractions moves it by second-order amounts, put back at the next exact re-synchronisation); dU is
  recovered in closed form as the least-squares multiplier. There is no outer Newton loop on dU and no
  bracketing, so nothing degrades near the traction bound (docs/theory.md P12).
* A symmetric preconditioner (`solver.tangential._preconditioner`) from Strang-circulant inverses of the
  2x2-block operator on the unpadded grid (`op.tangential_inverse`): M = A^-1 in stick; on a slip element,
  whose turning is resisted by a_tt + kappa, the two-term form Q P M P Q + D (Q = a_tt/(a_tt + kappa),
  D = kappa/(a_tt + kappa)^2) gives the element its own stiffness as diagonal and lets its coupling fade with
  kappa, so that edge elements where g -> 0 are not turned back and forth by their neighbours' residuals
  (cold Cattaneo 22 / 27 / 37 products at dx = 0.2 / 0.1 / 0.05 against 32 / 50 / 95 with M = A^-1 on
  every element). On contacts of 16000 elements and more a second circulant, the inverse
  of A + 4 a I, takes the slip elements with kappa of the order of a_tt (see that module).

The iteration itself (projection events, releases and turns, the cost of a step, lagged steps, the safeguards
against cycling and drift) is described in `solver.tangential._tangcg`.

`TangentialResult.displacement` is A tau plus `extra_slip` when that is given.

Stopping criterion (`TangentialParams.tol`): with u exactly re-synchronised,

    residual = max_I |r_I| / (a_self * max g)   <  tol

where r_I is the complementarity residual of element I in mm: the slip |s_I| in stick elements, the
tangential slip (slip not opposite to the traction) in slip elements weighted by the element's own
resistance to turning, |t_I . s_I| a_tt/(a_tt + kappa_I) with kappa_I = |s_I . n_I|/g_I, and slip elements
with s.n > 0 are released first (that violation, s.n, also counts); a_self = max(A^xx_II, A^yy_II) is the
self coefficient (mm/MPa). So the residual is the traction change, relative to max g, that one element
would need to remove its own error: a_self in stick, a_tt + kappa for turning a slip traction (without the
kappa weight, elements at the contact edge with g ~ 1e-4 max g and a direction error of 1e-9 rad would hold
the test far below what the tractions need). Against a reference solved at tol 1e-11 the traction error is
below 0.9 tol max g for tol 1e-4 ... 1e-8 on 55^2 ... 511^2 (Cattaneo grids);
`tests/solver/test_tangential_contract.py` checks < 3 tol max g.
|tau| <= g holds to round-off by construction at every iterate, and the force balance in every returned
result (it is restored before the final exact re-synchronisation).
"""
from dataclasses import dataclass
import math
from pathlib import Path

import numpy as np

from rollcontact.bem import compiled
from rollcontact.bem.errors import GrossSlidingError, InputError
from rollcontact.solver.memo import ProductMemo, same
from rollcontact.solver.tangential import _force_projection as FP, _moves
from rollcontact.solver.tangential._tangcg import ProjectedTangCG

#: Relative margin below the friction capacity sum g dA: a force within this of the capacity is gross
#: sliding (the stick zone would be far below one element and the problem has no usable solution).
CAPACITY_MARGIN = 1e-9
#: the last two converged tractions and their displacements A^tt tau, per operator (see solver.memo)
_memo = ProductMemo(size=2)


@dataclass(frozen=True)
class TangentialParams:
    """Tolerances of `solve_tangential`.

    tol: bound on the complementarity residual max_I |r_I| / (a_self max g) (see the module docstring):
        the slip error of every element, expressed as the traction (relative to the largest bound) that the
        element's own stiffness would need to remove it. 1e-8 gives shifts and tractions to about
        8 digits of the discrete solution (traction error 1.7e-9 - 8.7e-9 max g on the Cattaneo grids,
        measured against tol 1e-11).
    max_iter: budget of `op.tangential` products per solve (ConvergenceError beyond it).
    """

    tol: float = 1e-8
    max_iter: int = 500

    def __post_init__(self):
        if not (isinstance(self.tol, (int, float)) and math.isfinite(self.tol) and 0.0 < self.tol < 1.0):
            raise InputError(f"TangentialParams.tol = {self.tol!r}: must satisfy 0 < tol < 1")
        if isinstance(self.max_iter, bool) or int(self.max_iter) != self.max_iter or self.max_iter < 1:
            raise InputError(f"TangentialParams.max_iter = {self.max_iter!r}: must be an integer >= 1")


@dataclass
class TangentialResult:
    """Solution of one step (units MPa, mm, N; docs/theory.md §5.1)."""

    traction: np.ndarray        # (2, ny, nx) MPa
    shift_increment: np.ndarray  # (2,) mm, dU of this step (U_new = U_old + dU)
    force: np.ndarray           # (2,) N, sum tau dA
    slip: np.ndarray            # (2, ny, nx) mm, slip of this step (0 in stick)
    displacement: np.ndarray    # (2, ny, nx) mm, u = A tau (+ the coupling part if extra given)
    region: np.ndarray          # (ny, nx) int8: 0 exterior, 1 stick, 2 slip
    iterations: int             # op.tangential products of the solve (the cost, re-synchronisations included)
    residual: float
    converged: bool
    steps: int = 0              # CG search directions (the unit of TangCG's iteration counts); <= iterations


def traction_capacity(bound, grid) -> float:
    """Largest tangential force (N) the contact can carry: sum g dA with g = mu p the bound (MPa)."""
    return float(np.sum(bound)) * grid.cell_area


def solve_tangential(op, bound, previous_traction, *, force=None, shift=None, initial=None,
                     extra_slip=None, previous_displacement=None, previous_region=None,
                     params=TangentialParams()) -> "TangentialResult":
    """Solve one step of the transient tangential problem (docs/theory.md §5.1).

    Parameters
    ----------
    op : bem.HalfSpaceOperator (uses op.tangential, op.tangential_inverse, op.self_coefficients).
    bound : (ny, nx) traction bound g = mu p (MPa), zero outside the contact.
    previous_traction : (2, ny, nx) tau' of the previous step (MPa), on the full grid.
    force : (Fx, Fy) in N -- the total tangential force on the substrate; dU is unknown.
    shift : (dUx, dUy) in mm -- the prescribed rigid-shift increment; the force is an output.
        Exactly one of `force` and `shift` must be given.
    initial : optional (2, ny, nx) warm-start traction (MPa); default tau' projected onto the new discs.
    extra_slip : optional (2, ny, nx) slip (mm) added to s, e.g. the coupling term A^tz (p - p').
    previous_displacement : optional (2, ny, nx) u' = A^tt tau' (mm), the previous step's
        `TangentialResult.displacement` minus its extra slip; saves the product A tau'. Without it the
        product is taken from the solver's memo when tau' is the traction of a recent solve on `op`
        (the rolling case), else computed.
    previous_region : optional (ny, nx) region of a solve whose traction is `initial` (int8, 2 = slip),
        e.g. the previous outer iteration of the coupled loop: its slip elements start on the new bound
        (tau = g tau/|tau|) even where the bound grew, and the start is put on the force by shifting the
        stick elements only (`_force_projection.place_on_force`). Without it the start is the Euclidean projection of
        `initial` onto the discs and the force, which puts an element whose bound grew, and about half of
        the elements on the bound, inside the disc, i.e. in stick, and the division must be found again
        (coupled loop: about 2x the products). Not used for rolling steps, where it costs more (the
        pressure moves by a cell: 13.6 products per step against 11.1).
    params : TangentialParams.

    Returns TangentialResult; raises GrossSlidingError when |F| >= sum g dA (no equilibrium) and
    ConvergenceError when the residual does not reach params.tol within params.max_iter products.
    """
    grid = op.grid
    dA = grid.cell_area
    if (force is None) == (shift is None):
        raise InputError("solve_tangential: give exactly one of force=(Fx, Fy) N or shift=(dUx, dUy) mm")
    g, gmax = _checked_bound(bound, grid.shape)
    tau_p = _checked_previous_traction(previous_traction, grid.shape)
    capacity = float(np.sum(g)) * dA
    F, dU = _force_or_shift(force, shift, capacity)
    it = ProjectedTangCG(op, g, dU, None if F is None else F / dA,
                         None if extra_slip is None else np.asarray(extra_slip, dtype=float), params,
                         lambda region: _regime(force, capacity, region))
    ws = it.ws
    # start (docs/theory.md §5.1): u' = A tau', tau on the discs (and the force), u = A tau
    memo_reuses = _previous_displacement(it, tau_p, previous_displacement)
    if gmax == 0.0:  # no contact: zero traction, the step is pure rigid shift
        return _finish(it, extra_slip, dA, 0.0)
    FP.start_traction(ws.tau, tau_p if initial is None else initial, g, it.f_cells, previous_region, ws.region,
                      ws.u, it.axx, it.ayy)
    it.memo_reuses = _start_displacement(it, tau_p, memo_reuses)
    # projected TangCG with the force constraint deflated (docs/theory.md §5.4, §5.2); dU is its multiplier
    residual = it.run()
    if F is not None and not np.any(ws.region == 1):
        _stick_point_shift(ws.tau, ws.w, g, ws.region, dU, ws.slip)
    _memo.store(op, ws.tau, ws.u, it.memo_reuses)
    return _finish(it, extra_slip, dA, residual)


def _checked_bound(bound, shape):
    """The bound g = mu p (MPa) as a contiguous float array and its maximum, or InputError."""
    g = np.ascontiguousarray(bound, dtype=float)
    if g.shape != shape:
        raise InputError(f"bound has shape {g.shape}, the grid is {shape}")
    gmin, gmax = (float(g.min()), float(g.max())) if g.size else (0.0, 0.0)
    if not (gmin >= 0.0 and math.isfinite(gmax)):  # NaN fails both comparisons
        raise InputError("bound g = mu p must be finite and >= 0 (MPa)")
    return g, gmax


def _checked_previous_traction(previous_traction, shape):
    """tau' (MPa) as a float array of shape (2, ny, nx), or InputError."""
    tau_p = np.asarray(previous_traction, dtype=float)
    if tau_p.shape != (2,) + shape:
        raise InputError(f"previous_traction has shape {tau_p.shape}, expected {(2,) + shape}")
    return tau_p


def _force_or_shift(force, shift, capacity):
    """(F, dU): the prescribed force F (2,) N and dU = 0, or F = None and the prescribed shift dU (2,) mm (a
    copy: the solver writes the multiplier into it). GrossSlidingError when |F| reaches the capacity (N)."""
    if force is None:
        dU = np.asarray(shift, dtype=float).reshape(2).copy()
        if not np.all(np.isfinite(dU)):
            raise InputError(f"shift = {dU!r} mm must be finite")
        return None, dU
    F = np.asarray(force, dtype=float).reshape(2)
    Fmag = float(np.hypot(*F))
    if not np.all(np.isfinite(F)):
        raise InputError(f"force = {F!r} N must be finite")
    if Fmag >= capacity * (1.0 - CAPACITY_MARGIN):
        raise GrossSlidingError(
            f"tangential force |F| = {Fmag:.6g} N (F = ({F[0]:.6g}, {F[1]:.6g}) N) reaches the friction "
            f"capacity mu Fn = sum(mu p) dA = {capacity:.6g} N "
            f"(f_t = {Fmag / capacity if capacity > 0 else math.inf:.6g} >= 1): gross sliding, "
            "no static equilibrium")
    return F, np.zeros(2)


def _previous_displacement(it, tau_p, previous_displacement):
    """ws.u_prev <- u' = A tau': the given one, the memo's (tau' a recent solution) or one product (zero when
    tau' = 0). Returns the memo's reuse count of u' (0 when not from the memo)."""
    u_prev = it.ws.u_prev
    if previous_displacement is not None:
        u_given = np.asarray(previous_displacement, dtype=float)
        if u_given.shape != u_prev.shape or not np.all(np.isfinite(u_given)):
            raise InputError(f"previous_displacement: shape {u_given.shape} (expected {u_prev.shape}) and "
                             "finite values (mm) required")
        u_prev[...] = u_given
        return 0
    memo_reuses = 0
    if np.any(tau_p):
        memo, memo_reuses = _memo.lookup(it.op, tau_p)
        if memo is not None:
            u_prev[...] = memo
        else:
            it.matvec(tau_p, u_prev)
    return memo_reuses


def _start_displacement(it, tau_p, memo_reuses):
    """ws.u <- A tau of the starting traction: u' when tau = tau', else the memo's or one product. Returns
    the reuse count of the memoised products behind u and u' (the larger)."""
    ws = it.ws
    tau, u = ws.tau, ws.u
    if same(tau, tau_p):
        u[...] = ws.u_prev
    elif np.any(tau):
        memo, reuses = _memo.lookup(it.op, tau)
        if memo is not None:
            u[...] = memo
            memo_reuses = max(memo_reuses, reuses)
        else:
            it.matvec(tau, u)
    else:
        u[...] = 0.0
    return memo_reuses


#: The stick-point shift (`_stick_point_shift`) is kept only while every slip element with a resolved slip
#: (above STICK_POINT_RESOLVED of the largest) still slips within acos(STICK_POINT_ALIGN) = 8 degrees of the
#: direction opposite to its traction.
STICK_POINT_ALIGN = 0.99
STICK_POINT_RESOLVED = 1e-3


def _stick_point_shift(tau, w, g, region, dU, slip):
    """Rigid shift when the stick zone is smaller than one element (no stick element left, docs/theory.md P12).

    Without a stick element the multiplier of the force constraint is no longer a displacement of
    stuck material. When the slip directions are nearly parallel (a load in one direction, f_t -> 1), it is
    fixed only by their small Poisson tilts and grows without bound as |F| -> sum g dA (+15 % against Mindlin
    at f_t = 0.999, dx = 0.2 mm). The physical shift is then the displacement of the sub-element stick point,
    where the slip vanishes and which lies in the element of least slip: dU = w there (the continuum condition
    s = w - U <= 0 along the traction, with equality at the stick point); that element is marked as stick (it
    sits on the bound with zero slip, which Coulomb allows) and the slip of the step is recomputed. The
    tractions are the exact discrete solution and are not changed.

    When the slip directions differ (a turned or reversed load), they pin the multiplier and the stick-point
    shift would turn the slip of part of the slip area across its traction (a load turned by 90 degrees at
    f_t = 0.98: cosines up to -0.02, the shift off by 0.14 mm). The stick-point shift is therefore kept only if
    every resolved slip stays within 8 degrees of -tau/|tau| (STICK_POINT_ALIGN; at f_t = 0.999 from zero
    traction the worst is -0.998); otherwise the least-squares multiplier stands.
    """
    mag = np.where(g > 0, np.hypot(w[0] - dU[0], w[1] - dU[1]), np.inf)
    j, i = np.unravel_index(int(np.argmin(mag)), mag.shape)
    inside = region == 2
    inside[j, i] = False
    sx, sy = w[0] - w[0, j, i], w[1] - w[1, j, i]
    smag = np.hypot(sx, sy)
    resolved = inside & (smag > STICK_POINT_RESOLVED * smag[inside].max(initial=0.0))
    cos = -(tau[0] * sx + tau[1] * sy)[resolved] / (np.hypot(tau[0], tau[1]) * smag)[resolved]
    if cos.size and cos.min() < STICK_POINT_ALIGN:
        return False
    dU[0], dU[1] = w[0, j, i], w[1, j, i]
    region[j, i] = 1
    slip[0] = np.where(inside, sx, 0.0)
    slip[1] = np.where(inside, sy, 0.0)
    return True


def _regime(force, capacity, region):
    n_stick = int(np.count_nonzero(region == 1))
    n_slip = int(np.count_nonzero(region == 2))
    ft = "" if force is None else f"f_t = |F|/(mu Fn) = {float(np.hypot(*np.asarray(force, float))) / capacity:.6g}, "
    return f"{ft}{n_stick} stick and {n_slip} slip elements"


def _finish(it, extra_slip, dA, residual):
    ws = it.ws
    displacement = ws.u.copy()
    if extra_slip is not None:
        displacement += np.asarray(extra_slip, dtype=float)
    force = np.array([ws.tau[0].sum(), ws.tau[1].sum()]) * dA
    return TangentialResult(traction=ws.tau.copy(), shift_increment=it.dU.copy(), force=force,
                            slip=ws.slip.copy(), displacement=displacement, region=ws.region.copy(),
                            iterations=it.products, residual=float(residual), converged=True, steps=it.steps)


def kernels_cached() -> bool:
    """True when the solver's kernels are compiled for this machine (`rollcontact.bem.compiled`); False on the first
    run after an install or a change of the kernels, when building them takes about half a minute (2-core AMD EPYC)
    before the first step. With numba's JIT (ROLLCONTACT_KERNELS=jit, or no C compiler) it reads numba's cache
    location through a dispatcher; if that ever changes, it answers True (no message)."""
    ready = compiled.ready("rollcontact.solver")
    if ready is not None:
        return ready
    try:
        cache_dir = Path(_moves.step._cache.cache_path)
        return any(cache_dir.glob("_moves.step-*.nbi"))
    except Exception:  # numba internals moved, or the JIT not loaded yet: say nothing rather than fail a run
        return True
