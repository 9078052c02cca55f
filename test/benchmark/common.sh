# shellcheck shell=bash
# Shared by the benchmark scripts, sourced from the source tree's root as
#   . test/benchmark/common.sh BUILD_DIR
# $APP (BUILD_DIR/src/ddcontact, which must exist), RANKS (2) and REPS (3)
# from the environment, MPI environment for runs as root and oversubscribed,
# one BLAS/OpenMP thread per rank, a scratch directory removed on exit ($OUT),
# `median` (of numbers on stdin, one per line), the parsers of a ddcontact
# log and run_reps (repeated runs, medians) below.
APP="$1/src/ddcontact"
[[ -x "$APP" ]] || { echo "$(basename "$0"): no ddcontact in '$1/src' (build first)" >&2; exit 2; }
RANKS=${RANKS:-2}
REPS=${REPS:-3}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {if (NR==0) print "nan"; else if (NR%2) print a[(NR+1)/2]; else print (a[NR/2]+a[NR/2+1])/2}'; }

# run_stats LOG -> "dofs setup solve iterations memory": the DOF count of the
# header line and, from the "timing (max over ranks)" line, linear setup and
# solve seconds, dual/Krylov iterations summed over the solves and peak
# memory per rank (MiB).
run_stats() {
  local t
  t=$(grep "^timing" "$1")
  echo "$(sed -n 's/.* elements, \([0-9]*\) DOFs.*/\1/p' "$1")" \
       "$(sed -n 's/.*linear setup \([0-9.]*\) s.*/\1/p' <<< "$t")" \
       "$(sed -n 's/.*linear solve \([0-9.]*\) s.*/\1/p' <<< "$t")" \
       "$(sed -n 's/.*(\([0-9]*\) dual\/Krylov.*/\1/p' <<< "$t")" \
       "$(sed -n 's/.*peak memory per rank \([0-9.]*\) MiB.*/\1/p' <<< "$t")"
}

# feti_phases LOG -> "local coarse dirichlet | local_solves coarse_solves
# preconditioner" seconds of the run's FETI-DP line (max over ranks), or ""
# for another strategy.
feti_phases() {
  grep '^FETI-DP (max' "$1" | tr -c '0-9.\n' ' ' | awk '{print $1, $2, $3, "|", $4, $5, $6}'
}

# first_solve_iterations LOG -> dual/Krylov iterations of the first Newton
# solve (needs Newton/Print Iterations = true; 0 for a direct solve).
first_solve_iterations() {
  local n
  n=$(sed -n 's/.*iter  0 .*dual\/Krylov \([0-9]*\).*/\1/p' "$1" | head -1)
  echo "${n:-0}"
}

# run_reps DECK STEPS PER ARGS...: REPS runs of ddcontact DECK with STEPS load
# steps (VTK off) and ARGS -> "wall/step newton/step dual/newton setup solve
# dofs": medians of the wall time per step and of the linear setup / solve
# seconds (run_stats), Newton iterations per step and dual iterations per
# Newton iteration of the last run (history.csv). PER: "steps" divides by the
# nominal step count, "rows" by history.csv's rows (bisection sub-steps
# count). Prints "failed" (and the log's tail on stderr) if a run fails.
run_reps() {
  local deck=$1 steps=$2 per=$3
  shift 3
  local wall=() setup=() solve=() newton="" dual="" dofs=""
  for ((r = 0; r < REPS; r++)); do
    local log="$OUT/run.log"
    rm -rf "$OUT/o"
    if ! mpirun -np "$RANKS" "$APP" "$deck" --output-dir "$OUT/o" --set "Load Stepping/Number of Steps=$steps" \
         --set "Output/VTK=false" "$@" > "$log" 2>&1; then
      echo "failed"; tail -3 "$log" >&2; return
    fi
    local s t
    read -r dofs s t _ <<< "$(run_stats "$log")"
    setup+=("$s") solve+=("$t")
    # history.csv: wall_seconds of the last row; Newton and dual sums
    local h="$OUT/o/history.csv"
    wall+=("$(awk -F, -v per="$per" -v n="$steps" 'NR>1 {w=$10; k++} END {printf "%.4f", w/(per=="rows"?k:n)}' "$h")")
    newton=$(awk -F, -v per="$per" -v n="$steps" 'NR>1 {s+=$4; k++} END {printf "%.2f", s/(per=="rows"?k:n)}' "$h")
    dual=$(awk -F, 'NR>1 {s+=$5; t+=$4} END {printf "%.1f", (t ? s/t : 0)}' "$h")
  done
  echo "$(printf '%s\n' "${wall[@]}" | median) $newton $dual $(printf '%s\n' "${setup[@]}" | median)" \
       "$(printf '%s\n' "${solve[@]}" | median) $dofs"
}
