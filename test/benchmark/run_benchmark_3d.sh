#!/usr/bin/env bash
# 3-D performance benchmark (doc/performance.md, "3-D: block_3d"): not part
# of ctest. examples/block_3d.xml (Hex8 brick, 16 x 4 x 4 elements times
# Refinement N, 3 (16N+1)(4N+1)^2 DOFs: N = 5, 8, 11 -> 107163, 421443,
# 1075275) on RANKS ranks with MUMPS (monolithic direct), Belos CG + MueLu
# and FETI-DP (primal constraints PRIMAL, Dirichlet preconditioner, METIS
# subdomains of about SUB_DOFS DOFs each: 1650, the fastest of 64 ... 502
# subdomains at 421k DOFs with the default constraints and the Schur
# complement path, doc/performance.md). Prints a markdown table:
# median over REPS runs of linear set-up and solve seconds, dual/Krylov
# iterations (summed over the 2 Newton solves of the one load step, and of
# the first solve alone) and peak memory per rank; then the FETI-DP phase
# breakdown of each FETI-DP case (its last run).
#
#   bash test/benchmark/run_benchmark_3d.sh [BUILD_DIR]   # default: build
# Environment: RANKS (2), REPS (3), SIZES (refinements run with every
#   strategy, "5 8 11"), MUMPS_SIZES (refinements run with MUMPS only, to find
#   the largest that fits, "9 10"), SUBDOMAINS (FETI-DP subdomains per entry
#   of SIZES; default DOFs / SUB_DOFS rounded), SUB_DOFS (1650), PRIMAL
#   (Solver/FETI-DP/Primal Constraints; empty: the default),
#   MEM_FRACTION (0.9: share of MemAvailable the ranks may use together),
#   TIMEOUT (3600: seconds one run may take).
#
# Memory guard (the machine must never swap or call the OOM killer): before
# a case, its peak memory per rank is estimated from the two largest earlier
# sizes of the same strategy: a fixed 64 MiB plus a power law in the DOFs
# (exponent at least 4/3 for MUMPS, the fill of a nested-dissection
# factorisation in 3-D, and 1 for the others); a case whose
# estimate exceeds MEM_FRACTION x MemAvailable / RANKS is run once instead of
# REPS times, to measure whether it fits. Every rank runs under `prlimit --as`
# of that share, so a case that does not fit fails its allocation ("out of
# memory" in the table) instead of exhausting the machine (see guarded_run for the one allocation that
# spins instead of failing). The address-space limit also counts ~0.4 GiB per
# rank of mapped but unused libraries/MPI segments, so it errs on the safe side.
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
SUB_DOFS=${SUB_DOFS:-1650}
PRIMAL=${PRIMAL:-}
PRIMAL_ARGS=()
[[ -z $PRIMAL ]] || PRIMAL_ARGS=(--set "Solver/FETI-DP/Primal Constraints=$PRIMAL")
FETI_PHASES=()
MEM_FRACTION=${MEM_FRACTION:-0.9}
TIMEOUT=${TIMEOUT:-3600}
read -r -a SIZES <<< "${SIZES:-5 8 11}"
read -r -a MUMPS_SIZES <<< "${MUMPS_SIZES-9 10}"
read -r -a SUBS <<< "${SUBDOMAINS:-}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container

dofs_of() { echo $((3 * (16 * $1 + 1) * (4 * $1 + 1) ** 2)); }
# memory the ranks may use, MiB per rank
budget_mib() { awk -v f="$MEM_FRACTION" -v r="$RANKS" '/MemAvailable/ {printf "%d", f * $2 / 1024 / r}' /proc/meminfo; }
gib() { awk -v m="$1" 'BEGIN {printf "%.1f", m / 1024}'; }

