"""An elliptic profile run end to end (scene [geometry] Rx, Ry -> QuadricProfile -> grid -> solvers -> file):
the stored pressure against Hertz's elliptic solution (Johnson §4.2, `solver.analytic.HertzEllipse`), so that a
swap of x and y anywhere on the way, or a grid sized for the wrong axis, would show. Units mm, N, MPa."""
import math

import numpy as np
import pytest

from rollcontact.cases.run.scene_run import run_scene
from rollcontact.cases.scene.scene import default_scene
from rollcontact.solver.analytic import HertzEllipse


@pytest.mark.parametrize("rx, ry", [(80.0, 20.0), (20.0, 80.0)])
def test_elliptic_scene_has_hertz_semi_axes_along_the_right_axes(tmp_path, rx, ry):
    """Static step (periods = 0) on the seed's materials and load with Rx/Ry = 4 or 1/4 (semi-axes ratio 2.5):
    semi-axes from the second moments of the stored contact area (I_xx = pi a^3 b / 4 for an ellipse) within dx/2,
    approach within 0.5 % (both measured for dx = 0.2 mm in tests/solver/test_normal.py: 0.04 mm, 0.01 %; the
    grid here is the scene's, b/dx about 12), the load Fn carried, Coulomb's bound and the tangential force kept."""
    scene = default_scene().with_overrides([f"geometry.Rx={rx}", f"geometry.Ry={ry}", "motion.periods=0",
                                            "grid.dx=0.25", "grid.dy=0.25", "output.fields=all"])
    assert scene.radii == (rx, ry)
    d = run_scene(scene, tmp_path / "ellipse.h5")
    assert d.status == "complete"
    exact = HertzEllipse(rx, ry, scene.material_pair.E_star, scene.load.Fn)
    sx, sy = exact.a, exact.b                       # HertzEllipse: a along x, b along y
    assert (sx > sy) == (rx > ry)                     # the long axis lies along the larger radius
    X, Y = np.meshgrid(d.x, d.y)
    dx, dy = d.x[1] - d.x[0], d.y[1] - d.y[0]
    p = d.fields["p"][-1]
    contact = p > 0
    area = contact.sum() * dx * dy
    mx = math.sqrt(4.0 * np.sum(X[contact] ** 2) * dx * dy / area)
    my = math.sqrt(4.0 * np.sum(Y[contact] ** 2) * dx * dy / area)
    assert abs(mx - sx) < 0.5 * dx and abs(my - sy) < 0.5 * dy, (mx, my, sx, sy)
    assert d.history["approach"][-1] == pytest.approx(exact.approach, rel=5e-3)
    assert p.sum() * dx * dy == pytest.approx(scene.load.Fn, rel=1e-8)
    tau = np.hypot(d.fields["tau_x"][-1], d.fields["tau_y"][-1])
    assert np.all(tau <= scene.load.mu * p * (1 + 1e-9))
    F = np.array([d.fields["tau_x"][-1].sum(), d.fields["tau_y"][-1].sum()]) * dx * dy
    np.testing.assert_allclose(F, scene.Ft * np.asarray(scene.load_direction), rtol=0, atol=1e-8 * scene.Ft)
