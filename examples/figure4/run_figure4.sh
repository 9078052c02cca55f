#!/usr/bin/env bash
# Fang & Izzuddin (2022), Figure 4: strain-energy error of the two-half-rings
# benchmark (doc/figure4.md). One command:
#
#   bash examples/figure4/run_figure4.sh BUILD_OR_INSTALL_DIR [OUT_DIR]
#
# runs the five analyses of examples/two_half_rings.xml (or of --deck FILE)
#   decomposed-20/-50/-100  Contact/Formulation = Decomposed Node-To-Segment,
#                           Solver/Strategy = FETI-DP (--strategy), Partition/Method = By Body (--partition)
#   monolithic-20/-100      Contact/Formulation = Node-To-Segment, Solver/Strategy = Monolithic
#                           (monolithic-100 is the reference)
# then ddcontact-figure4 (summary table, OUT_DIR/figure4.csv, the paper's
# findings checked) and gnuplot (OUT_DIR/figure4.png: error and energy curves).
#
# BUILD_OR_INSTALL_DIR: a build tree (ddcontact and ddcontact-figure4 in src/)
# or an install prefix (in bin/). OUT_DIR default: ddcontact-out/figure4.
#
# Options (before or after the directories):
#   --deck FILE         the input deck (default examples/two_half_rings.xml); e.g. the 3-D
#                       examples/two_half_rings_3d_free.xml (the formulation names
#                       Node-To-Segment and Node-To-Surface are synonyms)
#   --np N              MPI ranks per run (default 2)
#   --strategy S        Solver/Strategy of the decomposed runs: FETI-DP (default) or Monolithic
#   --partition M       Partition/Method of the decomposed runs (default "By Body": one ring per
#                       subdomain); e.g. --partition METIS --subdomains 4
#   --subdomains K      Partition/Number of Subdomains of the decomposed runs (default: the method's)
#   --set PATH=VALUE    extra ddcontact override for all five runs (repeatable)
#   --ddcontact EXE     use this ddcontact instead of the one in BUILD_OR_INSTALL_DIR
#   --figure4-tool EXE  use this ddcontact-figure4 instead of the one in BUILD_OR_INSTALL_DIR
#   --check-floor F     passed to ddcontact-figure4 (check only points with U_ref > F max U_ref)
#   --assert-phases     passed to ddcontact-figure4 (make the phase criterion (b) part of the check)
#   --strict            exit 1 when the check of the paper's findings fails (default: report it, exit 0)
#   --use-run LABEL=DIR take run LABEL's history from DIR/history.csv, an earlier run of the
#                       same case (same deck, options and steps), instead of running it (repeatable)
#   --skip-runs         reuse the histories already in OUT_DIR/runs (re-analyse and re-plot only)
# Exit status: 0 done (check result printed), 1 a run, the tool or gnuplot failed (or the check
# with --strict), 2 bad usage.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
die() { echo "run_figure4.sh: $*" >&2; exit 2; }

np=2 strategy=FETI-DP partition="By Body" subdomains="" check_floor="" strict=0 skip_runs=0 deck="" assert_phases=0
ddc="" fig4=""
extra=()
use_runs=()
pos=()
while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --np|--strategy|--partition|--subdomains|--set|--ddcontact|--figure4-tool|--check-floor|--deck|--use-run)
      (($# >= 2)) || die "option $1 needs a value"
      case "$1" in
        --np) np=$2 ;;
        --strategy) strategy=$2 ;;
        --partition) partition=$2 ;;
        --subdomains) subdomains=$2 ;;
        --set) extra+=(--set "$2") ;;
        --use-run) [[ $2 == ?*=?* ]] || die "--use-run '$2': expected LABEL=DIR"; use_runs+=("$2") ;;
        --ddcontact) ddc=$2 ;;
        --figure4-tool) fig4=$2 ;;
        --check-floor) check_floor=$2 ;;
        --deck) deck=$2 ;;
      esac
      shift 2 ;;
    --strict) strict=1; shift ;;
    --assert-phases) assert_phases=1; shift ;;
    --skip-runs) skip_runs=1; shift ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) pos+=("$1"); shift ;;
  esac
