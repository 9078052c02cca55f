#!/usr/bin/env bash
# Mesh convergence of Hertz contact (examples/hertz_sphere.xml, doc/contact.md
# "Hertz contact"): the deck at several Sphere Octant refinements with the
# conventional element solved monolithically and the decomposed element under
# FETI-DP (one subdomain per body), each compared with Hertz's contact radius
# and peak pressure by ddcontact-hertz; one table at the end.
#
#   bash examples/hertz_convergence.sh [BUILD_DIR [OUT_DIR]]   # defaults: build, ddcontact-out/hertz
#
# Environment: NP (MPI ranks, 2), REFINEMENTS ("1 2 3"; Refinement 3 is
# 47k DOFs and takes minutes). Extra ddcontact options after "--" apply to
# every run. Exit status 1 if a run or ddcontact-hertz fails.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
out=${2:-ddcontact-out/hertz}
shift $(( $# > 2 ? 2 : $# ))
[[ ${1:-} == -- ]] && shift
NP=${NP:-2}
REFINEMENTS=${REFINEMENTS:-"1 2 3"}
app="$build/src/ddcontact"
tool="$build/src/ddcontact-hertz"
for exe in "$app" "$tool"; do
  [[ -x $exe ]] || { echo "hertz_convergence.sh: $exe not found (build first: bash cmake/setup.sh build)" >&2; exit 1; }
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OPENBLAS_NUM_THREADS=1
extra=("$@")
rows=()
for r in $REFINEMENTS; do
  for variant in conventional decomposed; do
    if [[ $variant == conventional ]]; then
      opts=(--set "Contact/Formulation=Node-To-Surface" --set "Solver/Strategy=Monolithic")
    else
      opts=()
    fi
    dir="$out/r$r-$variant"
    echo "== Refinement $r, $variant: mpirun -np $NP ddcontact examples/hertz_sphere.xml ${opts[*]}"
    start=$(date +%s.%N)
    mkdir -p "$out"
    mpirun -np "$NP" "$app" "$here/hertz_sphere.xml" --output-dir "$dir" \
      --set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$r" --set "Output/VTK=false" --set "Output/Progress=false" \
      "${opts[@]+"${opts[@]}"}" "${extra[@]+"${extra[@]}"}" > "$out/r$r-$variant.log" 2>&1 ||
      { cat "$out/r$r-$variant.log" >&2; echo "hertz_convergence.sh: the run failed" >&2; exit 1; }
    seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    report=$("$tool" "$dir")
    echo "$report"
    dofs=$(grep -o "[0-9]* DOFs" "$out/r$r-$variant.log" | head -1 | cut -d' ' -f1)
    a=$(echo "$report" | awk '/contact radius a/ {print $5, $6, $7}')
    p=$(echo "$report" | awk '/peak pressure p0/ {print $4, $5, $6}')
    n=$(echo "$report" | sed -n 's/.* \([0-9][0-9]*\) active slave nodes.*/\1/p')
    rows+=("$(printf '%-3s %-13s %7s %6s %10s %10s %9s %10s %10s %9s %8s' "$r" "$variant" "$dofs" "$n" $a $p "$seconds")")
  done
done
echo
echo "Hertz contact, mesh convergence ($NP ranks): a = contact radius (fit), p0 = peak pressure"
printf '%-3s %-13s %7s %6s %10s %10s %9s %10s %10s %9s %8s\n' ref variant DOFs active a_fe a_hertz err_a p0_fe p0_hertz err_p0 seconds
for row in "${rows[@]}"; do echo "$row"; done
