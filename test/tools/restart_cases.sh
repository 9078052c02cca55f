#!/usr/bin/env bash
# System tests of checkpoints and restart (doc/user-guide.md, "Checkpoints
# and restart"): a run stopped after step K continues from its checkpoint
# and ends as the uninterrupted run does.
#
#   restart_cases.sh CASE NP DDCONTACT COMPARE_HISTORY DECK WORKDIR [ddcontact args...]
#
# The ddcontact args (e.g. --set overrides) go to every run of the case.
# CASE:
#   sigterm         SIGTERM to rank 0 while step 5 is solved (the test seam
#                   DDCONTACT_FAULT_INJECTION=sigterm@5): every rank exits
#                   143 after step 5 naming the checkpoint; `--restart DIR`
#                   on NP ranks continues in DIR. history.csv equals the
#                   uninterrupted run's field for field except wall_seconds;
#                   the VTK series and results.e or its pieces (if written) are the same
#                   bytes.
#   newton-failure  every attempt at step 8 fails as Newton does (seam
#                   newton-failure@8): every rank exits 1 naming the
#                   checkpoint of step 7; then as sigterm.
#   unwritable      the same failure with a full disk for checkpoint.ddc
#                   (seam enospc@checkpoint.ddc): the error is the Newton
#                   failure, and says that the checkpoint could not be
#                   written and why.
#   kill            a real SIGTERM sent to every rank from outside once the
#                   run is past step 20 (the step it stops at is not known in
#                   advance); then as sigterm.
#   usr1-to-mpirun  SIGUSR1 sent to mpirun once the run is past step 20 (Open
#                   MPI forwards it to the ranks); then as sigterm.
#   other-ranks:M   stopped on NP ranks (sigterm@5), restarted on M ranks into
#                   another directory: history.csv equals the uninterrupted
#                   NP-rank run's to 1e-10 (summation order only; the dual
#                   iterations are not compared, they may differ by one).
#   other-mode:M    a checkpoint written on parts of the mesh ('Partition/
#                   Mesh On Every Rank' = false, NP ranks, sigterm@5)
#                   continued with the whole mesh on every rank, and one
#                   written with the whole mesh continued on parts, both on
#                   M ranks into other directories: history.csv equals the
#                   uninterrupted run's to 1e-10; with Output/Exodus the continued run's
#                   results.e, or its pieces on parts, equals the
#                   uninterrupted run's to 1e-10 (tools/check_exodus_pieces.py,
#                   PYTHON): the steps before the checkpoint are copied by
#                   node and element id across the two layouts.
#   corrupted       the checkpoint with a flipped byte, then cut short, then
#                   replaced by another file: every rank exits non-zero
#                   naming the file, and the interrupted run's directory is
#                   unchanged (byte for byte); the intact checkpoint then
#                   restarts.
#   deck-change     a restart whose deck changes a parameter a restart may
#                   not change (Contact/Penetration Tolerance, a body's
#                   mesh): refused naming the parameter, nothing changed; a
#                   change it may make (more steps) works.
#   extend          a finished run (20 steps to load factor 1) continued in
#                   its directory to 1.1 (22 steps): its 20 rows stay as
#                   they were, two follow, and no warning says a contact
#                   pair never paired (it paired before the restart).
#   memory-stop     under prlimit --as=4 GiB with Solver/Memory Stop Fraction
#                   = 0.05: after step 1 a rank maps more than 5 % of its
#                   address-space limit, and every rank exits 1 naming the
#                   limit and the checkpoint (the stop before memory runs
#                   out, doc/user-guide.md "Memory"); then as sigterm,
#                   without the limit.
#   no-checkpoint   Output/Checkpoint Interval = 0: a stopped run says it
#                   has no checkpoint, and --restart says so naming the
#                   directory.
#   reference       the uninterrupted run alone, into WORKDIR/reference: the
#                   reference that several cases share (REFERENCE_RUN).
# The cases below take DECK = test/inputs/restart_block.xml (a block read
# from restart_block.msh, 6 steps); each refusal leaves the directories it
# names unchanged (byte for byte):
#   input-change:K  a file the run read changed after it stopped (step 3) -
#                   K = gmsh: a node of restart_block.msh moved; map: an
#                   element of restart_block.map moved to the other
#                   subdomain; exodus: a node of an Exodus II mesh written
#                   from the block (tools/write_exodus_mesh.py, PYTHON) moved:
#                   --restart is refused naming the file and its parameter;
#                   with the file restored it restarts.
#   final-below     a restart to Final Load Factor 0.4 from the checkpoint of
#                   step 3 (load factor 0.5): refused, naming what it reached.
#   finished-checkpoint  a finished result in DIR, then a run into DIR stopped
#                   without a checkpoint (interval 0): --restart DIR is
#                   refused (the checkpoint in DIR is the finished run's).
#   rerun-stopped   a plain run into the directory of a stopped run with a
#                   checkpoint: refused, naming --restart and the staging
#                   directory to move away.
#   edited-result   a finished result whose history.csv was edited (same
#                   size), then one with a directory added: a new run into it
#                   is refused naming the file / the directory.
#   wrong-source    --restart DIR.partial and --restart
#                   DIR.partial/checkpoint.ddc: refused, naming DIR.
#   bad-checkpoint  the stopped run's checkpoint.ddc replaced by a directory,
#                   a link to /dev/zero, 8 GiB sparse files of version 1
#                   (read whole) and 2 under a 4 GiB address-space limit:
#                   refused naming the file.
#   exodus-messages Output/Exodus switched on at the restart: a warning
#                   naming the earlier run's missing results.e (no internal
#                   file names); a full disk while the restart writes
#                   results.e (seam enospc@results.e): "No space left on
#                   device" naming the file (on parts: a rank's piece), the
#                   stopped run's directory unchanged.
# Environment: REFERENCE_RUN, the directory of the uninterrupted run of the
# same deck, options and rank count (a case `reference`): the cases sigterm,
# newton-failure, kill, usr1-to-mpirun and other-ranks compare with it
# instead of running it again (extend continues its own reference).
set -u
case_name=$1 np=$2 app=$3 compare=$4 deck=$5 work=$6
shift 6
extra=("$@")
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
failures=0

