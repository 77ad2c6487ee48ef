"""The Manchester Contact Benchmark, case A-2.2, against the reference program's published results (docs/wheelrail.md).

    .venv/bin/python benchmarks/wheelrail_mbench.py [--quick] [-o DIR] [--sweep-dir DIR]
    .venv/bin/python benchmarks/wheelrail_mbench.py --extract CONTACT_EXAMPLES_DIR   (maintenance, see below)

S1002 wheels on UIC60 rails inclined 1:40 (the benchmark's profiles, cases/data/wheelrail), 10 kN per wheel, mu = 0.3,
G = 82 GPa, nu = 0.28, V = 2 m/s; the wheelset displaced laterally by 0-10 mm in 0.5 mm steps and yawed by 0-24 mrad
with it (y and yaw together), with the roll angle and the angular velocity that CONTACT's authors found for the
balanced wheelset: the 21 cases of each of CONTACT's decks mbench_a22_left.inp and mbench_a22_right.inp, grid 0.2 x
0.2 mm as there. Each case is run as a [wheelrail] scene (the shipped scene mbench_s1002_uic60.toml with side, y,
yaw, roll and omega set) and compared with CONTACT's reference output (*.ref_out), transcribed in
tests/data/wheelrail/mbench_a22_contact.csv (CONTACT's own numbers and conventions: forces on the rail, z down,
left-side profile coordinates towards the track centre; `to_rollcontact` converts them). The benchmark paper's tables
(Shackleton & Iwnicki 2008) are not reproduced here: its results are given as figures; the comparison is with the
reference program's output for the same cases.

Printed and written to DIR (default results/wheelrail_mbench/): per case the contact position on the rail and the
wheel, contact angle, rolling radius, normal force, tangential forces, spin moment, peak pressure and the wheelset's
height, both codes, and the largest differences; the figure mbench_contact_points.png/.pdf (contact positions on
rail and wheel, the rolling radius difference of the wheelset r_left - r_right, against y, both codes) and
mbench.json. Also, per patch, the planar study (`planar_study`: the forces with the rigid slip on the actual surfaces
and with each row's forces turned by the rail's own angle there). Before that, the Hertz check of two crowns (the
test of tests/cases/test_wheelrail_run.py on two grids), and after it the shipped scene's sweep of wheelrail.y over
0-10 mm in 0.5 mm steps (run files in --sweep-dir, default results/wheelrail_sweep/) with its contact-point diagram
and forces (DIR/wheelrail_sweep_*.png). --quick: 6 benchmark cases and 5 sweep positions. docs/wheelrail.md's tables
and figures come from this command (with -o docs/figures/wheelrail).

--extract DIR writes tests/data/wheelrail/mbench_a22_contact.csv from DIR/mbench_a22_left.ref_out and
mbench_a22_right.ref_out (a checkout of github.com/eve70a/CONTACT, examples/; Apache License 2.0).
"""
from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path
import platform
import re
import time

import numpy as np

import rollcontact

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "tests" / "data" / "wheelrail" / "mbench_a22_contact.csv"
SCENE = ROOT / "cases" / "mbench_s1002_uic60.toml"
COLUMNS = ("side", "case", "y_ws", "yaw", "roll", "vpitch", "vx", "z_ws", "FX_tr", "FY_tr", "FZ_tr", "n_patches",
           "x_tr", "y_r", "z_r", "delta", "x_w", "y_w", "z_w", "veloc", "cksi", "ceta", "cphi", "FN", "FX", "FS",
           "MN", "approach", "pmax", "ncon")
QUICK = {("right", 3), ("right", 9), ("right", 17), ("left", 5), ("left", 13), ("left", 21)}


