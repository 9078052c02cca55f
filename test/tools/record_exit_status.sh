#!/bin/sh
# record_exit_status.sh DIR COMMAND [ARGS...]
# Runs COMMAND as one MPI rank and writes its exit status to
# DIR/rank-<rank>.status, then exits 0, so that mpirun lets every rank
# finish and record its own status (mpirun stops the remaining ranks as soon
# as one exits non-zero). test/cmake/RunCase.cmake checks the files.
dir=$1
shift
"$@"
rc=$?
rank=${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}
echo "$rc" > "$dir/rank-$rank.status"
exit 0
