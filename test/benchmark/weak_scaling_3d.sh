#!/usr/bin/env bash
# FETI-DP weak scaling in 3-D by what one small machine can measure
# (doc/performance.md, "Weak scaling, on paper"): not part of ctest.
# The unit cube of examples/block_3d.xml (Length X = 1, Hex8, clamped at
# x = 0, traction on x = 1) with K x K x K elements, partitioned into a Box
# Grid of S = (K / H)^3 subdomains of H x H x H elements each, so that the
# subdomain size stays fixed while S grows (8 ... 1000 by default). Every
# case runs on RANKS ranks, however many subdomains: dual iterations and the
# coarse-problem size do not depend on the ranks, and the per-subdomain
# costs are measured where the 2 cores are not oversubscribed. One run per
# case (the iteration counts are deterministic; the seconds are one
# measurement each). Prints one markdown table: subdomains, DOFs, coarse
# DOFs (primal), dual iterations of the first Newton solve, and the phases
# of the FETI-DP set-up and solve (max over ranks): local factorisations
# per subdomain, coarse factorisation, and per dual iteration the
# subdomain work (local solves + preconditioner) per subdomain and the
# coarse solve.
#
#   bash test/benchmark/weak_scaling_3d.sh [BUILD_DIR]   # default: build
# Environment: RANKS (2), H (6: elements per subdomain edge), GRIDS
#   (subdomains per direction, "2 3 4 6 8 10"), PRIMAL (Solver/FETI-DP/
#   Primal Constraints, the default when empty), PARTITION ("Box Grid", or
#   METIS with the same number of subdomains).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container
H=${H:-6}
PRIMAL=${PRIMAL:-}
PARTITION=${PARTITION:-Box Grid}
read -r -a GRIDS <<< "${GRIDS:-2 3 4 6 8 10}"

echo "Machine: $(getconf _NPROCESSORS_ONLN) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo); $RANKS MPI ranks; one run per case; subdomains of ${H}^3 Hex8 ($PARTITION); primal constraints: ${PRIMAL:-default}; $(date -u '+%Y-%m-%d %H:%M UTC')"
echo
echo "| subdomains | DOFs | primal nodes | coarse DOFs | 1st solve dual its | local fact. ms / subdomain | coarse fact. s | subdomain work ms / it / subdomain | coarse solve ms / it | peak MiB / rank |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for k in "${GRIDS[@]}"; do
  n=$((k * H)) s=$((k * k * k))
  args=(--set "Mesh/Bodies/Block/Box/Length X=1.0"
        --set "Mesh/Bodies/Block/Box/Elements X=$n" --set "Mesh/Bodies/Block/Box/Elements Y=$n"
        --set "Mesh/Bodies/Block/Box/Elements Z=$n" --set "Solver/Strategy=FETI-DP"
        --set "Newton/Print Iterations=true" --set "Output/VTK=false")
  if [[ $PARTITION == "Box Grid" ]]; then
    args+=(--set "Partition/Method=Box Grid" --set "Partition/Box Grid X=$k" --set "Partition/Box Grid Y=$k"
           --set "Partition/Box Grid Z=$k")
  else
    args+=(--set "Partition/Method=$PARTITION" --set "Partition/Number of Subdomains=$s")
  fi
  [[ -z $PRIMAL ]] || args+=(--set "Solver/FETI-DP/Primal Constraints=$PRIMAL")
  log="$OUT/run.log"
  rm -rf "$OUT/o"
  if ! mpirun -np "$RANKS" "$APP" examples/block_3d.xml --output-dir "$OUT/o" "${args[@]}" > "$log" 2>&1; then
    echo "| $s | | failed: $(grep -m1 error "$log" | cut -c1-120) | | | | | | | |"
    continue
  fi
  read -r dofs _ _ its mem <<< "$(run_stats "$log")"
  first=$(first_solve_iterations "$log")
  primal=$(sed -n 's/^FETI-DP: .* subdomains, \([0-9]*\) primal nodes.*/\1/p' "$log")
  coarse=$(sed -n 's/^FETI-DP: .* coarse problem of \([0-9]*\) DOFs.*/\1/p' "$log")
  # FETI-DP (max over ranks): local factorisation A s, coarse factorisation B s,
  # Dirichlet factorisation C s; local solves D s, coarse solves E s, preconditioner F s
  read -r lf cf df ls cs pc <<< "$(grep '^FETI-DP (max' "$log" | tr -c '0-9.\n' ' ' | awk '{print $1, $2, $3, $4, $5, $6}')"
  # per subdomain: the busiest rank holds ceil(S / RANKS) of them
  awk -v s="$s" -v r="$RANKS" -v dofs="$dofs" -v p="$primal" -v c="$coarse" -v f="$first" -v its="$its" \
      -v lf="$lf" -v cf="$cf" -v df="$df" -v ls="$ls" -v cs="$cs" -v pc="$pc" -v mem="$mem" 'BEGIN {
    per = int((s + r - 1) / r)
    printf "| %d | %d | %d | %d | %d | %.1f | %.3f | %.3f | %.2f | %.0f |\n", s, dofs, p, c, f,
      1000 * (lf + df) / per, cf, 1000 * (ls + pc) / its / per, 1000 * cs / its, mem }'
done