# Measured peak MiB per rank, per strategy: "dofs:mib dofs:mib ..." in size order.
declare -A MEASURED=()
# estimate_mib STRATEGY DOFS -> estimated peak MiB per rank, or "" before any
# measurement: BASE_MIB (the footprint of a tiny run: MPI, Trilinos) plus a
# power law in the DOFs for the rest
BASE_MIB=64
estimate_mib() {
  local minexp=1
  [[ $1 == MUMPS ]] && minexp=1.3333
  awk -v n="$2" -v e0="$minexp" -v z="$BASE_MIB" -v pts="${MEASURED[$1]:-}" 'BEGIN {
    k = split(pts, p, " "); if (k == 0) exit
    split(p[k], b, ":"); e = e0
    if (k > 1) { split(p[k - 1], a, ":"); if (a[2] > z && b[2] > a[2]) { m = log((b[2] - z) / (a[2] - z)) / log(b[1] / a[1]); if (m > e) e = m } }
    printf "%d", z + (b[2] > z ? b[2] - z : 1) * (n / b[1]) ^ e }'
}

# guarded_run LIMIT_MIB LOG ARGS... -> exit status of ddcontact on RANKS ranks,
# each under an address-space limit of LIMIT_MIB; 137 after the watchdog
# killed it: OpenBLAS does not fail when its buffer allocation hits the limit
# but retries forever, so a rank whose address space stays within 160 MiB
# (more than its 128 MiB request) of the limit for 30 s counts as out of
# memory, and a run longer than TIMEOUT seconds is stopped too.
guarded_run() {
  local limit=$1 log=$2 pid near=0 start=$SECONDS
  shift 2
  nice mpirun -np "$RANKS" prlimit --as=$((limit * 1048576)) "$APP" examples/block_3d.xml \
    --set "Output/VTK=false" --set "Newton/Print Iterations=true" "$@" --output-dir "$OUT/o" > "$log" 2>&1 &
  pid=$!
  while kill -0 "$pid" 2> /dev/null; do
    sleep 1
    local top
    top=$(for c in $(pgrep -P "$pid"); do awk '/VmSize/ {print int($2 / 1024)}' "/proc/$c/status" 2> /dev/null; done | sort -n | tail -1)
    if [[ -n $top ]] && ((top > limit - 160)); then near=$((near + 1)); else near=0; fi
    if ((near >= 30)); then
      echo "guard: a rank spins at its address-space limit (${top} of ${limit} MiB): killed" >> "$log"
      kill "$pid"
    elif ((SECONDS - start > TIMEOUT)); then
      echo "guard: timed out after $TIMEOUT s: killed" >> "$log"
      kill "$pid"
    fi
  done
  wait "$pid"
}

# run_case ARGS... -> "ok dofs setup solve iterations first memory" (medians of
# REPS), "oom LIMIT_MIB", "timeout" or "failed: REASON"
run_case() {
  local setup=() solve=() iters=() first=() mem=() dofs="" log="$OUT/run.log"
  for ((r = 0; r < REPS; r++)); do
    local limit
    limit=$(budget_mib)
    if ! guarded_run "$limit" "$log" "$@"; then
      if grep -qiE 'memory allocation failed|bad_alloc|cannot allocate|out of memory|spins at its address-space limit' "$log"; then
        echo "oom $limit"
      elif grep -q 'guard: timed out' "$log"; then
        echo "timeout"
      else
        # the error line, and the exception's message where it follows its file position
        echo "failed: $(grep -m1 'error' "$log" | sed 's/.*error[^:]*: //; s/:[^:]*\.[ch]pp:[0-9]*: *$//')" \
             "$(grep -m1 -E 'encountered|::[A-Za-z]+\(\): ' "$log" | sed 's/^[A-Za-z:]*(): //')"
      fi
      tail -3 "$log" >&2
      return
    fi
    local s t i m
    read -r dofs s t i m <<< "$(run_stats "$log")"
    setup+=("$s") solve+=("$t") iters+=("$i") mem+=("$m") first+=("$(first_solve_iterations "$log")")
  done
  feti_phases "$log" > "$OUT/phases"
  echo "ok $dofs $(printf '%s\n' "${setup[@]}" | median) $(printf '%s\n' "${solve[@]}" | median)" \
       "$(printf '%s\n' "${iters[@]}" | median) $(printf '%s\n' "${first[@]}" | median)" \
       "$(printf '%s\n' "${mem[@]}" | median)"
}

