#!/usr/bin/env bash
# What building the mesh in ranges saves (doc/performance.md, "Memory at
# set-up"): examples/block_3d.xml (MODEL=block_3d), or the Hertz sphere
# with contact (MODEL=hertz_sphere: sphere and block at the refinement, the
# decomposed element under FETI-DP; another SOLVERS entry, e.g. MUMPS,
# solves the conventional element monolithically), on NP ranks with the
# whole mesh on every rank (METIS, PT-Scotch), each rank's part cut from the
# whole mesh it built
# (METIS, 'Partition/Mesh On Every Rank' = false), and the mesh built in
# ranges (PT-Scotch, the same parameter false: no rank holds the whole
# mesh), and the same mesh read from an Exodus II file whole on every rank
# (exodus-whole) or in slabs (exodus-ranges: each rank reads its range of
# the elements and a share of the coordinates and sets), or from a Gmsh file
# whole on every rank (gmsh-whole) or in ranges (gmsh-ranges: each rank keeps
# its range of the elements and a share of the nodes as the file streams
# by). The file is written first from a run's results.e
# (test/tools/write_exodus_mesh.py or write_gmsh_mesh.py, exodus_deck.py;
# not timed). One run per row. Prints a markdown table: peak resident memory per
# rank (min / median / max, /usr/bin/time), and seconds from the launch to
# the partition line and to the distribution line (the set-up before the
# solver's own) and in all, read from the output as it arrives. With NP
# above the host's cores the ranks are oversubscribed: memory is
# meaningful, time is not. Not part of ctest.
#
#   bash test/benchmark/mesh_in_ranges.sh [BUILD_DIR]     # default: build
# Environment: NP (16), MODEL (block_3d), REFINEMENT (8), SOLVERS
# ("Belos-MueLu FETI-DP"; for hertz_sphere "FETI-DP"), MESHES (the rows:
# "whole-metis whole-ptscotch parts-metis ranges"; also exodus-whole,
# exodus-ranges, gmsh-whole and gmsh-ranges).
set -euo pipefail
cd "$(dirname "$0")/../.."
# shellcheck source=common.sh
. test/benchmark/common.sh "${1:-build}"
NP=${NP:-16}
REFINEMENT=${REFINEMENT:-8}
MODEL=${MODEL:-block_3d}
MESHES=${MESHES:-whole-metis whole-ptscotch parts-metis ranges}
if [[ $MODEL == hertz_sphere ]]; then SOLVERS=${SOLVERS:-FETI-DP}; else SOLVERS=${SOLVERS:-Belos-MueLu FETI-DP}; fi
# DECK, the mesh's parameters (MESH_ARGS) and the others (RUN_ARGS).
case $MODEL in
  block_3d) DECK=examples/block_3d.xml MESH_ARGS=(--set "Mesh/Bodies/Block/Box/Refinement=$REFINEMENT") RUN_ARGS=() ;;
  hertz_sphere)
    DECK=examples/hertz_sphere.xml
    MESH_ARGS=(--set "Mesh/Bodies/Sphere/Sphere Octant/Refinement=$REFINEMENT"
      --set "Mesh/Bodies/Block/Box/Refinement=$REFINEMENT")
    RUN_ARGS=(--set "Partition/Method=METIS" --set "Partition/Number of Subdomains=0") ;;
  *) echo "MODEL must be block_3d or hertz_sphere, not '$MODEL'" >&2; exit 2 ;;
esac
MODEL_ARGS=("$DECK" "${MESH_ARGS[@]}" "${RUN_ARGS[@]}")

# solver_args SOLVER: the solver's parameters, in SOLVER_ARGS.
solver_args() {
  if [[ $1 == FETI-DP ]]; then SOLVER_ARGS=(--set Solver/Strategy=FETI-DP)
  else SOLVER_ARGS=(--set Solver/Strategy=Monolithic --set "Solver/Linear Solver/Type=$1"); fi
  if [[ $MODEL == hertz_sphere && $1 != FETI-DP ]]; then
    SOLVER_ARGS+=(--set "Contact/Formulation=Node-To-Surface")
  fi
}

