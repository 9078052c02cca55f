#!/usr/bin/env bash
# What the decomposed element's contact updates move between ranks
# (doc/performance.md, "The active set on the slots' owners"): the Hertz
# sphere (examples/hertz_sphere.xml) at one refinement, the decomposed
# element under FETI-DP, PT-Scotch subdomains with the mesh in ranges, on P
# ranks for each P of PS. An active-set update (in a Newton iteration and
# at a step's end) brings a slot's summed gaps and multipliers only to the
# ranks that evaluate its counterparts (ContactComponent::updateActiveSet());
# the step-end pairing still shares every slot's result with every rank.
# Both come from one run's last "contact:" line. Not part of ctest; counts
# bytes, not time, so oversubscribed runs are fine. Prints one markdown
# table: ranks, contact slots, the active-set updates and the most bytes a
# rank received per update, the pairing exchanges and their bytes per
# exchange per rank (summed over the ranks, divided by P).
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
echo "| ranks | DOFs | contact slots | active-set updates | bytes per update, largest rank | pairing exchanges | bytes per exchange per rank (mean) |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
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
  read -r n0 b0 n1 b1 <<< "$(sed -n "s/.*active-set updates: \([0-9]*\) with the evaluated slots' values (at most \([0-9]*\) bytes received by a rank), \([0-9]*\) with every slot's (at most \([0-9]*\)).*/\1 \2 \3 \4/p" "$log")"
  read -r ne be <<< "$(sed -n 's/^contact: \([0-9]*\) contact-geometry exchanges (\([0-9]*\) bytes between ranks).*/\1 \2/p' "$log")"
  awk -v p="$p" -v d="$dofs" -v s="$slots" -v n="$((n0 + n1))" -v b="$((b0 + b1))" -v ne="$ne" -v be="$be" 'BEGIN {
    printf "| %d | %d | %d | %d | %.0f | %d | %.0f |\n", p, d, s, n, (n ? b / n : 0), ne, (ne ? be / ne / p : 0) }'
done