. "$here/rank_status_lib.sh"

# run LOG NP [ddcontact args...]: every rank's exit status in $work/status.
# UNDER: a command mpirun is started under (e.g. prlimit --as=...).
run() {
  local log=$1 ranks=$2
  shift 2
  rm -rf "$work/status"
  mkdir -p "$work/status"
  ${UNDER:-} mpirun --oversubscribe -np "$ranks" sh "$here/record_exit_status.sh" "$work/status" "$app" "$deck" "${extra[@]}" \
    "$@" >"$log" 2>&1
}

# expect_in LOG REGEX WHAT
expect_in() {
  grep -Eq -e "$2" "$1" || { fail "$3: no match for '$2'"; sed 's/^/    | /' "$1"; }
}

# The uninterrupted run: $ref, run here unless REFERENCE_RUN names it.
ref=$work/reference
reference() {
  if [ -n "${REFERENCE_RUN:-}" ] && [ "$case_name" != extend ]; then
    ref=$REFERENCE_RUN
    [ -f "$ref/history.csv" ] || { fail "REFERENCE_RUN: no $ref/history.csv"; exit 1; }
    echo "the uninterrupted run: $ref"
    return
  fi
  run "$work/reference.log" "$np" --output-dir "$work/reference" ||
    true
  every_rank_succeeded "$work/reference.log" || exit 1
}

