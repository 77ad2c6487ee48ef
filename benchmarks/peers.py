"""Peer Hertz solvers for `accuracy_speed.py` (the optional `bench` extra: tamaas >= 2.9, ContactMechanics >= 1.8).

Each factory returns None when its package is not importable, else solve(grid, h, tol) -> (pressure (ny, nx)
MPa, approach mm or None) for the gap h (mm) on the `bem.Grid` under the normal force Fn (N), with the contact
modulus E_star (MPa). ContactMechanics' penetration tolerance is tol times the reference approach d_ref (mm).
"""
import numpy as np


def tamaas_solver(E_star, Fn):
    try:
        import tamaas as tm
    except ImportError:
        return None
    tm.set_log_level(tm.LogLevel.error)

    def solve(grid, h, tol):
        ny, nx = grid.shape
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [ny * grid.dy, nx * grid.dx], [ny, nx])
        model.E, model.nu = E_star, 0.0          # tamaas' Boussinesq uses E/(1 - nu^2) = E*
        tm.ModelFactory.registerNonPeriodic(model, "dcfft")
        solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(-h), tol)
        solver.setIntegralOperator("dcfft")
        solver.setMaxIterations(10000)
        solver.solve(Fn / (nx * ny * grid.cell_area))
        return np.array(model.traction).reshape(ny, nx), None
    return solve


def contactmechanics_solver(E_star, Fn, d_ref):
    try:
        from ContactMechanics import FreeFFTElasticHalfSpace
        from ContactMechanics.Systems import NonSmoothContactSystem
        from SurfaceTopography import Topography
    except ImportError:
        return None

    def solve(grid, h, tol):
        ny, nx = grid.shape
        size = (nx * grid.dx, ny * grid.dy)
        substrate = FreeFFTElasticHalfSpace((nx, ny), E_star, size)   # young = contact modulus E*
        system = NonSmoothContactSystem(substrate, Topography(np.ascontiguousarray(-h.T), size))
        res = system.minimize_proxy(external_force=Fn, pentol=tol * d_ref, maxiter=100000)
        if not res.success:
            raise RuntimeError(f"ContactMechanics: {res.message}")
        return res.jac.T / grid.cell_area, float(res.offset)
    return solve

