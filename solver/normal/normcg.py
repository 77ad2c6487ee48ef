"""Frictionless normal contact on the elastic half-space: NormCG (docs/theory.md §4.1, §4.3).

Problem (docs/theory.md §4.1), on the potential-contact grid of `op.grid`, element area dA = dx dy:

    e_I = h_I - d + u_I >= 0,   p_I >= 0,   p_I e_I = 0,   u = A^zz p (+ extra displacement),

with either the total force prescribed, sum_I p_I dA = Fn (the approach d is then the Lagrange multiplier
of that constraint), or the approach d prescribed (the force is an output). Units: p in MPa, h, d, u, e
in mm, Fn in N. Sign conventions (docs/theory.md §0): p >= 0 is compressive, u_z > 0 is the loss of
separation caused by deformation (into the bodies), d > 0 presses the bodies together, e is the
deformed gap.

Method: Vollebregt's NormCG (J. Comput. Phys. 257, 2014; BCCG, J. Optim. Theory Appl. 162, 2014), as
outlined in docs/theory.md §4.3:

* an active set C (elements with p > 0 plus those entering); p = 0 elsewhere;
* CG on the equations e_I = 0 for I in C, preconditioned by the Strang-circulant inverse of A^zz
  (`op.normal_inverse`), z = P_C M P_C r;
* deflation of the force constraint: in force mode z, and hence the search direction v, are projected
  to zero mean over C, so a CG step never changes sum p; d is recovered as mean_C (u + h);
* Polak-Ribiere beta = max(0, (r_k.z_k - r_{k-1}.z_k) / (r_{k-1}.z_{k-1})), step alpha = (r.v)/(v.Av);
* after every step (CONTACT's `normcg` for large grids) elements with p < 0 leave C (p set to 0, and in
  force mode p rescaled to Fn), exterior elements with e < 0 enter C with residual -e, and CG restarts
  from the preconditioned steepest descent. The first step is taken on the initial contact set (the
  support of the initial pressure), so a warm start is not flooded by the rough first estimate of d.
* start: the given `initial` pressure (warm start); otherwise, with a prescribed force, a Hertz-shaped
  estimate from the profile (`_cold_start`), and with a prescribed approach p = 0 on C = {h < d}.

Cost per iteration: one `op.normal` (A v, a padded forward + inverse FFT) and one `op.normal_inverse`
(about a fifth of that), plus three compiled element loops (`_direction`, `_step`, `_residual_and_entries`
in `solver/normal/_kernels.py`; 1.3-1.5 convolution pairs per iteration at 512^2, benchmarks/normal_hertz.py). The displacement u = A p is not recomputed by FFT: it is updated as
u += alpha A v, and the elements truncated to p = 0 are corrected exactly, either by adding their influence
columns (few elements, numba `_add_columns`) or, when many elements are truncated at once, by one extra
`op.normal(p)`. Work arrays are allocated once per call.
"""
from dataclasses import dataclass
import math
import weakref

import numpy as np

from rollcontact.bem.errors import ConvergenceError, InputError
from rollcontact.solver.memo import ProductMemo
from rollcontact.solver.normal._kernels import _add_columns, _direction, _residual_and_entries, _step

def _max_column_corrections(n_elements):
    """How many truncated elements are corrected by influence columns rather than by one extra FFT.

    Adding one column of A^zz costs O(N); one padded convolution O(N log N). Measured break-even on the
    2-core benchmark machine (numba column loop vs `op.normal`): 18 / 37 / 53 / 68 columns at
    64^2 / 256^2 / 512^2 / 1024^2 elements; sqrt(N)/12 clipped to [8, 64] stays below it.
    """
    return int(min(64, max(8, math.sqrt(n_elements) / 12.0)))


@dataclass(frozen=True)
class NormalParams:
    """Stopping rule of `solve_normal`.

    tol : the iteration stops when, after an iteration that did not change the active set C,
          (1) rms over the grid of (p_k - p_{k-1}) <= tol * rms of p_k        (update criterion, docs/theory.md §4.3)
          and
          (2) max over C of |e_I| <= tol * max over C of u_I                   (complementarity)
          hold together. u_I is the elastic displacement (mm), so (2) reads "the gap inside the contact
          is zero to tol times the peak elastic displacement" (= d for a Hertz contact). Outside C the
          unchanged active set guarantees e >= 0 and p = 0. The reported residual is the larger of the
          two ratios.
    max_iter : CG iterations (each one A v product) before ConvergenceError is raised.
    """

    tol: float = 1e-8
    max_iter: int = 200

    def __post_init__(self):
        if not (math.isfinite(self.tol) and 0.0 < self.tol < 1.0):
            raise InputError(f"NormalParams.tol = {self.tol!r}: must satisfy 0 < tol < 1")
        if int(self.max_iter) != self.max_iter or self.max_iter < 1:
            raise InputError(f"NormalParams.max_iter = {self.max_iter!r}: must be an integer >= 1")