def parse_ref_out(path) -> list[dict]:
    """The cases of a CONTACT module-1 output file: wheelset state, total forces and the first patch's data."""
    lines = Path(path).read_text().splitlines()
    cases, case, patch = [], None, None

    def values(i):
        return [float(v) for v in lines[i + 1].split()]

    for i, line in enumerate(lines):
        m = re.match(r"\s*Case\s+(\d+)", line)
        if m:
            case = {"case": int(m.group(1)), "n_patches": 0}
            cases.append(case)
        elif "S_WS        Y_WS" in line:
            v = values(i)
            case.update(y_ws=v[1], z_ws=v[2], roll=v[3], yaw=v[4])
        elif "VX_WS" in line:
            v = values(i)
            case.update(vx=v[0], vpitch=v[5])
        elif "FX(TR)      FY(TR)" in line:
            case.update(zip(("FX_tr", "FY_tr", "FZ_tr"), values(i)[:3]))
        elif "DATA FOR CONTACT PATCH" in line:
            case["n_patches"] += 1
            patch = case if case["n_patches"] == 1 else {}
        elif "XCP(TR)     YCP(TR)" in line:
            patch.update(zip(("x_tr", "y_tr", "z_tr", "delta", "y_r", "z_r"), values(i)))
        elif "XCP(W)      YCP(W)" in line:
            patch.update(zip(("x_w", "y_w", "z_w"), values(i)))
        elif "CHI         DQ" in line:
            patch.update(zip(("veloc", "cksi", "ceta", "cphi"), values(i)[2:6]))
        elif re.match(r"\s*FN\s+FX\s+FS\s+MN", line):
            patch.update(zip(("FN", "FX", "FS", "MN"), values(i)[:4]))
        elif "APPROACH     PMAX" in line:
            patch.update(approach=values(i)[3], pmax=values(i)[4])
        elif "NPOT   NCON" in line:
            patch["ncon"] = values(i)[1]
    return cases


def extract(folder: Path):
    rows = []
    for side in ("left", "right"):
        for c in parse_ref_out(folder / f"mbench_a22_{side}.ref_out"):
            rows.append({"side": side, **c})
    REFERENCE.parent.mkdir(parents=True, exist_ok=True)
    with open(REFERENCE, "w", newline="") as fh:
        fh.write("# CONTACT (github.com/eve70a/CONTACT, Apache-2.0), examples/mbench_a22_{left,right}.ref_out, commit "
                 "d431cdb: the Manchester benchmark case A-2.2 as CONTACT solved it; CONTACT's conventions (forces on "
                 "the rail; z down; a left side's y_r, y_w towards the track centre). Written by "
                 "benchmarks/wheelrail_mbench.py --extract.\n")
        w = csv.DictWriter(fh, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"{len(rows)} cases written to {REFERENCE}")


def reference_cases() -> list[dict]:
    """The rows of the reference CSV, numbers parsed."""
    with open(REFERENCE) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    return [{k: (v if k == "side" else float(v)) for k, v in r.items()} for r in rows]


def scene_of(row, base=None):
    """The [wheelrail] scene of a reference case: CONTACT's y_ws (to the right) is the right wheel's y towards its
    field side and the left wheel's away from it; its yaw (about z down) is minus rollcontact's (about z up); roll
    (about x) is the same; its VPITCH (about the axle, y to the right) is minus omega."""
    base = base or rollcontact.load_scene(SCENE)
    sign = 1.0 if row["side"] == "right" else -1.0
    return base.with_overrides({"wheelrail.side": row["side"], "wheelrail.y": sign * row["y_ws"],
                                "wheelrail.yaw": -row["yaw"], "wheelrail.roll": row["roll"],
                                "wheelrail.omega": -row["vpitch"], "wheelrail.speed": row["vx"]})


def to_rollcontact(row) -> dict:
    """CONTACT's numbers of a case in rollcontact's conventions (forces on the wheel; profile y to the field side;
    z_ws up; the largest patch's values)."""
    sign = 1.0 if row["side"] == "right" else -1.0
    return {"y_rail": sign * row["y_r"], "y_wheel": sign * row["y_w"], "contact_angle": row["delta"],
            "Fn": row["FN"], "Fx": -row["FX"], "Fy": row["FS"], "Mz": row["MN"], "pmax": row["pmax"],
            "xi": -row["cksi"], "eta": row["ceta"], "phi": row["cphi"], "z_ws": -row["z_ws"],
            "F_track_x": -row["FX_tr"], "F_track_y": row["FY_tr"], "F_track_z": row["FZ_tr"],
            "n_patches": int(row["n_patches"])}