# same_results DIR: DIR's results are the reference's (history field for
# field but wall_seconds; the VTK series and the Exodus file byte for byte).
same_results() {
  "$compare" "$ref/history.csv" "$1/history.csv" exact || fail "history.csv of $1 differs"
  if [ -d "$ref/vtk" ]; then
    [ "$(hashes "$ref/vtk")" = "$(hashes "$1/vtk")" ] || fail "the VTK series of $1 differs"
  fi
  if [ -f "$ref/results.e" ]; then
    cmp -s "$ref/results.e" "$1/results.e" || fail "results.e of $1 differs"
  fi
  # The pieces of a run on parts of the mesh (results.e.P.r), each.
  for piece in "$ref"/results.e.*.*; do
    [ -f "$piece" ] || continue
    cmp -s "$piece" "$1/${piece##*/}" || fail "${piece##*/} of $1 differs"
  done
  [ -f "$1/checkpoint.ddc" ] || fail "no checkpoint.ddc in the committed result $1"
}

# wait_for_rows N PID: until the stopped run's history has N rows (at most
# 60 s), or process PID has ended.
wait_for_rows() {
  local i rows
  for ((i = 0; i < 1200; i++)); do
    rows=$(($(wc -l <"$work/stopped.partial/history.csv" 2>/dev/null || echo 1) - 1))
    [ "$rows" -ge "$1" ] && return
    kill -0 "$2" 2>/dev/null || return
    sleep 0.05
  done
}

# restart_in_place LOG: continue the stopped run in its own directory.
restart_in_place() {
  run "$1" "$np" --restart "$work/stopped"
  every_rank_succeeded "$1" || return 1
  expect_in "$1" "continuing in '.*stopped.partial'" "restart in the same directory"
  expect_in "$1" "restart: continuing after step" "restart"
  [ ! -e "$work/stopped.partial" ] || fail "stopped.partial is still there after the restart committed"
  same_results "$work/stopped"
}

case "$case_name" in
sigterm)
  reference
  DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  expect_in "$work/stopped.log" "stopped by SIGTERM after step 5 .*checkpoint is '.*stopped.partial/checkpoint.ddc'" \
    "the stop message"
  [ "$(($(wc -l <"$work/stopped.partial/history.csv") - 1))" = 5 ] || fail "the stopped run's history has not 5 rows"
  restart_in_place "$work/restart.log"
  ;;
newton-failure)
  reference
  DDCONTACT_FAULT_INJECTION=newton-failure@8 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_failed "$work/stopped.log"
  expect_in "$work/stopped.log" "Newton did not converge in step 8 .*the checkpoint of step 7 .* is '.*stopped.partial/checkpoint.ddc'" \
    "the failure message"
  restart_in_place "$work/restart.log"
  ;;
memory-stop)
  reference
  UNDER="prlimit --as=4294967296" run "$work/stopped.log" "$np" --output-dir "$work/stopped" \
    --set "Solver/Memory Stop Fraction=0.05"
  every_rank_failed "$work/stopped.log"
  # The address-space limit decides (a rank maps ~500 MiB, 5 % of 4 GiB is
  # 205 MiB); on a host with less than ~3 GiB available the ranks' resident
  # size may pass 5 % of what the check allowed first: the same stop.
  expect_in "$work/stopped.log" "error: stopped after step 1 .* before memory runs out: (rank [0-9]+ maps [0-9.]+ [MG]iB, above 5 % of its address-space limit 4.0 GiB .ulimit -v.|(this rank holds|the [0-9]+ ranks on this host hold) [0-9.]+ [MG]iB, above 5 % of the [0-9.]+ [MG]iB the memory check allowed .*) .doc/user-guide.md, 'Memory'. 'Solver/Memory Stop Fraction'.. its checkpoint is '.*stopped.partial/checkpoint.ddc': continue with --restart '.*stopped' with fewer ranks per host" \
    "the stop message"
  [ "$(($(wc -l <"$work/stopped.partial/history.csv") - 1))" = 1 ] || fail "the stopped run's history has not 1 row"
  restart_in_place "$work/restart.log"
  ;;
