"""`rollcontact limits`: closed-form shakedown limits of oscillating rolling (solver.mdr.limits, theory §8).

    rollcontact limits --w 0.23 [--angle 90 | --kappa K]     f_t,lim, u_lim and a table u_sd(f_t)
    rollcontact limits --ft 0.46 [--angle 90 | --kappa K]    w_lim (the largest amplitude with shakedown)
    rollcontact limits --w 0.23 --ft 0.46                    both, and u_sd (or ratcheting) at (f_t, w)

Dimensionless inputs (seed Eq. 9): w = W/a, f_t = Ft/(mu Fn); outputs u = U/U0 with U0 = mu E* d/G*.
Without --angle/--kappa the three reference kappas are shown side by side: parallel (1.0) and
perpendicular (1.1), the seed's fits to CONTACT and experiments, and 1.5, the pure MDR (seed Eq. 12).
--angle uses solver.mdr.limits.kappa_for_angle (sin^2 interpolation between 0 and 90 deg - an assumption).

`register(subparsers)` is called by cases/cli/main.py; `run_cli(argv)` is a standalone entry for tests.
Bad values print a message naming the parameter and return exit code 2.
"""
from __future__ import annotations

import argparse
import sys

from rollcontact.bem.errors import InputError

TABLE_FRACTIONS = (0.0, 0.25, 0.5, 0.75, 0.9, 1.0)   # table rows: fractions of the largest f_t,lim shown


def _kappas(args):
    from rollcontact.solver.mdr import limits as lim
    """[(label, kappa)] to report, from --kappa, --angle, or the three reference values."""
    if args.kappa is not None:
        lim.check_kappa(args.kappa)
        return [("given", float(args.kappa))]
    if args.angle is not None:
        return [(f"angle={args.angle:g}deg", lim.kappa_for_angle(args.angle))]
    return [("parallel", lim.KAPPA_PARALLEL), ("perpendicular", lim.KAPPA_PERPENDICULAR),
            ("pure MDR", lim.KAPPA_MDR)]


def _setting(args):
    """'parallel'/'perpendicular' when the seed's ratcheting regression (Eqs. 20-21) applies, else None."""
    if args.kappa is not None:
        return None
    if args.angle is not None:
        return {0.0: "parallel", 180.0: "parallel", 90.0: "perpendicular"}.get(float(args.angle))
    return None


def handler(args, out=None) -> int:
    """Print the limits; 0 on success, 2 on a bad parameter (message on stderr)."""
    from rollcontact.solver.mdr import limits as lim
    out = out or sys.stdout
    if args.w is None and args.ft is None:
        print("rollcontact limits: error: give --w (amplitude W/a) and/or --ft (load ratio Ft/(mu Fn))",
              file=sys.stderr)
        return 2
    try:
        kappas = _kappas(args)
        if args.w is not None:
            lim.check_w(args.w)
        if args.ft is not None:
            lim.check_ft(args.ft)
        print("kappa (seed Eq. 13): " + ", ".join(f"{label} {k:g}" for label, k in kappas), file=out)
        if args.w is not None:
            w = float(args.w)
            print(f"w = W/a = {w:g}", file=out)
            print(f"  u_lim = 1 - w^2 = {lim.u_lim(w):.6f}   (seed Eq. 17, independent of kappa)", file=out)
            limits = [lim.f_t_lim(w, k) for _, k in kappas]
            for (label, k), f in zip(kappas, limits):
                print(f"  f_t,lim = {f:.6f}   ({label}, kappa = {k:g})", file=out)
            head = "  f_t        u_stat   " + "".join(f"  u_sd[{label}]".ljust(22) for label, _ in kappas)
            print(head.rstrip(), file=out)
            for frac in TABLE_FRACTIONS:
                f = frac * max(limits)
                row = f"  {f:<9.6f}  {lim.u_stat(f):.6f} "
                for (_, k), fl in zip(kappas, limits):
                    cell = f"{lim.u_shakedown(f, w, k):.6f}" if f <= fl else "ratcheting"
                    row += f"  {cell:<20}"
                print(row.rstrip(), file=out)
        if args.ft is not None:
            f = float(args.ft)
            print(f"f_t = Ft/(mu Fn) = {f:g}   (u_stat = {lim.u_stat(f):.6f}, seed Eq. 4)", file=out)
            for label, k in kappas:
                print(f"  w_lim = {lim.w_lim(f, k):.6f}   ({label}, kappa = {k:g})", file=out)
        if args.w is not None and args.ft is not None:
            f, w = float(args.ft), float(args.w)
            setting = _setting(args)
            if f >= 1.0:  # Ft >= mu Fn: no static equilibrium, not a ratchet (a run reports gross_sliding)
                print(f"  at (f_t, w) = ({f:g}, {w:g}): gross sliding (Ft >= mu Fn: the contact slides as a whole, "
                      "no shakedown and no ratchet rate)", file=out)
            for label, k in (kappas if f < 1.0 else ()):  # the state per kappa exists below the bound only
                if f <= lim.f_t_lim(w, k):
                    print(f"  at (f_t, w) = ({f:g}, {w:g}): shakedown, u_sd = {lim.u_shakedown(f, w, k):.6f}"
                          f"   ({label})", file=out)
                else:
                    msg = f"  at (f_t, w) = ({f:g}, {w:g}): beyond the limit, ratcheting ({label})"
                    if setting is not None or label in ("parallel", "perpendicular"):
                        s = setting or label
                        msg += (f"; seed regression Eq. {20 if s == 'parallel' else 21}: du per period ~ "
                                f"{lim.ratcheting_increment(f, w, s):.4f} (empirical fit)")
                    print(msg, file=out)
    except InputError as exc:
        print(f"rollcontact limits: error: {exc}", file=sys.stderr)
        return 2
    return 0


def register(subparsers) -> argparse.ArgumentParser:
    """Add the `limits` subcommand to an argparse subparsers object; handler set as `func`."""
    p = subparsers.add_parser(
        "limits", help="closed-form shakedown limits (MDR, seed Eqs. 12-19)",
        description="Closed-form shakedown limits of oscillating rolling (seed Eqs. 12-19, theory.md §8). "
                    "w = W/a, f_t = Ft/(mu Fn), u = U/U0 with U0 = mu E* d/G*.")
    p.add_argument("--w", type=float, help="oscillation amplitude w = W/a (0..1)")
    p.add_argument("--ft", type=float, help="tangential load ratio f_t = Ft/(mu Fn) (0..1)")
    group = p.add_mutually_exclusive_group()
    group.add_argument("--angle", type=float, help="angle between rolling direction and Ft, deg (0..180)")
    group.add_argument("--kappa", type=float, help="mapping parameter of seed Eq. 13 (0 < kappa <= 1.5)")
    p.set_defaults(func=handler)
    return p


def run_cli(argv=None) -> int:
    """Standalone entry (`rollcontact limits ...` without the main CLI): returns the exit code."""
    parser = argparse.ArgumentParser(prog="rollcontact")
    sub = parser.add_subparsers(dest="command", required=True)
    register(sub)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:               # argparse: bad syntax -> 2, --help -> 0
        return int(exc.code or 0)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(run_cli(sys.argv[1:]))
