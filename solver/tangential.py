"""Kalker's quasi-static transient ("shift") problem on the world-fixed grid (theory.md §5).

One step n -> n+1. Known: the previous traction tau' (2, ny, nx) in MPa, the traction bound
g = mu p (ny, nx) in MPa (zero outside the contact). Unknown: the traction tau (zero where g = 0) and the
rigid-shift increment dU (2,) in mm. With the slip of the step

    s = A (tau - tau') + e - dU                                   (e = extra_slip, e.g. A^tz (p - p'))

Coulomb's law holds per element: stick |tau| <= g with s = 0, slip tau = -g s/|s|, and the total force
sum tau dA = F (N). Signs (theory §0): tau acts on the substrate; U is the sphere's rigid shift relative
to the substrate far field, U.F > 0 under a steady load (Cattaneo: U_x > 0 for F along +x).

Method: active-set Newton-CG with deflation ("projected TangCG")
-------------------------------------------------------------------
The step is the convex program  min 1/2 (tau - tau')^T A (tau - tau') + e.tau  over the discs
|tau_I| <= g_I with sum tau = F/dA (dU is the multiplier of the force constraint). We solve it with one
nonlinear preconditioned conjugate-gradient loop in the spirit of TangCG (Zhao, Vollebregt & Oosterlee
2015, theory §5.4), with three choices that matter for speed:

* Exact Newton linearisation of the slip area. In a slip element the unknown is the direction of
  tau = g n; the linearised operator is t^T A t plus the curvature kappa = |s|/g (rotating a traction of
  fixed length changes its direction). The stick/slip operator K = P (A + kappa) P (P = identity in stick,
  t t^T in slip) is symmetric positive definite, so CG applies without change inside a fixed division.
* The force constraint by deflation, as the approach in NormCG (theory §4.3, §5.2 alternative): every
  direction is projected onto sum v = 0 in the free directions, so a CG step keeps the force (only the
  renormalisation of the slip tractions moves it, by second-order amounts, until the next exact
  re-synchronisation puts it back); dU is recovered in closed form as the least-squares multiplier
  (stick slip and tangential slip orthogonal to the constraint vectors). There is no outer Newton loop on
  dU and no bracketing, so there is nothing to degrade near the traction bound (P12).
* A symmetric preconditioner (`solver._preconditioner`) built from Strang-circulant inverses of the
  2x2-block operator on the unpadded grid (`op.tangential_inverse`). In the stick area it is M = A^-1; on a
  slip element, whose turning is resisted by a_tt + kappa, the two-term form Q P M P Q + D with
  Q = a_tt/(a_tt + kappa), D = kappa/(a_tt + kappa)^2 gives the element its own stiffness as diagonal and lets
  its coupling fade with kappa (before it, edge elements where g -> 0 were turned back and forth by their
  neighbours' residuals: cold Cattaneo 32 / 50 / 95 -> 22 / 27 / 37 products at dx = 0.2 / 0.1 / 0.05, and
  511^2 converges where it failed after 500). On contacts of 16000 elements and more a second circulant, the
  inverse of A + 4 a I, takes the slip elements with kappa of the order of a_tt: the two-term form weighted
  their smooth residuals by D ~ 1/(4 a_tt), far above the inverse symbol of A, and on wide slip rings those
  modes were badly conditioned (warm steps 31 / 59 -> 22 / 28 products at 217^2 / 511^2, cold 37 / 54 -> 34 /
  38). Both forms are symmetric positive definite, so CG applies unchanged inside a fixed division.

After each CG step, stick elements that leave their disc are projected radially onto it and become slip
(many changes per iteration are allowed, as in BCCG / NormCG), slip elements whose slip turns along the
traction (s.n > 0) are released to stick (or, when that slip exceeds 2 a_self g, more than the element's
own traction can undo over its whole range, their traction is turned against the slip, by the step that
minimises the energy along the turns (`_turn_reversed`): released, their stick residual would be far outside
the disc), slip elements are renormalised to
|tau| = g, and the force is restored by a uniform shift of the stick tractions wherever u is then
recomputed exactly; the CG recurrence restarts after any change of the division. The projected gradient
method (theory §5.5) is simpler but needs thousands of products on these problems; Gauss-Seidel (§5.3) is
sequential and grows with the grid.

Cost per iteration: one `op.tangential` (A v) and one `op.tangential_inverse` (preconditioner; two on
contacts of 16000 elements and more, a quarter of a product each); the element loops are numba kernels
(`solver._tangential_kernels`, `solver._preconditioner`) on preallocated buffers. The displacement
u = A tau is carried along (u += alpha A v); the small local corrections (renormalisation, projection) are
added with the self coefficients only, and u is recomputed exactly (one extra `op.tangential`) after steps
that changed the division by projection and always before convergence is accepted.
`TangentialResult.iterations` counts every `op.tangential` call of the solve (including the product A tau'
and the re-synchronisations), so it is the honest cost in convolution pairs.

Safeguards: a slip traction may turn by at most _MAX_TURN g per iteration (trust region of the
linearised rotation); when no stick element is left to restore the force (f_t -> 1: at every
re-synchronisation of the Cattaneo solve at f_t = 0.999), the slip tractions are turned on their rims
(`_force_projection.project_on_force` with the region: the plain Euclidean projection would pull all of them
inside their discs, into stick, and the division would collapse: f_t = 0.999 failed at dx = 0.2 with the
first, hard-threshold form of the slip preconditioner), and the CG recurrence restarts; when no element is
left in stick (stick zone below one element, f_t -> 1), the reported dU is the displacement of the
sub-element stick point (see `_stick_point_shift`).
Cycling safeguard: a cold solve close to the bound on fine grids (217^2, f_t >= 0.95) used to cycle between
release and projection. When the best exact residual has not halved for _STALL_PRODUCTS products, releases
become conservative (only once the face residual is below the violation); if that stalls too, the iteration
returns to the best exact iterate. When an exact re-synchronisation finds the residual far above the
tolerance (drift of the self-coefficient updates on dense slip areas), u is kept exact from then on. One
early re-synchronisation, when the residual first falls below _SYNC_EARLY tol, removes the drift of the large
early moves without restarting the recurrence, so that the final check rarely fails.
Product memo: A tau' is taken from the previous solve when tau' is its traction (rolling), see
`previous_displacement`.

`TangentialResult.displacement` is A tau plus `extra_slip` when that is given (the issue's convention).

Stopping criterion (`TangentialParams.tol`): with u exactly re-synchronised,

    residual = max_I |r_I| / (a_self * max g)   <  tol

where r_I is the complementarity residual of element I in mm: the slip |s_I| in stick elements, the
tangential slip (slip not opposite to the traction) in slip elements weighted by the element's own
resistance to turning, |t_I . s_I| a_tt/(a_tt + kappa_I) with kappa_I = |s_I . n_I|/g_I, and slip elements
with s.n > 0 are released first (that violation, s.n, also counts); a_self = max(A^xx_II, A^yy_II) is the
self coefficient (mm/MPa). So the residual is the traction change, relative to max g, that one element
would need to remove its own error: a_self in stick, a_tt + kappa for turning a slip traction. (Without
the kappa weight, elements at the contact edge with g ~ 1e-4 max g and a direction error of 1e-9 rad held
the test for 20 of 86 products at 511^2, where tol 1e-9 was out of reach; measured against a reference at
tol 1e-11 the traction error was 0.09-0.57 tol max g for tol 1e-4 ... 1e-8 on the Cattaneo grids;
`tests/solver/test_tangential.py` checks < 3 tol max g.)
|tau| <= g holds to round-off by construction at every iterate, and the force balance in every returned
result (it is restored before the final exact re-synchronisation).
"""
from dataclasses import dataclass
import math

