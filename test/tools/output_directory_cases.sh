#!/usr/bin/env bash
# System tests of the output directory's failure paths (doc/user-guide.md,
# "The output directory"), driven through the test seam
# DDCONTACT_FAULT_INJECTION (packages/io/src/DDC_ResultFile.hpp).
#
#   output_directory_cases.sh CASE NP DDCONTACT DECK WORKDIR
#
# CASE:
#   write-faults  a failing write / sync / close / create at each file of a
#                 result: every rank exits non-zero naming the file and the
#                 reason, the earlier result is byte-identical, the next run
#                 succeeds.
#   kill-stages   the process killed at each stage of a run and its commit:
#                 afterwards the old or the new result is complete, the next
#                 run recovers it (and says so), a normal run then succeeds.
#   concurrent    two runs into one directory: the second stops at start
#                 naming the first; the first's result is its own.
#   foreign       directories and files DDContact did not write (the output
#                 directory itself, reached directly or through "P/sub/..",
#                 files added to an earlier result, a D.partial, D.old or
#                 D.lock of someone else's, and a D.lock that is a symbolic
#                 link, an empty file, a FIFO or a directory): every rank
#                 exits non-zero at start naming the path, and every foreign
#                 file is still there.
# DECK is a small deck with VTK output (e.g. test/inputs/small_block.xml).
set -u
case_name=$1 np=$2 app=$3 deck=$4 work=$5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
out=$work/out
failures=0

. "$here/rank_status_lib.sh"

# run LOG [ddcontact args...]: runs ddcontact on $np ranks, each rank's exit
# status recorded in $work/status/rank-R.status; returns mpirun's status.
run() {
  local log=$1
  shift
  rm -rf "$work/status"
  mkdir -p "$work/status"
  mpirun --oversubscribe -np "$np" sh "$here/record_exit_status.sh" "$work/status" "$app" "$@" >"$log" 2>&1
}

# data rows of the history in $1
rows() { echo $(($(wc -l <"$1/history.csv") - 1)); }

# A complete earlier result with N steps into $out.
earlier() {
  run "$work/earlier.log" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=$1" ||
    { fail "earlier run failed"; sed 's/^/    | /' "$work/earlier.log"; exit 1; }
}

