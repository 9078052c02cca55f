#!/usr/bin/env bash
# Implicit dynamics with contact (doc/performance.md, "Dynamics with
# contact"): the Hertz impact (examples/sphere_impact.xml: a linear-elastic
# hemisphere dropped on a block 1000 times stiffer) at the deck's mesh
# refined REFINE times, STEPS time steps of DT. The paper's method (the
# decomposed element under FETI-DP on METIS subdomains: the subdomain
# matrices K^s + c M^s factorised once for the run) against the
# conventional element solved monolithically by MUMPS (K + c M with its
# contact rows factorised in every Newton iteration). Not part of ctest.
#
# Prints two markdown tables:
#  1. per configuration the median over REPS runs of the wall time per time
#     step, Newton iterations per step, dual iterations per Newton
#     iteration, linear set-up / solve seconds, and the wall ratio to
#     Monolithic over the same steps. Monolithic takes about half a minute
#     per step at Refinement 4, so both methods are compared over the first
#     MONO_STEPS steps (the contact phase, the dearest part of the run); the
#     paper's method then runs the whole STEPS steps (FULL_REPS runs) for
#     its cost per step over a whole impact;
#  2. FETI-DP dual iterations per Newton iteration against the time step
#     (DTS) with the default coarse space (vertices and edge averages) and
#     with vertices only (DT_STEPS steps each, one run).
#
#   bash test/benchmark/dynamics.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), REFINE (4: 108,036 DOFs), STEPS (100),
#              DT (0.01), MONO_STEPS (10), FULL_REPS (1), SUBDOMAINS
#              ("16"), DTS ("0.02 0.01 0.005"), DT_STEPS (20).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container
REFINE=${REFINE:-4}
STEPS=${STEPS:-100}
DT=${DT:-0.01}
MONO_STEPS=${MONO_STEPS:-10}
FULL_REPS=${FULL_REPS:-1}
DT_STEPS=${DT_STEPS:-20}
read -r -a SUBS <<< "${SUBDOMAINS:-16}"
read -r -a DTS <<< "${DTS:-0.02 0.01 0.005}"
DECK=examples/sphere_impact.xml
mesh=(--set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$REFINE")
timing() {  # timing STEPS DT -> the Dynamics options of STEPS steps of DT
  echo "Dynamics/Final Time=$(awk -v n="$1" -v h="$2" 'BEGIN {printf "%.10g", n * h}')"
}

echo "Hertz impact, Refinement $REFINE, time step $DT, $RANKS ranks, median of $REPS runs ($FULL_REPS for the whole impact)"
echo
echo "| method | DOFs | steps | wall s / step | Newton / step | dual its / Newton it | linear setup s | linear solve s | wall ratio to Monolithic |"
echo "|---|---|---|---|---|---|---|---|---|"
read -r mw mn _ ms mv dofs <<< "$(run_reps "$DECK" "$MONO_STEPS" steps "${mesh[@]}" \
    --set "$(timing "$MONO_STEPS" "$DT")" --set "Dynamics/Time Step=$DT" \
    --set "Contact/Formulation=Node-To-Surface" --set "Solver/Strategy=Monolithic")"
echo "| conventional, Monolithic (MUMPS) | $dofs | $MONO_STEPS | $mw | $mn | - | $ms | $mv | 1 |"
for n in "${SUBS[@]}"; do
  feti=(--set "Partition/Method=METIS" --set "Partition/Number of Subdomains=$n")
  read -r w nn d s v _ <<< "$(run_reps "$DECK" "$MONO_STEPS" steps "${mesh[@]}" \
      --set "$(timing "$MONO_STEPS" "$DT")" --set "Dynamics/Time Step=$DT" "${feti[@]}")"
  ratio=$(awk -v a="$w" -v b="$mw" 'BEGIN {printf "%.3f", a / b}')
  echo "| decomposed, FETI-DP, METIS $n | $dofs | $MONO_STEPS | $w | $nn | $d | $s | $v | $ratio |"
  read -r w nn d s v _ <<< "$(REPS=$FULL_REPS run_reps "$DECK" "$STEPS" steps "${mesh[@]}" \
      --set "$(timing "$STEPS" "$DT")" --set "Dynamics/Time Step=$DT" "${feti[@]}")"
  echo "| decomposed, FETI-DP, METIS $n, whole impact | $dofs | $STEPS | $w | $nn | $d | $s | $v | - |"
done

echo
echo "FETI-DP dual iterations per Newton iteration against the time step ($DT_STEPS steps, METIS ${SUBS[0]}, 1 run each)"
echo
echo "| time step | coarse space | dual its / Newton it | Newton / step | wall s / step |"
echo "|---|---|---|---|---|"
for dt in "${DTS[@]}"; do
  for primal in "Automatic" "Vertices"; do
    read -r w nn d _ <<< "$(REPS=1 run_reps "$DECK" "$DT_STEPS" steps "${mesh[@]}" \
        --set "$(timing "$DT_STEPS" "$dt")" --set "Dynamics/Time Step=$dt" \
        --set "Partition/Method=METIS" --set "Partition/Number of Subdomains=${SUBS[0]}" \
        --set "Solver/FETI-DP/Primal Constraints=$primal")"
    echo "| $dt | $primal | $d | $nn | $w |"
  done
done
