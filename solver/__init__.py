"""Contact solvers on a `rollcontact.bem` operator. Imports only `rollcontact.bem`. Units: mm, N, MPa.

    normal/      frictionless normal contact: NormCG (docs/theory.md §4)
    tangential/  Kalker's transient shift problem with a prescribed force: projected TangCG (docs/theory.md §5)
    rolling/     one step of rolling on the world-fixed grid: shifted gap profiles, the coupled normal +
                 tangential step, the load path and its time stepping, shakedown classification (docs/theory.md §6)
    creep/       rolling with creepage and spin: the steady state in contact-fixed coordinates, the transient on the
                 world-fixed grid from rest or Cattaneo's state, prescribed forces, creep curves, Kalker's
                 coefficients (docs/theory.md §7.3, §11.5)
    visco/       viscoelastic bodies (Standard Linear Solid): element states and their exact step update, the steady
                 rolling operator and its non-symmetric normal solver, Hunter's cylinder (docs/theory.md §12.3)
    mdr/         the 1-D MDR model of oscillating rolling and its closed-form limits (docs/theory.md §8)
    analytic     closed-form references: Hertz, Cattaneo-Mindlin, Hertz ellipse (docs/theory.md §7)
    memo         the product memo the normal and tangential solvers share
"""