def ours(result) -> dict:
    """rollcontact's values of a case: its largest patch's and the totals."""
    s = result.summary
    k = int(np.argmax(s["patch_Fn"]))
    pick = {name: float(np.atleast_1d(s["patch_" + name])[k]) for name in
            ("y_rail", "y_wheel", "contact_angle", "rolling_radius", "Fn", "Fx", "Fy", "Mz", "pmax", "xi", "eta",
             "phi")}
    pick.update({name: float(s[name]) for name in ("z_ws", "F_track_x", "F_track_y", "F_track_z")})
    pick["n_patches"] = int(s["n_patches"])
    pick["cpu_time"] = float(s["cpu_time"])
    return pick


class _SurfaceSlip:
    """The steady problem of a patch with a given rigid slip field (2, ny, nx) in place of (xi - phi s, eta + phi x)."""

    def __init__(self, problem, field):
        self.__dict__.update(problem.__dict__)
        self._problem, self._field = problem, field

    def __getattr__(self, name):
        return getattr(self._problem, name)

    def rigid_slip(self, xi, eta, phi, pressure=None):
        return self._field.copy()


def planar_study(scene) -> list[dict]:
    """Where the planar patch errs: per patch of the scene, the forces with the rigid slip evaluated on the plane
    (what rollcontact and CONTACT's planar mode solve) and on the actual surfaces (the wheel's undeformed surface
    point of each cell, projected on the rail's local tangent there, as CONTACT's D = 3), on the same pressure; and the
    total force with each row's normal and tangential loads turned by the rail's local angle instead of the patch's
    one. Side frame (the right wheel mirrored); forces on the wheel, N."""
    from rollcontact.bem.grid import Grid
    from rollcontact.cases.scene import wheelrail as W
    from rollcontact.solver.creep.steady import SPIN_OFFSET, SteadyRolling, solve_steady
    from rollcontact.solver.wheelrail.patch import patch_gap, rail_distance
    from rollcontact.solver.wheelrail.solve import WheelRailParams, solve_wheel
    wr = scene.wheelrail
    rail, wheel = W.geometry(wr)
    omega_v = W.omega_per_speed(wr)
    pair, mu = scene.material_pair, scene.load.mu
    dx, dy = scene.spacing
    res = solve_wheel(rail, wheel, wr.side, wr.y, wr.Fz, omega_v, pair, mu, dx, dy, yaw=wr.yaw, roll=wr.roll,
                      params=WheelRailParams(tol=scene.solver.tol))
    sign = W.side_sign(wr)
    search = W.search(wr)
    wheel_now = search.wheel(res.dz)
    position = search.position(res.dz)
    out = []
    for p in res.patches:
        frame, g = p.frame, p.grid
        grid = g if sign > 0 else Grid(g.nx, g.ny, g.dx, g.dy, g.i0, -(g.j0 + g.ny - 1))
        flip = (lambda a: a) if sign > 0 else (lambda a: a[::-1])
        pressure = flip(p.pressure)
        X, S = grid.mesh()
        shifted = grid.x + SPIN_OFFSET * grid.dx
        rail_t = rail_distance(rail, frame, grid.y)
        _, t_w = patch_gap(rail_t, wheel_now, frame, shifted, grid.y)
        points = frame.point(X + SPIN_OFFSET * grid.dx, S) + t_w[None] * frame.e_n[:, None, None]
        spin = omega_v * position.axle
        v = np.cross(spin[:, None, None], points - position.centre[:, None, None], axis=0)
        v[0] += 1.0
        t0 = float(wheel_now.distance_along(frame.origin.reshape(3, 1), frame.e_n, start=[0.0])[0])
        carried = np.cross(spin, frame.origin + t0 * frame.e_n - position.centre)
        rolling = 0.5 * (1.0 - carried[0])
        c, s = math.cos(frame.angle), math.sin(frame.angle)
        y_rows = frame.origin[1] + grid.y * c - rail_t * s
        local = np.arctan(rail.surface.slope(y_rows))                   # the rail's angle below each row
        e_s = np.stack([np.zeros_like(local), np.cos(local), np.sin(local)])
        field = np.stack([v[0], np.einsum("ij,ijk->jk", e_s, v)]) / rolling
        problem = SteadyRolling(grid, pair)
        planar = solve_steady(problem, pressure, mu, *_side_creepages(p, sign))
        surface = solve_steady(_SurfaceSlip(problem, field), pressure, mu)
        rows_n = pressure.sum(axis=1) * grid.cell_area
        rows_s = planar.traction[1].sum(axis=1) * grid.cell_area
        turned_y = float(np.sum(rows_s * np.cos(local) - rows_n * np.sin(local)))
        turned_z = float(np.sum(rows_s * np.sin(local) + rows_n * np.cos(local)))
        flat_y = planar.force[1] * c - p.Fn * s
        flat_z = planar.force[1] * s + p.Fn * c
        out.append({"y_rail": p.y_rail, "angle": p.contact_angle, "spread": p.angle_spread, "Fn": p.Fn,
                    "dFx": surface.force[0] - planar.force[0], "dFs": surface.force[1] - planar.force[1],
                    "Fx": planar.force[0], "Fs": planar.force[1], "dFy_turn": turned_y - flat_y,
                    "dFz_turn": turned_z - flat_z})
    return out


