#!/usr/bin/env bash
# Weak scaling by ranks (doc/performance.md, "Weak scaling by ranks"): not
# part of ctest. For each rank count P in PS, a model of about DOFS_PER_RANK
# x P DOFs, run once on P ranks:
# - elasticity: examples/block_3d.xml (Hex8, 768 R^3 DOFs at Refinement R),
#   with FETI-DP (automatic subdomain count) and with Belos-MueLu;
# - contact: examples/hertz_sphere.xml (decomposed element under FETI-DP,
#   4 load steps, METIS with the automatic subdomain count), refined as
#   Refinement 3's 50,424 DOFs x (R / 3)^3.
# One table row per run: DOFs, subdomains, coarse DOFs, dual/Krylov
# iterations, wall seconds, the share of the wall time outside the solver
# (MPI start, mesh, partition, model set-up, output: wall - assembly -
# linear set-up - linear solve), the coarse problem's share of FETI-DP's
# time, peak MiB per rank and the weak-scaling efficiency T(first P) / T(P)
# of the same model and strategy.
#
# On a machine with a core per rank the seconds mean something (the
# targets: 250k DOFs per rank from 1 to 16 ranks, outside-solver share <= 10 %
# and coarse share <= 15 % at 16 ranks, efficiency >= 70 %). Oversubscribed
# (more ranks than cores) only the DOFs, coarse sizes, iterations and memory
# per rank do.
#
#   bash test/benchmark/weak_scaling_ranks.sh [BUILD_DIR]     # default: build
# Environment: PS ("1 2 4 8 16"), DOFS_PER_RANK (250000), MODELS
#   ("block_3d hertz"), BLOCK_STRATEGIES ("FETI-DP Belos-MueLu"), BLOCK_MESH
#   ("whole"; "ranges": both models with PT-Scotch and Partition/Mesh On
#   Every Rank = false, so no rank builds the whole mesh).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container
PS=${PS:-"1 2 4 8 16"}
DOFS_PER_RANK=${DOFS_PER_RANK:-250000}
MODELS=${MODELS:-"block_3d hertz"}
BLOCK_STRATEGIES=${BLOCK_STRATEGIES:-"FETI-DP Belos-MueLu"}
BLOCK_MESH=${BLOCK_MESH:-whole}
cores=$(nproc --all)

# refinement MODEL P -> the refinement that gives about DOFS_PER_RANK x P DOFs.
refinement() {
  awk -v m="$1" -v p="$2" -v d="$DOFS_PER_RANK" 'BEGIN {
    per = (m == "block_3d") ? 768 : 50424 / 27; r = int((d * p / per) ^ (1 / 3) + 0.5); print (r < 1 ? 1 : r) }'
}

# run_case MODEL STRATEGY P: one run, one table row; T1 (first P of the
# model and strategy) kept in t_first.
declare -A t_first
run_case() {
  local model=$1 strategy=$2 p=$3 r deck args=() log="$OUT/run.log"
  r=$(refinement "$model" "$p")
  if [[ $model == block_3d ]]; then
    deck=examples/block_3d.xml
    args=(--set "Mesh/Bodies/Block/Box/Refinement=$r")
    [[ $BLOCK_MESH == ranges ]] && args+=(--set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=false")
    if [[ $strategy == FETI-DP ]]; then args+=(--set "Solver/Strategy=FETI-DP")
    else args+=(--set "Solver/Strategy=Monolithic" --set "Solver/Linear Solver/Type=$strategy"); fi
  else
    deck=examples/hertz_sphere.xml
    args=(--set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$r" --set "Mesh/Bodies/Block/Box/Refinement=$r"
          --set "Partition/Method=METIS" --set "Partition/Number of Subdomains=0")
    if [[ $BLOCK_MESH == ranges ]]; then
      args+=(--set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=false")
    fi
  fi
  rm -rf "$OUT/o"
  local t0 t1
  t0=$(date +%s.%N)
  if ! mpirun -np "$p" "$APP" "$deck" --output-dir "$OUT/o" --set "Output/VTK=false" "${args[@]}" > "$log" 2>&1; then
    echo "| $model | $strategy | $p | $r | failed: $(grep -m1 'error' "$log" | cut -c1-120) |"; return
  fi
  t1=$(date +%s.%N)
  local dofs setup solve its mem subs coarse assembly
  read -r dofs setup solve its mem <<< "$(run_stats "$log")"
  assembly=$(sed -n 's/^timing.*assembly \([0-9.]*\) s.*/\1/p' "$log")
  subs=$(sed -n 's/.*DOFs, \([0-9]*\) subdomains on.*/\1/p' "$log")
  coarse=$(sed -n 's/.*coarse problem of \([0-9]*\) DOFs.*/\1/p' "$log")
  local cf cs
  read -r _ cf _ _ _ cs _ <<< "$(feti_phases "$log")"
  local key="$model/$strategy"
  local wall
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}')
  [[ -n ${t_first[$key]:-} ]] || t_first[$key]=$wall
  awk -v m="$model" -v s="$strategy" -v p="$p" -v r="$r" -v dofs="$dofs" -v subs="${subs:-$p}" \
      -v coarse="${coarse:--}" -v its="$its" -v wall="$wall" -v asm="${assembly:-0}" -v setup="$setup" \
      -v solve="$solve" -v cf="${cf:-}" -v cs="${cs:-}" -v mem="$mem" -v t1="${t_first[$key]}" 'BEGIN {
    outside = 100 * (wall - asm - setup - solve) / wall
    share = (cf == "") ? "-" : sprintf("%.0f %%", 100 * (cf + cs) / (setup + solve))
    printf "| %s | %s | %d | %d | %d | %d | %s | %d | %.2f | %.0f %% | %s | %.0f | %.2f |\n",
      m, s, p, r, dofs, subs, coarse, its, wall, outside, share, mem, t1 / wall }'
}

echo "Weak scaling by ranks: about $DOFS_PER_RANK DOFs per rank, one run each, $cores cores" \
     "$( (( cores < ${PS##* } )) && echo "(oversubscribed beyond $cores ranks: seconds not meaningful)")"
echo
echo "| model | strategy | ranks | refinement | DOFs | subdomains | coarse DOFs | dual/Krylov its | wall s | outside solver | coarse share | peak MiB / rank | efficiency |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for model in $MODELS; do
  strategies=$BLOCK_STRATEGIES
  [[ $model == hertz ]] && strategies="FETI-DP"
  for strategy in $strategies; do
    for p in $PS; do run_case "$model" "$strategy" "$p"; done
  done
done
