"""Preconditioner of the tangential solver's linearised stick/slip operator (numba element loops).

Inside a fixed division the solver (`solver.tangential`) runs CG on K = P (A + kappa) P: P = identity in stick
and t t^T in slip (t the slip tangent), A = A^tt the influence operator and kappa = max(-s.n, 0)/g >= 0 the
curvature of turning a slip traction of fixed length (mm/MPa). kappa is a local stiffness that varies from 0 at
the stick edge to far above the self coefficient a_tt where g -> 0 (the contact edge, and most of the slip area
near full sliding). For a constant kappa the ideal preconditioner is the Strang-circulant inverse of A + kappa I:
like A^-1 on smooth residuals (whose stiffness, the symbol of A, dwarfs kappa) and like 1/(a_tt + kappa) on the
element scale. The preconditioner is

    z = Pi ( sum_l W_l P M_l P W_l r + D r ),   M_l = circulant inverse of A + kappa_l I (`op.tangential_inverse`),

with Pi the deflation of the force constraint (prescribed force only). Two forms:

* two-term (one circulant, M_0 = A^-1): W_0 = a_tt/(a_tt + kappa), D = kappa/(a_tt + kappa)^2 on slip elements
  (1 and 0 in stick). The diagonal of a slip element is 1/(a_tt + kappa), the inverse of its own stiffness for
  turning, and its coupling to the others fades with kappa.
* shifted levels (contacts of MIN_CONTACT_ELEMENTS and more): kappa_l = LEVELS[l] a_ref (a_ref the mean self
  coefficient), W_l = sqrt(w_l) with w_l hat functions in log(1 + kappa/a_tt) (stick elements and slip
  elements with kappa = 0 have w_0 = 1); above the last level the weight passes to D = w_diag/(a_tt + kappa)
  over BLEND. The two-term form weights the smooth residuals of slip elements with kappa ~ a_tt by
  D ~ 1/(4 a_tt), far above the inverse symbol of A, and conditions these modes badly on wide slip rings; the
  shifted level takes them. On the Cattaneo scene (benchmarks/tangential_cattaneo.py) it needs a quarter to a
  half fewer products in warm steps at 217^2 and 511^2 (counted without the lagged projected steps of
  `solver.tangential._tangcg`, which lower every count: after a load / profile change 22 / 26 and 28 / 37
  against 31 / 40 and 59 / 83 with the two-term form), for one more circulant (a quarter of a product) per
  iteration; on smaller contacts that does not pay in time (MIN_CONTACT_ELEMENTS). A third level
  (kappa = 64 a_ref) helps only at f_t = 0.999 and is not used.

Both are symmetric in r and positive definite (sums of W M W with M positive definite, D >= 0), so CG applies
unchanged.
"""
import math

import numpy as np

from rollcontact.bem.compiled import inline, kernel

# LEVELS, BLEND (and _P, _N) are compile-time constants of the cached numba kernels: change them here, in the
# source (which invalidates the cache), not by patching the module at run time. MIN_CONTACT_ELEMENTS is read
# in Python and may be patched.
#: kappa_l / a_ref of the circulant levels (level 0 is the plain inverse of A^tt).
LEVELS = (0.0, 4.0)
#: width, in log(1 + kappa/a_tt), over which the last level hands the weight to the diagonal.
BLEND = 1.4
#: the shifted levels (l >= 1) are used only on contacts of at least this many elements (a/dx ~ 70). Each level
#: costs about a quarter of a product per iteration. Single-thread time, shifted / two-term form, on the Cattaneo
#: scene (benchmarks/tangential_cattaneo.py): 217^2 (28849 contact elements) cold 1.07, warm load 0.81, profile
#: 0.72; 511^2 about 0.7 / 0.5 / 0.5; but 109^2 (7221) cold 1.20, warm 0.93-0.96, and a coupled step at
#: a/dx = 40 (about 5000) 1.09-1.17, with 5-25 % fewer products; on 55^2 (1801) no fewer products at all.
MIN_CONTACT_ELEMENTS = 16000
_P = tuple(math.log1p(x) for x in LEVELS)
_N = len(LEVELS)


@inline
def a_tt(nrm, axx, ayy, j, i):
    """Self coefficient along the slip tangent t = (-n_y, n_x) of element (j, i): t^T diag(a_xx, a_yy) t
    (a copy, `_linearised._a_tt`, lives there: numba's cache is per file)."""
    return axx * nrm[1, j, i] * nrm[1, j, i] + ayy * nrm[0, j, i] * nrm[0, j, i]


@inline
def _weight(rho, level):
    """Weight w_level of an element with rho = kappa/a_tt (level _N is the diagonal); the weights sum to 1."""
    p = math.log1p(rho)
    last = _N - 1
    if p >= _P[last]:
        t = min((p - _P[last]) / BLEND, 1.0)
        if level == _N:
            return t
        return 1.0 - t if level == last else 0.0
    for lv in range(last):
        if p < _P[lv + 1]:
            t = (p - _P[lv]) / (_P[lv + 1] - _P[lv])
            if level == lv:
                return 1.0 - t
            return t if level == lv + 1 else 0.0
    return 0.0


#: forms of the preconditioner (`mode` of the kernels)
PLAIN, TWO_TERM, SHIFTED = 0, 1, 2


@inline
def _slip_weights(nrm, kappa, axx, ayy, j, i, mode, level):
    """(W_level, D) of slip element (j, i) in the given form (W is the factor applied on both sides of M_level)."""
    if mode == PLAIN:
        return (1.0 if level == 0 else 0.0), 0.0
    kk = kappa[j, i]
    att = a_tt(nrm, axx, ayy, j, i)
    if mode == TWO_TERM:
        return (att / (att + kk) if level == 0 else 0.0), kk / ((att + kk) * (att + kk))
    rho = kk / att
    return math.sqrt(_weight(rho, level)), _weight(rho, _N) / (att + kk)