unwritable)
  DDCONTACT_FAULT_INJECTION=newton-failure@8,enospc@checkpoint.ddc run "$work/stopped.log" "$np" \
    --output-dir "$work/stopped"
  every_rank_failed "$work/stopped.log"
  expect_in "$work/stopped.log" \
    "error: solver failure: Newton did not converge in step 8 .*; the checkpoint of the last converged step could not be written: .*checkpoint.ddc.*No space left on device" \
    "the failure message"
  [ ! -e "$work/stopped.partial/checkpoint.ddc" ] || fail "a checkpoint.ddc was left behind"
  ;;
kill)
  reference
  rm -rf "$work/status"
  mkdir -p "$work/status"
  mpirun --oversubscribe -np "$np" sh "$here/record_exit_status.sh" "$work/status" "$app" "$deck" "${extra[@]}" \
    --output-dir "$work/stopped" >"$work/stopped.log" 2>&1 &
  launcher=$!
  wait_for_rows 20 "$launcher"
  # Every rank's ddcontact process (found by its output directory; not the
  # record_exit_status.sh around it, nor mpirun).
  pkill -TERM -f "^$app .*--output-dir $work/stopped\$" || fail "no ddcontact process to signal"
  wait "$launcher"
  every_rank_status "$work/stopped.log" 143
  expect_in "$work/stopped.log" "stopped by SIGTERM after step [0-9]+ " "the stop message"
  rows=$(($(wc -l <"$work/stopped.partial/history.csv") - 1))
  total=$(($(wc -l <"$ref/history.csv") - 1))
  [ "$rows" -lt "$total" ] || fail "the run was not stopped before its end ($rows of $total rows)"
  echo "stopped after $rows of $total steps"
  restart_in_place "$work/restart.log"
  ;;
usr1-to-mpirun)
  reference
  # ddcontact directly under mpirun: the signal goes to the processes mpirun
  # started (a record_exit_status.sh around them would die of it).
  mpirun --oversubscribe -np "$np" "$app" "$deck" "${extra[@]}" --output-dir "$work/stopped" >"$work/stopped.log" 2>&1 &
  launcher=$!
  wait_for_rows 20 "$launcher"
  kill -USR1 "$launcher" || fail "mpirun had ended"
  wait "$launcher" && fail "mpirun exited 0 after SIGUSR1"
  expect_in "$work/stopped.log" "stopped by SIGUSR1 after step [0-9]+ " "the stop message"
  restart_in_place "$work/restart.log"
  ;;