def _side_creepages(patch, sign):
    xi, eta, phi = patch.creepages
    return xi, sign * eta, sign * phi


def rolling_radius(wheel_profile, radius, y_w):
    """The wheel's radius (mm) at its profile coordinate y_w by rollcontact's spline of the profile."""
    return radius - float(wheel_profile(y_w))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="6 cases instead of 42")
    ap.add_argument("-o", "--output", default=str(ROOT / "results" / "wheelrail_mbench"), help="output folder")
    ap.add_argument("--extract", metavar="CONTACT_EXAMPLES_DIR", help="write the reference CSV (maintenance)")
    ap.add_argument("--sweep-dir", default=str(ROOT / "results" / "wheelrail_sweep"),
                    help="folder of the y sweep's run files")
    args = ap.parse_args()
    if args.extract:
        extract(Path(args.extract))
        return
    from rollcontact.cases.scene.wheelrail import geometry
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    base = rollcontact.load_scene(SCENE)
    wheel = geometry(base.wheelrail)[1]
    hertz = hertz_check(out)
    rows = [r for r in reference_cases() if not args.quick or (r["side"], int(r["case"])) in QUICK]
    rollcontact.run(scene_of(rows[0], base))                      # warm-up: numba compiled or loaded
    records = []
    for row in rows:
        result = rollcontact.run(scene_of(row, base))
        if result.status != "complete":
            raise SystemExit(f"{row['side']} case {int(row['case'])}: {result.error}")
        ref, mine = to_rollcontact(row), ours(result)
        ref["rolling_radius"] = rolling_radius(wheel.profile, wheel.radius, ref["y_wheel"])
        records.append({"side": row["side"], "case": int(row["case"]), "y_ws": row["y_ws"], "yaw": row["yaw"],
                        "contact": ref, "rollcontact": mine})
    table = hertz + "\n\n" + report(records)
    study = []
    for row in rows:
        for patch in planar_study(scene_of(row, base)):
            study.append({"side": row["side"], "y_ws": row["y_ws"], **patch})
    table += "\n\n" + planar_report(study)
    print(table)
    (out / "mbench.md").write_text(table + "\n")
    meta = {"machine": platform.node(), "python": platform.python_version(), "date": time.strftime("%Y-%m-%d %H:%M"),
            "load": list(_load()), "cases": records, "planar_study": study}
    (out / "mbench.json").write_text(json.dumps(meta, indent=1))
    for path in figure(records, base, out):
        print(path)
    for path in y_sweep(base, Path(args.sweep_dir), out, 5 if args.quick else 21):
        print(path)


