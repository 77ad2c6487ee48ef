"""Contact solvers on a `bem` operator: normal, tangential (Kalker's shift problem), time stepping,
and the 1-D MDR model. Imports only `bem`. Units: mm, N, MPa.
"""
