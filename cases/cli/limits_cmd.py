"""`rollcontact limits`: closed-form shakedown limits of oscillating rolling (solver.mdr.limits, docs/theory.md §8).

    rollcontact limits --w 0.23 [--angle 90 | --kappa K]     f_t,lim, u_lim and a table u_sd(f_t)
    rollcontact limits --ft 0.46 [--angle 90 | --kappa K]    w_lim (the largest amplitude with shakedown)
    rollcontact limits --w 0.23 --ft 0.46                    both, and u_sd (or ratcheting) at (f_t, w)

Dimensionless inputs (seed Eq. 9): w = W/a, f_t = Ft/(mu Fn); outputs u = U/U0 with U0 = mu E* d/G*.
Without --angle/--kappa the three reference kappas are shown side by side: parallel (1.0) and
perpendicular (1.1), the seed's fits to CONTACT and experiments, and 1.5, the pure MDR (seed Eq. 12).
--angle uses solver.mdr.limits.kappa_for_angle (sin^2 interpolation between 0 and 90 deg - an assumption).

Over `rollcontact.limits` (cases.closed_forms). `register(subparsers)` is called by cases/cli/main.py; `run_cli(argv)`
is a standalone entry for tests. Bad values print a message naming the parameter and return exit code 2.
"""
from __future__ import annotations

import argparse
import sys


def handler(args, out=None) -> int:
    """Print the limits (`rollcontact.limits`, cases.closed_forms); 0 on success, 2 on a bad parameter (message on
    stderr)."""
    from rollcontact.cases import api
    from rollcontact.cases.arguments import command_line
    try:
        with command_line():
            limits = api.limits(args.w, args.ft, angle=args.angle, kappa=args.kappa)
    except api.InputError as exc:
        print(f"rollcontact limits: error: {exc}", file=sys.stderr)
        return 2
    print(limits.report(), file=out or sys.stdout)
    return 0


def register(subparsers) -> argparse.ArgumentParser:
    """Add the `limits` subcommand to an argparse subparsers object; handler set as `func`."""
    p = subparsers.add_parser(
        "limits", help="closed-form shakedown limits (MDR, seed Eqs. 12-19)",
        description="Closed-form shakedown limits of oscillating rolling (seed Eqs. 12-19, docs/theory.md §8). "
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