other-ranks:*)
  ranks=${case_name#other-ranks:}
  reference
  DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  run "$work/restart.log" "$ranks" --restart "$work/stopped" --output-dir "$work/continued"
  np=$ranks every_rank_succeeded "$work/restart.log"
  expect_in "$work/restart.log" "restart: continuing after step 5 " "restart"
  # The physics (the dual iterations may differ by one with the rank count).
  "$compare" "$ref/history.csv" "$work/continued/history.csv" 1e-10 load_factor strain_energy \
    newton_iterations active_contacts contact_force_x contact_force_y contact_exchanges external_work ||
    fail "history.csv differs above 1e-10"
  [ -f "$work/stopped.partial/checkpoint.ddc" ] || fail "the stopped run's checkpoint is gone"
  ;;
other-mode:*)
  ranks=${case_name#other-mode:}
  reference
  parts=(--set "Partition/Mesh On Every Rank=false")
  for written in parts whole; do
    if [ "$written" = parts ]; then stop_args=("${parts[@]}") go_args=(); else stop_args=() go_args=("${parts[@]}"); fi
    DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped-$written.log" "$np" "${stop_args[@]}" \
      --output-dir "$work/stopped-$written"
    every_rank_status "$work/stopped-$written.log" 143
    run "$work/restart-$written.log" "$ranks" "${go_args[@]}" --restart "$work/stopped-$written" \
      --output-dir "$work/continued-$written"
    np=$ranks every_rank_succeeded "$work/restart-$written.log"
    expect_in "$work/restart-$written.log" "restart: continuing after step 5 " "restart of the run on $written"
    "$compare" "$ref/history.csv" "$work/continued-$written/history.csv" 1e-10 load_factor strain_energy \
      newton_iterations external_work ||
      fail "history.csv of the checkpoint written on $written differs above 1e-10"
    # With Output/Exodus (the reference's results.e): the continued run's
    # file, or its pieces on parts, holds every step, those copied from the
    # stopped run's file or pieces by node and element id.
    if [ -f "$ref/results.e" ]; then
      "${PYTHON:-python3}" "$here/check_exodus_pieces.py" "$ref/results.e" "$work/continued-$written/results.e" 1e-10 ||
        fail "results.e of the checkpoint written on $written differs from the uninterrupted run's above 1e-10"
    fi
  done
  ;;
corrupted)
  DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  checkpoint=$work/stopped.partial/checkpoint.ddc
  cp "$checkpoint" "$work/intact.ddc"
  before=$(hashes "$work/stopped.partial")
  size=$(stat -c %s "$checkpoint")
  # A flipped byte in the middle.
  printf "$(printf '\\%03o' $(($(od -An -tu1 -j $((size / 2)) -N1 "$checkpoint") ^ 1)))" |
    dd of="$checkpoint" bs=1 seek=$((size / 2)) conv=notrunc status=none
  broken=$(hashes "$work/stopped.partial")
  run "$work/flipped.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/flipped.log"
  expect_in "$work/flipped.log" "checkpoint '.*stopped.partial/checkpoint.ddc' is corrupted or truncated" "a flipped byte"
  [ "$(hashes "$work/stopped.partial")" = "$broken" ] || fail "the stopped run's directory changed (flipped byte)"
  # Cut short.
  head -c $((size - 100)) "$work/intact.ddc" >"$checkpoint"
  broken=$(hashes "$work/stopped.partial")
  run "$work/truncated.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/truncated.log"
  expect_in "$work/truncated.log" "checkpoint '.*stopped.partial/checkpoint.ddc' is corrupted or truncated" "cut short"
  [ "$(hashes "$work/stopped.partial")" = "$broken" ] || fail "the stopped run's directory changed (cut short)"
  # Not a checkpoint at all.
  cp "$work/stopped.partial/history.csv" "$checkpoint"
  run "$work/foreign.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/foreign.log"
  expect_in "$work/foreign.log" "stopped.partial/checkpoint.ddc.* not a DDContact checkpoint" "a foreign file"
  # The intact one restarts.
  cp "$work/intact.ddc" "$checkpoint"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  run "$work/restart.log" "$np" --restart "$work/stopped"
  every_rank_succeeded "$work/restart.log"
  ;;
deck-change)
  DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  before=$(hashes "$work/stopped.partial")
  run "$work/penetration.log" "$np" --restart "$work/stopped" --set "Contact/Penetration Tolerance=2e-6"
  every_rank_failed "$work/penetration.log"
  expect_in "$work/penetration.log" \
    "restart: parameter 'Contact/Penetration Tolerance' is '2e-06' in this deck but was '1e-06' in the run that wrote the checkpoint '.*stopped.partial/checkpoint.ddc'; .* may change only Load Stepping, " \
    "a changed contact parameter"
  run "$work/mesh.log" "$np" --restart "$work/stopped" --set "Mesh/Bodies/Lower Ring/Annular Sector/Refinement=2"
  every_rank_failed "$work/mesh.log"
  expect_in "$work/mesh.log" "restart: parameter 'Mesh/Bodies/Lower Ring/Annular Sector/Refinement' is '2' in this deck but was '1'" \
    "a changed mesh"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  # Allowed: more steps for the rest of the run, into another directory.
  run "$work/steps.log" "$np" --restart "$work/stopped" --set "Load Stepping/Number of Steps=40" \
    --output-dir "$work/finer"
  every_rank_succeeded "$work/steps.log"
  expect_in "$work/steps.log" "step  40/40  load 1 " "the rest of the run in 40 steps"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
