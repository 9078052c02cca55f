#!/usr/bin/env bash
# Two-half-rings reference curves: runs the monolithic nonlinear NTS analysis
# with 20 and 100 steps on 2 ranks and plots strain energy, external work and
# the contact force resultant against the load factor (gnuplot, PNG).
#
#   bash doc/plots/half_rings.sh [BUILD_DIR]     # default: build
# Writes doc/img/half_rings_energy.png, doc/img/half_rings_force.png and
# prints the run times.
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${1:-build}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
out=ddcontact-out/half_rings_plots
mkdir -p "$out"
for n in 20 100; do
  start=$(date +%s.%N)
  mpirun -np 2 "$B/src/ddcontact" examples/two_half_rings.xml --output-dir "$out/nts$n" \
    --set "Contact/Formulation=Node-To-Segment" --set "Solver/Strategy=Monolithic" \
    --set "Load Stepping/Number of Steps=$n" --set "Output/VTK=false" > "$out/nts$n.log" 2>&1 || { cat "$out/nts$n.log"; exit 1; }
  end=$(date +%s.%N)
  printf "monolithic NTS, %3d steps, 2 ranks: %.2f s wall (history.csv wall_seconds of the last step: %s)\n" \
    "$n" "$(awk -v a="$start" -v b="$end" 'BEGIN {print b - a}')" "$(tail -1 "$out/nts$n/history.csv" | cut -d, -f10)"
done
gnuplot <<GP
set datafile separator ","
set terminal pngcairo size 900,560 noenhanced
set key top left
set grid
set xlabel "load factor"
set output "doc/img/half_rings_energy.png"
set title "Two half-rings, monolithic nonlinear NTS: strain energy and external work"
set ylabel "energy"
plot "$out/nts100/history.csv" every ::1 using 2:3 with lines lw 2 title "strain energy, 100 steps", \
     "$out/nts100/history.csv" every ::1 using 2:11 with lines dt 2 lw 2 title "external work, 100 steps", \
     "$out/nts20/history.csv" every ::1 using 2:3 with points pt 7 title "strain energy, 20 steps"
set output "doc/img/half_rings_force.png"
set title "Two half-rings, monolithic nonlinear NTS: contact force on the slave ring"
set ylabel "force"
plot "$out/nts100/history.csv" every ::1 using 2:7 with lines lw 2 title "F_x, 100 steps", \
     "$out/nts100/history.csv" every ::1 using 2:8 with lines lw 2 title "F_y, 100 steps", \
     "$out/nts20/history.csv" every ::1 using 2:7 with points pt 7 title "F_x, 20 steps", \
     "$out/nts20/history.csv" every ::1 using 2:8 with points pt 5 title "F_y, 20 steps"
GP
echo "plots: doc/img/half_rings_energy.png doc/img/half_rings_force.png"