@kernel("void(f8[:, :, ::1], i1[:, ::1], f8[:, ::1], f8, f8, f8[:, :, ::1], i8, i8, f8[:, :, ::1])")
def inputs(nrm, region, kappa, axx, ayy, res, mode, level, out):
    """out = W_level res (res is already P r: tangential in slip; W = 1 in stick for level 0, else 0)."""
    ny, nx = region.shape
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            wt = 0.0
            if r == 1:
                wt = 1.0 if level == 0 else 0.0
            elif r == 2:
                wt = _slip_weights(nrm, kappa, axx, ayy, j, i, mode, level)[0]
            out[0, j, i] = wt * res[0, j, i]
            out[1, j, i] = wt * res[1, j, i]


@kernel("UniTuple(f8, 2)(f8[:, :, ::1], i1[:, ::1], f8[:, ::1], f8, f8, f8[:, :, ::1], i8, f8[:, :, ::1], "
        "f8[:, :, :, ::1], b1, f8, f8, f8, f8[:, :, ::1])")
def combine(nrm, region, kappa, axx, ayy, res, mode, z, bufs, deflate, gxx, gxy, gyy, q_prev):
    """z <- Pi (sum_l W_l P M_l P W_l res + D res) from the levels' outputs (level 0 in z, level l >= 1 in
    bufs[l - 1], used in the SHIFTED form only); returns (res.z, z.q_prev), the preconditioned residual norm and
    the numerator of the conjugation coefficient.

    Pi z = z - C G^-1 C^T z with C = [P e_x, P e_y] (the force-constraint vectors restricted to the free
    directions) and G = C^T C (from `gram_and_fit`); applied only if deflate (prescribed force).
    """
    ny, nx = region.shape
    cx = 0.0
    cy = 0.0
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r == 0:
                z[0, j, i] = 0.0
                z[1, j, i] = 0.0
                continue
            if r == 2:
                tx = -nrm[1, j, i]
                ty = nrm[0, j, i]
                w0, d = _slip_weights(nrm, kappa, axx, ayy, j, i, mode, 0)
                ft = d * (tx * res[0, j, i] + ty * res[1, j, i]) + w0 * (tx * z[0, j, i] + ty * z[1, j, i])
                if mode == SHIFTED:
                    for lv in range(1, _N):
                        wl = _slip_weights(nrm, kappa, axx, ayy, j, i, mode, lv)[0]
                        ft += wl * (tx * bufs[lv - 1, 0, j, i] + ty * bufs[lv - 1, 1, j, i])
                z[0, j, i] = tx * ft
                z[1, j, i] = ty * ft
            cx += z[0, j, i]
            cy += z[1, j, i]
    det = gxx * gyy - gxy * gxy
    lx = ly = 0.0
    if deflate and det > 1e-300:
        lx = (gyy * cx - gxy * cy) / det
        ly = (-gxy * cx + gxx * cy) / det
    rz = 0.0
    zq = 0.0
    for j in range(ny):
        for i in range(nx):
            r = region[j, i]
            if r == 0:
                continue
            if r == 1:
                z[0, j, i] -= lx
                z[1, j, i] -= ly
            else:
                tx = -nrm[1, j, i]
                ty = nrm[0, j, i]
                lt = tx * lx + ty * ly
                z[0, j, i] -= tx * lt
                z[1, j, i] -= ty * lt
            rz += res[0, j, i] * z[0, j, i] + res[1, j, i] * z[1, j, i]
            zq += z[0, j, i] * q_prev[0, j, i] + z[1, j, i] * q_prev[1, j, i]
    return rz, zq


class Preconditioner:
    """The buffers of one solve (allocated once) and `apply`, z = Pi (sum_l W_l P M_l P W_l r + D r)."""

    def __init__(self, op, shape, n_contact):
        ny, nx = shape
        self.op = op
        self.mode = SHIFTED if (n_contact >= MIN_CONTACT_ELEMENTS and _N > 1) else TWO_TERM
        self.bufs = np.zeros((max(_N - 1, 1), 2, ny, nx)) if self.mode == SHIFTED else np.zeros((1, 2, 1, 1))
        self.shifts = [rho * 0.5 * (op.self_coefficients["xx"] + op.self_coefficients["yy"]) for rho in LEVELS]

    @property
    def shifted(self):
        return self.mode == SHIFTED

    def apply(self, nrm, region, kappa, axx, ayy, res, z, deflate, gram, q_prev, levels=True):
        """z = Pi (sum_l W_l P M_l P W_l res + D res); returns (res.z, z.q_prev). levels=False: z = Pi res (the
        fallback when the preconditioner has lost definiteness)."""
        gxx, gxy, gyy = gram
        if not levels:
            z[...] = res
            return combine(nrm, region, kappa, axx, ayy, res, PLAIN, z, self.bufs, deflate, gxx, gxy, gyy, q_prev)
        mode = self.mode
        inputs(nrm, region, kappa, axx, ayy, res, mode, 0, z)
        self.op.tangential_inverse(z[0], z[1], out=z)
        if mode == SHIFTED:
            for level in range(1, _N):
                f = self.bufs[level - 1]
                inputs(nrm, region, kappa, axx, ayy, res, mode, level, f)
                self.op.tangential_inverse(f[0], f[1], out=f, shift=self.shifts[level])
        return combine(nrm, region, kappa, axx, ayy, res, mode, z, self.bufs, deflate, gxx, gxy, gyy, q_prev)
