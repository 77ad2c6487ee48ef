"""Non-quadratic undeformed distances (IBASE = 2, 3, 9) as a sampled profile, `[geometry] shape = "file"`.

IBASE = 2: a body of revolution, h = p(y) + (x - XM)^2 / (2 RM) with p interpolated linearly between NN heights from
Y1 in steps DY1 (and extrapolated linearly); IBASE = 3: h = B1 sin(B2 (x - B3)) - B4 sin(B5 (x - B6)) + x^2/B7 +
y^2/B8; IBASE = 9: h given at every element's centre (element I = ix + (iy - 1) MX). The profile is sampled at the
deck's element centres, over the potential contact and beyond it (three times its half-widths, so that rollcontact's
estimate of the contact and its margin lie inside the file): the analytic forms are evaluated there, the given
values of IBASE = 9 extended by linear extrapolation from the edge (where the deck allows no contact; the note says
so). The file's origin is the element of least h, the contact's centre for the kinematics. Units: mm.
"""
from __future__ import annotations

import numpy as np

from rollcontact.cases.decks.case import Case
from rollcontact.cases.decks.draft import Draft

#: how far the sampled profile reaches, in half-widths of the deck's potential contact about its centre
REACH = 3.0


def sampled_profile(case: Case, d: Draft, xl: float, yl: float, dx: float, dy: float, mx: int, my: int):
    """(x, y, h, (x0, y0)) of the deck's undeformed distance on its lattice (x, y relative to (x0, y0)), or None after
    a refusal."""
    if mx < 2 or my < 2:
        d.refuse("MX, MY", f"{mx} x {my}", "needs a 2D (line) contact: one element across", case.line_of("MX"))
        return None
    xc = xl + (np.arange(mx) + 0.5) * dx
    yc = yl + (np.arange(my) + 0.5) * dy
    ibase = case.value("IBASE")
    if ibase == 9:
        h0 = np.asarray(case.value("H"), dtype=float).reshape(my, mx)
    else:
        h0 = _analytic(case, *np.meshgrid(xc, yc))
    iy, ix = np.unravel_index(np.argmin(h0), h0.shape)
    x0, y0 = float(xc[ix]), float(yc[iy])
    half_x = max(x0 - xc[0], xc[-1] - x0) + dx / 2
    half_y = max(y0 - yc[0], yc[-1] - y0) + dy / 2
    kx = np.arange(-int(np.ceil(REACH * half_x / dx)), int(np.ceil(REACH * half_x / dx)) + 1)
    ky = np.arange(-int(np.ceil(REACH * half_y / dy)), int(np.ceil(REACH * half_y / dy)) + 1)
    x, y = kx * dx, ky * dy
    if ibase == 9:
        h = _extended(h0, xc - x0, yc - y0, x, y)
        d.note("the undeformed distance H given per element is extended beyond the deck's potential contact by "
               "linear extrapolation from its edge (where the deck allows no contact)")
    else:
        h = _analytic(case, *np.meshgrid(x + x0, y + y0))
    if not np.all(np.isfinite(h)):
        d.refuse(f"IBASE = {ibase}", None, "gives an undeformed distance that is not finite over the contact")
        return None
    return x, y, h, (x0, y0)


def _analytic(case: Case, X, Y):
    b = case.value("B")
    if case.value("IBASE") == 3:
        with np.errstate(divide="ignore", invalid="ignore"):
            return (b[0] * np.sin(b[1] * (X - b[2])) - b[3] * np.sin(b[4] * (X - b[5])) + X ** 2 / b[6] +
                    Y ** 2 / b[7])
    heights = np.asarray(b, dtype=float)
    y1, dy1, xm, rm = case.value("Y1"), case.value("DY1"), case.value("XM"), case.value("RM")
    t = (Y - y1) / dy1
    k = np.clip(np.floor(t).astype(int), 0, len(heights) - 2)
    profile = heights[k] + (t - k) * (heights[k + 1] - heights[k])
    return profile + (X - xm) ** 2 / (2.0 * rm)


def _extended(h0, xs, ys, x, y):
    """h0 on (ys, xs) extended to (y, x) by linear extrapolation along each axis from the edge."""
    def along(values, src, dst, axis):
        values = np.moveaxis(values, axis, -1)
        lo = (values[..., 1] - values[..., 0]) / (src[1] - src[0])
        hi = (values[..., -1] - values[..., -2]) / (src[-1] - src[-2])
        out = np.empty(values.shape[:-1] + (len(dst),))
        for j, t in enumerate(dst):
            if t < src[0]:
                out[..., j] = values[..., 0] + lo * (t - src[0])
            elif t > src[-1]:
                out[..., j] = values[..., -1] + hi * (t - src[-1])
            else:
                out[..., j] = values[..., int(np.argmin(np.abs(src - t)))]
        return np.moveaxis(out, -1, axis)
    return along(along(h0, xs, x, 1), ys, y, 0)
