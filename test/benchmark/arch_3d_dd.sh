#!/usr/bin/env bash
# Nonlinear 3-D performance (doc/performance.md, "Nonlinear: the 3-D arch"):
# the neo-Hookean half-ring arch (examples/half_ring_arch_3d.xml, large
# rotations, no contact), FETI-DP with METIS subdomains against the
# monolithic direct solve (MUMPS) of the same model, at the deck's mesh
# (4 x 64 x 4 Hex8) refined REFINE times in every direction. Not part of
# ctest. Prints one markdown table: per configuration the median over REPS
# runs of the wall time per load step, Newton iterations per step, FETI-DP
# dual iterations per Newton iteration and the linear set-up / solve seconds.
#
#   bash test/benchmark/arch_3d_dd.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), STEPS (10), REFINE ("1 2"),
#              SUBDOMAINS ("8 32": METIS subdomains of the FETI-DP runs).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container
STEPS=${STEPS:-10}
read -r -a REFINE <<< "${REFINE:-1 2}"
read -r -a SUBS <<< "${SUBDOMAINS:-8 32}"

echo "3-D neo-Hookean arch, $STEPS steps, $RANKS ranks, median of $REPS runs"
echo
echo "| mesh | DOFs | strategy | wall s / step | Newton / step | dual its / Newton it | linear setup s | linear solve s | wall ratio to Monolithic |"
echo "|---|---|---|---|---|---|---|---|---|"
for f in "${REFINE[@]}"; do
  nr=$((4 * f)) nc=$((64 * f)) na=$((4 * f))
  mesh=(--set "Mesh/Bodies/Arch/Cylindrical Shell Sector/Radial Elements=$nr"
        --set "Mesh/Bodies/Arch/Cylindrical Shell Sector/Circumferential Elements=$nc"
        --set "Mesh/Bodies/Arch/Cylindrical Shell Sector/Axial Elements=$na")
  read -r mw mn _ ms mv dofs <<< "$(run_reps examples/half_ring_arch_3d.xml "$STEPS" steps "${mesh[@]}" \
      --set "Solver/Strategy=Monolithic")"
  echo "| $nr x $nc x $na | $dofs | Monolithic (MUMPS) | $mw | $mn | - | $ms | $mv | 1 |"
  for n in "${SUBS[@]}"; do
    read -r w nn d s v _ <<< "$(run_reps examples/half_ring_arch_3d.xml "$STEPS" steps "${mesh[@]}" \
        --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=$n")"
    ratio=$(awk -v a="$w" -v b="$mw" 'BEGIN {printf "%.2f", a / b}')
    echo "| $nr x $nc x $na | $dofs | FETI-DP, METIS $n | $w | $nn | $d | $s | $v | $ratio |"
  done
done
