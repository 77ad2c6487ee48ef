"""What the tangential solver would need with perfect linear algebra: the same solver with an exact preconditioner.

    .venv/bin/python benchmarks/tangential_oracle.py [--dx 0.2 0.1]

The Cattaneo chains of `tangential_cattaneo.py` (cold f_t = 0.5 from zero; warm load f_t 0.5 -> 0.52; warm profile:
the pressure moved by one cell in y), solved twice at the default tolerance: with the solver's own preconditioner
(circulant inverses, `solver.tangential._preconditioner`) and with an oracle that replaces it by the exact inverse of the
linearised operator of the current division, K = B^T (A + kappa) B (B: both directions in stick, the slip tangent in
slip; kappa the turning curvature of slip tractions), with the force constraint eliminated exactly:

    z = K^-1 r - K^-1 C (C^T K^-1 C)^-1 C^T K^-1 r,   C = B^T [e_x, e_y].

K is assembled from the dense influence blocks (`op.tangential_block`) and factorised (Cholesky) at every
application, since the division and kappa change from one iteration to the next. Everything else (division
updates, projections, re-synchronisations, releases, the stopping rule) is the solver's own, so the oracle's
product count is what identifying the division costs when every linear solve on a division is exact. The two runs
must reach the same solution (region and traction within the tolerance; checked here).

The oracle is an experiment, not a method: one application costs a dense factorisation (reported below in units
of one `op.tangential` product measured in the same run). Memory grows as (2 n_contact)^2: 109^2 needs about 3 GB
and 4 minutes; 217^2 would need 50 GB. Product counts do not depend on the machine. JSON to
benchmarks/results/tangential_oracle.json.
"""
import contextlib
import statistics
import time

import numpy as np
import scipy.linalg as sla

from rollcontact.solver.tangential import _preconditioner as PC
from rollcontact.solver.tangential.shift import TangentialParams
from tangential_cattaneo import cattaneo_scene, median_time
from tangential_tolerance import chain, grids_main


class ExactPreconditioner(PC.Preconditioner):
    """z = exact solution of the linearised, force-constrained system of the current division (dense)."""

    blocks = None       # (xx, xy, yy) among the elements of `where` (set by `exact_preconditioner`)
    where = None        # grid index -> position in the blocks (-1 outside the contact union)
    times = []          # seconds per application

    def apply(self, nrm, region, kappa, axx, ayy, res, z, deflate, gram, q_prev, levels=True):
        if not levels:  # the solver's fallback after a loss of definiteness: keep its own
            return super().apply(nrm, region, kappa, axx, ayy, res, z, deflate, gram, q_prev, levels)
        t0 = time.perf_counter()
        xx, xy, yy = self.blocks
        stick, slip = np.nonzero(region == 1), np.nonzero(region == 2)
        s, l = self.where[stick], self.where[slip]
        tx, ty = -nrm[1][slip], nrm[0][slip]
        ns = s.size
        ix = np.ix_
        # A^tt is symmetric: the yx block is the transpose of the xy block
        k_ss = np.block([[xx[ix(s, s)], xy[ix(s, s)]], [xy[ix(s, s)].T, yy[ix(s, s)]]])
        k_sl = np.vstack([xx[ix(s, l)] * tx + xy[ix(s, l)] * ty, xy[ix(l, s)].T * tx + yy[ix(s, l)] * ty])
        k_ll = (tx[:, None] * (xx[ix(l, l)] * tx + xy[ix(l, l)] * ty)
                + ty[:, None] * (xy[ix(l, l)].T * tx + yy[ix(l, l)] * ty) + np.diag(kappa[slip]))
        k = np.block([[k_ss, k_sl], [k_sl.T, k_ll]])
        factor = sla.cho_factor(0.5 * (k + k.T))
        r = np.concatenate([res[0][stick], res[1][stick], tx * res[0][slip] + ty * res[1][slip]])
        y = sla.cho_solve(factor, r)
        if deflate:
            c = np.zeros((r.size, 2))
            c[:ns, 0] = c[ns:2 * ns, 1] = 1.0
            c[2 * ns:, 0], c[2 * ns:, 1] = tx, ty
            kc = sla.cho_solve(factor, c)
            y -= kc @ np.linalg.solve(c.T @ kc, c.T @ y)
        z[...] = 0.0
        z[0][stick], z[1][stick] = y[:ns], y[ns:2 * ns]
        z[0][slip], z[1][slip] = tx * y[2 * ns:], ty * y[2 * ns:]
        self.times.append(time.perf_counter() - t0)
        return float(np.vdot(res, z)), float(np.vdot(z, q_prev))


@contextlib.contextmanager
def exact_preconditioner(op, contact):
    """Within the block, every tangential solve uses `ExactPreconditioner` (dense over the elements of `contact`)."""
    rows, cols = np.nonzero(contact)
    where = -np.ones(contact.shape, dtype=np.intp)
    where[rows, cols] = np.arange(rows.size)
    ExactPreconditioner.blocks, ExactPreconditioner.where = op.tangential_block(rows, cols), where
    ExactPreconditioner.times = []
    saved, PC.Preconditioner = PC.Preconditioner, ExactPreconditioner
    try:
        yield ExactPreconditioner.times
    finally:
        PC.Preconditioner = saved
        ExactPreconditioner.blocks = ExactPreconditioner.where = None


def run(dx):
    grid, op, _, _, g, g2 = cattaneo_scene(dx)
    params = TangentialParams()
    tx, ty = np.random.default_rng(0).random((2,) + grid.shape)
    _, t_pair = median_time(lambda: op.tangential(tx, ty, out=np.empty((2,) + grid.shape)), 20)
    zero = np.zeros((2,) + grid.shape)
    own = chain(op, g, g2, zero, params)
    with exact_preconditioner(op, (g > 0) | (g2 > 0)) as times:
        exact = chain(op, g, g2, zero, params)
    row = {"dx_mm": dx, "grid": list(grid.shape), "pair_time_s": t_pair,
           "oracle_apply_time_s": statistics.median(times), "oracle_applications": len(times)}
    for name in own:
        a, b = own[name], exact[name]
        row[name] = {"products": a.iterations, "cg_steps": a.steps,
                     "oracle_products": b.iterations, "oracle_cg_steps": b.steps,
                     "stick_elements": int((a.region == 1).sum()),
                     "region_differs": int((a.region != b.region).sum()),
                     "traction_difference_rel_max_g": float(np.abs(a.traction - b.traction).max() / g.max())}
    print(f"{grid.shape[0]}^2: products (CG steps) cold / load / profile, own preconditioner "
          + " / ".join(f"{row[k]['products']} ({row[k]['cg_steps']})" for k in own)
          + ", exact " + " / ".join(f"{row[k]['oracle_products']} ({row[k]['oracle_cg_steps']})" for k in own)
          + "; regions differ in " + "/".join(str(row[k]["region_differs"]) for k in own)
          + " elements, tractions by " + "/".join(f"{row[k]['traction_difference_rel_max_g']:.1e}" for k in own)
          + f" max g; one exact application {row['oracle_apply_time_s']:.2f} s = "
          + f"{row['oracle_apply_time_s'] / t_pair:.0f} products", flush=True)
    return row


if __name__ == "__main__":
    grids_main(__doc__, "tangential_oracle", run, (0.2, 0.1))