@dataclass
class NormalResult:
    """Solution of the normal problem (units mm, N, MPa; arrays of shape (ny, nx) of the grid).

    pressure     : p >= 0 (MPa).
    approach     : d (mm), rigid approach; with a prescribed force, the multiplier of the force
                   constraint (mean of h + u over the contact).
    displacement : u_z = A^zz p (+ extra_displacement if given) (mm), positive into the bodies.
    gap          : deformed gap e = h - d + u_z (mm); >= 0 outside, 0 up to tol inside the contact.
    contact      : p > 0.
    force        : sum p dA (N).
    iterations   : CG iterations (A v products) used.
    residual     : max(rms(p_k - p_{k-1}) / rms(p_k), max_C |e| / max_C u) at the last iteration.
    converged    : True (a run that does not converge raises ConvergenceError).
    """

    pressure: np.ndarray
    approach: float
    displacement: np.ndarray
    gap: np.ndarray
    contact: np.ndarray
    force: float
    iterations: int
    residual: float
    converged: bool


# --- helpers -----------------------------------------------------------------------------------------

_kernel_cache = weakref.WeakKeyDictionary()

#: the last converged pressure and its displacement A^zz p, per operator (see solver.memo)
_memo = ProductMemo(size=1)


def _wrapped_kernel(op):
    """A^zz coefficients on the padded domain in wrap-around order (mm/MPa), cached per operator.

    Recovered from the operator's own spectrum (which folds in 1/(Py Px)), so the column corrections
    use exactly the convolution `op.normal` applies.
    """
    kernel = _kernel_cache.get(op)
    if kernel is None:
        py, px = op.padded
        kernel = np.fft.irfft2(op.spectra["zz"], s=(py, px)) * (py * px)
        _kernel_cache[op] = kernel
    return kernel


def _field(name, value, shape):
    """A finite float64 C-contiguous copy of a grid field, or InputError naming the parameter."""
    arr = np.asarray(value, dtype=float)
    if arr.shape != shape:
        raise InputError(f"{name}: shape {arr.shape} does not match the grid shape (ny, nx) = {shape}")
    if not math.isfinite(float(arr.sum())) and not np.all(np.isfinite(arr)):  # the sum is the cheap test
        raise InputError(f"{name}: contains {np.count_nonzero(~np.isfinite(arr))} non-finite values "
                         "(NaN or inf); every element must be a finite number")
    return np.ascontiguousarray(arr, dtype=np.float64)


def _cold_start(h_eff, force, dA, E_star):
    """Initial pressure (MPa) for a prescribed force without a warm start: a Hertz-shaped estimate.

    With s = h - min h, the Hertz solution of a paraboloid is p ~ sqrt(t - s) on {s < t}, where
    t = d/2 and the contact area A(t) = |{s < t}| satisfies Fn = (4/3) E* sqrt(A/pi) (2t) (docs/theory.md
    docs/theory.md §7.1: Fn = (4/3) E* a d, a^2 = A/pi). The same rule is applied to any profile: t is found from the
    cumulative histogram of s, then p is scaled to Fn. It is only a starting point; NormCG corrects it.
    """
    s = h_eff - h_eff.min()
    smax = float(s.max())
    if smax <= 0.0:
        return np.full_like(h_eff, force / (dA * h_eff.size))
    counts, edges = np.histogram(s, bins=1024, range=(0.0, smax))
    area = dA * np.cumsum(counts)              # area of {s < edges[k+1]}
    f_est = (4.0 / 3.0) * E_star * np.sqrt(area / math.pi) * 2.0 * edges[1:]
    k = int(np.searchsorted(f_est, force))
    t = float(edges[min(k + 1, edges.size - 1)])
    p = np.sqrt(np.maximum(t - s, 0.0))
    p *= force / (dA * p.sum())
    return p


# --- solver ------------------------------------------------------------------------------------------

