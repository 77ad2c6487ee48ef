"""`[geometry] shape = "file"`: a measured or designed profile h(x, y) read from a file, its checksum, and an
estimate of its contact size. Units mm, N, MPa.

Formats (x, y relative to the body's centre, h the gap of the undeformed profile, mm):
    .npz   arrays x (nx,), y (ny,) strictly increasing, h (ny, nx)
    .npy   an (N, 3) array of rows x, y, h on a regular grid (every (x, y) pair once, any order)
    .csv   the same rows, comma-separated, an optional header line
The profile is interpolated (cubic, `solver.rolling.profiles.ArrayProfile`) and moves with the centre. The file's
SHA-256 is the scene key `geometry.sha256`: filled in when a scene leaves it out, so that the scene stored in a
run file names the file and its checksum, and checked when given (a stored scene refuses a changed file).

Contact size (for the default grid a/12, the grid's extent and the unit of w): the MDR contact radius under Fn
of the profile's lower radial envelope f(r) = min over the samples at distance >= r of (h - h_min) (a body of
revolution at most as high as the profile in every direction, so its contact is at least as wide; an estimate,
the run still stops with ContactEdgeError if a contact reaches the grid's edge). The file must cover every point
the run evaluates relative to the centre: the contact box (the estimate + 10 %) plus the grid margin plus twice
the rolling amplitude (the world-fixed grid spans +-W around the centre's mean position).
"""
from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from rollcontact.bem.errors import SceneError

_CACHE: dict = {}