case "$case_name" in
write-faults)
  # The result of a 2-step run: parameters.xml, history.csv, vtk/ (steps 0..2,
  # one piece per subdomain = per rank), the manifest.
  last_piece=$(printf "vtk/step_00002_piece_%04d.vtu" $((np - 1)))
  faults=(
    "enospc@parameters.xml|parameters.xml.*No space left on device"
    "enospc@history.csv|history.csv.*No space left on device"
    "enospc@vtk/step_00001.pvtu|step_00001.pvtu.*No space left on device"
    "enospc@$last_piece|$last_piece.*No space left on device"
    "enospc@vtk/solution.pvd|solution.pvd.*No space left on device"
    "enospc@ddcontact-result.txt:start|ddcontact-result.txt.tmp': No space left on device"
    "enospc@ddcontact-result.txt|ddcontact-result.txt.tmp': No space left on device"
    "eio-fsync@history.csv|history.csv' to disk \\(fsync\\): Input/output error"
    "eio-fsync@$last_piece|$last_piece' to disk \\(fsync\\): Input/output error"
    "eio-close@vtk/step_00002.pvtu|close .*step_00002.pvtu': Input/output error"
    "eacces@parameters.xml|cannot create .*parameters.xml.tmp': Permission denied"
    "eacces@vtk/step_00000_piece_0000.vtu|cannot create .*step_00000_piece_0000.vtu': Permission denied"
  )
  earlier 1
  before=$(hashes "$out")
  for item in "${faults[@]}"; do
    fault=${item%%|*}
    regex=${item#*|}
    log=$work/$(echo "$fault" | tr '@/' '__').log
    DDCONTACT_FAULT_INJECTION=$fault run "$log" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=2"
    every_rank_failed "$log" || continue
    grep -Eq "ddcontact: error: .*$regex" "$log" || { fail "$fault: message does not match '$regex'"; sed 's/^/    | /' "$log"; }
    grep -q "MPI_ABORT" "$log" && fail "$fault: ended through MPI_Abort"
    [ "$(hashes "$out")" = "$before" ] || fail "$fault: the earlier result changed"
    echo "ok: $fault -> every rank failed, earlier result intact"
  done
  run "$work/after.log" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=2"
  every_rank_succeeded "$work/after.log" && [ "$(rows "$out")" = 2 ] || fail "the run after the faults did not succeed"
  ;;
kill-stages)
  # stage | the result the next run must find: old (1 step) or new (2 steps)
  stages=("staged|old" "commit-begin|old" "commit-manifest-written|new" "commit-old-moved|new"
    "commit-new-moved|new" "removing-old-result|new")
  for item in "${stages[@]}"; do
    stage=${item%%|*}
    expect=${item#*|}
    rm -rf "$out" "$out.partial" "$out.old" "$out.lock"
    earlier 1
    before=$(hashes "$out")
    log=$work/kill_$stage.log
    # A rank killed by a signal makes mpirun end the others: SIGTERM, then
    # SIGKILL after odls_base_sigkill_timeout (1 s by default, 2 s a run in
    # all). Nothing of theirs is checked here, so they go at once.
    DDCONTACT_FAULT_INJECTION=kill@$stage OMPI_MCA_odls_base_sigkill_timeout=0 \
      run "$log" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=2"
    grep -q "step *2/2" "$log" || [ "$stage" = staged ] || { fail "$stage: the killed run did not get to its end"; continue; }
    # On disk now: the old or the new complete result, under D, D.old or D.partial.
    complete=0
    for d in "$out" "$out.old" "$out.partial"; do
      grep -q "^status: complete" "$d/ddcontact-result.txt" 2>/dev/null && complete=1
    done
    [ $complete = 1 ] || fail "$stage: no complete result left on disk"
    # The next run (here one that then stops on bad input) recovers.
    log2=$work/recover_$stage.log
    run "$log2" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=0"
    every_rank_failed "$log2" >/dev/null || true
    [ -e "$out.old" ] && fail "$stage: '$out.old' left after recovery"
    [ -e "$out.partial" ] && fail "$stage: '$out.partial' left after recovery"
    if [ "$expect" = old ]; then
      [ "$(hashes "$out")" = "$before" ] || fail "$stage: the old result is not intact after recovery"
    else
      grep -q "^status: complete" "$out/ddcontact-result.txt" && [ "$(rows "$out")" = 2 ] ||
        fail "$stage: the new (2-step) result was not recovered"
    fi
    grep -q "ddcontact: output: " "$log2" || fail "$stage: the recovery was silent"
    run "$work/normal_$stage.log" "$deck" --output-dir "$out" --set "Load Stepping/Number of Steps=3"
    every_rank_succeeded "$work/normal_$stage.log" && [ "$(rows "$out")" = 3 ] || fail "$stage: the next normal run failed"
    echo "ok: killed at $stage -> $expect result recovered"
  done
  ;;
concurrent)
  earlier 1
  go=$work/go
  # The first run stops right after taking the lock until $go exists.
  mkdir -p "$work/status1"
  DDCONTACT_FAULT_INJECTION="pause@locked=$go" mpirun --oversubscribe -np "$np" \
    sh "$here/record_exit_status.sh" "$work/status1" "$app" "$deck" --output-dir "$out" \
    --set "Load Stepping/Number of Steps=3" >"$work/first.log" 2>&1 &
  first=$!
  for _ in $(seq 1 600); do
    grep -q "^started: " "$out.lock" 2>/dev/null && break
    sleep 0.1
  done
  grep -q "^started: " "$out.lock" 2>/dev/null || fail "the first run never took the lock"
  second_deck=$work/second.xml
  cp "$deck" "$second_deck"
  run "$work/second.log" "$second_deck" --output-dir "$out" --set "Load Stepping/Number of Steps=5"
  every_rank_failed "$work/second.log" &&
    grep -Eq "output directory '.*out' is in use by another ddcontact run \(pid: [0-9]+, host: .*, input: .*$(basename "$deck"), started: " "$work/second.log" ||
    { fail "the second run did not stop naming the first"; sed 's/^/    | /' "$work/second.log"; }
  touch "$go"
  wait $first
  for ((r = 0; r < np; r++)); do
    [ "$(cat "$work/status1/rank-$r.status" 2>/dev/null)" = 0 ] || fail "first run: rank $r did not succeed"
  done
  grep -q "^input: .*/$(basename "$deck")\$" "$out/ddcontact-result.txt" || fail "the result does not name the first run's input"
  [ "$(rows "$out")" = 3 ] || fail "the result is not the first run's (3 steps)"
  [ -e "$out.lock" ] && fail "the lock file was not removed"
  echo "ok: concurrent runs"
  ;;