def solve_normal(op, profile, *, force=None, approach=None, initial=None, extra_displacement=None,
                 params=NormalParams()) -> NormalResult:
    """Frictionless normal contact by NormCG (docs/theory.md §4.3) on the grid of `op`.

    Parameters
    ----------
    op : bem.operator.HalfSpaceOperator (its grid and materials define A^zz, mm/MPa).
    profile : undeformed gap h (mm), shape (ny, nx) of op.grid, e.g. |x - c|^2 / (2R).
    force : prescribed normal force Fn (N, > 0); the approach d is then solved for.
    approach : prescribed approach d (mm); the force is then an output. Give exactly one of the two.
    initial : warm-start pressure (MPa), shape (ny, nx), e.g. the previous step's; negative values are
        treated as 0. In force mode it is rescaled to Fn.
    extra_displacement : an additional normal displacement (mm, same sign as u_z) added to A p, e.g.
        A^zt tau for normal-tangential coupling (the solver then sees h* = h + extra).
    params : NormalParams (tolerance, iteration budget; the stopping rule is documented there).

    Returns NormalResult. Raises InputError on invalid input (naming the parameter) and ConvergenceError
    (solver='normal') when tol is not reached within params.max_iter iterations.
    """
    force, approach = _checked_load(params, force, approach)
    shape, dA = op.grid.shape, op.grid.cell_area
    h = _field("profile", profile, shape)
    extra = None if extra_displacement is None else _field("extra_displacement", extra_displacement, shape)
    h_eff = h if extra is None else h + extra
    p, u, reuses = _start(op, h_eff, force, initial)
    if approach is not None and not np.any(p > 0.0) and not np.any(h_eff < approach):
        # the surfaces do not touch even rigidly: the exact solution is p = 0
        return _result(h, extra, p, u, approach, dA, 0, 0.0)
    # in approach mode a cold start has C = {h* < d}: the first residual is d - h* > 0 there
    cg = _NormCG(op, p, u, h_eff, force, approach, reuses)
    residual = math.inf
    while cg.iterations < params.max_iter:
        residual, rms_p = cg.iterate()
        if not math.isfinite(residual) and rms_p > 0.0:
            break
        if not cg.changed and residual <= params.tol:
            _memo.store(op, p, u, cg.reuses)
            return _result(h, extra, p, u, cg.d, dA, cg.iterations, residual)
        if approach is not None and not cg.active.any() and rms_p == 0.0:
            return _result(h, extra, p, u, cg.d, dA, cg.iterations, 0.0)
    raise _not_converged(cg, params, residual)


def _checked_load(params, force, approach):
    """(force, approach) as floats, exactly one of them given (the other None), or InputError."""
    if not isinstance(params, NormalParams):
        raise InputError(f"params = {params!r}: must be a NormalParams instance")
    if (force is None) == (approach is None):
        raise InputError("solve_normal: give exactly one of force (Fn in N) and approach (d in mm); got "
                         f"force = {force!r}, approach = {approach!r}")
    if force is not None:
        force = float(force)
        if not (math.isfinite(force) and force > 0.0):
            raise InputError(f"force = {force!r} N: must be a finite positive normal force")
    else:
        approach = float(approach)
        if not math.isfinite(approach):
            raise InputError(f"approach = {approach!r} mm: must be finite")
    return force, approach


def _start(op, h_eff, force, initial):
    """Initial pressure p (MPa, on Fn when the force is prescribed), its displacement u = A p (mm; zero when
    p = 0) and the memo's reuse count of u.

    The warm start `initial` (negative values cut to 0) takes A p from the memo when it is the last
    converged pressure; without it, or with an all-zero one in force mode, the Hertz-shaped `_cold_start`
    (force prescribed) or p = 0 (approach prescribed).
    """
    dA = op.grid.cell_area
    deflate = force is not None
    memo = None
    if initial is not None:
        p = np.maximum(_field("initial", initial, h_eff.shape), 0.0)
        # a warm start is usually the previous converged pressure, whose A p the memo holds
        memo, reuses = _memo.lookup(op, p)
        if deflate and not np.any(p > 0.0):
            p, memo = _cold_start(h_eff, force, dA, op.materials.E_star), None
    elif deflate:
        p = _cold_start(h_eff, force, dA, op.materials.E_star)
    else:
        p = np.zeros(h_eff.shape)
    scale = force / (dA * p.sum()) if deflate else 1.0
    if deflate:
        p *= scale
    u = np.zeros(h_eff.shape)
    if memo is None:
        reuses = 0
    if np.any(p > 0.0):
        if memo is not None:
            np.multiply(memo, scale, out=u)
        else:
            op.normal(p, out=u)
    return p, u, reuses


def _update_ratio(dp2, p2, n):
    """(rms(p_k - p_{k-1}) / rms(p_k), rms(p_k)) from the sums of squares over the n elements."""
    rms_p = math.sqrt(p2 / n)
    update = math.sqrt(dp2 / n) / rms_p if rms_p > 0.0 else (0.0 if dp2 == 0.0 else math.inf)
    return update, rms_p


