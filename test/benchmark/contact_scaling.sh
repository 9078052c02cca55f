#!/usr/bin/env bash
# Across-partition contact at growing mesh sizes (doc/performance.md,
# "Across-partition contact that pays"): the Hertz sphere
# (examples/hertz_sphere.xml, a soft hemisphere pressed on a block 1000
# times stiffer, 4 load steps) refined, on METIS subdomains of the default
# size (Partition/Number of Subdomains = 0), every solver option at its
# default. Per refinement two runs of the same mesh:
#   - the conventional node-to-surface element solved monolithically (MUMPS),
#     the reference a user would otherwise run;
#   - the paper's decomposed element under FETI-DP.
# Not part of ctest. Prints one markdown table: DOFs, subdomains, wall time
# of the whole process (median of REPS runs while a run takes under a
# minute, else one run), Newton solves, dual iterations per Newton solve,
# how often the matrices were factorised, peak memory per rank, and the
# ratio of the wall times.
#
#   bash test/benchmark/contact_scaling.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), REFINE ("2 3 4 5"). A refinement whose
#   monolithic factorisation would not fit the memory (estimated from the
#   DOFs, MemAvailable) is run for FETI-DP only.
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
read -r -a REFINE <<< "${REFINE:-2 3 4 5}"
DECK=examples/hertz_sphere.xml

# MUMPS' LDL^T of this 3-D problem took 0.75 GiB per rank at 50k DOFs on 2
# ranks (refinement 3) and grows like DOFs^(4/3) (nested-dissection fill in
# 3-D); refuse what would take more than 80 % of the memory available.
fits_monolithic() {
  local dofs=$1 avail
  avail=$(awk '/MemAvailable/ {print $2 / 1048576}' /proc/meminfo)
  awk -v n="$dofs" -v a="$avail" -v r="$RANKS" \
    'BEGIN {need = r * 0.75 * (n / 50424) ^ (4 / 3); exit !(need < 0.8 * a)}'
}

# one RUN_ARGS... -> "wall newton dual/newton factorisations memory subdomains dofs" of one run
one() {
  local log="$OUT/run.log" t0 t1
  rm -rf "$OUT/o"
  t0=$(date +%s.%N)
  if ! mpirun -np "$RANKS" "$APP" "$DECK" --output-dir "$OUT/o" --set "Output/VTK=false" "$@" > "$log" 2>&1; then
    echo "failed"; tail -3 "$log" >&2; return
  fi
  t1=$(date +%s.%N)
  local dofs mem solves dual subs fact
  read -r dofs _ _ dual mem <<< "$(run_stats "$log")"
  solves=$(sed -n 's/.* over \([0-9]*\) solves.*/\1/p' "$log")
  subs=$(sed -n 's/^FETI-DP: \([0-9]*\) subdomains,.*/\1/p' "$log")
  # FETI-DP: how often each subdomain matrix was factorised; the monolithic
  # solve refactorises the whole matrix for every Newton solve with contact.
  fact=$(sed -n 's/.*each subdomain factorised \([0-9]*\) time.*/\1 per subdomain/p' "$log")
  [[ -n "$fact" ]] || fact="$solves"
  echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}') $solves" \
       "$(awk -v d="$dual" -v s="$solves" 'BEGIN {printf "%.1f", (s ? d / s : 0)}')" \
       "${fact// /_} $mem ${subs:-1} $dofs"
}

# runs RUN_ARGS... -> one()'s fields with the median wall time of REPS runs
# (one run if the first takes a minute or more)
runs() {
  local first walls rest
  first=$(one "$@")
  [[ "$first" == failed ]] && { echo failed; return; }
  read -r walls rest <<< "$first"
  if awk -v w="$walls" 'BEGIN {exit !(w < 60)}'; then
    for ((r = 1; r < REPS; r++)); do
      local w
      read -r w _ <<< "$(one "$@")"
      walls="$walls $w"
    done
  fi
  echo "$(tr ' ' '\n' <<< "$walls" | median) $rest"
}

echo "Hertz sphere (examples/hertz_sphere.xml), METIS subdomains of the default size, $RANKS ranks, defaults;"
echo "wall: whole process, median of $REPS runs under a minute, else one run"
echo
echo "| refinement | DOFs | formulation, strategy | subdomains | wall s | Newton solves | dual its / Newton solve | factorisations | peak MiB / rank | wall ratio to Monolithic |"
echo "|---|---:|---|---:|---:|---:|---:|---|---:|---:|"
for f in "${REFINE[@]}"; do
  mesh=(--set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$f" --set "Mesh/Bodies/Block/Box/Refinement=$f")
  read -r w n d fa m s dofs <<< "$(runs "${mesh[@]}" --set "Partition/Method=METIS" \
      --set "Partition/Number of Subdomains=0")"
  mono="-"
  if [[ "$w" != failed ]] && fits_monolithic "$dofs"; then
    read -r mw mn _ mfa mm _ _ <<< "$(runs "${mesh[@]}" --set "Contact/Formulation=Node-To-Surface" \
        --set "Solver/Strategy=Monolithic")"
    echo "| $f | $dofs | conventional, Monolithic (MUMPS) | 1 | $mw | $mn | - | $mfa | $mm | 1 |"
    [[ "$mw" != failed ]] && mono=$mw
  elif [[ "$w" != failed ]]; then
    echo "| $f | $dofs | conventional, Monolithic (MUMPS) | - | does not fit | - | - | - | - | - |"
  fi
  ratio=$(awk -v a="$w" -v b="$mono" 'BEGIN {if (b == "-" || a == "failed") print "-"; else printf "%.2f", a / b}')
  echo "| $f | ${dofs:--} | decomposed, FETI-DP | $s | $w | $n | $d | ${fa//_/ } | $m | $ratio |"
done
