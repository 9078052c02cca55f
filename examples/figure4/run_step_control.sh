#!/usr/bin/env bash
# Step control by the frozen-geometry error on the two-half-rings benchmark
# (doc/figure4.md, "Step control"). One command:
#
#   bash examples/figure4/run_step_control.sh BUILD_OR_INSTALL_DIR [OUT_DIR]
#
# runs, from examples/two_half_rings_adaptive.xml (or --deck FILE):
#   reference        Contact/Formulation = Node-To-Segment, Solver/Strategy = Monolithic, 100 steps
#   fixed-100        the deck's decomposed element and strategy, 100 equal steps, no step control
#   tol-T            the deck with Step Control/Error Tolerance = T, for every T of --tolerances
# and ddcontact-figure4 on them: per run the steps, rejected and repeated
# steps, contact exchanges, the max relative strain-energy error where the
# reference exceeds 2 % of its peak (--check-floor), the peak strain energy's
# error and the wall time (OUT_DIR/summary.txt).
#
# BUILD_OR_INSTALL_DIR: a build tree (ddcontact and ddcontact-figure4 in src/)
# or an install prefix (in bin/). OUT_DIR default: ddcontact-out/step_control.
#
# Options (before or after the directories):
#   --deck FILE         the input deck (default examples/two_half_rings_adaptive.xml); e.g. the 3-D
#                       examples/two_half_rings_3d_free.xml (its own Load Stepping sets the first step)
#   --tolerances "T..." Step Control/Error Tolerance of the adaptive runs (default "0.02 0.01 0.005 0.002")
#   --np N              MPI ranks per run (default 2)
#   --partition M       Partition/Method of the decomposed runs (default: the deck's); e.g. "By Body"
#   --subdomains K      Partition/Number of Subdomains of the decomposed runs (default: the deck's,
#                       0 with --partition "By Body")
#   --check-floor F     error only where U_ref > F max U_ref (default 0.02)
#   --set PATH=VALUE    extra ddcontact override for all runs (repeatable)
#   --check             assert (exit 1) for every adaptive run: max error <= 1 %, peak strain energy
#                       within 0.5 %, fewer contact exchanges than fixed-100
#   --ddcontact EXE, --figure4-tool EXE   executables from elsewhere
#   --use-run LABEL=DIR take run LABEL's history from DIR/history.csv, an earlier run of the
#                       same case (same deck, options and steps), instead of running it (repeatable)
#   --skip-runs         reuse the histories already in OUT_DIR/runs
# Exit status: 0 done, 1 a run or the tool failed (or the check with --check), 2 bad usage.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
die() { echo "run_step_control.sh: $*" >&2; exit 2; }

np=2 partition="" subdomains="" check_floor=0.02 check=0 skip_runs=0 deck="" tolerances="0.02 0.01 0.005 0.002"
ddc="" fig4=""
extra=()
use_runs=()
pos=()
while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --np|--partition|--subdomains|--set|--ddcontact|--figure4-tool|--check-floor|--deck|--tolerances|--use-run)
      (($# >= 2)) || die "option $1 needs a value"
      case "$1" in
        --np) np=$2 ;;
        --partition) partition=$2 ;;
        --subdomains) subdomains=$2 ;;
        --set) extra+=(--set "$2") ;;
        --use-run) [[ $2 == ?*=?* ]] || die "--use-run '$2': expected LABEL=DIR"; use_runs+=("$2") ;;
        --ddcontact) ddc=$2 ;;
        --figure4-tool) fig4=$2 ;;
        --check-floor) check_floor=$2 ;;
        --deck) deck=$2 ;;
        --tolerances) tolerances=$2 ;;
      esac
      shift 2 ;;
    --check) check=1; shift ;;
    --skip-runs) skip_runs=1; shift ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) pos+=("$1"); shift ;;
  esac
done
((${#pos[@]} >= 1 && ${#pos[@]} <= 2)) || { usage >&2; exit 2; }
prefix=${pos[0]}
out=${pos[1]:-ddcontact-out/step_control}
[[ $np =~ ^[1-9][0-9]*$ ]] || die "--np '$np': expected a positive integer"
[[ -z $subdomains || $subdomains =~ ^[0-9]+$ ]] || die "--subdomains '$subdomains': expected an integer"
for t in $tolerances; do
  [[ $t =~ ^[0-9]*\.?[0-9]+([eE]-?[0-9]+)?$ ]] || die "--tolerances: '$t' is not a number"
done
[[ -n ${tolerances// /} ]] || die "--tolerances: no tolerance given"

here=$(cd "$(dirname "$0")" && pwd)
deck=${deck:-$here/../two_half_rings_adaptive.xml}
[[ -f $deck ]] || die "input deck not found: $deck"
me=run_step_control.sh
# shellcheck source=lib.sh
. "$here/lib.sh"
locate_tools

mkdir -p "$out/runs" "$out/logs"
decomposed=()
[[ -n $partition ]] && decomposed+=(--set "Partition/Method=$partition")
[[ -n $subdomains || $partition == "By Body" ]] && decomposed+=(--set "Partition/Number of Subdomains=${subdomains:-0}")
run() {  # run LABEL [ddcontact args...]
  local label=$1
  shift
  run_case "$label" "" "$deck" "$@" ${extra[@]+"${extra[@]}"}
}
echo "== runs ($np ranks, $ddc, $(basename "$deck"); logs in $out/logs)"
run reference --set "Step Control/Error Tolerance=0" --set "Load Stepping/Number of Steps=100" \
  --set "Contact/Formulation=Node-To-Segment" --set "Solver/Strategy=Monolithic"
run fixed-100 --set "Step Control/Error Tolerance=0" --set "Load Stepping/Number of Steps=100" ${decomposed[@]+"${decomposed[@]}"}
for t in $tolerances; do
  run "tol-$t" --set "Step Control/Error Tolerance=$t" ${decomposed[@]+"${decomposed[@]}"}
done

echo "== ddcontact-figure4"
tool_args=(--reference "$out/runs/reference/history.csv" --run "fixed-100=$out/runs/fixed-100/history.csv"
           --check-floor "$check_floor")
for t in $tolerances; do tool_args+=(--adaptive-run "tol-$t=$out/runs/tol-$t/history.csv"); done
if ((check)); then
  fixed_exchanges=$(awk -F, 'NR == 1 {for (i = 1; i <= NF; ++i) if ($i == "contact_exchanges") c = i; next}
                              {s += $c} END {print s}' "$out/runs/fixed-100/history.csv")
  tool_args+=(--max-error 0.01 --max-peak-error 0.005 --max-exchanges "$fixed_exchanges")
fi
set +e
"$fig4" "${tool_args[@]}" 2>&1 | tee "$out/summary.txt"
status=${PIPESTATUS[0]}
set -e
case $status in
  0) ;;
  1) echo "run_step_control.sh: the check FAILED (see above)" >&2; exit 1 ;;
  *) echo "run_step_control.sh: ddcontact-figure4 failed (exit $status)" >&2; exit 1 ;;
esac
echo "== outputs: $out/summary.txt; runs in $out/runs/<label>/history.csv, logs in $out/logs"
