#!/usr/bin/env bash
# The FETI-DP coarse problem as the subdomains grow (doc/performance.md,
# "The coarse problem at 2,048 subdomains, measured"): block_3d at
# Refinement 8 (421,443 DOFs) on RANKS ranks, one Newton step, for each
# subdomain count in COUNTS and each primal constraint choice in PRIMALS
# (Solver/FETI-DP/Primal Constraints) and each partitioner in METHODS
# (Partition/Method) and each solver method in SOLVERS
# (Solver/FETI-DP/Method: FETI-DP, BDDC). One row per run: coarse DOFs, dual
# iterations, local / coarse factorisation, coarse solves and the rest of
# FETI-DP's time (s), the coarse share of FETI-DP's time, peak MiB per rank.
# REPS runs each, medians of the seconds. Not part of ctest: a run takes
# 15-60 s and up to 4.5 GiB per rank.
#
# Usage: bash test/benchmark/coarse_scaling.sh BUILD_DIR
#        COUNTS="255 1024 2048 4096" PRIMALS="Automatic Vertices" METHODS=METIS SOLVERS=FETI-DP
#        REFINEMENT=8 REPS=1
set -euo pipefail
cd "$(dirname "$0")/../.."
. test/benchmark/common.sh "${1:?usage: coarse_scaling.sh BUILD_DIR}"
COUNTS=${COUNTS:-"255 1024 2048 4096"}
PRIMALS=${PRIMALS:-"Automatic Vertices"}
METHODS=${METHODS:-METIS}
SOLVERS=${SOLVERS:-FETI-DP}
REFINEMENT=${REFINEMENT:-8}
REPS=${REPS:-1}

echo "block_3d, Refinement $REFINEMENT, FETI-DP on $RANKS ranks, medians of $REPS run(s)"
echo
echo "| subdomains | partition | method | primal constraints | coarse DOFs | Krylov its | local fact. s | coarse fact. s | coarse solves s | other s | total s | coarse share | peak MiB / rank |"
echo "|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for n in $COUNTS; do
  for method in $METHODS; do
  for solver in $SOLVERS; do
  for primal in $PRIMALS; do
    rows=()
    for ((r = 0; r < REPS; r++)); do
      log="$OUT/run.log"
      rm -rf "$OUT/o"
      if ! mpirun -np "$RANKS" "$APP" examples/block_3d.xml --output-dir "$OUT/o" --set "Output/VTK=false" \
           --set "Mesh/Bodies/Block/Box/Refinement=$REFINEMENT" --set "Solver/Strategy=FETI-DP" \
           --set "Partition/Number of Subdomains=$n" --set "Solver/FETI-DP/Primal Constraints=$primal" \
           --set "Partition/Method=$method" --set "Solver/FETI-DP/Method=$solver" > "$log" 2>&1; then
        echo "| $n | $method | $solver | $primal | failed: $(tail -1 "$log") |"; continue 2
      fi
      coarse=$(sed -n 's/.*coarse problem of \([0-9]*\) DOFs.*/\1/p' "$log")
      read -r _ setup solve its mem <<< "$(run_stats "$log")"
      read -r lf cf df _ ls cs pc <<< "$(feti_phases "$log")"
      rows+=("$(awk -v s="$setup" -v t="$solve" -v lf="$lf" -v cf="$cf" -v cs="$cs" \
                 'BEGIN {tot = s + t; printf "%.2f %.2f %.2f %.2f %.2f %.0f", lf, cf, cs, tot - cf - cs - lf, tot, 100 * (cf + cs) / tot}')")
    done
    med() { printf '%s\n' "${rows[@]}" | awk -v k="$1" '{print $k}' | median; }
    echo "| $n | $method | $solver | $primal | $coarse | $its | $(med 1) | $(med 2) | $(med 3) | $(med 4) | $(med 5) | $(med 6) % | ${mem%.*} |"
  done
  done
  done
done