extend)
  reference
  cp "$work/reference/history.csv" "$work/finished.csv"
  run "$work/extend.log" "$np" --restart "$work/reference" --set "Load Stepping/Final Load Factor=1.1" \
    --set "Load Stepping/Number of Steps=22"
  every_rank_succeeded "$work/extend.log"
  expect_in "$work/extend.log" "restart: continuing after step 20 \(load factor 1\) from .*reference/checkpoint.ddc" \
    "restart from the finished run"
  expect_in "$work/extend.log" "step  22/22  load 1.1 " "the two further steps"
  grep -q "never paired" "$work/extend.log" && fail "a pair that paired before the restart is reported as never paired"
  head -n 21 "$work/reference/history.csv" >"$work/first20.csv"
  "$compare" "$work/finished.csv" "$work/first20.csv" exact || fail "the finished run's rows changed"
  ;;
reference)
  reference
  ;;
no-checkpoint)
  DDCONTACT_FAULT_INJECTION=sigterm@5 run "$work/stopped.log" "$np" --output-dir "$work/stopped" \
    --set "Output/Checkpoint Interval=0"
  every_rank_status "$work/stopped.log" 143
  expect_in "$work/stopped.log" "stopped by SIGTERM after step 5 .*; no checkpoint \(Output/Checkpoint Interval = 0\)" \
    "the stop message"
  run "$work/restart.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/restart.log"
  expect_in "$work/restart.log" "--restart '.*stopped': no checkpoint in '.*stopped.partial' or '.*stopped'" \
    "restart without a checkpoint"
  ;;
input-change:*)
  kind=${case_name#input-change:}
  src=$(dirname "$deck")
  cp "$deck" "$src/restart_block.msh" "$src/restart_block.map" "$work/"
  deck=$work/$(basename "$deck")
  case $kind in
  gmsh)
    file=$work/restart_block.msh param="Mesh/Bodies/Block/Gmsh/File"
    edit() { sed -i 's/^0.25 0.25 0$/0.26 0.25 0/' "$file"; }
    ;;
  map)
    file=$work/restart_block.map param="Partition/Element Map File"
    extra+=(--set "Partition/Method=Element Map File" --set "Partition/Element Map File=restart_block.map")
    edit() { sed -i '0,/^0 0 1 1$/s//0 1 1 1/' "$file"; }
    ;;
  exodus)
    file=$work/restart_block.e param="Mesh/Bodies/Block/Exodus/File"
    run "$work/source.log" 1 --output-dir "$work/source" --set "Output/Exodus=true" \
      --set "Load Stepping/Number of Steps=1" --set "Output/Checkpoint Interval=0"
    np=1 every_rank_succeeded "$work/source.log" || exit 1
    "${PYTHON:-python3}" "$here/write_exodus_mesh.py" "$work/source/results.e" "$file" &&
      "${PYTHON:-python3}" "$here/exodus_deck.py" "$deck" "$work/exodus.xml" "$file" || exit 1
    deck=$work/exodus.xml
    edit() { "${PYTHON:-python3}" -c "import netCDF4, sys; d = netCDF4.Dataset(sys.argv[1], 'r+'); d['coordx'][6] += 0.01; d.close()" "$file"; }
    ;;
  esac
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  cp "$file" "$work/original"
  before=$(hashes "$work/stopped.partial")
  edit
  cmp -s "$file" "$work/original" && fail "the edit left $file as it was"
  run "$work/changed.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/changed.log"
  expect_in "$work/changed.log" \
    "restart: the file '.*$(basename "$file")' \('$param'\) changed since the run that wrote the checkpoint '.*stopped.partial/checkpoint.ddc' read it .*restore the file, or start the run anew" \
    "a changed $kind file"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  cp "$work/original" "$file"
  run "$work/restored.log" "$np" --restart "$work/stopped"
  every_rank_succeeded "$work/restored.log"
  expect_in "$work/restored.log" "restart: continuing after step 3 " "the restart with the file restored"
  ;;