import numpy as np

from bem.errors import ConvergenceError, GrossSlidingError, InputError
from ._memo import ProductMemo, same
from . import _force_projection as FP
from . import _preconditioner as PC
from . import _tangential_kernels as K

#: Relative margin below the friction capacity sum g dA: a force within this of the capacity is gross
#: sliding (the stick zone would be far below one element and the problem has no usable solution).
CAPACITY_MARGIN = 1e-9
#: Largest tangent move of a slip traction per iteration, relative to its bound (about 0.5 rad).
_MAX_TURN = 0.5
#: A slip element whose slip points along its traction and exceeds _FLIP_SLIP a_self g is turned against its
#: slip rather than released to stick (`_turn_reversed`).
_FLIP_SLIP = 2.0
#: Up to this many turned elements the curvature of the turns comes from their dense influence block (k^2
#: coefficients, about 0.1 ms for 100), above it from one product (`_turn_reversed`).
_DENSE_TURNS = 256

#: the last two converged tractions and their displacements A^tt tau, per operator (see solver._memo)
_memo = ProductMemo(size=2)
#: Safeguard 1: products without halving the best exact residual before releases become conservative.
_STALL_PRODUCTS = 30
#: Safeguard 2: an exact re-synchronisation that finds the residual above _SYNC_JUMP tol switches to exact u.
_SYNC_JUMP = 1e4
#: One early exact re-synchronisation when the residual first falls below _SYNC_EARLY tol: the drift of the
#: self-coefficient updates made in the large early moves is then removed while the CG recurrence continues,
#: so the final check usually passes at once (paper rolling: 26 -> 22 products per ratcheting step).
_SYNC_EARLY = 1e4


