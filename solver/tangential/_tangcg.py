"""The iteration of the tangential solver: projected TangCG on one step (the problem, the method's three main
choices and the stopping criterion are described in `solver.tangential.shift`).

`ProjectedTangCG` owns the buffers of one solve (`Workspace`) and the state of the iteration: the stick/slip
division, the CG recurrence, the force constraint and its multiplier dU, the exact re-synchronisations of
u = A tau, and the safeguards against cycling. One pass of `run` is

    evaluate (division, shift fit, residual; releases and turns)  ->  safeguards  ->  re-synchronise or accept
    ->  one preconditioned CG step (one product), with projection events.

After each CG step, stick elements that leave their disc are projected radially onto it and become slip
(many changes per iteration, as in BCCG / NormCG); slip elements whose slip turns along the traction
(s.n > 0) are released to stick, or, when that slip exceeds 2 a_self g (more than the element's own traction
can undo), their traction is turned against the slip by the step that minimises the energy along the turns
(`ProjectedTangCG.turn_reversed`); slip elements are renormalised to |tau| = g, and the force is
restored by a uniform shift of the stick tractions wherever u is then recomputed exactly; the CG recurrence
restarts after any change of the division. The projected gradient method (docs/theory.md §5.5) is simpler but needs
thousands of products on these problems (it serves only as the cycling safeguard below); Gauss-Seidel (docs/theory.md §5.3)
is sequential and grows with the grid.

Cost per iteration: one `op.tangential` (A v) and one `op.tangential_inverse` (two on contacts of 16000
elements and more, a quarter of a product each); the element loops are numba kernels
(`solver.tangential._moves`, `solver.tangential._preconditioner`) on preallocated buffers. The displacement
u = A tau is carried along (u += alpha A v); local corrections (renormalisation, projection) are added with
the self coefficients only, and u is recomputed exactly (one extra `op.tangential`) after steps that changed
the division by projection and always before convergence is accepted. While the division is being
identified (the previous step projected elements) the next step is a lagged projected step
(`ProjectedTangCG.lagged_step`: along the preconditioned residual with the previous exact step
length, then u exactly), one product where an exact step and its re-synchronisation take two; it is undone,
and not tried again in the solve, if it raised the energy. `TangentialResult.iterations` counts every
`op.tangential` call of the solve (including the product A tau' and the re-synchronisations): the cost in
convolution pairs.

Safeguards: a slip traction may turn by at most MAX_TURN g per iteration (trust region of the linearised
rotation). When no stick element is left to restore the force (f_t -> 1), the slip tractions are turned on
their rims (`_force_projection.project_on_force` with the region; the plain Euclidean projection would pull
them all inside their discs, into stick, and the division would collapse) and the CG recurrence restarts;
when no element is left in stick (stick zone below one element), the reported dU is the displacement of the
sub-element stick point (`_stick_point_shift`). The active-set iteration is not monotone in the energy
(projection events, releases) and can cycle (cold solves close to the bound on fine grids, warm starts far
from a load turned near the bound): when the best exact residual has not halved for STALL_PRODUCTS products,
GRADIENT_PRODUCTS steps of the accelerated projected gradient method (docs/theory.md §5.5; monotone in the energy, so
it leaves any cycle) run from the best exact iterate, and CG resumes from there
(`ProjectedTangCG.gradient_phase`). When an exact re-synchronisation finds the residual far above the
tolerance (drift of the self-coefficient updates on dense slip areas), u is kept exact from then on. One
early re-synchronisation, when the residual first falls below SYNC_EARLY tol, removes the drift of the large
early moves without restarting the recurrence, so that the final check rarely fails.
Product memo: A tau' is taken from the previous solve when tau' is its traction (rolling), see
`previous_displacement`.

Units: tractions and bounds MPa, displacements and slips mm, forces as sums of tractions over the elements
(MPa x elements).
"""
import math

import numpy as np

from rollcontact.bem.errors import ConvergenceError
from rollcontact.solver.tangential import _force_projection as FP
from rollcontact.solver.tangential import _gradient_phase as GP
from rollcontact.solver.tangential import _preconditioner as PC
from rollcontact.solver.tangential import _linearised as KC
from rollcontact.solver.tangential import _division as KD
from rollcontact.solver.tangential import _moves as KM

