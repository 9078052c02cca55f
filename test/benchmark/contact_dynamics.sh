#!/usr/bin/env bash
# Contact in dynamics (doc/user-guide.md, "Contact in dynamics"): what the
# contact-surface mass and the integrator do to an impact. The bar impact
# (examples/bar_impact.xml: two elastic bars meeting at t = 0, exact contact
# time 2L/c = 20, velocities reversed, energy kept) with each integrator,
# the surface mass redistributed (the default) or kept, and the time step
# halved. Not part of ctest (the acceptance checks are in
# analysis_dynamics_contact). Prints one markdown table: per run the number
# of separate contact intervals (1 is right), the last time in contact
# (exact: 20), the largest and the final total energy over the initial
# (exact: 1 throughout) and the largest contact force over rho c v A = 0.1.
#
#   bash test/benchmark/contact_dynamics.sh [BUILD_DIR]     # default: build
# Environment: RANKS (2), STEPS ("0.25 0.125": time steps).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # no CMA in this container
read -r -a DTS <<< "${STEPS:-0.25 0.125}"

# summary HISTORY -> "intervals last_in_contact max_energy final_energy max_force"
summary() {
  awk -F, 'NR == 1 {for (i = 1; i <= NF; i++) c[$i] = i; next}
    {t = $c["time"]; a = $c["active_contacts"]; E = $c["total_energy"]; f = -$c["contact_force_x"]
     if (a > 0 && !on) n++
     on = a > 0
     if (on) last = t
     if (E > Emax) Emax = E
     if (f > fmax) fmax = f
     Eend = E}
    END {printf "%d %s %.4f %.4f %.2f", n, last, Emax / 0.1, Eend / 0.1, fmax / 0.1}' "$1"
}

echo "Bar impact (examples/bar_impact.xml, decomposed element, FETI-DP, $RANKS ranks)"
echo
echo "| integrator | surface mass | time step | contact intervals | last in contact | max energy / initial | final energy / initial | max force / (rho c v A) |"
echo "|---|---|---|---|---|---|---|---|"
for scheme in Newmark HHT-alpha Generalized-alpha; do
  for mass in Redistributed Kept; do
    for dt in "${DTS[@]}"; do
      dir="$OUT/$scheme-$mass-$dt"
      if ! mpirun -np "$RANKS" "$APP" examples/bar_impact.xml --output-dir "$dir" --set "Output/VTK=false" \
          --set "Dynamics/Integrator=$scheme" --set "Dynamics/Contact Surface Mass=$mass" \
          --set "Dynamics/Time Step=$dt" > "$OUT/log" 2>&1; then
        echo "| $scheme | $mass | $dt | failed | | | | |"
        tail -3 "$OUT/log" >&2
        continue
      fi
      read -r n last emax eend fmax <<< "$(summary "$dir/history.csv")"
      echo "| $scheme | $mass | $dt | $n | $last | $emax | $eend | $fmax |"
    done
  done
done
