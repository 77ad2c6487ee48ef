"""Restarted GMRES with right preconditioning, for the non-symmetric systems of steady viscoelastic rolling (Saad &
Schultz 1986, SIAM J. Sci. Stat. Comput. 7:856-869; Saad 2003, Iterative Methods for Sparse Linear Systems, §9.3.2).

Solves A x = b for a linear operator given as a function on flat float64 vectors; M approximates A^-1 (applied to the
Krylov vectors: the residual it minimises is the true one, so the stopping rule needs no preconditioned norm).
"""
from __future__ import annotations

import math

import numpy as np


def _dot(a, b) -> float:
    """a . b by numpy's own loop (einsum): BLAS's threaded dot took milliseconds on a loaded 2-core machine."""
    return float(np.einsum("i,i->", a, b))


def _norm(a) -> float:
    return math.sqrt(_dot(a, a))


def gmres(apply, precondition, b, x0=None, *, tol=1e-8, max_products=500, restart=50):
    """x, products, relative residual |b - A x| / |b| after GMRES(restart) from x0 (default 0), stopped when the
    relative residual is <= tol or after max_products applications of A (then the caller decides what to do)."""
    b = np.asarray(b, dtype=float)
    n = b.size
    x = np.zeros(n) if x0 is None else np.array(x0, dtype=float)
    bnorm = _norm(b)
    if bnorm == 0.0:
        return np.zeros(n), 0, 0.0
    products = 0
    r = b - apply(x) if np.any(x) else b.copy()
    products += 1 if np.any(x) else 0
    beta = _norm(r)
    while beta > tol * bnorm and products < max_products:
        m = min(restart, max_products - products)
        V = np.empty((m + 1, n))
        Z = np.empty((m, n))
        H = np.zeros((m + 1, m))
        cs, sn = np.zeros(m), np.zeros(m)
        g = np.zeros(m + 1)
        g[0] = beta
        V[0] = r / beta
        k_done = 0
        for k in range(m):
            Z[k] = precondition(V[k])
            w = apply(Z[k])
            products += 1
            for i in range(k + 1):                      # modified Gram-Schmidt
                H[i, k] = _dot(w, V[i])
                w -= H[i, k] * V[i]
            H[k + 1, k] = _norm(w)
            if H[k + 1, k] > 0.0:
                V[k + 1] = w / H[k + 1, k]
            for i in range(k):                          # previous rotations
                t = cs[i] * H[i, k] + sn[i] * H[i + 1, k]
                H[i + 1, k] = -sn[i] * H[i, k] + cs[i] * H[i + 1, k]
                H[i, k] = t
            denom = math.hypot(H[k, k], H[k + 1, k])
            cs[k], sn[k] = (1.0, 0.0) if denom == 0.0 else (H[k, k] / denom, H[k + 1, k] / denom)
            H[k, k] = cs[k] * H[k, k] + sn[k] * H[k + 1, k]
            H[k + 1, k] = 0.0
            g[k + 1] = -sn[k] * g[k]
            g[k] = cs[k] * g[k]
            k_done = k + 1
            if abs(g[k + 1]) <= tol * bnorm or H[k, k] == 0.0:
                break
        y = np.zeros(k_done)
        for i in range(k_done - 1, -1, -1):             # back substitution
            y[i] = (g[i] - _dot(H[i, i + 1:k_done], y[i + 1:])) / H[i, i] if H[i, i] != 0.0 else 0.0
        x += np.einsum("k,kn->n", y, Z[:k_done])
        r = b - apply(x)
        products += 1
        beta = _norm(r)
        if k_done == 0:
            break
    return x, products, beta / bnorm