#: Largest tangent move of a slip traction per iteration, relative to its bound (about 0.5 rad).
MAX_TURN = 0.5
#: A slip element whose slip points along its traction and exceeds FLIP_SLIP a_self g is turned against its
#: slip rather than released to stick (`ProjectedTangCG.turn_reversed`).
FLIP_SLIP = 2.0
#: The curvature of k turned elements comes from their dense influence block (`op.tangential_block`: 3 k^2
#: lookups) while k^2 <= DENSE_TURNS x the grid's element count, else from one product
#: (`ProjectedTangCG.turn_reversed`). At k^2 = N the block costs 0.07 / 1.4 ms against a product of 0.28 / 3.8 ms
#: (55^2 / 217^2).
DENSE_TURNS = 1.0
#: Safeguard 1: products without halving the best exact residual before a gradient phase, and its products
#: (`ProjectedTangCG.track_progress`). Chosen on the cycling cases of benchmarks/tangential_fuzz.py (load turned
#: near the bound): stall / gradient products 30 / 40 after two stages of conservative releases: 160 / 224 products
#: at 55^2 / 217^2; 20 / 20 at the first stall: 70-74 / 108-151; the stability map unchanged (81 of 81).
STALL_PRODUCTS = 20
GRADIENT_PRODUCTS = 20
#: Safeguard 2: an exact re-synchronisation that finds the residual above SYNC_JUMP tol switches to exact u.
SYNC_JUMP = 1e4
#: One early exact re-synchronisation when the residual first falls below SYNC_EARLY tol: the drift of the
#: self-coefficient updates made in the large early moves is then removed while the CG recurrence continues,
#: so the final check usually passes at once (paper rolling: 22 products per ratcheting step, 26 without it).
SYNC_EARLY = 1e4
#: Lagged steps (`ProjectedTangCG.lagged_step`) continue while each lowers the residual below LAG_RHO times the
#: residual at the previous one (benchmarks/tangential_fuzz.py, 55^2: 0.3 / 0.5 / 0.7 / none; 0.7 kept the
#: Cattaneo counts of no limit and cuts chains of lagged steps that clip the same 1-7 elements in turn:
#: warm max 26 products, 61 without a limit).
LAG_RHO = 0.7


class Workspace:
    """Preallocated grid buffers of one solve (allocated once per call, reused by every iteration)."""

    def __init__(self, shape):
        ny, nx = shape
        f2 = lambda: np.zeros((2, ny, nx))
        self.tau, self.u, self.u_prev, self.w = f2(), f2(), f2(), f2()
        self.res, self.z, self.v, self.av, self.q, self.slip = f2(), f2(), f2(), f2(), f2(), f2()
        self.nrm = f2()  # unit direction of the slip tractions (written by KD.classify)
        self.d, self.ad = f2(), f2()  # direction of the turns of reversed slip tractions and its product
        self.zero = f2()  # stands for the product of a lagged step's direction, which is not computed
        self.kappa = np.zeros((ny, nx))
        self.region = np.zeros((ny, nx), np.int8)


