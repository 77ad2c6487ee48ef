"""Steady rolling and the transient rolled from rest agree with a slip-velocity law (docs/friction.md, "Validation";
the issue's bound 0.5 %): a steel sphere (R = 300 mm, Fn = 20 kN, dx = 0.6 mm) at V = 30 m/s, mu(s) = 0.15 + 0.15
2^(-s/100 mm/s), rolled over 4 contact lengths at step dx; with step = dx the transient's discretisation is the
steady one's, so it reaches the steady state to the solver tolerance, in full sliding and in partial slip with
memory."""
import pytest

import rollcontact
from rollcontact.cases.scene.scene import Scene

BASE = {"materials.E1": 210e3, "materials.nu1": 0.28, "materials.E2": 210e3, "materials.nu2": 0.28,
        "load.Fn": 20e3, "rolling.speed": 30000.0, "grid.dx": 0.6, "friction.law": "exponential",
        "friction.mu_kin": 0.15, "friction.mu_1": 0.15, "friction.s_1": 100.0}


@pytest.mark.parametrize("over", [{"rolling.xi": 0.01},                                   # beyond the peak
                                  {"rolling.xi": 0.003, "friction.memory_distance": 0.005}],  # partial slip
                         ids=["full sliding", "partial slip with memory"])
def test_transient_from_rest_reaches_the_steady_state_with_a_falling_law(over):
    scene = Scene.from_toml_text('[geometry]\nR = 300.0\n[rolling]\nmode = "steady"\n', name="sphere")
    scene = scene.with_overrides({**BASE, **over})
    steady = rollcontact.run(scene)
    transient = rollcontact.run(scene.with_overrides({"rolling.mode": "transient"}))
    assert transient.status == "complete" and steady.status == "complete"
    assert transient.summary["F_x"] == pytest.approx(steady.summary["F_x"], rel=5e-3)
    assert transient.summary["F_x_steady"] == steady.summary["F_x"]
