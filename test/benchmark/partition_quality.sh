#!/usr/bin/env bash
# Parallel partitioning against METIS (doc/partitioning.md): for each case,
# the edge cut (facets between subdomains) and the largest subdomain of
# Partition/Method = METIS (serial, on every rank) and PT-Scotch (the dual
# graph built and partitioned in parallel on RANKS ranks), and their ratio;
# the target is a PT-Scotch edge cut within 1.2 times METIS's. Each run is
# stopped after its "partition:" line (the solve is not needed), so the
# script takes about a minute. Not part of ctest.
#
# Usage: bash test/benchmark/partition_quality.sh BUILD_DIR
#        (RANKS, default 2; the cases below: deck, subdomains, --set ...)
set -euo pipefail
cd "$(dirname "$0")/../.."
. test/benchmark/common.sh "${1:?usage: partition_quality.sh BUILD_DIR}"

# partition_line DECK METHOD ARGS... -> "cut largest mean" of the run's
# partition line; the run is stopped once it has printed it.
partition_line() {
  local deck=$1 method=$2 dir pid line=""
  shift 2
  dir=$(mktemp -d -p "$OUT")
  mpirun -np "$RANKS" "$APP" "$deck" --output-dir "$dir/out" --set "Partition/Method=$method" "$@" \
    > "$dir/log" 2>&1 &
  pid=$!
  while kill -0 "$pid" 2> /dev/null; do
    line=$(grep -m1 "^partition:" "$dir/log" 2> /dev/null || true)
    [[ -n "$line" ]] && { kill "$pid" 2> /dev/null; break; }
    sleep 0.2
  done
  wait "$pid" 2> /dev/null || true
  [[ -n "$line" ]] || line=$(grep -m1 "^partition:" "$dir/log" || true)
  [[ -n "$line" ]] || { echo "no partition line for $deck $method:" >&2; tail -5 "$dir/log" >&2; exit 1; }
  sed -n 's/.*edge cut \([0-9]*\) facets, largest subdomain \([0-9]*\) elements (mean \([0-9.]*\)).*/\1 \2 \3/p' <<< "$line"
}

# deck|case|arguments (an underscore in an argument stands for a space)
CASES=(
  "examples/block_3d.xml|Refinement 3, 15 subdomains|--set Mesh/Bodies/Block/Box/Refinement=3 --set Partition/Number_of_Subdomains=15"
  "examples/block_3d.xml|Refinement 8, 255 subdomains|--set Mesh/Bodies/Block/Box/Refinement=8 --set Partition/Number_of_Subdomains=255"
  "examples/block_3d.xml|Refinement 8, 2048 subdomains|--set Mesh/Bodies/Block/Box/Refinement=8 --set Partition/Number_of_Subdomains=2048"
  "examples/hertz_sphere.xml|8 subdomains|--set Partition/Number_of_Subdomains=8"
  "examples/hertz_sphere.xml|Refinement 3, 31 subdomains|--set Mesh/Bodies/Sphere/Sphere_Octant/Refinement=3 --set Mesh/Bodies/Block/Box/Refinement=3 --set Partition/Number_of_Subdomains=31"
  "examples/mindlin_sphere.xml|25 subdomains|--set Partition/Number_of_Subdomains=25"
  "examples/cattaneo_2d.xml|8 subdomains|--set Partition/Number_of_Subdomains=8"
  "examples/two_half_rings_3d.xml|16 subdomains|--set Partition/Number_of_Subdomains=16"
  "examples/elastic_block.xml|Refinement 8, 256 subdomains|--set Mesh/Bodies/Block/Rectangle/Refinement=8 --set Partition/Number_of_Subdomains=256"
)

echo "PT-Scotch on $RANKS ranks against METIS: edge cut in facets, largest subdomain in elements (mean)"
echo
echo "| deck | case | METIS cut | PT-Scotch cut | ratio | METIS largest | PT-Scotch largest | mean |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for c in "${CASES[@]}"; do
  IFS='|' read -r deck label extra <<< "$c"
  args=()
  for a in $extra; do args+=("${a//_/ }"); done
  read -r mc ml mean < <(partition_line "$deck" METIS "${args[@]}")
  read -r pc pl _ < <(partition_line "$deck" PT-Scotch "${args[@]}")
  ratio=$(awk -v a="$pc" -v b="$mc" 'BEGIN {printf "%.3f", a / b}')
  echo "| $(basename "$deck") | $label | $mc | $pc | $ratio | $ml | $pl | $mean |"
done
