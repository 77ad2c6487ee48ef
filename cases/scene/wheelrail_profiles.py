"""Wheel and rail profile files of a [wheelrail] scene: reading them, their checksums (docs/wheelrail.md, "Profile
files"). Units: mm.

Formats, chosen by the file's extension:
    .prr, .prw   SIMPACK rail / wheel profile: the points between `point.begin` and `point.end`, with the file's own
                 processing options applied in SIMPACK's order (shift.y, shift.z; rotate; the bounds bound.y.min/max,
                 bound.z.min/max when min < max; mirror.y, mirror.z; the length unit units.len.f, lengths per metre),
                 its smoothing (approx.smooth) not; SIMPACK's z points downwards, so z is negated. The header's `type`
                 (0 rail, 1 wheel) must match the key the file is given for.
    any other    two columns y, z (mm) per line, separated by a comma, semicolon or white space; blank lines, lines
                 starting with #, % or ! and a leading header line of text are skipped.
The result follows the project's convention: y lateral, positive towards the field side, z upwards (the rail's
top surface; the wheel's running surface relative to its rolling circle, the flange at z < 0), y strictly
increasing (a file listed the other way round is reversed). Refused with SceneError naming the key: a file that
is missing or unreadable, has fewer than 4 points or values that are not finite, whose y turns back (the profile
must be a function z(y): cut overhanging side faces off), or a wheel whose flange (its lowest point) lies on the
field side (y > 0: the file is mirrored; for SIMPACK set mirror.y). A file is read once per checksum.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rollcontact.bem.errors import SceneError
from rollcontact.cases.scene.profile_file import sha256_of

_CACHE: dict = {}
#: the SIMPACK header `type` of each key
_SIMPACK_TYPE = {"wheel_profile": 1, "rail_profile": 0}


def read_profile(path: str, key: str) -> tuple[np.ndarray, np.ndarray, str]:
    """(y, z, sha256) of the profile file `path` given as [wheelrail] `key` ('wheel_profile' or 'rail_profile')."""
    label = f"[wheelrail] {key} = {path!r}"
    p = Path(path)
    if not p.is_file():
        raise SceneError(f"{label}: no such file")
    try:
        digest = sha256_of(path)
    except OSError as exc:
        raise SceneError(f"{label}: cannot be read ({exc.strerror})") from None
    if (path, key, digest) in _CACHE:
        return _CACHE[(path, key, digest)]
    try:
        text = p.read_text(errors="replace")
    except OSError as exc:
        raise SceneError(f"{label}: cannot be read ({exc.strerror})") from None
    if p.suffix.lower() in (".prr", ".prw"):
        y, z = _simpack(text, label, key)
    else:
        y, z = _columns(text, label)
    y, z = _increasing(y, z, label)
    if key == "wheel_profile" and y[int(np.argmin(z))] > 0:
        raise SceneError(f"{label}: the flange (the lowest point, z = {z.min():.4g} mm) lies at y = "
                         f"{y[int(np.argmin(z))]:.4g} mm > 0; a wheel profile has its flange towards the track centre "
                         "(y < 0): mirror the file's y (SIMPACK: mirror.y = 1)")
    _CACHE[(path, key, digest)] = (y, z, digest)
    return y, z, digest


def _columns(text: str, label: str):
    rows, header_done = [], False
    for number, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s[0] in "#%!":
            continue
        parts = s.replace(",", " ").replace(";", " ").split()
        try:
            values = [float(v) for v in parts]
        except ValueError:
            if not rows and not header_done:
                header_done = True          # one header line of text
                continue
            raise SceneError(f"{label}: line {number} is not two numbers y, z: {s[:60]!r}") from None
        if len(values) != 2:
            raise SceneError(f"{label}: line {number} has {len(values)} values; expected two columns y, z (mm)")
        rows.append(values)
    if not rows:
        raise SceneError(f"{label}: no profile points (expected two columns y, z in mm)")
    a = np.array(rows)
    return a[:, 0], a[:, 1]


def _simpack(text: str, label: str, key: str):
    """Points and options of a SIMPACK profile (module docstring)."""
    options, points, blocks = {}, [], []
    for number, raw in enumerate(text.splitlines(), 1):
        line = raw.split("!", 1)[0].strip()
        if not line:
            continue
        if line.endswith(".begin") and "=" not in line:
            blocks.append(line[:-len(".begin")])
            continue
        if line.endswith(".end") and "=" not in line:
            blocks = blocks[:-1]
            continue
        if blocks and blocks[-1] == "point":
            try:
                values = [float(v) for v in line.replace(",", " ").split()]
            except ValueError:
                raise SceneError(f"{label}: line {number} in point.begin ... point.end is not numbers") from None
            if len(values) not in (2, 3):
                raise SceneError(f"{label}: line {number}: expected y, z (and a weight), got {len(values)} values")
            points.append(values[:2])
        elif "=" in line:
            name, _, value = line.partition("=")
            options[".".join(blocks + [name.strip()])] = value.strip().strip("'\"")
    if not points:
        raise SceneError(f"{label}: no point.begin ... point.end block: not a SIMPACK profile")

    def number(name, default):
        try:
            return float(options.get("spline." + name, default))
        except ValueError:
            raise SceneError(f"{label}: {name} = {options['spline.' + name]!r} is not a number") from None

    kind = options.get("header.type")
    if kind is not None and kind.strip() in ("0", "1") and int(kind) != _SIMPACK_TYPE[key]:
        what = {0: "rail", 1: "wheel"}[int(kind)]
        raise SceneError(f"{label}: a SIMPACK {what} profile (type = {kind}), given for {key}")
    a = np.array(points, dtype=float)
    y = a[:, 0] + number("shift.y", 0.0)
    z = a[:, 1] + number("shift.z", 0.0)
    angle = number("rotate", 0.0) / number("units.ang.f", 1.0)
    if angle:
        c, s = np.cos(angle), np.sin(angle)
        y, z = c * y - s * z, s * y + c * z
    keep = np.ones(y.size, dtype=bool)
    for name, v in (("y", y), ("z", z)):
        lo, hi = number(f"bound.{name}.min", 1.0), number(f"bound.{name}.max", 0.0)
        if lo < hi:
            keep &= (v >= lo) & (v <= hi)
    y, z = y[keep], z[keep]
    if int(number("mirror.y", 0)) == 1:
        y = -y
    if int(number("mirror.z", 0)) == 1:
        z = -z
    scale = 1000.0 / number("units.len.f", 1000.0)
    return y * scale, -z * scale


def _increasing(y, z, label):
    """y, z with y strictly increasing (reversed if the file lists it decreasing); SceneError otherwise."""
    if y.size < 4:
        raise SceneError(f"{label}: {y.size} points; a profile needs at least 4")
    for name, v in (("y", y), ("z", z)):
        if not np.all(np.isfinite(v)):
            raise SceneError(f"{label}: {name} is not finite at point {int(np.flatnonzero(~np.isfinite(v))[0])}")
    if y[-1] < y[0]:
        y, z = y[::-1], z[::-1]
    bad = np.flatnonzero(np.diff(y) <= 0)
    if bad.size:
        i = int(bad[0])
        raise SceneError(f"{label}: y turns back (or repeats) at y = {y[i]:.6g}, {y[i + 1]:.6g} mm: the profile must "
                         "be a function z(y) with y strictly monotone; cut overhanging side faces off, and join "
                         "repeated points")
    return np.ascontiguousarray(y), np.ascontiguousarray(z)
