"""The cycling safeguard of the tangential solver (`solver.tangential._tangcg`, safeguard 1): steps of the accelerated
projected gradient method on one step's convex program (docs/theory.md §5.5), which never raise the energy and so leave
any cycle of the active-set iteration.

Tractions MPa, displacements mm; `it` is the `ProjectedTangCG` iteration whose workspace is used.
"""
import math

import numpy as np

from rollcontact.solver.tangential import _force_projection as FP


def gradient_phase(it, n):
    """n steps (one product each) of the accelerated projected gradient method (FISTA with adaptive restart,
    docs/theory.md §5.5) on the step's convex program, from the best exact iterate: tau <- P(y - grad(y)/L) with P
    the Euclidean projection onto the discs (and the force, `FP.project_on_force`), L = `op.tangential_norm`
    and y the extrapolated point. The energy never rises (a step that would raise it restarts the momentum
    instead), so it leaves any cycle of the active-set iteration. It converges slowly (docs/theory.md §5.5), but
    identifies the division: from a state at f_t = 0.95, the load f_t = 0.98 turned by 2 rad (217^2) cycled
    at an energy 6e-5 above the minimum for 500 products without it; from the plain start, 40 gradient steps
    and CG converge in 65 products, and with the safeguard's stall of 20 products and 20 steps in 117.
    Leaves u = A tau exact; the CG buffers serve as scratch."""
    ws, g, dU = it.ws, it.g, it.dU
    tau, u, u_prev = ws.tau, ws.u, ws.u_prev
    tau[...] = it.tau_best
    u[...] = it.u_best
    t_old, u_old, y, uy, tn, un = ws.v, ws.av, ws.z, ws.q, ws.d, ws.ad
    t_old[...] = tau
    u_old[...] = u
    step = 1.0 / it.op.tangential_norm()
    shift = None if it.force_mode else dU
    energy = it.energy
    j_cur, theta = energy(tau, u), 1.0
    for _ in range(max(n, 0)):
        theta_new = 0.5 * (1.0 + math.sqrt(1.0 + 4.0 * theta * theta))
        beta = (theta - 1.0) / theta_new
        np.subtract(tau, t_old, out=y)
        y *= beta
        y += tau
        np.subtract(u, u_old, out=uy)
        uy *= beta
        uy += u
        # y - grad/L with grad = A(y - tau') + e (- dU for a prescribed shift)
        uy -= u_prev
        if it.has_e:
            uy += it.e_arr
        if shift is not None:
            uy[0] -= shift[0]
            uy[1] -= shift[1]
        uy *= step
        y -= uy
        if it.force_mode:
            FP.project_on_force(y, g, it.f_cells, tn)
        else:
            tn[...] = y
            FP.project_discs(tn, g)
        it.matvec(tn, un)
        j_new = energy(tn, un)
        if j_new > j_cur:  # restart the momentum from the current iterate
            theta = 1.0
            t_old[...] = tau
            u_old[...] = u
            continue
        t_old[...] = tau
        u_old[...] = u
        tau[...] = tn
        u[...] = un
        j_cur, theta = j_new, theta_new
    it.synced = True
