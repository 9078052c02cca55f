#!/usr/bin/env bash
# Coulomb friction's cost (doc/contact.md "Friction", doc/feti-dp.md
# "Friction rows"): Cattaneo's cylinder (examples/cattaneo_2d.xml) slid by a
# prescribed x displacement of its top after the press (Q/(mu P) = 0.5; the
# variant FETI-DP can solve, every body held by its own supports), 6 load
# steps, on RANKS ranks:
#   - the decomposed element under FETI-DP on METIS subdomains, without and
#     with friction (mu = 0.3): Newton iterations per step and dual
#     iterations per Newton solve, and their ratio;
#   - the same against the conventional frictional element and the
#     decomposed one solved monolithically (MUMPS): wall time per step.
# Medians of REPS runs. Not part of ctest. Prints a markdown table.
#
#   bash test/benchmark/contact_friction.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), SUBDOMAINS (8).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
SUBDOMAINS=${SUBDOMAINS:-8}
DECK=examples/cattaneo_2d.xml
SLIDE=(--set "Boundary Conditions/Push/Type=Displacement" --set "Boundary Conditions/Push/Components=X"
       --set "Boundary Conditions/Push/Value X=0.0025" --set "Boundary Conditions/Push/Traction X=0")
DECOMPOSED=(--set "Contact/Formulation=Decomposed Node-To-Surface")
CONVENTIONAL=(--set "Contact/Formulation=Node-To-Surface")
FETI=(--set "Solver/Strategy=FETI-DP" --set "Partition/Method=METIS" --set "Partition/Number of Subdomains=$SUBDOMAINS")
MONO=(--set "Solver/Strategy=Monolithic")

echo "Cattaneo's cylinder slid after the press, $RANKS ranks, medians of $REPS runs ($(date -u +%Y-%m-%d))"
echo
echo "| case | DOFs | Newton / step | dual / Newton | wall s / step |"
echo "|---|---|---|---|---|"
declare -A row
for c in feti0 feti mono_dec mono_conv; do
  case $c in
    feti0) args=("${DECOMPOSED[@]}" "${FETI[@]}") label="decomposed, FETI-DP METIS $SUBDOMAINS, mu = 0"; m=0 ;;
    feti) args=("${DECOMPOSED[@]}" "${FETI[@]}") label="decomposed, FETI-DP METIS $SUBDOMAINS, mu = 0.3"; m=0.3 ;;
    mono_dec) args=("${DECOMPOSED[@]}" "${MONO[@]}") label="decomposed, Monolithic (MUMPS), mu = 0.3"; m=0.3 ;;
    mono_conv) args=("${CONVENTIONAL[@]}" "${MONO[@]}") label="conventional, Monolithic (MUMPS), mu = 0.3"; m=0.3 ;;
  esac
  read -r wall newton dual _ _ dofs <<< "$(run_reps "$DECK" 6 steps "${SLIDE[@]}" "${args[@]}" \
    --set "Contact/Pairs/Cylinder on block/Friction Coefficient=$m")"
  row[$c]="$wall $newton $dual"
  echo "| $label | $dofs | $newton | $dual | $wall |"
done
read -r _ _ d0 <<< "${row[feti0]}"
read -r wf _ d1 <<< "${row[feti]}"
read -r wc _ _ <<< "${row[mono_conv]}"
echo
awk -v a="$d1" -v b="$d0" -v f="$wf" -v c="$wc" 'BEGIN {
  printf "dual iterations per Newton solve, friction / frictionless: %.2f\n", a / b
  printf "wall time per step, decomposed FETI-DP / conventional Monolithic (friction): %.2f\n", f / c }'
