#!/usr/bin/env bash
# 3-D contact performance (doc/performance.md): the decomposed
# node-to-surface element under FETI-DP against the conventional element
# solved monolithically (MUMPS), on the free-face half-rings
# (examples/two_half_rings_3d_free.xml) and the ironing example
# (examples/ironing_3d.xml), each at its own mesh and at a refined one. Not
# part of ctest. Prints one markdown table: per run the median over REPS runs
# of the wall time per load step and, from the run's own counters, Newton
# iterations per step, FETI-DP dual iterations per Newton iteration and the
# linear set-up / solve seconds.
#
#   bash test/benchmark/contact_3d.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), CASES ("rings ironing"),
#   RINGS_STEPS (20), RINGS_REFINE ("1 2": elements x f in every direction),
#   IRONING_STEPS (40), IRONING_REFINE ("1 1.5": the slab's and the die's
#   element counts x f, rounded; the die keeps 1 radial element).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
read -r -a CASES <<< "${CASES:-rings ironing}"
RINGS_STEPS=${RINGS_STEPS:-20}
IRONING_STEPS=${IRONING_STEPS:-40}
read -r -a RINGS_REFINE <<< "${RINGS_REFINE:-1 2}"
read -r -a IRONING_REFINE <<< "${IRONING_REFINE:-1 1.5}"
# A Monolithic run rejects a Solver/FETI-DP sublist: the ironing deck's
# conventional runs use it without that sublist (as examples/ironing_3d.sh).
sed '/<ParameterList name="FETI-DP">/,/<\/ParameterList>/d' examples/ironing_3d.xml > "$OUT/ironing_3d_monolithic.xml"

# scaled COUNT FACTOR -> COUNT * FACTOR rounded to an integer (at least 1)
scaled() { awk -v n="$1" -v f="$2" 'BEGIN {m = int(n * f + 0.5); print (m < 1 ? 1 : m)}'; }

# run_case DECK STEPS ARGS... -> "wall/step newton/step dual/newton setup solve dofs" (medians of REPS)
run_case() {
  local deck=$1 steps=$2
  shift 2
  run_reps "$deck" "$steps" steps "$@"
}

# row CASE MESH STEPS DECK_DECOMPOSED DECK_CONVENTIONAL MESH_ARGS...: one
# conventional Monolithic and one decomposed FETI-DP run (the deck's
# partition)
row() {
  local name=$1 mesh=$2 steps=$3 dd=$4 conv=$5
  shift 5
  local mw mn ms mv dofs w nn d s v ratio
  read -r mw mn _ ms mv dofs <<< "$(run_case "$conv" "$steps" "$@" \
      --set "Contact/Formulation=Node-To-Surface" --set "Solver/Strategy=Monolithic")"
  echo "| $name | $mesh | $dofs | $steps | conventional, Monolithic (MUMPS) | $mw | $mn | - | $ms | $mv | 1 |"
  read -r w nn d s v _ <<< "$(run_case "$dd" "$steps" "$@" \
      --set "Contact/Formulation=Decomposed Node-To-Surface" --set "Solver/Strategy=FETI-DP")"
  ratio=$(awk -v a="$w" -v b="$mw" 'BEGIN {printf "%.2f", a / b}')
  echo "| $name | $mesh | $dofs | $steps | decomposed, FETI-DP | $w | $nn | $d | $s | $v | $ratio |"
}

echo "3-D contact, $RANKS ranks, median of $REPS runs"
echo
echo "| case | mesh | DOFs | steps | formulation, strategy | wall s / step | Newton / step | dual its / Newton it | linear setup s | linear solve s | wall ratio to Monolithic |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for c in "${CASES[@]}"; do
  case $c in
    rings)
      deck=examples/two_half_rings_3d_free.xml
      for f in "${RINGS_REFINE[@]}"; do
        nr=$(scaled 2 "$f") nc=$(scaled 32 "$f") na=$(scaled 4 "$f")
        mesh=()
        for ring in "Lower Ring" "Upper Ring"; do
          mesh+=(--set "Mesh/Bodies/$ring/Cylindrical Shell Sector/Radial Elements=$nr")
          mesh+=(--set "Mesh/Bodies/$ring/Cylindrical Shell Sector/Circumferential Elements=$nc")
          mesh+=(--set "Mesh/Bodies/$ring/Cylindrical Shell Sector/Axial Elements=$na")
        done
        row "half-rings, free faces (METIS 8)" "$nr x $nc x $na per ring" "$RINGS_STEPS" "$deck" "$deck" "${mesh[@]}"
      done ;;
    ironing)
      for f in "${IRONING_REFINE[@]}"; do
        sx=$(scaled 18 "$f") sy=$(scaled 6 "$f") sz=$(scaled 8 "$f") dc=$(scaled 36 "$f") da=$(scaled 4 "$f")
        mesh=(--set "Mesh/Bodies/Slab/Box/Elements X=$sx" --set "Mesh/Bodies/Slab/Box/Elements Y=$sy"
              --set "Mesh/Bodies/Slab/Box/Elements Z=$sz"
              --set "Mesh/Bodies/Die/Cylindrical Shell Sector/Circumferential Elements=$dc"
              --set "Mesh/Bodies/Die/Cylindrical Shell Sector/Axial Elements=$da")
        row "ironing (METIS 4)" "slab $sx x $sy x $sz, die 1 x $dc x $da" "$IRONING_STEPS" examples/ironing_3d.xml \
          "$OUT/ironing_3d_monolithic.xml" "${mesh[@]}"
      done ;;
    *) echo "contact_3d.sh: unknown case '$c' in CASES (rings, ironing)" >&2; exit 2 ;;
  esac
done