class _NormCG:
    """The state and work buffers of one NormCG solve (the only large allocations of the solve).

    p and u (= A p) are updated in place; `iterate` takes one CG step on the active set C (`active`),
    `changed` tells whether it changed C, `d` is the approach (mean_C (u + h*) with a prescribed force).
    """

    def __init__(self, op, p, u, h_eff, force, approach, reuses):
        shape = p.shape
        self.op, self.p, self.u, self.force, self.reuses = op, p, u, force, reuses
        self.dA = op.grid.cell_area
        self.deflate = force is not None
        self.target = 0.0 if self.deflate else approach    # the d passed to the residual kernel
        self.active = p > 0.0
        self.r = np.empty(shape)
        self.r_prev = np.zeros(shape)
        self.z = np.empty(shape)
        self.v = np.zeros(shape)
        self.q = np.empty(shape)
        self.flat = {k: a.reshape(-1) for k, a in
                     dict(p=p, u=u, h=h_eff, r=self.r, r_prev=self.r_prev, z=self.z, v=self.v, q=self.q,
                          active=self.active).items()}
        self.max_columns = _max_column_corrections(op.grid.size)
        self.trunc_index = np.empty(self.max_columns, dtype=np.int64)
        self.trunc_value = np.empty(self.max_columns)
        self.kernel = None
        self.rz_old = 0.0
        self.iterations = 0
        self.changed = False
        f = self.flat
        self.d = _residual_and_entries(f["u"], f["h"], self.target, f["active"], f["r"], self.deflate,
                                       not self.active.any())[0]

    def iterate(self):
        """One NormCG iteration (docs/theory.md §4.3); returns (residual, rms p) of the stopping rule."""
        self.iterations += 1
        self._direction()
        ntrunc, dp2, p2 = self._step()
        entered, emax, umax = self._residual()
        self.changed = bool(ntrunc or entered)
        if self.changed:
            self.rz_old = 0.0  # active set changed: restart with the preconditioned steepest descent
        update, rms_p = _update_ratio(dp2, p2, self.p.size)
        gap_ratio = emax / umax if umax > 0.0 else (0.0 if emax == 0.0 else math.inf)
        return max(update, gap_ratio), rms_p

    def _direction(self):
        """Preconditioned, projected residual z = P_C M P_C r (deflated in force mode), the Polak-Ribiere
        direction v and its product q = A v."""
        f = self.flat
        self.op.normal_inverse(self.r, out=self.z)
        self.rz_old = _direction(f["z"], f["r"], f["r_prev"], f["v"], self.rz_old, f["active"], self.deflate)
        self.op.normal(self.v, out=self.q)

    def _step(self):
        """p += alpha v, u += alpha q; elements with p < 0 leave C (p = 0, their influence removed from u
        exactly) and the pressure is rescaled to Fn. Returns (elements truncated, |dp|^2, |p|^2)."""
        f = self.flat
        ntrunc, psum, dp2, p2 = _step(f["p"], f["u"], f["v"], f["q"], f["r"], f["active"], self.trunc_index,
                                      self.trunc_value)
        if ntrunc:
            if ntrunc <= self.max_columns:
                if self.kernel is None:
                    self.kernel = _wrapped_kernel(self.op)
                _add_columns(f["u"], self.kernel, self.op.grid.nx, self.trunc_index, self.trunc_value, ntrunc)
            else:
                self.op.normal(self.p, out=self.u)
                self.reuses = 0  # u is exact again
            if self.deflate:
                scale = self.force / (self.dA * psum)
                self.p *= scale
                self.u *= scale
                p2 *= scale * scale
        return ntrunc, dp2, p2

    def _residual(self):
        """New residual r = -e on C (the old one kept for Polak-Ribiere), the approach d, and the exterior
        elements with e < 0 entering C. Returns (elements entered, max_C |e|, max_C u)."""
        f = self.flat
        self.r, self.r_prev = self.r_prev, self.r
        f["r"], f["r_prev"] = f["r_prev"], f["r"]
        self.d, entered, emax, umax = _residual_and_entries(f["u"], f["h"], self.target, f["active"], f["r"],
                                                            self.deflate, True)
        return entered, emax, umax


def _not_converged(cg, params, residual):
    """The ConvergenceError of a solve that ran out of iterations (or whose residual is not finite)."""
    active = cg.active
    ncon = int(np.count_nonzero(active))
    edge = bool(active[0].any() or active[-1].any() or active[:, 0].any() or active[:, -1].any())
    regime = (f"{'force' if cg.deflate else 'approach'} prescribed, {ncon} of {active.size} elements in "
              f"contact, last iteration changed the contact set: {cg.changed}"
              + ("; the contact reaches the grid edge (grid too small?)" if edge else ""))
    return ConvergenceError(f"NormCG did not reach tol within max_iter = {params.max_iter} iterations",
                            solver="normal", iterations=cg.iterations, residual=float(residual), tol=params.tol,
                            regime=regime)


def _result(h, extra, p, u, d, dA, iterations, residual) -> NormalResult:
    """Assemble the output fields; u is A p on entry (extra displacement added here)."""
    displacement = u if extra is None else u + extra
    gap = h - d + displacement
    return NormalResult(pressure=p, approach=float(d), displacement=displacement, gap=gap,
                        contact=p > 0.0, force=float(p.sum() * dA), iterations=int(iterations),
                        residual=float(residual), converged=True)