def hertz_check(out: Path) -> str:
    """Two crowns (wheel 150 mm, rail 300 mm) on a cylinder of radius 460 mm under 10 kN against Hertz (the test
    test_two_crowns_on_a_cylinder_give_hertz_ellipse), on two grids: the errors of the semi-axes (from the pressure's
    second moments), the approach and p0 (%)."""
    import sys
    sys.path.insert(0, str(ROOT / "tests" / "cases"))
    from test_wheelrail_run import crown_scene
    from rollcontact.solver.analytic import HertzEllipse
    lines = ["| dx x dy (mm) | grid | a | b | approach | p0 |", "|---|---|---|---|---|---|"]
    for dx, dy in ((0.2, 0.1), (0.1, 0.05)):
        scene = crown_scene(out, dx=dx, dy=dy)
        r = rollcontact.run(scene)
        patch, s = r.patches[0], r.summary
        p = patch.fields["p"]
        X, Y = np.meshgrid(patch.x, patch.y)
        a, b = (math.sqrt(5.0 * float((p * V ** 2).sum() / p.sum())) for V in (X, Y))
        h = HertzEllipse(460.0, 100.0, scene.material_pair.E_star, 10000.0)
        err = [100 * (v / w - 1) for v, w in ((a, h.a), (b, h.b), (s["lowering"], h.approach), (s["patch_pmax"][0], h.p0))]
        lines.append(f"| {dx} x {dy} | {p.shape[1]} x {p.shape[0]} | " + " | ".join(f"{e:+.3f} %" for e in err) + " |")
    for name in ("wheel.txt", "rail.csv"):
        (out / name).unlink(missing_ok=True)
    lines.append(f"Hertz: a = {h.a:.4f} mm, b = {h.b:.4f} mm, approach {h.approach:.5f} mm, p0 = {h.p0:.1f} MPa")
    return "\n".join(lines)


def y_sweep(base, folder: Path, out: Path, count: int) -> list:
    """The shipped scene's sweep of wheelrail.y over 0-10 mm (`count` positions) on 2 workers, and its figures."""
    from rollcontact.cases.plots.wheelrail_figures import plot_wheelrail_folder
    rollcontact.sweep(base, {"wheelrail.y": f"0:10:{count}"}, folder, jobs=2, overwrite=True)
    paths = plot_wheelrail_folder(folder, out, overwrite=True)
    renamed = []
    for p in paths:
        target = out / p.name.replace(folder.name, "wheelrail_sweep", 1)
        p.replace(target)
        renamed.append(target)
    return renamed


def _load():
    try:
        import os
        return os.getloadavg()
    except OSError:
        return (math.nan,) * 3


def report(records) -> str:
    """A markdown table per case and the largest differences (outside CONTACT's combined two-point patch)."""
    head = ("| side | y_ws (mm) | patches | rail y (mm) | wheel y | angle (rad) | Fn (N) | Fx (N) | Fy (N) | Mz (N mm) "
            "| pmax (MPa) | z_ws (mm) |\n|---|---|---|---|---|---|---|---|---|---|---|---|")
    lines = [head]
    worst = {}
    for r in records:
        c, m = r["contact"], r["rollcontact"]

        def cell(name, fmt):
            return f"{m[name]:{fmt}} / {c[name]:{fmt}}"
        lines.append(f"| {r['side']} | {r['y_ws']:.1f} | {m['n_patches']} / {c['n_patches']} | {cell('y_rail', '.3f')} | "
                     f"{cell('y_wheel', '.3f')} | {cell('contact_angle', '.4f')} | {cell('Fn', '.0f')} | "
                     f"{cell('Fx', '.1f')} | {cell('Fy', '.1f')} | {cell('Mz', '.0f')} | {cell('pmax', '.0f')} | "
                     f"{cell('z_ws', '.4f')} |")
        if m["n_patches"] != c["n_patches"]:
            continue
        mu_fn = 0.3 * c["Fn"]
        for name, diff in (("y_rail (mm)", abs(m["y_rail"] - c["y_rail"])),
                           ("contact angle (rad)", abs(m["contact_angle"] - c["contact_angle"])),
                           ("rolling radius (mm)", abs(m["rolling_radius"] - c["rolling_radius"])),
                           ("Fn (%)", 100 * abs(m["Fn"] / c["Fn"] - 1)),
                           ("Fx (% of mu Fn)", 100 * abs(m["Fx"] - c["Fx"]) / mu_fn),
                           ("Fy (% of mu Fn)", 100 * abs(m["Fy"] - c["Fy"]) / mu_fn),
                           ("pmax (%)", 100 * abs(m["pmax"] / c["pmax"] - 1)),
                           ("z_ws (mm)", abs(m["z_ws"] - c["z_ws"]))):
            key = name
            if key not in worst or diff > worst[key][0]:
                worst[key] = (diff, f"{r['side']} y = {r['y_ws']:.1f}")
    lines.append("")
    lines.append("each cell: rollcontact / CONTACT; largest differences (cases with the same number of patches): "
                 + "; ".join(f"{k} {v[0]:.3g} ({v[1]})" for k, v in worst.items()))
    cpu = [r["rollcontact"]["cpu_time"] for r in records]
    lines.append(f"rollcontact CPU time per case: median {np.median(cpu):.3f} s, largest {max(cpu):.3f} s")
    return "\n".join(lines)