final-below)
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  before=$(hashes "$work/stopped.partial")
  run "$work/below.log" "$np" --restart "$work/stopped" --set "Load Stepping/Final Load Factor=0.4"
  every_rank_failed "$work/below.log"
  expect_in "$work/below.log" \
    "restart: 'Load Stepping/Final Load Factor' = 0.4 lies below the load factor 0.5 the checkpoint '.*stopped.partial/checkpoint.ddc' reached \(step 3\)" \
    "a final load factor below the checkpoint's"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
finished-checkpoint)
  run "$work/finished.log" "$np" --output-dir "$work/run"
  every_rank_succeeded "$work/finished.log" || exit 1
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/run" \
    --set "Output/Checkpoint Interval=0"
  every_rank_status "$work/stopped.log" 143
  before=$(hashes "$work/run")$(hashes "$work/run.partial")
  run "$work/restart.log" "$np" --restart "$work/run"
  every_rank_failed "$work/restart.log"
  expect_in "$work/restart.log" \
    "--restart '.*run': the run that did not finish in '.*run.partial' left no checkpoint .*belongs to the earlier, finished run committed in '.*run', not to it" \
    "the finished run's checkpoint"
  [ "$(hashes "$work/run")$(hashes "$work/run.partial")" = "$before" ] || fail "the result or the staging directory changed"
  ;;
rerun-stopped)
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  before=$(hashes "$work/stopped.partial")
  run "$work/rerun.log" "$np" --output-dir "$work/stopped"
  every_rank_failed "$work/rerun.log"
  expect_in "$work/rerun.log" \
    "'.*stopped.partial' is the staging directory of an earlier run that did not finish and holds its checkpoint '.*stopped.partial/checkpoint.ddc'; continue that run with --restart '.*stopped', or, to start anew and discard it, move or remove" \
    "a plain run into a stopped run's directory"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
edited-result)
  run "$work/finished.log" "$np" --output-dir "$work/result" --set "Load Stepping/Number of Steps=2"
  every_rank_succeeded "$work/finished.log" || exit 1
  cp "$work/result/history.csv" "$work/history.csv"
  # One character of a value changed, the size kept.
  sed -i '2s/0/1/' "$work/result/history.csv"
  cmp -s "$work/result/history.csv" "$work/history.csv" && fail "the edit left history.csv as it was"
  before=$(hashes "$work/result")
  run "$work/edited.log" "$np" --output-dir "$work/result"
  every_rank_failed "$work/edited.log"
  expect_in "$work/edited.log" "'.*result/history.csv' changed since DDContact wrote it .*move it away or choose another --output-dir" \
    "an edited file of the result"
  [ "$(hashes "$work/result")" = "$before" ] || fail "the edited result changed"
  cp "$work/history.csv" "$work/result/history.csv"
  mkdir "$work/result/mine"
  run "$work/added.log" "$np" --output-dir "$work/result"
  every_rank_failed "$work/added.log"
  expect_in "$work/added.log" "'.*result/mine/' is a directory DDContact did not make there" "a directory added to the result"
  [ -d "$work/result/mine" ] || fail "the added directory is gone"
  ;;
wrong-source)
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  before=$(hashes "$work/stopped.partial")
  run "$work/partial.log" "$np" --restart "$work/stopped.partial"
  every_rank_failed "$work/partial.log"
  expect_in "$work/partial.log" "--restart '.*stopped.partial' names the staging directory of a run; name the run's output directory instead: --restart '.*stopped'" \
    "--restart DIR.partial"
  run "$work/file.log" "$np" --restart "$work/stopped.partial/checkpoint.ddc"
  every_rank_failed "$work/file.log"
  expect_in "$work/file.log" "--restart '.*stopped.partial/checkpoint.ddc' names a file; .*that is --restart '.*stopped'\)" \
    "--restart naming the checkpoint"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
