# shellcheck shell=bash
# Shared by the benchmark scripts, sourced from the source tree's root as
#   . test/benchmark/common.sh BUILD_DIR
# $APP (BUILD_DIR/src/ddcontact, which must exist), RANKS (2) and REPS (3)
# from the environment, MPI environment for runs as root and oversubscribed,
# one BLAS/OpenMP thread per rank, a scratch directory removed on exit ($OUT),
# `median` (of numbers on stdin, one per line) and the parsers of a ddcontact
# log below.
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

# first_solve_iterations LOG -> dual/Krylov iterations of the first Newton
# solve (needs Newton/Print Iterations = true; 0 for a direct solve).
first_solve_iterations() {
  local n
  n=$(sed -n 's/.*iter  0 .*dual\/Krylov \([0-9]*\).*/\1/p' "$1" | head -1)
  echo "${n:-0}"
}
