#!/usr/bin/env bash
# Performance benchmark (doc/performance.md): not part of ctest. Prints two
# markdown tables:
#  1. examples/elastic_block.xml at ~50k, 200k, 800k DOFs on RANKS ranks with
#     every strategy: median over REPS runs of set-up (factorisation /
#     preconditioner / FETI-DP coarse problem) and solve seconds, Krylov or
#     dual iterations and peak memory per rank (max over ranks);
#  2. FETI-DP dual iterations of one linear solve for 4, 16, 64 subdomains
#     x H/h = 8, 16, 32, Dirichlet and lumped preconditioners
#     (test/benchmark/square.xml).
#
#   bash test/benchmark/run_benchmark.sh [BUILD_DIR]   # default build
# Environment: RANKS (2), REPS (3), SIZES (refinements, "10 20 40"),
#              SUBDOMAINS (FETI-DP subdomains per size, "16 64 256": about
#              3200 DOFs each, the automatic count's size in 2-D), TABLE2 (1),
#              PRIMAL (Solver/FETI-DP/Primal Constraints; empty: the default),
#              STRATEGIES ("MUMPS Belos-MueLu Belos-FROSch FETI-DP").
# Each elastic-block run is 1 load step = 2 Newton solves of the same
# matrix (the second checks convergence); times are summed over both. The
# FETI-DP rows are followed by their phase breakdown (last run).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
read -r -a SIZES <<< "${SIZES:-10 20 40}"
read -r -a SUBS <<< "${SUBDOMAINS:-16 64 256}"
PRIMAL=${PRIMAL:-}
read -r -a STRATEGIES <<< "${STRATEGIES:-MUMPS Belos-MueLu Belos-FROSch FETI-DP}"
PRIMAL_ARGS=()
[[ -z $PRIMAL ]] || PRIMAL_ARGS=(--set "Solver/FETI-DP/Primal Constraints=$PRIMAL")
FETI_PHASES=()   # phase rows of the FETI-DP cases
LAST_PHASES=""   # run_case: the phases of its last run

# run_case LABEL ARGS... -> prints "setup solve iterations memory dofs" (medians) or "failed"
run_case() {
  local setup=() solve=() iters=() mem=() dofs=""
  for ((r = 0; r < REPS; r++)); do
    local log="$OUT/run.log"
    if ! mpirun -np "$RANKS" "$APP" "$@" --output-dir "$OUT/o" > "$log" 2>&1; then
      echo "failed"; tail -3 "$log" >&2; return
    fi
    local s t i m
    read -r dofs s t i m <<< "$(run_stats "$log")"
    setup+=("$s") solve+=("$t") iters+=("$i") mem+=("$m")
  done
  LAST_PHASES="| $dofs | $(feti_phases "$log" | tr -d '|' | awk '{$1 = $1; gsub(/ /, " | "); print}') |"
  echo "$(printf '%s\n' "${setup[@]}" | median) $(printf '%s\n' "${solve[@]}" | median)" \
       "$(printf '%s\n' "${iters[@]}" | median) $(printf '%s\n' "${mem[@]}" | median) $dofs"
}

echo "Machine: $(getconf _NPROCESSORS_ONLN) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(. /etc/os-release; echo "$PRETTY_NAME"); $RANKS MPI ranks; median of $REPS runs"
echo
echo "| DOFs | subdomains | strategy | setup s | solve s | iterations | peak memory / rank MiB |"
echo "| ---: | ---: | --- | ---: | ---: | ---: | ---: |"
for i in "${!SIZES[@]}"; do
  ref=${SIZES[$i]}
  nsub=${SUBS[$i]:-${SUBS[-1]}}
  base=(examples/elastic_block.xml --set "Mesh/Bodies/Block/Rectangle/Refinement=$ref" --set "Output/VTK=false"
        --set "Output/Progress=true")
  for strat in "${STRATEGIES[@]}"; do
    if [ "$strat" = FETI-DP ]; then
      args=("${base[@]}" --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=$nsub"
            "${PRIMAL_ARGS[@]}")
      subs=$nsub
    else
      args=("${base[@]}" --set "Solver/Linear Solver/Type=$strat")
      subs=$RANKS
    fi
    run_case "${args[@]}" > "$OUT/case" || true
    read -r s t it m d < "$OUT/case"
    if [ "$strat" = FETI-DP ] && [ "$s" != failed ]; then FETI_PHASES+=("$LAST_PHASES"); fi
    if [ "$s" = failed ]; then
      echo "| ? | $subs | $strat | failed | | | |"
    else
      label=$strat
      [ "$strat" = MUMPS ] && label="MUMPS (direct)"
      [ "$strat" = Belos-MueLu ] && label="Belos CG + MueLu SA"
      [ "$strat" = Belos-FROSch ] && label="Belos GMRES + FROSch GDSW"
      [ "$strat" = FETI-DP ] && label="FETI-DP (${PRIMAL:-default constraints}, Dirichlet, default local (CHOLMOD) and coarse (MUMPS) solvers, CG)"
      echo "| $d | $subs | $label | $s | $t | $it | $m |"
    fi
  done
done
if ((${#FETI_PHASES[@]})); then
  echo
  echo "FETI-DP phases (last run, seconds, max over ranks):"
  echo
  echo "| DOFs | local factorisation | coarse factorisation | Dirichlet factorisation | local solves | coarse solves | preconditioner |"
  echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  printf '%s\n' "${FETI_PHASES[@]}"
fi

if [ "${TABLE2:-1}" = 1 ]; then
  echo
  echo "FETI-DP (${PRIMAL:-default constraints}) dual iterations to relative residual 1e-8 (Belos CG), unit square, Box Grid N x N subdomains, one linear solve:"
  echo
  echo "| subdomains | H/h | Dirichlet | Lumped |"
  echo "| ---: | ---: | ---: | ---: |"
  for n in 2 4 8; do
    for hh in 8 16 32; do
      ref=$((n * hh / 8))
      row="| $((n * n)) | $hh |"
      for pre in Dirichlet Lumped; do
        log="$OUT/it.log"
        if mpirun -np "$RANKS" "$APP" test/benchmark/square.xml --output-dir "$OUT/it" \
            --set "Mesh/Bodies/Square/Rectangle/Refinement=$ref" --set "Solver/Strategy=FETI-DP" \
            --set "Partition/Method=Box Grid" --set "Partition/Box Grid X=$n" --set "Partition/Box Grid Y=$n" \
            --set "Solver/FETI-DP/Preconditioner=$pre" --set "Solver/FETI-DP/Belos/Convergence Tolerance=1e-8" \
            "${PRIMAL_ARGS[@]}" \
            > "$log" 2>&1; then
          # the first Newton solve (the second only confirms convergence)
          row="$row $(first_solve_iterations "$log") |"
        else
          row="$row failed |"
        fi
      done
      echo "$row"
    done
  done
fi
