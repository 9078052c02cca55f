#!/usr/bin/env bash
# Ironing in 3-D (examples/ironing_3d.xml, doc/contact.md "Ironing"): the
# decomposed node-to-surface element under FETI-DP against the conventional
# element solved monolithically, at several step counts; prints the largest
# differences of the contact force over the sliding phase (load factor >
# 0.25, where the die slides).
#
#   bash examples/ironing_3d.sh [BUILD_DIR [OUT_DIR]]   # defaults: build, ddcontact-out/ironing_3d
#
# Environment: NP (MPI ranks, 2), STEPS ("40 80": step counts; both runs of
# a count use it), CHECK (optional bound: exit 1 unless, at every step
# count, max dFy/|Fy| <= CHECK and both runs end with the die in contact).
# SKIP_RUNS=1 reuses the histories already in OUT_DIR (compare only).
# Extra ddcontact options after "--" apply to every run.
# Columns: max |Fy_dd - Fy_conv| / max |Fy_conv| and max |F_dd - F_conv| /
# max |F_conv| (F the whole contact force vector) over the sliding phase.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
out=${2:-ddcontact-out/ironing_3d}
shift $(( $# > 2 ? 2 : $# ))
[[ ${1:-} == -- ]] && shift
NP=${NP:-2}
STEPS=${STEPS:-"40 80"}
CHECK=${CHECK:-}
SKIP_RUNS=${SKIP_RUNS:-0}
app="$build/src/ddcontact"
[[ -x $app ]] || { echo "ironing_3d.sh: $app not found (build first: bash cmake/setup.sh build)" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OPENBLAS_NUM_THREADS=1
extra=("$@")
# The conventional reference is solved monolithically: its deck is the
# shipped one without the Solver/FETI-DP sublist (which a Monolithic run
# rejects as not applying to it).
mkdir -p "$out"
sed '/<ParameterList name="FETI-DP">/,/<\/ParameterList>/d' "$here/ironing_3d.xml" > "$out/ironing_3d_monolithic.xml"
rows=()
for n in $STEPS; do
  for variant in decomposed conventional; do
    opts=()
    deck="$here/ironing_3d.xml"
    if [[ $variant == conventional ]]; then
      opts=(--set "Contact/Formulation=Node-To-Surface" --set "Solver/Strategy=Monolithic")
      deck="$out/ironing_3d_monolithic.xml"
    fi
    if [[ $SKIP_RUNS == 1 && -f $out/$variant-$n/history.csv ]]; then
      echo "== $n steps, $variant: reusing $out/$variant-$n/history.csv"
      continue
    fi
    echo "== $n steps, $variant: mpirun -np $NP ddcontact $deck ${opts[*]+${opts[*]}}"
    mpirun -np "$NP" "$app" "$deck" --output-dir "$out/$variant-$n" \
      --set "Load Stepping/Number of Steps=$n" --set "Output/VTK=false" \
      "${opts[@]+"${opts[@]}"}" "${extra[@]+"${extra[@]}"}" > "$out/$variant-$n.log" 2>&1 ||
      { cat "$out/$variant-$n.log" >&2; echo "ironing_3d.sh: the run failed" >&2; exit 1; }
    grep -E "^timing" "$out/$variant-$n.log" || true
  done
  # history.csv columns by name; rows of both runs at the same load factors.
  rows+=("$(awk -F, -v n="$n" '
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    FILENAME == ARGV[1] { lf[FNR] = $col["load_factor"]; x[FNR] = $col["contact_force_x"];
                          y[FNR] = $col["contact_force_y"]; z[FNR] = $col["contact_force_z"]; secs_dd = $col["wall_seconds"];
                          active_dd = $col["active_contacts"]; next }
    {
      if ($col["load_factor"] != lf[FNR]) { print "load factors differ at row " FNR > "/dev/stderr"; bad = 1; exit 1 }
      secs_conv = $col["wall_seconds"]
      if ($col["load_factor"] <= 0.25 + 1e-12) next
      cy = $col["contact_force_y"]; cx = $col["contact_force_x"]; cz = $col["contact_force_z"]
      dy = y[FNR] - cy; d = sqrt((x[FNR] - cx)^2 + dy^2 + (z[FNR] - cz)^2); f = sqrt(cx^2 + cy^2 + cz^2)
      if (dy < 0) dy = -dy; if (cy < 0) cy = -cy
      if (dy > maxdy) maxdy = dy; if (cy > maxy) maxy = cy; if (d > maxd) maxd = d; if (f > maxf) maxf = f
    }
    END { if (!bad) printf "%-6s %14.4f %14.4f %10.1f %10.1f %8d %8d", n, maxdy / maxy, maxd / maxf, secs_dd, secs_conv,
                           active_dd, $col["active_contacts"] }
  ' "$out/decomposed-$n/history.csv" "$out/conventional-$n/history.csv")")
done
echo
echo "Ironing, sliding phase (load factor > 0.25): decomposed FETI-DP vs conventional Monolithic ($NP ranks)"
printf '%-6s %14s %14s %10s %10s %8s %8s\n' steps "max dFy/|Fy|" "max |dF|/|F|" "s (dd)" "s (conv)" "end (dd)" "(conv)"
for row in "${rows[@]}"; do echo "$row"; done
if [[ -n $CHECK ]]; then
  ok=1
  for row in "${rows[@]}"; do
    read -r _ dfy _ _ _ end_dd end_conv <<< "$row"
    awk -v d="$dfy" -v c="$CHECK" 'BEGIN { exit !(d <= c) }' || ok=0
    (( end_dd > 0 && end_conv > 0 )) || ok=0
  done
  if (( ok )); then
    echo "check passed: max dFy/|Fy| <= $CHECK at every step count, the die in contact at the end"
  else
    echo "check FAILED: max dFy/|Fy| > $CHECK or a run ends without contact" >&2
    exit 1
  fi
fi