def planar_report(study) -> str:
    """The planar study's table: per patch its contact angle, the spread of the rail's angle across the contact, and
    the force changes of the surface slip and of the rows' own angles, relative to mu Fn."""
    lines = ["| side | y_ws (mm) | rail y (mm) | contact angle (rad) | angle spread (rad) | Fx, Fs planar (N) | "
             "surface slip: dFx, dFs (% mu Fn) | local angles: dF_track_y, dF_track_z (% mu Fn) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in study:
        mu_fn = 0.3 * r["Fn"]
        lines.append(f"| {r['side']} | {r['y_ws']:.1f} | {r['y_rail']:.2f} | {r['angle']:.3f} | {r['spread']:.3f} | "
                     f"{r['Fx']:.0f}, {r['Fs']:.0f} | {100 * r['dFx'] / mu_fn:+.2f}, {100 * r['dFs'] / mu_fn:+.2f} | "
                     f"{100 * r['dFy_turn'] / mu_fn:+.2f}, {100 * r['dFz_turn'] / mu_fn:+.2f} |")
    return "\n".join(lines)


def figure(records, base, out):
    from rollcontact.cases.plots.common import plt, save_figure
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), layout="constrained")
    for side, colour in (("left", "C0"), ("right", "C3")):
        rs = [r for r in records if r["side"] == side]
        y = [r["y_ws"] for r in rs]
        for ax, name in zip(axes[:2], ("y_rail", "y_wheel")):
            ax.plot(y, [r["rollcontact"][name] for r in rs], "o-", color=colour, ms=4, label=f"{side}, rollcontact")
            ax.plot(y, [r["contact"][name] for r in rs], "x", color="k", ms=6,
                    label="CONTACT" if side == "right" else None)
    both = {}
    for r in records:
        both.setdefault(r["y_ws"], {})[r["side"]] = r
    ys = sorted(y for y, d in both.items() if len(d) == 2)
    if ys:
        for code, style in (("rollcontact", "o-"), ("contact", "x")):
            axes[2].plot(ys, [both[y]["left"][code]["rolling_radius"] - both[y]["right"][code]["rolling_radius"]
                              for y in ys], style, color="k" if code == "contact" else "C2",
                         label="CONTACT" if code == "contact" else "rollcontact")
    axes[0].set_ylabel("on the rail: y_r (mm, to the field side)")
    axes[1].set_ylabel("on the wheel: y_w (mm, to the field side)")
    axes[2].set_ylabel("r_left - r_right (mm)")
    for ax in axes:
        ax.set_xlabel("wheelset displacement y_ws (mm, to the right)")
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    fig.suptitle("Manchester Contact Benchmark, case A-2.2 (S1002 on UIC60 1:40, 10 kN per wheel, yaw 2.4 mrad per mm): "
                 "contact positions and rolling radius difference", fontsize=10)
    return save_figure(fig, out, "mbench_contact_points", overwrite=True)


if __name__ == "__main__":
    main()
