"""Wheel-rail contact geometry: lateral profiles, the wheelset over its rail, the contact search, planar patches
and their creepages (docs/theory.md §12.5, docs/wheelrail.md).

    profile     a lateral profile z(y) as a C2 cubic spline
    placement   the rail in the track (inclination, gauge point) and the wheel on its wheelset (flange back)
    wheel       the wheel as a body of revolution at a wheelset position: its silhouette along the track and the
                distance to it along a line
    search      the vertical gap along the profiles, its interpenetration regions and the contact patches with
                their reference points, contact angles and tangent planes
    patch       the undeformed gap h(x, s) of a patch in its tangent plane and the creepages there
    balance     a patch being solved, and the wheel's lowering at which the patches carry the vertical load
    layout      where the patches go: the coarse passes, their load centres, the grids over their interpenetration
    solve       one wheel on its rail: the vertical position for the load, each patch's normal and steady
                tangential problem, the forces in track coordinates

Coordinates (docs/wheelrail.md): track x along the direction of travel, y to the left, z upwards; a profile's y
is positive towards the field side, z upwards. Units: mm, N, MPa, rad, s.

The geometry (profile, placement, wheel, search, patch) needs numpy and scipy only; balance, layout and solve bring
in the contact solvers (`solve` is imported on first use of its names here).
"""
from rollcontact.solver.wheelrail.profile import Profile
from rollcontact.solver.wheelrail.placement import RailPlacement, WheelPlacement, place_rail
from rollcontact.solver.wheelrail.wheel import WheelPosition
from rollcontact.solver.wheelrail.search import ContactSearch, PatchFrame

_SOLVE = ("PATCH_SOLVERS", "PatchProblem", "PatchResult", "WheelRailParams", "WheelRailResult", "solve_wheel")

__all__ = ["Profile", "RailPlacement", "WheelPlacement", "place_rail", "WheelPosition", "ContactSearch",
           "PatchFrame", *_SOLVE]


def __getattr__(name):
    if name in _SOLVE:
        from rollcontact.solver.wheelrail import solve
        return getattr(solve, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
