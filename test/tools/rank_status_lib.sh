# Shared by the output test scripts (sourced): checks of the per-rank exit
# statuses that tools/record_exit_status.sh leaves in $work/status, for $np
# ranks, and checksums of a directory's files. fail() counts a failed check
# in $failures.
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# every_rank_failed LOG: each rank recorded a non-zero status.
every_rank_failed() {
  local r
  for ((r = 0; r < np; r++)); do
    local s
    s=$(cat "$work/status/rank-$r.status" 2>/dev/null || echo missing)
    if [ "$s" = missing ] || [ "$s" = 0 ]; then
      fail "rank $r exit status '$s', expected non-zero ($1)"
      sed 's/^/    | /' "$1"
      return 1
    fi
  done
}

every_rank_succeeded() {
  local r
  for ((r = 0; r < np; r++)); do
    local s
    s=$(cat "$work/status/rank-$r.status" 2>/dev/null || echo missing)
    if [ "$s" != 0 ]; then
      fail "rank $r exit status '$s', expected 0 ($1)"
      sed 's/^/    | /' "$1"
      return 1
    fi
  done
}

# every_rank_status LOG CODE: each rank exited with CODE.
every_rank_status() {
  local r
  for ((r = 0; r < np; r++)); do
    local s
    s=$(cat "$work/status/rank-$r.status" 2>/dev/null || echo missing)
    if [ "$s" != "$2" ]; then
      fail "rank $r exit status '$s', expected $2 ($1)"
      sed 's/^/    | /' "$1"
      return 1
    fi
  done
}

# hashes PATH: checksums of a file, or of every file below a directory.
hashes() {
  if [ -f "$1" ]; then
    sha256sum <"$1"
  else
    (cd "$1" 2>/dev/null && find . -type f -print0 | sort -z | xargs -0 -r sha256sum) || echo "<no directory $1>"
  fi
}