echo "Machine: $(getconf _NPROCESSORS_ONLN) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(. /etc/os-release; echo "$PRETTY_NAME"); $RANKS MPI ranks; median of $REPS runs; load average at start $(cut -d' ' -f1 /proc/loadavg); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo
echo "| DOFs | subdomains | strategy | setup s | solve s | iterations | 1st solve iterations | peak memory / rank MiB |"
echo "| ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |"
mapfile -t ALL < <(printf '%s\n' "${SIZES[@]}" "${MUMPS_SIZES[@]}" | sort -nu)
for ref in "${ALL[@]}"; do
  n=$(dofs_of "$ref")
  strategies=(MUMPS)
  nsub=""
  for i in "${!SIZES[@]}"; do
    if [[ ${SIZES[$i]} == "$ref" ]]; then
      strategies=(MUMPS Belos-MueLu FETI-DP)
      nsub=${SUBS[$i]:-$(( (n + SUB_DOFS / 2) / SUB_DOFS ))}
      ((nsub >= 2)) || nsub=2
    fi
  done
  base=(--set "Mesh/Bodies/Block/Box/Refinement=$ref")
  for strat in "${strategies[@]}"; do
    case $strat in
      MUMPS) label="MUMPS (direct)" subs=$RANKS
        args=("${base[@]}" --set "Solver/Strategy=Monolithic" --set "Solver/Linear Solver/Type=MUMPS") ;;
      Belos-MueLu) label="Belos CG + MueLu SA" subs=$RANKS
        args=("${base[@]}" --set "Solver/Strategy=Monolithic" --set "Solver/Linear Solver/Type=Belos-MueLu") ;;
      FETI-DP) label="FETI-DP (${PRIMAL:-default constraints}, Dirichlet, default local (CHOLMOD) and coarse (MUMPS) solvers, CG)" subs=$nsub
        args=("${base[@]}" --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=$nsub"
              "${PRIMAL_ARGS[@]}" --set "Solver/FETI-DP/Belos/Maximum Iterations=5000") ;;
    esac
    est=$(estimate_mib "$strat" "$n")
    avail=$(budget_mib)
    reps=$REPS note=""
    if [[ -n $est ]] && ((est > avail)); then
      reps=1 note=" (1 run: estimated $(gib "$est") GiB per rank > $(gib "$avail") GiB available)"
    fi
    result=$(REPS=$reps run_case "${args[@]}") || true
    read -r status d s t it first m <<< "$result"
    case $status in
      ok) echo "| $d | $subs | $label$note | $s | $t | $it | $first | $m |"
          MEASURED[$strat]="${MEASURED[$strat]:-} $d:$m"
          if [[ $strat == FETI-DP ]]; then
            FETI_PHASES+=("| $d | $subs | $(tr -d '|' < "$OUT/phases" | awk '{$1 = $1; gsub(/ /, " | "); print}') |")
          fi ;;
      oom) echo "| $n | $subs | $label$note | out of memory (limit $(gib "$d") GiB per rank) | | | | |" ;;
      timeout) echo "| $n | $subs | $label | timed out (> $TIMEOUT s) | | | | |" ;;
      *) echo "| $n | $subs | $label | ${result//|/\\|} | | | | |" ;;
    esac
  done
done
if ((${#FETI_PHASES[@]})); then
  echo
  echo "FETI-DP phases (last run, seconds, max over ranks):"
  echo
  echo "| DOFs | subdomains | local factorisation | coarse factorisation | Dirichlet factorisation | local solves | coarse solves | preconditioner |"
  echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
  printf '%s\n' "${FETI_PHASES[@]}"
fi
