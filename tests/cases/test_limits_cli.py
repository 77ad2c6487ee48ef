"""`rollcontact limits` subcommand (cases/cli/limits_cmd.py): closed-form shakedown limits on the command line."""
import argparse

import pytest

from rollcontact.cases.cli import limits_cmd
from rollcontact.solver.mdr import limits as L


def test_amplitude_gives_limit_load_u_lim_and_a_u_sd_table(capsys):
    assert limits_cmd.run_cli(["limits", "--w", "0.23", "--angle", "90"]) == 0
    out = capsys.readouterr().out
    assert f"f_t,lim = {L.f_t_lim(0.23, 1.1):.6f}" in out          # seed Eq. 19: 0.748217
    assert f"u_lim = 1 - w^2 = {L.u_lim(0.23):.6f}" in out
    assert "u_stat" in out and f"{L.u_shakedown(0.374108, 0.23, 1.1):.5f}" in out


def test_default_shows_parallel_perpendicular_and_pure_mdr(capsys):
    assert limits_cmd.run_cli(["limits", "--w", "0.23"]) == 0
    out = capsys.readouterr().out
    for k in (1.0, 1.1, 1.5):
        assert f"f_t,lim = {L.f_t_lim(0.23, k):.6f}" in out
    assert "ratcheting" in out                                     # rows above the smaller limits


def test_load_ratio_gives_w_lim_and_the_state_at_the_point(capsys):
    assert limits_cmd.run_cli(["limits", "--ft", "0.77", "--w", "0.23", "--kappa", "1.0"]) == 0
    out = capsys.readouterr().out
    assert f"w_lim = {L.w_lim(0.77, 1.0):.6f}" in out             # seed Eq. 18: 0.23
    assert "shakedown, u_sd = 0.947100" in out                     # exactly on the kappa = 1 limit
    assert limits_cmd.run_cli(["limits", "--ft", "0.77", "--w", "0.23", "--angle", "90"]) == 0
    assert "ratcheting" in capsys.readouterr().out                 # seed Fig. 4b (perpendicular)


@pytest.mark.parametrize("argv, name", [
    (["limits", "--w", "1.5"], "w = 1.5"), (["limits", "--ft", "-0.2"], "f_t = -0.2"),
    (["limits", "--w", "0.2", "--kappa", "0"], "kappa = 0"), (["limits", "--w", "nan"], "w = nan"),
    (["limits", "--w", "0.2", "--angle", "270"], "angle = 270"), (["limits"], "--w"),
    (["limits", "--w", "abc"], "--w"), (["limits", "--w", "0.2", "--angle", "9", "--kappa", "1"], "--kappa"),
])
def test_bad_values_name_the_parameter_and_exit_2(argv, name, capsys):
    assert limits_cmd.run_cli(argv) == 2
    assert name in capsys.readouterr().err


def test_register_plugs_into_a_main_parser():
    parser = argparse.ArgumentParser(prog="rollcontact")
    sub = parser.add_subparsers(dest="command")
    limits_cmd.register(sub)
    args = parser.parse_args(["limits", "--w", "0.1"])
    assert args.func is limits_cmd.handler and args.w == 0.1


def test_at_or_beyond_the_traction_bound_it_says_gross_sliding_not_a_ratchet_rate(capsys):
    # f_t = 1 is Ft = mu Fn: no static equilibrium (a run reports gross_sliding), so no ratchet rate applies
    assert limits_cmd.run_cli(["limits", "--ft", "1", "--w", "0.23"]) == 0
    verdict = [line for line in capsys.readouterr().out.splitlines() if "at (f_t, w)" in line]
    assert len(verdict) == 1 and "gross sliding" in verdict[0], verdict
