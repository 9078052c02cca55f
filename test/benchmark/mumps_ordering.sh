#!/usr/bin/env bash
# The fill-reducing ordering of the monolithic MUMPS solve (doc/performance.md,
# "MUMPS: METIS' ordering"): block_3d at each Refinement of REFINEMENTS and
# the Mindlin sphere (examples/mindlin_sphere.xml, 3-D contact with friction,
# 15 factorisations), Solver/Strategy = Monolithic with MUMPS on RANKS ranks,
# for each Solver/Linear Solver/MUMPS/Ordering of ORDERINGS. One row per run:
# entries in the factor and MUMPS' own factorisation seconds (the first
# factorisation, from its Verbose output), the linear set-up seconds of the
# run (every analysis, ordering and factorisation), the wall seconds and the
# peak MiB per rank. REPS runs each (3), medians of the seconds. Not part of
# ctest: a Refinement 8 run takes 40-50 s and 3.7 GiB per rank.
#
# Usage: bash test/benchmark/mumps_ordering.sh BUILD_DIR
#        REFINEMENTS="4 6 8" ORDERINGS="METIS Auto" MINDLIN=1 REPS=3
set -euo pipefail
cd "$(dirname "$0")/../.."
. test/benchmark/common.sh "${1:?usage: mumps_ordering.sh BUILD_DIR}"
REFINEMENTS=${REFINEMENTS:-"4 6 8"}
ORDERINGS=${ORDERINGS:-"METIS Auto"}
MINDLIN=${MINDLIN:-1}

echo "Monolithic MUMPS on $RANKS ranks, medians of $REPS run(s)"
echo
echo "| model | DOFs | ordering | entries in the factor | factorisation s | linear set-up s | wall s | peak MiB / rank |"
echo "|---|---:|---|---:|---:|---:|---:|---:|"

# row MODEL DECK ARGS...: the rows of one model, one per ordering.
row() {
  local model=$1 deck=$2
  shift 2
  for ordering in $ORDERINGS; do
    local fact=() setup=() wall=() entries="" dofs="" mem=""
    for ((r = 0; r < REPS; r++)); do
      local log="$OUT/run.log"
      rm -rf "$OUT/o"
      local t0 t1
      t0=$(date +%s.%N)
      if ! mpirun -np "$RANKS" "$APP" "$deck" --output-dir "$OUT/o" --set "Output/VTK=false" \
           --set "Solver/Strategy=Monolithic" --set "Solver/Linear Solver/Type=MUMPS" \
           --set "Solver/Linear Solver/MUMPS/Ordering=$ordering" --set "Solver/Linear Solver/MUMPS/Verbose=true" \
           "$@" > "$log" 2>&1; then
        echo "| $model | | $ordering | failed: $(tail -1 "$log") |"; continue 2
      fi
      t1=$(date +%s.%N)
      entries=$(sed -n 's/.*INFOG(29)  Number of entries in factors *= *\([0-9]*\).*/\1/p' "$log" | head -1)
      fact+=("$(sed -n 's/.*Elapsed time for factorization *= *\([0-9.]*\).*/\1/p' "$log" | head -1)")
      local s
      read -r dofs s _ _ mem <<< "$(run_stats "$log")"
      setup+=("$s")
      wall+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}')")
    done
    med() { printf '%s\n' "$@" | median; }
    echo "| $model | $dofs | $ordering | $entries | $(med "${fact[@]}") | $(med "${setup[@]}") | $(med "${wall[@]}") | ${mem%.*} |"
  done
}

for r in $REFINEMENTS; do
  row "block_3d R$r" examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=$r"
done
if [[ "$MINDLIN" == 1 ]]; then
  row "mindlin_sphere" examples/mindlin_sphere.xml
fi
