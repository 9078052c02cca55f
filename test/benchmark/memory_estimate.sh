#!/usr/bin/env bash
# The memory estimate against measured memory (doc/user-guide.md, "Memory"):
# one run per case, the estimate of the run's first line ("estimated memory
# ... per rank") against its peak resident memory per rank less that of an
# empty run (test/inputs/small_block.xml) on as many ranks. Not part of
# ctest. Prints two markdown tables: the cases on RANKS ranks, and
# examples/block_3d.xml at Refinement 6 (181,875 DOFs) on 1-16 ranks
# (oversubscribed: memory is meaningful, time is not), where what every rank
# duplicates (mesh, METIS's graph) weighs most.
#
#   bash test/benchmark/memory_estimate.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), TABLES ("cases ranks"), RANK_COUNTS ("1 2 4 8 16").
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"

# mib VALUE UNIT -> MiB
mib() { awk -v v="$1" -v u="$2" 'BEGIN { f = u == "KiB" ? 1 / 1024 : u == "GiB" ? 1024 : u == "TiB" ? 1048576 : u == "B" ? 1 / 1048576 : 1; printf "%.0f", v * f }'; }

# base NP -> the peak per rank (MiB) of an empty run on NP ranks
base() {
  mpirun -np "$1" "$APP" test/inputs/small_block.xml --output-dir "$OUT/o" >"$OUT/base.log" 2>&1
  run_stats "$OUT/base.log" | awk '{print $5}'
}

# run_case LABEL DECK ARGS... -> a table row (on $NP ranks, less $BASE)
run_case() {
  local label=$1 deck=$2
  shift 2
  local log=$OUT/run.log
  mpirun -np "$NP" "$APP" "$deck" --set "Load Stepping/Number of Steps=1" --output-dir "$OUT/o" "$@" >"$log" 2>&1 ||
    { echo "| $label | failed: $(grep -m1 error "$log") | | |"; return; }
  read -r dofs _ _ _ peak <<< "$(run_stats "$log")"
  read -r value unit <<< "$(sed -n 's/.*estimated memory \([0-9.]*\) \([KMGT]*i*B\) per rank.*/\1 \2/p' "$log")"
  local estimate measured
  estimate=$(mib "$value" "$unit")
  measured=$(awk -v p="$peak" -v b="$BASE" 'BEGIN { printf "%.0f", p - b }')
  echo "| $label | $dofs | $measured | $estimate | $(awk -v e="$estimate" -v m="$measured" 'BEGIN { printf "%.2f", m / e }') |"
}

B3=examples/block_3d.xml
B2=examples/elastic_block.xml
TABLES=${TABLES:-cases ranks}

if [[ " $TABLES " == *" ranks "* ]]; then
  echo "block_3d at Refinement 6 on 1-16 ranks: the largest rank's peak less an empty run's on as many ranks"
  echo
  echo "| case | DOFs | measured MiB | estimate MiB | measured / estimate |"
  echo "|---|---|---|---|---|"
  for NP in ${RANK_COUNTS:-1 2 4 8 16}; do
    BASE=$(base "$NP")
    run_case "Belos-MueLu, $NP ranks" $B3 --set "Mesh/Bodies/Block/Box/Refinement=6" \
      --set "Solver/Linear Solver/Type=Belos-MueLu" --set Output/VTK=false
    run_case "FETI-DP, $NP ranks" $B3 --set "Mesh/Bodies/Block/Box/Refinement=6" --set Solver/Strategy=FETI-DP \
      --set Output/VTK=false
  done
  echo
fi
[[ " $TABLES " == *" cases "* ]] || exit 0
NP=$RANKS
BASE=$(base "$NP")
echo "Memory estimate against measured peak per rank less an empty run's $BASE MiB, $RANKS ranks"
echo
echo "| case | DOFs | measured MiB | estimate MiB | measured / estimate |"
echo "|---|---|---|---|---|"
for r in 3 4 5; do run_case "Hex8, MUMPS, Refinement $r" $B3 --set "Mesh/Bodies/Block/Box/Refinement=$r"; done
for r in 2 3; do
  run_case "Hex20, MUMPS, Refinement $r" $B3 --set "Mesh/Bodies/Block/Box/Refinement=$r" \
    --set "Mesh/Bodies/Block/Element/Type=Hex20"
done
for r in 16 32; do run_case "Quad4, MUMPS, Refinement $r" $B2 --set "Mesh/Bodies/Block/Rectangle/Refinement=$r"; done
run_case "Hex8, Amesos2, Refinement 3" $B3 --set "Mesh/Bodies/Block/Box/Refinement=3" --set "Solver/Linear Solver/Type=Amesos2"
run_case "Hex8, Belos-MueLu, Refinement 4" $B3 --set "Mesh/Bodies/Block/Box/Refinement=4" \
  --set "Solver/Linear Solver/Type=Belos-MueLu"
for r in 4 5; do run_case "Hex8, FETI-DP, Refinement $r" $B3 --set "Mesh/Bodies/Block/Box/Refinement=$r" --set Solver/Strategy=FETI-DP; done
for r in 16 32; do
  run_case "Quad4, FETI-DP, Refinement $r" $B2 --set "Mesh/Bodies/Block/Rectangle/Refinement=$r" --set Solver/Strategy=FETI-DP
done
run_case "Hertz sphere, FETI-DP, Refinement 3" examples/hertz_sphere.xml \
  --set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=3"