bad-checkpoint)
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  checkpoint=$work/stopped.partial/checkpoint.ddc
  before=$(hashes "$work/stopped.partial")
  mv "$checkpoint" "$work/intact.ddc"
  mkdir "$checkpoint"
  run "$work/directory.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/directory.log"
  expect_in "$work/directory.log" "'.*stopped.partial/checkpoint.ddc' is not a regular file \(a directory\)" "a directory"
  rmdir "$checkpoint"
  ln -s /dev/zero "$checkpoint"
  run "$work/device.log" "$np" --restart "$work/stopped"
  every_rank_failed "$work/device.log"
  expect_in "$work/device.log" "'.*stopped.partial/checkpoint.ddc' is not a regular file \(a link to a device" "a link to a device"
  rm "$checkpoint"
  # 8 GiB of zeros after the first line. Version 1 files are read whole on
  # rank 0 and broadcast: refused by size. Version 2: its head says what to
  # read; zeros are refused without reading them.
  for version in 1 2; do
    printf 'DDContact checkpoint %s\n' "$version" >"$checkpoint"
    truncate -s 8G "$checkpoint"
    rm -rf "$work/status"
    mkdir -p "$work/status"
    prlimit --as=4294967296 mpirun --oversubscribe -np "$np" sh "$here/record_exit_status.sh" "$work/status" "$app" \
      "$deck" "${extra[@]}" --restart "$work/stopped" >"$work/large$version.log" 2>&1
    every_rank_failed "$work/large$version.log"
  done
  expect_in "$work/large1.log" "the checkpoint '.*stopped.partial/checkpoint.ddc' is 8.0 GiB; reading it takes about 16 GiB per rank, more than the .* available" \
    "an 8 GiB checkpoint"
  expect_in "$work/large2.log" \
    "the checkpoint '.*stopped.partial/checkpoint.ddc' is corrupted or truncated \(8589934592 bytes\)" \
    "an 8 GiB checkpoint of version 2"
  rm "$checkpoint"
  mv "$work/intact.ddc" "$checkpoint"
  [ "$(hashes "$work/stopped.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
exodus-messages)
  # Exodus II output switched on only at the restart: a warning that names
  # no internal file.
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/stopped.log" "$np" --output-dir "$work/stopped"
  every_rank_status "$work/stopped.log" 143
  run "$work/switched.log" "$np" --restart "$work/stopped" --set "Output/Exodus=true"
  every_rank_succeeded "$work/switched.log"
  expect_in "$work/switched.log" \
    "warning: restart: results.e holds none of the 3 steps before the checkpoint: the run that wrote it left no results.e \('.*stopped.partial/results.e'; Output/Exodus was false in that run" \
    "Exodus II output switched on at the restart"
  grep -Eq "before-restart|ex_open" "$work/switched.log" && fail "a message names an internal file or library call"
  # A full disk while the restart writes results.e (seam enospc@results.e).
  DDCONTACT_FAULT_INJECTION=sigterm@3 run "$work/exodus.log" "$np" --output-dir "$work/exodus" \
    --set "Output/Exodus=true"
  every_rank_status "$work/exodus.log" 143
  before=$(hashes "$work/exodus.partial")
  DDCONTACT_FAULT_INJECTION=enospc@results.e run "$work/full.log" "$np" --restart "$work/exodus" \
    --output-dir "$work/full" --set "Output/Exodus=true"
  every_rank_failed "$work/full.log"
  expect_in "$work/full.log" "cannot write step 4 of the Exodus II results '.*full.partial/results.e(\.[0-9]+\.[0-9]+)?' \(time\): No space left on device" \
    "a full disk while writing results.e"
  [ "$(hashes "$work/exodus.partial")" = "$before" ] || fail "the stopped run's directory changed"
  ;;
*)
  echo "unknown case $case_name"
  exit 2
  ;;
esac
[ "$failures" = 0 ] && echo "PASS: $case_name on $np ranks" || echo "$failures failed checks"
exit $((failures > 0))