done
((${#pos[@]} >= 1 && ${#pos[@]} <= 2)) || { usage >&2; exit 2; }
prefix=${pos[0]}
out=${pos[1]:-ddcontact-out/figure4}
[[ $np =~ ^[1-9][0-9]*$ ]] || die "--np '$np': expected a positive integer"
[[ -z $subdomains || $subdomains =~ ^[0-9]+$ ]] || die "--subdomains '$subdomains': expected an integer"

here=$(cd "$(dirname "$0")" && pwd)
deck=${deck:-$here/../two_half_rings.xml}
[[ -f $deck ]] || die "input deck not found: $deck"
me=run_figure4.sh
# shellcheck source=lib.sh
. "$here/lib.sh"
locate_tools
command -v gnuplot > /dev/null || die "gnuplot not found (Debian: apt-get install gnuplot-nox; cmake/setup.sh installs it)"

mkdir -p "$out/runs" "$out/logs"
# The runs: label, steps, formulation, strategy.
# The deck's own partition (two_half_rings.xml: METIS, 4 subdomains) is replaced, count included.
decomposed_partition=(--set "Partition/Method=$partition" --set "Partition/Number of Subdomains=${subdomains:-0}")
run() {  # run LABEL STEPS FORMULATION STRATEGY [extra ddcontact args...]
  local label=$1 steps=$2 formulation=$3 strat=$4
  shift 4
  run_case "$label" "$(printf "%3d steps  %-26s %-10s" "$steps" "$formulation" "$strat")" "$deck" \
    --set "Load Stepping/Number of Steps=$steps" --set "Contact/Formulation=$formulation" \
    --set "Solver/Strategy=$strat" "$@" ${extra[@]+"${extra[@]}"}
}
echo "== runs ($np ranks, $ddc; decomposed: $strategy, partition $partition${subdomains:+, $subdomains subdomains}; logs in $out/logs)"
run decomposed-20 20 "Decomposed Node-To-Segment" "$strategy" "${decomposed_partition[@]}"
run decomposed-50 50 "Decomposed Node-To-Segment" "$strategy" "${decomposed_partition[@]}"
run decomposed-100 100 "Decomposed Node-To-Segment" "$strategy" "${decomposed_partition[@]}"
run monolithic-20 20 "Node-To-Segment" Monolithic
run monolithic-100 100 "Node-To-Segment" Monolithic

echo "== ddcontact-figure4"
tool_args=(--reference "$out/runs/monolithic-100/history.csv")
for l in decomposed-20 decomposed-50 decomposed-100 monolithic-20; do
  tool_args+=(--run "$l=$out/runs/$l/history.csv")
done
tool_args+=(--csv "$out/figure4.csv" --check)
[[ -n $check_floor ]] && tool_args+=(--check-floor "$check_floor")
((assert_phases)) && tool_args+=(--assert-phases)
set +e
"$fig4" "${tool_args[@]}" 2>&1 | tee "$out/summary.txt"
status=${PIPESTATUS[0]}
set -e
case $status in
  0) check="passed" ;;
  1) check="FAILED (see above)" ;;
  *) echo "run_figure4.sh: ddcontact-figure4 failed (exit $status)" >&2; exit 1 ;;
esac

echo "== gnuplot"
# One style per run in both panels: label:colour:point type.
styles=("decomposed-20:#d62728:7" "decomposed-50:#1f77b4:5" "decomposed-100:#2ca02c:9" "monolithic-20:#ff7f0e:4")
{
  cat <<GP
set datafile separator ","
set terminal pngcairo size 900,1100 noenhanced font ",10"
set output "$out/figure4.png"
set multiplot layout 2,1 title "$(basename "$deck") (after Fang & Izzuddin 2022, Fig. 4)\ndecomposed runs with Solver/Strategy = $strategy, partition $partition${subdomains:+ ($subdomains subdomains)}, $np ranks"
set grid
set xlabel "load factor"
set xrange [0:1]
set logscale y
set format y "%.0e"
set ylabel "relative strain-energy error |U - U_ref| / U_ref"
set key inside center right box opaque
set title "strain-energy error against the 100-step monolithic NTS reference (where U_ref > 1e-8 max U_ref; 0 drawn at 1e-16)"
plot \\
GP
  sep=""
  for spec in "${styles[@]}"; do
    IFS=: read -r l c pt <<< "$spec"
    printf '%s  "%s" every ::1 using 2:(strcol(1) eq "%s" ? ($5 > 1e-16 ? $5 : 1e-16) : NaN) with linespoints lc rgb "%s" pt %s ps 0.7 lw 1.5 title "%s"' \
      "$sep" "$out/figure4.csv" "$l" "$c" "$pt" "$l"
    sep=$', \\\n'
  done
  echo
  cat <<GP
unset logscale y
set format y "%g"
set ylabel "strain energy U"
set key inside top right box opaque
set title "strain energy"
plot "$out/runs/monolithic-100/history.csv" every ::1 using 2:3 with lines lw 2.5 lc rgb "black" title "monolithic-100 (reference)", \\
GP
  sep=""
  for spec in "${styles[@]}"; do
    IFS=: read -r l c pt <<< "$spec"
    style="linespoints lw 1.5 ps 0.7"
    [[ $l == monolithic-20 ]] && style="points ps 1.3"
    printf '%s     "%s" every ::1 using 2:3 with %s lc rgb "%s" pt %s title "%s"' \
      "$sep" "$out/runs/$l/history.csv" "$style" "$c" "$pt" "$l"
    sep=$', \\\n'
  done
  echo
  echo "unset multiplot"
} > "$out/figure4.gp"
gnuplot "$out/figure4.gp" || { echo "run_figure4.sh: gnuplot failed ($out/figure4.gp)" >&2; exit 1; }

echo "== outputs"
echo "  figure:  $out/figure4.png (gnuplot script $out/figure4.gp)"
echo "  points:  $out/figure4.csv (run,load_factor,strain_energy,reference_energy,relative_error)"
echo "  summary: $out/summary.txt"
echo "  runs:    $out/runs/<label>/history.csv, logs in $out/logs"
echo "  check of the paper's findings: $check"
if ((strict)) && ((status == 1)); then exit 1; fi
exit 0
