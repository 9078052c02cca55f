#!/bin/bash
# foreign_owner_case.sh NP APP DECK WORK
# A result directory written by another user, whose files this user may not
# delete: a run into it (or into a directory whose previous result 'D.old'
# is such a one) must stop at start, on every rank, naming the directory,
# its owner and what to do, and leave everything as it was. Before, the run
# exited 0 leaving an undeletable D.old and every later run failed with
# "Permission denied" and no hint.
#
# Needs two users: runs as root, writes the earlier result as root and runs
# the second run as 'nobody' (setpriv). Without root or setpriv it is
# skipped (exit 77).
set -u
np=$1 app=$2 deck=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
if [ "$(id -u)" != 0 ] || ! command -v setpriv >/dev/null || ! id nobody >/dev/null 2>&1; then
  echo "SKIP: needs root, setpriv and the user 'nobody' to act as two users"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
chmod 0777 "$work"  # both users may create entries (no sticky bit: renames allowed)
out=$work/out
failures=0
. "$here/rank_status_lib.sh"

mpirun --oversubscribe -np "$np" "$app" "$deck" --output-dir "$out" >"$work/earlier.log" 2>&1 ||
  { fail "the earlier run (as root) failed"; cat "$work/earlier.log"; exit 1; }
chmod -R go-w "$out"

# as_nobody LOG OUTDIR: the run as 'nobody'; every rank's status recorded.
as_nobody() {
  rm -rf "$work/status"
  mkdir -p "$work/status"
  chmod 0777 "$work/status"
  setpriv --reuid=nobody --regid=nogroup --clear-groups env HOME="$work" TMPDIR="$work" \
    mpirun --oversubscribe -np "$np" sh "$here/record_exit_status.sh" "$work/status" "$app" "$deck" --output-dir "$2" \
    >"$1" 2>&1
}

# 1. The result itself belongs to root.
before=$(hashes "$out")
as_nobody "$work/replace.log" "$out"
every_rank_failed "$work/replace.log"
grep -q "output directory '$out' holds an earlier result that this run could not remove when it replaces it: '$out' (owner root) does not let this user (nobody) delete its entries: Permission denied; choose another --output-dir, or have its owner remove it" "$work/replace.log" ||
  { fail "replace: message"; sed 's/^/    | /' "$work/replace.log"; }
[ "$(hashes "$out")" = "$before" ] || fail "replace: '$out' changed"
for p in "$out.old" "$out.partial" "$out.lock"; do [ -e "$p" ] && fail "replace: '$p' was left behind"; done
echo "ok: replace"

# 2. A previous result 'D.old' that belongs to root, left by a commit.
mv "$out" "$out.old"
before=$(hashes "$out.old")
as_nobody "$work/old.log" "$out"
every_rank_failed "$work/old.log"
grep -q "'$out.old', a previous result of output directory '$out' left by an earlier commit, cannot be removed: '$out.old' (owner root) does not let this user (nobody) delete its entries" "$work/old.log" ||
  { fail "old: message"; sed 's/^/    | /' "$work/old.log"; }
[ "$(hashes "$out.old")" = "$before" ] || fail "old: '$out.old' changed"
echo "ok: old"

if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all checks passed"
