#!/usr/bin/env bash
# DDContact set-up on Debian 12: installs what is missing (apt), configures
# and builds, then runs the main example or the test suite.
#
#   bash cmake/setup.sh example   # build + the two half-rings on 2 MPI ranks: the paper's
#                                 # method and the conventional monolithic reference
#   bash cmake/setup.sh test      # build + the whole ctest suite
#
# Environment: BUILD_DIR (default: build), JOBS (default: nproc).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-example}
case "$mode" in example|test|build) ;; *) echo "usage: $0 example|test|build" >&2; exit 2;; esac

# --- 1. Debian packages ----------------------------------------------------
packages=(
  build-essential cmake pkg-config
  openmpi-bin libopenmpi-dev
  trilinos-all-dev libptscotch-dev      # Trilinos 13.2 (its CMake config needs PT-Scotch); PT-Scotch partitions in parallel
  libmumps-dev libmetis-dev libeigen3-dev
  libsuitesparse-dev                    # CHOLMOD (FETI-DP local solver)
  libopenblas0-serial libopenblas-dev   # 2.7x faster MUMPS than reference BLAS
  libgtest-dev libgmock-dev                # GoogleTest + GoogleMock matchers
  gnuplot-nox                           # plots in doc/
  doxygen                               # API reference of the public headers (target doc, ctest)
  libexodusii-dev                       # Exodus II results (Output/Exodus)
  python3-vtk9 python3-meshio python3-netcdf4  # tests: independent readers of the Exodus output
  python3-scipy                         # test/benchmark/cluster_iterations.py (a study, not a test)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi

# --- 2. configure and build ------------------------------------------------
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
cmake --build "$BUILD_DIR" -j "$JOBS"

# MPI in containers / CI: allow root, allow more ranks than cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OPENBLAS_NUM_THREADS=1

# --- 3. run ------------------------------------------------------------------
case "$mode" in
  example)
    bash examples/two_half_rings.sh "$BUILD_DIR" ddcontact-out/two_half_rings
    ;;
  test)
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS"
    ;;
esac
