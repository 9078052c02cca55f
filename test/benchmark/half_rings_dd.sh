#!/usr/bin/env bash
# Across-partition contact performance (doc/performance.md): the
# two-half-rings benchmark with the decomposed node-to-segment element,
# FETI-DP against the monolithic direct solve (MUMPS) of the same model, at
# the default mesh (4 x 64 Quad4 per ring) and at a mesh refined 4x in each
# direction (16 x 256). Not part of ctest. Prints one markdown table: per
# configuration the median over REPS runs of the wall time per load step, and
# (from the run's own counters) Newton iterations per step and FETI-DP dual
# iterations per Newton iteration, plus the linear set-up / solve seconds.
#
#   bash test/benchmark/half_rings_dd.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), STEPS (20), REFINE ("1 4"),
#              FETI ("By Body:0 METIS:4 METIS:8": Partition/Method:Number of Subdomains).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
STEPS=${STEPS:-20}
read -r -a REFINE <<< "${REFINE:-1 4}"
read -r -a FETI <<< "${FETI:-By_Body:0 METIS:4 METIS:8}"

# run_case ARGS... -> "wall/step newton/step dual/newton setup solve dofs" (medians of REPS)
run_case() {
  run_reps examples/two_half_rings.xml "$STEPS" rows --set "Contact/Formulation=Decomposed Node-To-Segment" "$@"
}

echo "Two half-rings, decomposed NTS, $STEPS steps, $RANKS ranks, median of $REPS runs"
echo
echo "| mesh per ring | DOFs | strategy | partition | wall s / step | Newton / step | dual its / Newton it | linear setup s | linear solve s | wall ratio to Monolithic |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for f in "${REFINE[@]}"; do
  nr=$((4 * f)) nc=$((64 * f))
  mesh=()
  for ring in "Lower Ring" "Upper Ring"; do
    mesh+=(--set "Mesh/Bodies/$ring/Annular Sector/Radial Elements=$nr")
    mesh+=(--set "Mesh/Bodies/$ring/Annular Sector/Circumferential Elements=$nc")
  done
  read -r mw mn md ms mv dofs <<< "$(run_case "${mesh[@]}" --set "Solver/Strategy=Monolithic")"
  echo "| $nr x $nc | $dofs | Monolithic (MUMPS) | - | $mw | $mn | - | $ms | $mv | 1 |"
  for spec in "${FETI[@]}"; do
    method=${spec%%:*} method=${method//_/ } n=${spec##*:}
    read -r w nn d s v _ <<< "$(run_case "${mesh[@]}" --set "Solver/Strategy=FETI-DP" \
        --set "Partition/Method=$method" --set "Partition/Number of Subdomains=$n")"
    label="$method"
    [[ "$n" != 0 ]] && label="$method, $n subdomains"
    ratio=$(awk -v a="$w" -v b="$mw" 'BEGIN {printf "%.2f", a / b}')
    echo "| $nr x $nc | $dofs | FETI-DP | $label | $w | $nn | $d | $s | $v | $ratio |"
  done
done
