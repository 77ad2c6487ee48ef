"""An input deck of the reference program CONTACT (module 1, wheel on rail) for the positions of a [wheelrail] sweep
of the shipped Manchester scene (cases/mbench_s1002_uic60.toml), for side-by-side runs (benchmarks/wheelrail_speed.py,
docs/wheelrail.md). Only for comparisons: rollcontact never needs CONTACT.

The deck repeats, per case, the full problem as CONTACT's example mbench_a22_right.inp states it (right wheel, steady
rolling, vertical force prescribed, 0.2 mm grid, the benchmark's profiles in the working folder), with the wheelset's
lateral position y_ws, yaw, roll and pitch velocity of each case. CONTACT's frame: y to the right, z down; its yaw is
about z down (minus rollcontact's), its pitch velocity about y to the right (minus rollcontact's omega).
"""
from __future__ import annotations

from pathlib import Path

CASE = """  1 MODULE
 1203100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0000021    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1e-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  {dx}   {dx}   1.000   90d   8.0   4.0      DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  {y}  10000.  {roll} {yaw}  0.0      S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0  {vpitch} VS,VY,VZ, VROLL,VYAW,VPITCH
"""


def write_deck(path, ys, *, yaw=0.0, roll=0.0, omega=4.3481181, dx=0.2):
    """Write CONTACT's deck `path` (<experim>.inp) with one case per lateral position in `ys` (mm, right wheel; yaw and
    roll in rollcontact's track frame, rad; omega in rad/s)."""
    text = "".join(CASE.format(dx=dx, y=y, roll=roll, yaw=-yaw, vpitch=-omega) for y in ys) + "  0 MODULE\n"
    Path(path).write_text(text)
