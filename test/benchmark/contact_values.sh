#!/usr/bin/env bash
# What the decomposed element's active-set updates move between ranks
# (doc/performance.md, "The active set on the slots' owners"): the Hertz
# sphere (examples/hertz_sphere.xml) at one refinement, the decomposed
# element under FETI-DP, PT-Scotch subdomains with the mesh in ranges, on P
# ranks for each P of PS. In a Newton iteration only the ranks that evaluate
# a slot's counterparts receive its summed gaps and multipliers; at a step's
# end every rank receives every slot's, which is what every update moved
# before (ContactComponent::updateActiveSet(), everySlot). Both come from one
# run's last "contact:" line. Not part of ctest; counts bytes, not time, so
# oversubscribed runs are fine. Prints one markdown table: ranks, contact
# slots, updates in Newton iterations and at step ends, and the most bytes
# a rank received per update of each kind.
#
#   bash test/benchmark/contact_values.sh [BUILD_DIR]      # default: build
# Environment: PS ("2 4 8 16"), REFINEMENT (4), SUBDOMAINS (32, at least
#   the largest P), FRICTION (0: the deck's frictionless pair; e.g. 0.3).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
read -r -a PS <<< "${PS:-2 4 8 16}"
REFINEMENT=${REFINEMENT:-4}
SUBDOMAINS=${SUBDOMAINS:-32}
FRICTION=${FRICTION:-0}

echo "Hertz sphere, Refinement $REFINEMENT, $SUBDOMAINS PT-Scotch subdomains in ranges, friction coefficient $FRICTION"
echo
echo "| ranks | DOFs | contact slots | updates in Newton iterations | bytes per update, largest rank | updates at step ends | bytes per update, largest rank | ratio |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|"
for p in "${PS[@]}"; do
  log="$OUT/run_$p.log"
  rm -rf "$OUT/o"
  if ! mpirun -np "$p" "$APP" examples/hertz_sphere.xml --output-dir "$OUT/o" --set Output/VTK=false \
      --set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$REFINEMENT" \
      --set "Mesh/Bodies/Block/Box/Refinement=$REFINEMENT" \
      --set Solver/Strategy=FETI-DP --set Partition/Method=PT-Scotch \
      --set "Partition/Number of Subdomains=$SUBDOMAINS" --set "Partition/Mesh On Every Rank=false" \
      --set "Contact/Pairs/Sphere on block/Friction Coefficient=$FRICTION" \
      --set "Output/Checkpoint Interval=0" > "$log" 2>&1; then
    echo "| $p | failed |"; tail -3 "$log" >&2; continue
  fi
  dofs=$(sed -n 's/.* elements, \([0-9]*\) DOFs.*/\1/p' "$log")
  slots=$(sed -n 's/.* of \([0-9]*\) contact slots.*/\1/p' "$log")
  read -r n0 b0 n1 b1 <<< "$(sed -n 's/.*active-set updates: \([0-9]*\) in Newton iterations (at most \([0-9]*\) bytes received by a rank), \([0-9]*\) at step ends (at most \([0-9]*\)).*/\1 \2 \3 \4/p' "$log")"
  awk -v p="$p" -v d="$dofs" -v s="$slots" -v n0="$n0" -v b0="$b0" -v n1="$n1" -v b1="$b1" 'BEGIN {
    i = n0 ? b0 / n0 : 0; e = n1 ? b1 / n1 : 0
    printf "| %d | %d | %d | %d | %.0f | %d | %.0f | %.1f |\n", p, d, s, n0, i, n1, e, (i > 0 ? e / i : 0) }'
done