@dataclass(frozen=True)
class TangentialParams:
    """Tolerances of `solve_tangential`.

    tol: bound on the complementarity residual max_I |r_I| / (a_self max g) (see the module docstring):
        the slip error of every element, expressed as the traction (relative to the largest bound) that the
        element's own stiffness would need to remove it. 1e-8 gives shifts and tractions to about
        8 digits of the discrete solution (traction error 2e-9 - 4e-9 max g on the Cattaneo grids).
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
    """Solution of one step (units MPa, mm, N; theory.md §5.1)."""

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


class _Workspace:
    """Preallocated grid buffers of one solve (allocated once per call, reused by every iteration)."""

    def __init__(self, shape):
        ny, nx = shape
        f2 = lambda: np.zeros((2, ny, nx))
        self.tau, self.u, self.u_prev, self.w = f2(), f2(), f2(), f2()
        self.res, self.z, self.v, self.av, self.q, self.slip = f2(), f2(), f2(), f2(), f2(), f2()
        self.nrm = f2()  # unit direction of the slip tractions (written by K.classify)
        self.d, self.ad = f2(), f2()  # direction of the turns of reversed slip tractions and its product
        self.kappa = np.zeros((ny, nx))
        self.region = np.zeros((ny, nx), np.int8)


def solve_tangential(op, bound, previous_traction, *, force=None, shift=None, initial=None,
                     extra_slip=None, previous_displacement=None, previous_region=None,
                     params=TangentialParams()) -> "TangentialResult":
    """Solve one step of the transient tangential problem (theory.md §5.1).

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
        (coupled loop: about 2x the products). Not used for rolling steps, where it measured worse (the
        pressure moves by a cell: 11.1 -> 13.6 products per step).
    params : TangentialParams.

    Returns TangentialResult; raises GrossSlidingError when |F| >= sum g dA (no equilibrium) and
    ConvergenceError when the residual does not reach params.tol within params.max_iter products.
    """
    grid = op.grid
    shape = grid.shape
    dA = grid.cell_area
    if (force is None) == (shift is None):
        raise InputError("solve_tangential: give exactly one of force=(Fx, Fy) N or shift=(dUx, dUy) mm")
    g = np.ascontiguousarray(bound, dtype=float)
    if g.shape != shape:
        raise InputError(f"bound has shape {g.shape}, the grid is {shape}")
    gmin, gmax = (float(g.min()), float(g.max())) if g.size else (0.0, 0.0)
    if not (gmin >= 0.0 and math.isfinite(gmax)):  # NaN fails both comparisons
        raise InputError("bound g = mu p must be finite and >= 0 (MPa)")
    tau_p = np.asarray(previous_traction, dtype=float)
    if tau_p.shape != (2,) + shape:
        raise InputError(f"previous_traction has shape {tau_p.shape}, expected {(2,) + shape}")
    force_mode = force is not None
    capacity = float(np.sum(g)) * dA
    if force_mode:
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
        dU = np.zeros(2)
    else:
        dU = np.asarray(shift, dtype=float).reshape(2).copy()
        if not np.all(np.isfinite(dU)):
            raise InputError(f"shift = {dU!r} mm must be finite")

    ws = _Workspace(shape)
    precond = PC.Preconditioner(op, shape, int(np.count_nonzero(g)))
    tau, u, u_prev, w, res, z, v, av, q, slip, kappa, region, nrm = (
        ws.tau, ws.u, ws.u_prev, ws.w, ws.res, ws.z, ws.v, ws.av, ws.q, ws.slip, ws.kappa, ws.region, ws.nrm)
    axx, ayy = op.self_coefficients["xx"], op.self_coefficients["yy"]
    a_self = max(axx, ayy)
    products = 0

    def matvec(field, out):
        nonlocal products
        products += 1
        op.tangential(field[0], field[1], out=out)

    # --- previous displacement and starting traction -----------------------------------------------
    memo_reuses = 0
    if previous_displacement is not None:
        u_given = np.asarray(previous_displacement, dtype=float)
        if u_given.shape != (2,) + shape or not np.all(np.isfinite(u_given)):
            raise InputError(f"previous_displacement: shape {u_given.shape} (expected {(2,) + shape}) and "
                             "finite values (mm) required")
        u_prev[...] = u_given
    elif np.any(tau_p):
        memo, memo_reuses = _memo.lookup(op, tau_p)
        if memo is not None:
            u_prev[...] = memo
        else:
            matvec(tau_p, u_prev)
    if gmax == 0.0:  # no contact: zero traction, the step is pure rigid shift
        return _finish(op, tau, u, u_prev, extra_slip, dU, region, slip, dA, 0, 0.0, True, force_mode, 0)
    FP.start_traction(tau, tau_p if initial is None else initial, g, F / dA if force_mode else None,
                      previous_region, region, u, axx, ayy)
    if same(tau, tau_p):
        u[...] = u_prev
    elif np.any(tau):
        memo, reuses = _memo.lookup(op, tau)
        if memo is not None:
            u[...] = memo
            memo_reuses = max(memo_reuses, reuses)
        else:
            matvec(tau, u)
    else:
        u[...] = 0.0
    e = None if extra_slip is None else np.asarray(extra_slip, dtype=float)
    e_arr = w if e is None else e  # a placeholder of the right type when there is no extra slip

    tol = params.tol
    scale = a_self * gmax
    gxx = gxy = gyy = 0.0  # Gram matrix of the force constraint (force mode, from K.gram_and_fit)
    f_cells = F / dA if force_mode else None  # prescribed sum of tau over the elements (MPa)
    restore_tol = 1e-15 * float(np.sum(g))
    restart = True
    synced = True
    vq_prev = 1.0
    rmax = math.inf
    n_stick = n_slip = 0
    release_ratio = math.inf  # release as soon as the multiplier says so (TangCG rule), see safeguard 1
    exact = exact_after_sync = False  # see safeguard 2
    tau_best, u_best = tau.copy(), u.copy()
    stage = 0
    best, best_at, released = math.inf, 0, 0
    early_synced = False
    steps = 0
    while True:
        # slip of the step for the current traction and division
        n_stick, n_slip, *gram = K.classify(tau, g, region, nrm, u, u_prev, e_arr, e is not None, w)
        for release_round in range(3):
            if force_mode:
                gxx, gxy, gyy, bx, by = gram if release_round == 0 else K.gram_and_fit(nrm, region, w)
                det = gxx * gyy - gxy * gxy
                if det > 1e-12 * (gxx + gyy) ** 2:
                    dU[0] = (gyy * bx - gxy * by) / det
                    dU[1] = (-gxy * bx + gxx * by) / det
                elif gxx + gyy > 0:  # one free direction only (e.g. a single slip element)
                    tr = gxx + gyy
                    dU[0], dU[1] = bx / tr, by / tr
            rmax, snmax, rstop = K.residual(nrm, g, region, w, dU[0], dU[1], res, kappa, slip, axx, ayy)
            # Release slip elements whose slip points along the traction (s.n > 0: the traction must go
            # back inside) only once the current face is solved better than that violation: releasing
            # on a poor multiplier estimate makes the division cycle near the traction bound.
            # (the last round only evaluates, so that the residual always describes the current state)
            if snmax <= tol * scale or rmax > release_ratio * snmax or release_round == 2:
                break
            # A slip element whose slip points along its traction and exceeds what its own traction can undo
            # over its whole range (|s| > 2 a_self g) must keep slipping: turn its traction against the slip
            # instead of releasing it (released, its stick residual -s would be far outside its disc and the
            # step that clips it back wrecked the iterate: f_t = 0.75 and 0.9 failed at 511^2). Only in the
            # first round, before any release: the re-classification below derives the division afresh.
            if release_round == 0:
                synced = _turn_reversed(op, tau, nrm, g, region, w, dU, u, u_prev, e_arr, e is not None,
                                        n_stick if force_mode else -1, ws, _FLIP_SLIP * a_self, matvec, synced,
                                        f_cells, restore_tol, axx, ayy)[1]
            released += K.release(nrm, region, w, dU[0], dU[1], 0.0)
            restart = True
        residual_rel = max(rstop, snmax) / scale
        if not math.isfinite(residual_rel):
            raise ConvergenceError("non-finite residual in the tangential solver", solver="tangential",
                                   iterations=products, regime=_regime(force, capacity, region))
        if synced and residual_rel < 0.5 * best:
            best, best_at, released = residual_rel, products, 0
            tau_best[...] = tau
            u_best[...] = u
        elif products - best_at > _STALL_PRODUCTS and stage < 2:
            # Safeguard 1 (cycling of the division, f_t -> 1 on fine grids), when the best exact residual
            # has not halved for _STALL_PRODUCTS products: first release a slip element only once the
            # current face is solved better than its violation (BCCG's rule); if that stalls too, go
            # back to the best exact iterate and continue from there with that rule.
            stage += 1
            release_ratio, best_at, restart = 1.0, products, True
            if stage == 2:
                tau[...] = tau_best
                u[...] = u_best
                synced = True
                continue
        if synced and exact_after_sync and residual_rel >= _SYNC_JUMP * tol:
            # Safeguard 2: the exact re-synchronisation revealed that the self-coefficient updates of the
            # renormalisations had drifted (dense slip areas on fine grids, where sum_J A_IJ ~ sqrt(N) a_self):
            # keep u exact after every step from now on.
            exact = True
        exact_after_sync = False
        if not (synced or early_synced) and residual_rel < _SYNC_EARLY * tol:
            if force_mode and any(FP.restore_force(tau, region, g, f_cells, u, axx, ayy, restore_tol)):
                restart = True  # the division changed: the recurrence is not kept
            matvec(tau, u)  # early exact re-synchronisation; the CG recurrence is kept
            synced = early_synced = True
            memo_reuses = 0
            continue
        if residual_rel < tol:
            if synced:
                if force_mode and not np.any(region == 1):
                    _stick_point_shift(w, g, region, dU, slip)
                _memo.store(op, tau, u, memo_reuses)
                return _finish(op, tau, u, u_prev, extra_slip, dU, region, slip, dA, products,
                               residual_rel, True, force_mode, steps)
            if force_mode:
                FP.restore_force(tau, region, g, f_cells, u, axx, ayy, restore_tol)
            matvec(tau, u)  # re-synchronise u = A tau exactly before accepting
            synced = True
            exact_after_sync = True
            memo_reuses = 0
            restart = True
            continue
        if products >= params.max_iter:
            raise ConvergenceError(
                "tangential solver did not converge", solver="tangential (projected TangCG)",
                iterations=products, residual=residual_rel, tol=tol,
                regime=_regime(force, capacity, region))

        # preconditioned, deflated residual: z = Pi (sum_l W_l P M_l P W_l r + D r) (solver._preconditioner)
        rz, zq = precond.apply(nrm, region, kappa, axx, ayy, res, z, force_mode, (gxx, gxy, gyy), q)
        if rz <= 0.0:  # preconditioner lost definiteness on this division: plain residual
            rz, zq = precond.apply(nrm, region, kappa, axx, ayy, res, z, force_mode, (gxx, gxy, gyy), q,
                                   levels=False)
            restart = True
        if restart:
            v[...] = z
        else:
            K.conjugate(z, v, -zq / vq_prev)
        matvec(v, av)
        steps += 1
        vq, rv = K.curvature_product(nrm, region, kappa, v, av, q, res)
        if vq <= 0.0 or rv <= 0.0:
            if restart:
                raise ConvergenceError("tangential solver: search direction is not a descent direction",
                                       solver="tangential", iterations=products, residual=residual_rel,
                                       tol=tol, regime=_regime(force, capacity, region))
            restart = True
            continue
        alpha = rv / vq
        n_clip, dmax, fsx, fsy, n_stick = K.step(tau, v, alpha, u, av, g, region, axx, ayy, _MAX_TURN)
        restart = n_clip > 0
        vq_prev = vq
        synced = synced and dmax == 0.0
        projected = False
        # The renormalisation moved the force by second-order amounts. It is put back only where u is then
        # recomputed exactly (here after a projection event, and before the early and final
        # re-synchronisations). Restoring it after every step cost a re-synchronisation and a restart per step
        # when no stick element is left (the rims must turn: f_t = 0.999, 43 -> 21 products at 217^2; other
        # counts unchanged). In between, the iterate misses the force by the renormalisations since.
        if force_mode and (n_clip > 0 or (exact and dmax > 0.0)):
            if K.restore_force(tau, region, g, f_cells[0], f_cells[1], u, axx, ayy, restore_tol, fsx, fsy, n_stick):
                # no stick element left to carry the force: turn the slip tractions (they stay on their rim)
                FP.project_on_force(tau.copy(), g, f_cells, tau, region)
                projected = restart = True  # a turn of every slip traction: not a local correction
        if n_clip > 0 or projected or (exact and dmax > 0.0):
            matvec(tau, u)  # projection moved many tractions: re-synchronise u exactly
            synced = True
            memo_reuses = 0


def _turn_reversed(op, tau, nrm, g, region, w, dU, u, u_prev, e_arr, has_e, n_stick, ws, big, matvec, synced,
                   f_cells, restore_tol, axx, ayy):
    """Turn the slip tractions whose slip points along them and exceeds big g against their slip, with an exact
    line search on the energy of the step. Made whole and all at once (a Jacobi step), the turns of neighbouring
    edge elements interact: 67 turns raised the energy threefold and the solve cycled (profile step with
    previous_region, Cattaneo 55^2: no convergence in 500 products; prescribed shift at 511^2: 129 products).
    Along the turns d the energy is J(t) = J + t s.d + t^2 d.Ad/2, so t = min(1, -s.d/d.Ad) (t = 1 for a single
    element: that is the threshold big = 2 a_self). At t = 1 the turned elements stay on their rim, below it
    they lie inside their disc (stick). Up to _DENSE_TURNS turned elements d.Ad is summed from their dense
    influence block and u is updated by the self coefficients (the force is then restored by the stick
    elements as after any step); above it d is made force-neutral by a uniform shift of the stick elements
    (n_stick > 0; n_stick < 0 for a prescribed shift) and one product A d gives the curvature and the exact
    update of u. Re-classifies the iterate when anything moved. Returns (number of turned elements, synced)."""
    d, ad = ws.d, ws.ad
    n_turn, cx, cy = K.flip_direction(tau, nrm, g, region, w, dU[0], dU[1], big, d)
    if n_turn == 0:
        return 0, synced
    dense = n_turn <= _DENSE_TURNS
    if dense:
        rows, cols = np.nonzero((d[0] != 0.0) | (d[1] != 0.0))
        xx, xy, yy = op.tangential_block(rows, cols)
        dx, dy = d[0, rows, cols], d[1, rows, cols]
        curv = float(dx @ (xx @ dx + 2.0 * (xy @ dy)) + dy @ (yy @ dy))
    else:
        if n_stick > 0:
            K.shift_stick(d, region, -cx / n_stick, -cy / n_stick)
        matvec(d, ad)
        curv = K.dot(d, ad)
    descent = -K.slope(w, dU[0], dU[1], d, region)
    if descent <= 0.0:
        return 0, synced  # not a descent direction: the elements are released instead
    t = 1.0 if curv <= descent else descent / curv
    synced = synced and not dense and K.apply_flip(tau, d, t, u, ad, not dense, g, region, axx, ayy) == 0
    if dense:
        K.apply_flip(tau, d, t, u, ad, False, g, region, axx, ayy)
    if f_cells is not None and (dense or n_stick == 0):  # the turns moved the force
        if FP.restore_force(tau, region, g, f_cells, u, axx, ayy, restore_tol)[0]:
            matvec(tau, u)  # the rims turned: not a local correction
            synced = True
    K.classify(tau, g, region, nrm, u, u_prev, e_arr, has_e, w)
    return n_turn, synced


def _stick_point_shift(w, g, region, dU, slip):
    """Rigid shift when the stick zone is smaller than one element (no stick element left, P12).

    Without a stick element the multiplier of the force constraint is no longer a displacement of
    stuck material: it is fixed only by the small Poisson tilts of the slip directions and grows
    without bound as |F| -> sum g dA (+15 % against Mindlin at f_t = 0.999, dx = 0.2 mm). The
    physical shift is the displacement of the sub-element stick point, where the slip vanishes and
    which lies in the element of least slip. We report dU = w there (the continuum condition
    s = w - U <= 0 along the traction, with equality at the stick point), mark that element as stick
    (it sits on the bound with zero slip, which Coulomb allows), and recompute the slip of the step.
    The tractions are the exact discrete solution and are not changed.
    """
    mag = np.where(g > 0, np.hypot(w[0] - dU[0], w[1] - dU[1]), np.inf)
    j, i = np.unravel_index(int(np.argmin(mag)), mag.shape)
    dU[0], dU[1] = w[0, j, i], w[1, j, i]
    region[j, i] = 1
    inside = region == 2
    slip[0] = np.where(inside, w[0] - dU[0], 0.0)
    slip[1] = np.where(inside, w[1] - dU[1], 0.0)


def _regime(force, capacity, region):
    n_stick = int(np.count_nonzero(region == 1))
    n_slip = int(np.count_nonzero(region == 2))
    ft = "" if force is None else f"f_t = |F|/(mu Fn) = {float(np.hypot(*np.asarray(force, float))) / capacity:.6g}, "
    return f"{ft}{n_stick} stick and {n_slip} slip elements"


def _finish(op, tau, u, u_prev, extra_slip, dU, region, slip, dA, products, residual, converged, force_mode,
            steps):
    displacement = u.copy()
    if extra_slip is not None:
        displacement += np.asarray(extra_slip, dtype=float)
    force = np.array([tau[0].sum(), tau[1].sum()]) * dA
    return TangentialResult(traction=tau.copy(), shift_increment=dU.copy(), force=force, slip=slip.copy(),
                            displacement=displacement, region=region.copy(), iterations=products,
                            residual=float(residual), converged=converged, steps=steps)
