#!/bin/sh
# The runs behind docs/shapes.md (issue #27): for each shape, a 3-D sweep of f_t at w = 0.23 in both settings
# (motion.angle = 0 parallel, 90 perpendicular), the same sweep on the 1-D MDR model, and the 3-D limit search at
# w = 0.23 in both settings; then the project's figures. Usage: sh docs/shapes/run_all.sh [OUTDIR] (default
# /tmp/shapes27). About 12 min on one core (11 min 39 s measured, 2 cores shared with other work).
set -e
OUT=${1:-/tmp/shapes27}
RC=.venv/bin/rollcontact
for s in cone power4 flat_rounded; do
  $RC sweep docs/shapes/$s.toml --vary load.ft=0.1:0.8:8 --vary motion.angle=0,90 -o $OUT/${s}_sweep --jobs 1 -q
  $RC sweep docs/shapes/$s.toml --vary load.ft=0.1:0.8:8 --set solver.fidelity=mdr -o $OUT/${s}_mdr --jobs 1 -q
  $RC limit-search docs/shapes/$s.toml --vary motion.w=0.23 --vary motion.angle=0,90 -o $OUT/${s}_limits --jobs 1 -q
done
# figures: the sweep folders with their limit-search brackets, and the maps of one flat-punch run
FIG=docs/shapes/figures
for s in cone power4 flat_rounded; do
  cp $OUT/${s}_limits/limits.csv $OUT/${s}_sweep/limits.csv
  $RC plot $OUT/${s}_sweep -o $FIG --overwrite > $FIG/${s}_table.txt
done
$RC plot $OUT/flat_rounded_sweep/ft=0.5_angle=90__*.h5 -o $OUT/flat_plots --overwrite
cp $OUT/flat_plots/ft=0.5_angle=90__*_maps_step241.png $FIG/flat_rounded_maps.png
rm -f $FIG/*.pdf