# file_model SOLVER KIND: MODEL_ARGS reading the model's mesh from
# $OUT/mesh.e (KIND exodus) or $OUT/mesh.msh (gmsh), written once from a
# one-step run's results.e (solved by SOLVER).
file_model() {
  local mesh=$OUT/mesh.e writer=write_exodus_mesh.py
  if [[ $2 == gmsh ]]; then mesh=$OUT/mesh.msh writer=write_gmsh_mesh.py; fi
  if [[ ! -f $OUT/w/results.e ]]; then
    solver_args "$1"
    mpirun -np "$NP" "$APP" "${MODEL_ARGS[@]}" "${SOLVER_ARGS[@]}" --set Output/Exodus=true --set Output/VTK=false \
      --set "Load Stepping/Number of Steps=1" --set "Output/Checkpoint Interval=0" --set "Solver/Memory Check=false" \
      --output-dir "$OUT/w" >"$OUT/w.log" 2>&1 || { echo "writing the mesh failed:" >&2; tail -5 "$OUT/w.log" >&2; exit 1; }
  fi
  if [[ ! -f $OUT/$2.xml ]]; then
    /usr/bin/python3 "test/tools/$writer" "$OUT/w/results.e" "$mesh"
    /usr/bin/python3 test/tools/exodus_deck.py "$DECK" "$OUT/$2.xml" "$mesh"
  fi
  MODEL_ARGS=("$OUT/$2.xml" "${RUN_ARGS[@]}")
}

# stamped: each line of stdin prefixed with the seconds since the start.
stamped() { python3 -u -c 'import sys, time
t0 = time.time()
for line in sys.stdin: sys.stdout.write("%.2f %s" % (time.time() - t0, line))'; }

# row SOLVER MODE ARGS... -> a table row
row() {
  local solver=$1 mode=$2
  shift 2
  local log=$OUT/run.log
  solver_args "$solver"
  mpirun -np "$NP" /usr/bin/time -f "RSS %M" "$APP" "${MODEL_ARGS[@]}" "${SOLVER_ARGS[@]}" --set Output/VTK=false \
    --set "Output/Checkpoint Interval=0" --set "Solver/Memory Check=false" --output-dir "$OUT/o" "$@" 2>&1 |
    stamped >"$log" || { echo "| $solver | $mode | failed: $(grep -m1 -i error "$log") | | | |"; return; }
  local rss partition distribution wall
  rss=$(sed -n 's/.*RSS \([0-9]*\)$/\1/p' "$log" | awk '{print $1 / 1024}' | sort -g |
    awk '{a[NR] = $1} END {printf "%.0f / %.0f / %.0f", a[1], a[int((NR + 1) / 2)], a[NR]}')
  partition=$(awk '/ partition: / {print $1; exit}' "$log")
  distribution=$(awk '/ distribution: / {print $1; exit}' "$log")
  wall=$(tail -1 "$log" | awk '{print $1}')
  echo "| $solver | $mode | $rss | ${partition:--} | $distribution | $wall |"
}

echo "$MODEL at Refinement $REFINEMENT on $NP ranks"
echo
echo "| solver | mesh | peak MiB per rank (min / median / max) | s to partition | s to distribution | s in all |"
echo "|---|---|---|---:|---:|---:|"
for solver in $SOLVERS; do
  for mesh in $MESHES; do
    case $mesh in
      whole-metis) row "$solver" "whole, METIS" ;;
      whole-ptscotch) row "$solver" "whole, PT-Scotch" --set Partition/Method=PT-Scotch ;;
      parts-metis) row "$solver" "parts cut from the whole, METIS" --set "Partition/Mesh On Every Rank=false" ;;
      ranges) row "$solver" "in ranges, PT-Scotch" --set Partition/Method=PT-Scotch \
        --set "Partition/Mesh On Every Rank=false" ;;
      exodus-whole | exodus-ranges | gmsh-whole | gmsh-ranges)
        saved=("${MODEL_ARGS[@]}")
        kind=${mesh%-*}
        file_model "$solver" "$kind"
        label=$([[ $kind == gmsh ]] && echo "Gmsh" || echo "Exodus II")
        if [[ $mesh == *-whole ]]; then row "$solver" "$label, whole, PT-Scotch" --set Partition/Method=PT-Scotch
        else row "$solver" "$label, in $([[ $kind == gmsh ]] && echo ranges || echo slabs), PT-Scotch" \
          --set Partition/Method=PT-Scotch --set "Partition/Mesh On Every Rank=false"; fi
        MODEL_ARGS=("${saved[@]}") ;;
      *) echo "MESHES: unknown row '$mesh'" >&2; exit 2 ;;
    esac
  done
done