foreign)
  mine=$work/mine
  mkdir -p "$mine/notes"
  echo "two years of work" >"$mine/thesis.tex"
  echo "a" >"$mine/notes/a.txt"
  # check NAME OUTPUT-DIR REGEX DIR-THAT-MUST-BE-INTACT
  check() {
    local before log=$work/$1.log
    before=$(hashes "$4")
    run "$log" "$deck" --output-dir "$2"
    every_rank_failed "$log" || return
    grep -Eq "ddcontact: error: .*$3" "$log" || { fail "$1: message does not match '$3'"; sed 's/^/    | /' "$log"; }
    [ "$(hashes "$4")" = "$before" ] || fail "$1: '$4' changed"
    grep -q "step " "$log" && fail "$1: the run did not stop at start"
    echo "ok: $1"
  }
  check foreign_dir "$mine" "'$mine' exists and was not written by ddcontact.*choose another --output-dir" "$mine"
  check foreign_dotdot "$mine/notes/.." "'$mine' exists and was not written by ddcontact" "$mine"
  [ -e "$mine.partial" ] && fail "a staging directory was created next to '$mine'"
  [ -e "$mine.lock" ] && fail "the lock file '$mine.lock' was left behind"
  earlier 1
  echo "my plot" >"$out/plot.png"
  check foreign_file_in_result "$out" "holds files DDContact did not write: '$out/plot.png'" "$out"
  rm "$out/plot.png"
  for suffix in partial old; do
    mkdir -p "$out.$suffix"
    echo keep >"$out.$suffix/keep.txt"
    check "foreign_$suffix" "$out" "'$out.$suffix' exists and was not written by ddcontact" "$out.$suffix"
    rm -rf "$out.$suffix"
  done
  echo "someone's file" >"$out.lock"
  check foreign_lock "$out" "'$out.lock' exists and was not written by ddcontact" "$out.lock"
  rm "$out.lock"
  # The lock is never opened through a link: a link to someone's file (which
  # the run would have locked, overwritten and unlinked at its end) or a
  # dangling one (whose target it would have created) is refused.
  ln -s "$mine/thesis.tex" "$out.lock"
  check lock_symlink "$out" "'$out.lock' is a symbolic link.*does not follow links" "$mine"
  [ -L "$out.lock" ] || fail "lock_symlink: the link '$out.lock' was removed"
  rm "$out.lock"
  ln -s "$work/nowhere" "$out.lock"
  check lock_dangling_symlink "$out" "'$out.lock' is a symbolic link" "$mine"
  [ -e "$work/nowhere" ] && fail "lock_dangling_symlink: the link's target '$work/nowhere' was created"
  rm "$out.lock"
  # An empty file nobody holds is not a lock DDContact made (it used to be
  # taken over and deleted at the end of the run).
  : >"$out.lock"
  check lock_empty_foreign "$out" "'$out.lock' exists, is empty and no ddcontact run holds it" "$out.lock"
  [ -f "$out.lock" ] || fail "lock_empty_foreign: '$out.lock' was removed"
  rm "$out.lock"
  mkfifo "$out.lock"
  check lock_fifo "$out" "'$out.lock' exists and is not a regular file" "$mine"
  [ -p "$out.lock" ] || fail "lock_fifo: the FIFO '$out.lock' was removed"
  rm "$out.lock"
  mkdir "$out.lock"
  check lock_directory "$out" "'$out.lock' exists and is not a regular file" "$mine"
  rmdir "$out.lock" || fail "lock_directory: '$out.lock' is no longer an empty directory"
  # A regular file where the directory should be.
  echo "a file" >"$work/afile"
  check not_a_directory "$work/afile" "'$work/afile' exists and is not a directory" "$work/afile"
  ;;
*)
  echo "unknown case '$case_name'"
  exit 2
  ;;
esac
if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all checks passed"