def sha256_of(path: str) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def read_profile_file(path: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """(x, y, h, sha256) of a profile file; SceneError naming [geometry] path for a missing, unreadable, not finite
    or irregular one. Cached by path and checksum."""
    key = "[geometry] path"
    p = Path(path)
    if not p.is_file():
        raise SceneError(f"{key} = {path!r}: no such file")
    digest = sha256_of(path)
    if (path, digest) in _CACHE:
        return _CACHE[(path, digest)]
    try:
        if p.suffix == ".npz":
            with np.load(p) as data:
                x, y, h = (np.asarray(data[k], dtype=float) for k in ("x", "y", "h"))
        elif p.suffix in (".npy", ".csv"):
            rows = (np.load(p) if p.suffix == ".npy" else _read_csv(p)).astype(float)
            x, y, h = _gridded(rows, path)
        else:
            raise SceneError(f"{key} = {path!r}: allowed formats are .npz (x, y, h), .npy or .csv (rows x, y, h)")
    except SceneError:
        raise
    except (OSError, ValueError, KeyError) as exc:
        raise SceneError(f"{key} = {path!r}: not a profile file ({exc})") from None
    if x.ndim != 1 or y.ndim != 1 or h.shape != (y.size, x.size) or x.size < 4 or y.size < 4:
        raise SceneError(f"{key} = {path!r}: expected x (nx,), y (ny,), h (ny, nx) with nx, ny >= 4, got "
                         f"{x.shape}, {y.shape}, {h.shape}")
    for name, v in (("x", x), ("y", y), ("h", h)):
        if not np.all(np.isfinite(v)):
            raise SceneError(f"{key} = {path!r}: {name} is not finite everywhere")
    if np.any(np.diff(x) <= 0) or np.any(np.diff(y) <= 0):
        raise SceneError(f"{key} = {path!r}: x and y must be strictly increasing")
    _CACHE[(path, digest)] = (x, y, h, digest)
    return x, y, h, digest


def _read_csv(p: Path) -> np.ndarray:
    """The rows of a .csv profile (a header line skipped); SceneError for a file without rows (numpy would only
    warn)."""
    with open(p) as f:
        lines = [ln for ln in f.read().splitlines() if ln.strip()]
    skip = 0 if lines and _numeric(lines[0]) else 1
    if len(lines) <= skip:
        raise SceneError(f"[geometry] path = {str(p)!r}: holds no rows of x, y, h (an empty file, or a header only)")
    return np.loadtxt(p, delimiter=",", skiprows=skip, ndmin=2)


def _numeric(line: str) -> bool:
    try:
        [float(v) for v in line.split(",")]
        return True
    except ValueError:
        return False


def _gridded(rows, path):
    if rows.ndim != 2 or rows.shape[1] != 3:
        raise SceneError(f"[geometry] path = {path!r}: expected rows of x, y, h (shape (N, 3)), got {rows.shape}")
    x, ix = np.unique(rows[:, 0], return_inverse=True)
    y, iy = np.unique(rows[:, 1], return_inverse=True)
    if rows.shape[0] != x.size * y.size:
        raise SceneError(f"[geometry] path = {path!r}: the rows are not a regular grid ({rows.shape[0]} rows for "
                         f"{x.size} x values and {y.size} y values)")
    h = np.full((y.size, x.size), np.nan)
    h[iy, ix] = rows[:, 2]
    return x, y, h


def envelope_contact_radius(x, y, h, E_star: float, Fn: float, key=None) -> float:
    """MDR contact radius (mm) of the lower radial envelope of h under Fn (module docstring); cached under `key`
    (e.g. the file's checksum) when given."""
    if key is not None and (key, E_star, Fn) in _CACHE:
        return _CACHE[(key, E_star, Fn)]
    a = _envelope_radius(x, y, h, E_star, Fn)
    if key is not None:
        _CACHE[(key, E_star, Fn)] = a
    return a


def _envelope_radius(x, y, h, E_star, Fn):
    X, Y = np.meshgrid(x, y)
    r = np.hypot(X, Y).ravel()
    order = np.argsort(r)[::-1]
    f = np.minimum.accumulate((h.ravel() - h.min())[order])[::-1]   # min over the samples at distance >= r
    r = r[order][::-1]
    ds = max(min(np.diff(x).min(), np.diff(y).min()) / 4, r.max() / 2000)   # at most 2000 x 2000 below
    s = np.arange(1, int(r.max() / ds) + 1) * ds
    fk = np.interp(s, r, f)
    slope = np.diff(np.concatenate(([0.0], fk))) / ds                # f' on (s_{k-1}, s_k)
    lo = np.concatenate(([0.0], s[:-1]))
    # g(s_j) = s_j sum_k f'_k [asin(min(s_k, s_j)/s_j) - asin(min(s_{k-1}, s_j)/s_j)]
    ratio_hi = np.minimum(s[None, :], s[:, None]) / s[:, None]
    ratio_lo = np.minimum(lo[None, :], s[:, None]) / s[:, None]
    g = s * ((np.arcsin(ratio_hi) - np.arcsin(ratio_lo)) @ slope)
    G = np.concatenate(([0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(s))))
    force = 2.0 * E_star * (s * g - G)
    if force[-1] < Fn:
        raise SceneError(f"[geometry] path: the profile's samples (up to r = {r.max():.4g} mm from the centre) do "
                         f"not reach the contact that carries Fn = {Fn:.6g} N; the file must cover a larger region")
    return float(np.interp(Fn, force, s))


def check_coverage(x, y, need_x: float, need_y: float, path: str):
    """SceneError unless the file's samples cover |x| <= need_x and |y| <= need_y (mm, relative to the centre)."""
    if x[0] > -need_x or x[-1] < need_x or y[0] > -need_y or y[-1] < need_y:
        raise SceneError(
            f"[geometry] path = {path!r}: the profile covers x in [{x[0]:.4g}, {x[-1]:.4g}], y in [{y[0]:.4g}, "
            f"{y[-1]:.4g}] mm; the run needs |x| <= {need_x:.4g} and |y| <= {need_y:.4g} mm about the centre "
            "(the estimated contact + 10 %, the grid margin and twice the rolling amplitude)")


def allowed_digest(given: str | None, digest: str, path: str):
    if given is not None and given != digest:
        raise SceneError(f"[geometry] sha256 = {given!r} does not match the file {path!r} (sha256 {digest}): the "
                         "file changed since the scene was written; restore it, or leave sha256 out to accept it")

