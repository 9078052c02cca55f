#!/usr/bin/env bash
# Coulomb friction's cost (doc/contact.md "Friction", doc/feti-dp.md
# "Friction rows"), on RANKS ranks, medians of REPS runs; one markdown table
# per case:
#   - cattaneo: Cattaneo's cylinder (examples/cattaneo_2d.xml) slid by a
#     prescribed x displacement of its top after the press (Q/(mu P) = 0.5;
#     the variant FETI-DP can solve, every body held by its own supports),
#     6 load steps, METIS SUBDOMAINS subdomains;
#   - hertz3: the Hertz sphere (examples/hertz_sphere.xml) at Refinement 3
#     (50,424 DOFs), 4 load steps, METIS with the default subdomain count.
#     Normal load only: the quarter model's symmetry planes admit no
#     tangential load; the sphere's surface slides outwards on the 1000
#     times stiffer block, so the contact has stick and slip nodes;
#   - mindlin: Mindlin's half model (examples/mindlin_sphere.xml, 41,910
#     DOFs) with a tangential load after the normal one: the sphere's top
#     slid 0.0015 in x after the press (Q/(mu P) = 0.515), 2 load steps,
#     METIS SUBDOMAINS subdomains (with the default 25 FETI-DP does not
#     converge on its graded mesh even without friction: doc/contact.md,
#     "Mindlin").
# Each table: the decomposed element under FETI-DP without and with
# friction (mu = 0.3): Newton iterations per step and dual iterations per
# Newton solve, and their ratio; against the conventional frictional element
# and the decomposed one solved monolithically (MUMPS): wall time per step.
# Not part of ctest.
#
#   bash test/benchmark/contact_friction.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), REPS (3), SUBDOMAINS (8, cattaneo and mindlin),
# CASES ("cattaneo hertz3 mindlin").
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
SUBDOMAINS=${SUBDOMAINS:-8}
CASES=${CASES:-cattaneo hertz3 mindlin}
DECOMPOSED=(--set "Contact/Formulation=Decomposed Node-To-Surface")
CONVENTIONAL=(--set "Contact/Formulation=Node-To-Surface")
MONO=(--set "Solver/Strategy=Monolithic")

# friction_table TITLE DECK STEPS PAIR FETI_ARGS_NAME ARGS...: the table of
# one case (the header comment), ARGS common to its runs.
friction_table() {
  local title=$1 deck=$2 steps=$3 pair=$4 fetiName=$5
  shift 5
  local -n fetiArgs=$fetiName
  echo "$title, $RANKS ranks, medians of $REPS runs ($(date -u +%Y-%m-%d))"
  echo
  echo "| case | DOFs | Newton / step | dual / Newton | wall s / step |"
  echo "|---|---|---|---|---|"
  local -A row
  local c args label m wall newton dual dofs
  for c in feti0 feti mono_dec mono_conv; do
    case $c in
      feti0) args=("${DECOMPOSED[@]}" "${fetiArgs[@]}") label="decomposed, FETI-DP, mu = 0"; m=0 ;;
      feti) args=("${DECOMPOSED[@]}" "${fetiArgs[@]}") label="decomposed, FETI-DP, mu = 0.3"; m=0.3 ;;
      mono_dec) args=("${DECOMPOSED[@]}" "${MONO[@]}") label="decomposed, Monolithic (MUMPS), mu = 0.3"; m=0.3 ;;
      mono_conv) args=("${CONVENTIONAL[@]}" "${MONO[@]}") label="conventional, Monolithic (MUMPS), mu = 0.3"; m=0.3 ;;
    esac
    read -r wall newton dual _ _ dofs <<< "$(run_reps "$deck" "$steps" steps "$@" "${args[@]}" \
      --set "Contact/Pairs/$pair/Friction Coefficient=$m")"
    row[$c]="$wall $newton $dual"
    echo "| $label | $dofs | $newton | $dual | $wall |"
  done
  local d0 d1 wf wc
  read -r _ _ d0 <<< "${row[feti0]}"
  read -r wf _ d1 <<< "${row[feti]}"
  read -r wc _ _ <<< "${row[mono_conv]}"
  echo
  awk -v a="$d1" -v b="$d0" -v f="$wf" -v c="$wc" 'BEGIN {
    printf "dual iterations per Newton solve, friction / frictionless: %.2f\n", a / b
    printf "wall time per step, decomposed FETI-DP / conventional Monolithic (friction): %.2f\n", f / c }'
  echo
}

# The 'Push' condition of the Cattaneo and Mindlin decks turned into a
# prescribed x displacement of the top (every body held by its own supports,
# as FETI-DP needs), and FETI-DP on SUBDOMAINS METIS subdomains.
slid_by() {
  SLID=(--set "Boundary Conditions/Push/Type=Displacement" --set "Boundary Conditions/Push/Components=X"
        --set "Boundary Conditions/Push/Value X=$1" --set "Boundary Conditions/Push/Traction X=0")
}
FETI_METIS_N=(--set "Solver/Strategy=FETI-DP" --set "Partition/Method=METIS"
              --set "Partition/Number of Subdomains=$SUBDOMAINS")

for case in $CASES; do
  case $case in
    cattaneo)
      slid_by 0.0025
      friction_table "Cattaneo's cylinder slid after the press (FETI-DP on METIS $SUBDOMAINS)" \
        examples/cattaneo_2d.xml 6 "Cylinder on block" FETI_METIS_N "${SLID[@]}" ;;
    hertz3)
      FETI_HERTZ=(--set "Solver/Strategy=FETI-DP" --set "Partition/Method=METIS")
      friction_table "Hertz sphere at Refinement 3 (FETI-DP on METIS, default subdomains)" \
        examples/hertz_sphere.xml 4 "Sphere on block" FETI_HERTZ \
        --set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=3" --set "Mesh/Bodies/Block/Box/Refinement=3" ;;
    mindlin)
      slid_by 0.0015
      friction_table "Mindlin's sphere slid after the press (FETI-DP on METIS $SUBDOMAINS)" \
        examples/mindlin_sphere.xml 2 "Sphere on block" FETI_METIS_N "${SLID[@]}" ;;
    *) echo "contact_friction.sh: unknown case '$case' in CASES (cattaneo, hertz3, mindlin)" >&2; exit 2 ;;
  esac
done
