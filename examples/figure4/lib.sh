# Shared by run_figure4.sh and run_step_control.sh (sourced, not run): the
# executables from a build tree or an install prefix, the MPI settings, and
# one logged run. The caller defines die(), prefix (BUILD_OR_INSTALL_DIR),
# out (OUT_DIR), np, skip_runs, use_runs (the LABEL=DIR of --use-run) and
# its name in `me`.

# find_exe NAME: PREFIX/src/NAME (build tree) or PREFIX/bin/NAME (install).
find_exe() {
  local d
  for d in "$prefix/src" "$prefix/bin"; do
    if [[ -x $d/$1 ]]; then echo "$d/$1"; return 0; fi
  done
  return 1
}

# locate_tools: ddc (ddcontact) and fig4 (ddcontact-figure4) from PREFIX
# unless given (--ddcontact, --figure4-tool); mpirun must exist.
locate_tools() {
  [[ -d $prefix ]] || die "BUILD_OR_INSTALL_DIR '$prefix' is not a directory"
  if [[ -z $ddc ]]; then
    ddc=$(find_exe ddcontact) || die "no ddcontact in $prefix/src or $prefix/bin (or give --ddcontact EXE)"
  fi
  if [[ -z $fig4 ]]; then
    fig4=$(find_exe ddcontact-figure4) ||
      die "no ddcontact-figure4 in $prefix/src or $prefix/bin: build it (cmake --build $prefix --target ddcontact-figure4) or give --figure4-tool EXE"
  fi
  [[ -x $ddc ]] || die "--ddcontact '$ddc' is not an executable"
  [[ -x $fig4 ]] || die "--figure4-tool '$fig4' is not an executable"
  command -v mpirun > /dev/null || die "mpirun not found"
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OPENBLAS_NUM_THREADS=1
}

# used_run LABEL: the DIR of --use-run LABEL=DIR, or nothing.
used_run() {
  local u
  for u in ${use_runs[@]+"${use_runs[@]}"}; do
    [[ ${u%%=*} == "$1" ]] && { echo "${u#*=}"; return 0; }
  done
  return 0
}

# run_case LABEL DESCRIPTION DECK [ddcontact args...]: one run on np ranks
# into OUT_DIR/runs/LABEL (log OUT_DIR/logs/LABEL.log), timed; with
# skip_runs only checks that its history is there; with --use-run LABEL=DIR
# copies DIR/history.csv there instead (DIR: an earlier run of the same
# case). Exits 1 with the log's tail when the run fails. The caller creates
# OUT_DIR/runs and OUT_DIR/logs.
run_case() {
  local label=$1 description=$2 deck=$3
  shift 3
  local dir="$out/runs/$label" log="$out/logs/$label.log" used
  used=$(used_run "$label")
  if [[ -n $used ]]; then
    [[ -f $used/history.csv ]] || { echo "$me: --use-run $label=$used: $used/history.csv missing" >&2; exit 1; }
    mkdir -p "$dir"
    cp "$used/history.csv" "$dir/history.csv"
    printf "  %-15s %s the run in %s\n" "$label" "$description" "$used"
    return 0
  fi
  if ((skip_runs)); then
    [[ -f $dir/history.csv ]] || { echo "$me: --skip-runs: $dir/history.csv missing" >&2; exit 1; }
    return 0
  fi
  local t0 t1
  t0=$(date +%s.%N)
  if ! mpirun -np "$np" "$ddc" "$deck" --output-dir "$dir" --set "Output/VTK=false" "$@" > "$log" 2>&1; then
    echo "$me: run $label FAILED ($log):" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  t1=$(date +%s.%N)
  printf "  %-15s %s %6.2f s\n" "$label" "$description" "$(awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}')"
}