class ProjectedTangCG:
    """One step's iteration on the bound g (MPa). dU (2,) mm is the shift increment: prescribed (f_cells None)
    or the multiplier of the force constraint sum tau = f_cells (MPa x elements), written in place. extra: the
    extra slip (2, ny, nx) mm or None. regime(region) describes the state for error messages.

    The caller fills ws.u_prev = A tau', ws.tau (the start) and ws.u = A tau, counting its products with
    `matvec`, then calls `run`."""

    def __init__(self, op, g, dU, f_cells, extra, params, regime):
        self.op, self.g, self.dU, self.f_cells, self.params, self.regime = op, g, dU, f_cells, params, regime
        self.force_mode = f_cells is not None
        self.ws = ws = Workspace(g.shape)
        self.has_e = extra is not None
        self.e_arr = ws.w if extra is None else extra  # a placeholder of the right type when there is none
        self.axx, self.ayy = op.self_coefficients["xx"], op.self_coefficients["yy"]
        self.a_self = max(self.axx, self.ayy)
        self.scale = self.a_self * float(g.max())
        self.restore_tol = 1e-15 * float(np.sum(g))
        self.precond = PC.Preconditioner(op, g.shape, int(np.count_nonzero(g)))
        self.products = 0  # op.tangential calls (the cost)
        self.steps = 0  # CG search directions
        self.memo_reuses = 0  # reuses of a memoised product behind u (see solver.memo)
        self.gram = (0.0, 0.0, 0.0)  # Gram matrix of the force constraint (force mode)
        self.n_stick = 0
        self.restart, self.synced, self.vq_prev = True, True, 1.0
        self.lag_alpha = 0.0  # step length of the next lagged projected step; 0: none (`lagged_step`)
        self.lagging = True
        self.lag_r = math.inf
        self.exact = self.exact_after_sync = False  # safeguard 2
        self.early_synced = False
        self.best, self.best_at = math.inf, 0
        self.tau_best = self.u_best = None

    def matvec(self, field, out):
        """out = A^tt field (one product, counted)."""
        self.products += 1
        self.op.tangential(field[0], field[1], out=out)

    def run(self):
        """Iterate until the exactly re-synchronised residual is below params.tol; returns it. The solution is
        left in the workspace (tau, u, region, slip, w) and dU. Raises ConvergenceError beyond max_iter."""
        ws, tol = self.ws, self.params.tol
        self.tau_best, self.u_best = ws.tau.copy(), ws.u.copy()
        while True:
            r = self.evaluate()
            if not math.isfinite(r):
                raise ConvergenceError("non-finite residual in the tangential solver", solver="tangential",
                                       iterations=self.products, regime=self.regime(ws.region))
            if self.track_progress(r):
                continue
            if self.synced and self.exact_after_sync and r >= SYNC_JUMP * tol:
                # Safeguard 2: the exact re-synchronisation revealed that the self-coefficient updates of the
                # renormalisations had drifted (dense slip areas on fine grids, where sum_J A_IJ ~ sqrt(N)
                # a_self): keep u exact after every step from now on.
                self.exact = True
            self.exact_after_sync = False
            if not (self.synced or self.early_synced) and r < SYNC_EARLY * tol:
                self.resync(early=True)
                continue
            if r < tol:
                if self.synced:
                    return r
                self.resync(early=False)
                continue
            if self.products >= self.params.max_iter:
                raise ConvergenceError(
                    "tangential solver did not converge", solver="tangential (projected TangCG)",
                    iterations=self.products, residual=r, tol=tol, regime=self.regime(ws.region))
            self.cg_step(r)

    def evaluate(self):
        """Division, shift fit and residual of the current iterate, with up to two rounds of releases (and
        turns of reversed slip tractions in the first). Returns the relative residual."""
        ws, g, dU, tol = self.ws, self.g, self.dU, self.params.tol
        self.n_stick, _, *gram = KD.classify(ws.tau, g, ws.region, ws.nrm, ws.u, ws.u_prev, self.e_arr,
                                            self.has_e, ws.w)
        for release_round in range(3):
            if self.force_mode:
                self.fit_shift(*(gram if release_round == 0 else KD.gram_and_fit(ws.nrm, ws.region, ws.w)))
            _, snmax, rstop = KC.residual(ws.nrm, g, ws.region, ws.w, dU[0], dU[1], ws.res, ws.kappa, ws.slip,
                                            self.axx, self.ayy)
            # Release slip elements whose slip points along the traction (s.n > 0: the traction must go back
            # inside), as soon as the multiplier says so (TangCG's rule). The last round only evaluates, so that
            # the residual always describes the current state.
            if snmax <= tol * self.scale or release_round == 2:
                return max(rstop, snmax) / self.scale
            # A slip element whose slip points along its traction and exceeds what its own traction can undo
            # over its whole range (|s| > 2 a_self g) must keep slipping: turn its traction against the slip
            # instead of releasing it (released, its stick residual -s would be far outside its disc and the
            # step that clips it back wrecked the iterate: f_t = 0.75 and 0.9 failed at 511^2). Only in the
            # first round, before any release: the re-classification derives the division afresh.
            if release_round == 0:
                self.turn_reversed()
            KD.release(ws.nrm, ws.region, ws.w, dU[0], dU[1], 0.0)
            self.restart = True

    def fit_shift(self, gxx, gxy, gyy, bx, by):
        """dU = least-squares multiplier of the force constraint from the Gram sums of `KD.gram_and_fit`."""
        self.gram = (gxx, gxy, gyy)
        dU = self.dU
        det = gxx * gyy - gxy * gxy
        if det > 1e-12 * (gxx + gyy) ** 2:
            dU[0] = (gyy * bx - gxy * by) / det
            dU[1] = (-gxy * bx + gxx * by) / det
        elif gxx + gyy > 0:  # one free direction only (e.g. a single slip element)
            tr = gxx + gyy
            dU[0], dU[1] = bx / tr, by / tr

    def track_progress(self, r):
        """Safeguard 1 (cycling of the division). When the best exact residual has not halved for STALL_PRODUCTS
        products, take GRADIENT_PRODUCTS steps of the accelerated projected gradient from the best exact iterate
        (`gradient_phase`) and resume CG from there. Returns True when the iterate was replaced."""
        if self.synced and r < 0.5 * self.best:
            self.best, self.best_at = r, self.products
            self.tau_best[...] = self.ws.tau
            self.u_best[...] = self.ws.u
            return False
        if self.products - self.best_at <= STALL_PRODUCTS:
            return False
        self.gradient_phase(min(GRADIENT_PRODUCTS, self.params.max_iter - self.products))
        self.restart, self.early_synced, self.exact_after_sync = True, False, False
        self.lag_alpha = 0.0
        self.best, self.best_at = math.inf, self.products
        return True

    def gradient_phase(self, n):
        """n steps of the accelerated projected gradient from the best exact iterate (`solver.tangential._gradient_phase`)."""
        GP.gradient_phase(self, n)

    def energy(self, t, ut):
        """The step's energy J = 1/2 (t - tau') A (t - tau') + (e - dU).t up to a constant (dU only for a prescribed
        shift; in force mode sum t is fixed), from t and ut = A t."""
        acc = 0.5 * KC.dot(t, ut) - KC.dot(t, self.ws.u_prev)
        if self.has_e:
            acc += KC.dot(self.e_arr, t)
        if not self.force_mode:
            acc -= self.dU[0] * float(t[0].sum()) + self.dU[1] * float(t[1].sum())
        return acc

    def exact_u(self):
        """u = A tau by one product: u is exact again and no longer rests on a memoised product."""
        self.matvec(self.ws.tau, self.ws.u)
        self.synced, self.memo_reuses = True, 0

    def lag_due(self, r):
        """True when the next step is a lagged projected step (`lagged_step`): the previous step clipped elements
        and the residual r fell below LAG_RHO times its value at that step."""
        return self.restart and self.lag_alpha > 0.0 and r < LAG_RHO * self.lag_r

    def resync(self, early):
        """Restore the force (force mode) and recompute u = A tau exactly. The early re-synchronisation keeps
        the CG recurrence unless the restoration changed the division; the final one (before accepting)
        restarts it and arms safeguard 2."""
        ws = self.ws
        changed = (False, False)
        if self.force_mode:
            changed = FP.restore_force(ws.tau, ws.region, self.g, self.f_cells, ws.u, self.axx, self.ayy,
                                       self.restore_tol)
        self.exact_u()
        if early:
            self.early_synced = True
            self.restart = self.restart or any(changed)
        else:
            self.exact_after_sync = self.restart = True

    def cg_step(self, r):
        """One preconditioned, deflated CG step (one product) on the current division, then back onto the
        discs; projection events re-synchronise u and restart the recurrence. In the identification phase a
        lagged projected step (`lagged_step`) is taken instead."""
        ws, g = self.ws, self.g
        tau, u, region, v, av = ws.tau, ws.u, ws.region, ws.v, ws.av
        # preconditioned, deflated residual: z = Pi (sum_l W_l P M_l P W_l r + D r) (solver.tangential._preconditioner)
        args = (ws.nrm, region, ws.kappa, self.axx, self.ayy, ws.res, ws.z, self.force_mode, self.gram, ws.q)
        rz, zq = self.precond.apply(*args)
        lag = self.lag_due(r)
        if rz <= 0.0:  # preconditioner lost definiteness on this division: plain residual
            rz, zq = self.precond.apply(*args, levels=False)
            self.restart, lag = True, False  # the lagged length belongs to the other preconditioner
        if lag:
            self.lag_r = r
            self.lagged_step()
            return
        if self.restart:
            v[...] = ws.z
        else:
            KC.conjugate(ws.z, v, -zq / self.vq_prev)
        self.matvec(v, av)
        self.steps += 1
        vq, rv = KC.curvature_product(ws.nrm, region, ws.kappa, v, av, ws.q, ws.res)
        if vq <= 0.0 or rv <= 0.0:
            if self.restart:
                raise ConvergenceError("tangential solver: search direction is not a descent direction",
                                       solver="tangential", iterations=self.products, residual=r,
                                       tol=self.params.tol, regime=self.regime(region))
            self.restart = True
            return
        n_clip, dmax, fsx, fsy, self.n_stick = KM.step(tau, v, rv / vq, u, av, g, region, self.axx, self.ayy,
                                                      MAX_TURN)
        self.restart = n_clip > 0
        self.lag_alpha = rv / vq if (n_clip > 0 and self.lagging) else 0.0
        self.lag_r = r
        self.vq_prev = vq
        self.synced = self.synced and dmax == 0.0
        projected = False
        # The renormalisation moved the force by second-order amounts. It is put back only where u is then
        # recomputed exactly (here after a projection event, and before the early and final
        # re-synchronisations). Restoring it after every step would cost a re-synchronisation and a restart per
        # step when no stick element is left (the rims must turn: f_t = 0.999 at 217^2 takes 43 products that
        # way, 21 this way). In between, the iterate misses the force by the renormalisations since.
        exact_step = self.exact and dmax > 0.0
        if self.force_mode and (n_clip > 0 or exact_step):
            # with no stick element left to carry the force the slip tractions turn on their rims: a turn of
            # every slip traction, not a local correction
            projected = FP.restore_force_from_sums(tau, region, g, self.f_cells, u, self.axx, self.ayy,
                                                   self.restore_tol, fsx, fsy, self.n_stick)
            self.restart = self.restart or projected
        if n_clip > 0 or projected or exact_step:
            self.exact_u()  # projection moved many tractions: re-synchronise u exactly

    def lagged_step(self):
        """One projected step tau <- P(tau + alpha z) along the preconditioned residual z with alpha the exact step
        length of the last CG step, the force restored, then u = A tau exactly: one product, where an exact CG
        step followed by a projection event costs two (A v for the line search, then the re-synchronisation
        after the clip and the force restoration). `cg_step` takes it instead of a restarted CG step while the
        previous step clipped elements (stick tractions projected onto their disc, or slip tractions held by
        the MAX_TURN trust region) and the residual keeps falling (LAG_RHO): the identification phase, where
        every step restarts the recurrence anyway. It is the expansion step of Dostal's MPRGP, with the
        lagged Cauchy length of projected steepest descent for its fixed length. Not monotone: a step that
        raised the energy is undone (its product is lost) and lagged steps end for the solve (fuzz campaign,
        55^2 near_bound: max 52 products with this check, 72 without).

        Cattaneo products (55^2 / 109^2 / 217^2 / 511^2; benchmarks/tangential_cattaneo.py), with lagged steps
        and without: cold 18 / 21 / 26 / 30 and 22 / 27 / 34 / 38, warm load 15 / 19 / 19 / 22 and
        15 / 22 / 22 / 28, warm profile 19 / 22 / 21 / 31 and 20 / 27 / 26 / 37. Alternatives that do worse:
        0.7 or 1.4 times the lagged length (511^2 cold 283 and 55), the exact minimiser along the step actually
        taken (Cauchy-Barzilai-Borwein; 511^2 load 29), lagged steps only while at least 8 or 32 elements are
        clipped (no better; 32: 511^2 cold 71)."""
        ws, g = self.ws, self.g
        tau, u, region = ws.tau, ws.u, ws.region
        ws.v[...] = tau
        ws.av[...] = u
        # from the carried u: after dense turns (`turn_reversed`) it is exact only up to the self-coefficient
        # updates, so the comparison may err; that costs products (an undo, or a step kept), never accuracy
        j_old, synced_old, reuses_old = self.energy(tau, u), self.synced, self.memo_reuses
        n_clip, _, fsx, fsy, self.n_stick = KM.step(tau, ws.z, self.lag_alpha, u, ws.zero, g, region, self.axx,
                                                   self.ayy, MAX_TURN)
        self.steps += 1
        if self.force_mode:
            FP.restore_force_from_sums(tau, region, g, self.f_cells, u, self.axx, self.ayy, self.restore_tol, fsx,
                                       fsy, self.n_stick)
        self.exact_u()
        self.restart = True
        if n_clip == 0:
            self.lag_alpha = 0.0
        if self.energy(tau, u) > j_old:
            tau[...] = ws.v
            u[...] = ws.av
            self.synced, self.memo_reuses = synced_old, reuses_old
            self.lag_alpha, self.lagging = 0.0, False  # region and n_stick are renewed by the next `evaluate`

    def turn_reversed(self):
        """Turn the slip tractions whose slip points along them and exceeds FLIP_SLIP a_self g against their
        slip, with an exact line search on the energy of the step. Made whole and all at once (a Jacobi step),
        the turns of neighbouring edge elements interact: 67 turns raised the energy threefold and the solve
        cycled (profile step with previous_region, Cattaneo 55^2: no convergence in 500 products; prescribed
        shift at 511^2: 129 products). Along the turns d the energy is J(t) = J + t s.d + t^2 d.Ad/2, so
        t = min(1, -s.d/d.Ad) (t = 1 for a single element: that is the threshold FLIP_SLIP = 2). At t = 1 the
        turned elements stay on their rim, below it they lie inside their disc (stick).

        In force mode with stick elements d is made force-neutral by a uniform shift of the stick elements, so the
        slope s.d is exact. While k^2 <= DENSE_TURNS N, d.Ad is summed from the turned elements' dense influence
        block (`op.tangential_block`) and u is updated by the self coefficients; that curvature leaves out the
        terms of the stick shift (of the order of (sum d)^2 / n_stick), so the step may raise the energy
        slightly (24 such dense turns in the 560 cases of benchmarks/tangential_fuzz.py, the largest rise 1.1e-3
        of the energy, with the slope of the turned elements alone; the cycling safeguard covers the rest). Above it one product
        A d gives the exact curvature and the exact update of u; taking the product always would cost 0.9 products
        and 10 % of the time per ratcheting step of the paper scenes. With no stick element left, the force is
        restored by turning the rims (`FP.restore_force`). Re-classifies the iterate when anything moved. Returns
        the number of turned elements."""
        ws, g, dU, axx, ayy = self.ws, self.g, self.dU, self.axx, self.ayy
        tau, u, region, d, ad = ws.tau, ws.u, ws.region, ws.d, ws.ad
        n_turn, cx, cy = KM.flip_direction(tau, ws.nrm, g, region, ws.w, dU[0], dU[1], FLIP_SLIP * self.a_self, d)
        if n_turn == 0:
            return 0
        n_stick = self.n_stick if self.force_mode else 0
        dense = n_turn * n_turn <= DENSE_TURNS * g.size
        if dense:
            rows, cols = np.nonzero((d[0] != 0.0) | (d[1] != 0.0))
            xx, xy, yy = self.op.tangential_block(rows, cols)
            dx, dy = d[0, rows, cols], d[1, rows, cols]
            curv = float(dx @ (xx @ dx + 2.0 * (xy @ dy)) + dy @ (yy @ dy))
        if n_stick > 0:
            KM.shift_stick(d, region, -cx / n_stick, -cy / n_stick)
        if not dense:
            self.matvec(d, ad)
            curv = KC.dot(d, ad)
        # -s.d with s = w - dU; d vanishes outside the contact
        descent = dU[0] * float(d[0].sum()) + dU[1] * float(d[1].sum()) - KC.dot(ws.w, d)
        if descent <= 0.0:
            return 0  # not a descent direction: the elements are released instead
        t = 1.0 if curv <= descent else descent / curv
        n_proj = KM.apply_flip(tau, d, t, u, ad, not dense, g, region, axx, ayy)
        self.synced = self.synced and not dense and n_proj == 0
        if self.force_mode and n_stick == 0:  # the turns moved the force and no stick element took it up
            rims_turned, _ = FP.restore_force(tau, region, g, self.f_cells, u, axx, ayy, self.restore_tol)
            if rims_turned:
                self.exact_u()  # not a local correction
            else:
                self.synced = False  # the elements turned into stick were shifted (self coefficients)
        KD.classify(tau, g, region, ws.nrm, u, ws.u_prev, self.e_arr, self.has_e, ws.w)
        return n_turn
