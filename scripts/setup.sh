#!/usr/bin/env bash
# dembridge setup: installs what is missing from Debian's packages, configures and builds in
# Release, then runs the main example (default) or the whole ctest suite (--test).
# Quick when nothing changed: the apt step is skipped when every package is present and the
# build is incremental (ccache is used when installed).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=example
for arg in "$@"; do
  case "$arg" in
    --test) mode=test ;;
    --example) mode=example ;;
    *) echo "setup.sh: unknown argument '$arg' (use --test or --example)" >&2; exit 2 ;;
  esac
done

packages=(build-essential cmake ninja-build ccache pkg-config
  libdeal.ii-dev petsc-dev libeigen3-dev libopenmpi-dev openmpi-bin
  gmsh libgmsh-dev python3-meshio python3-matplotlib python3-numpy
  libgtest-dev nlohmann-json3-dev libcli11-dev
  pybind11-dev python3-dev # the Python module (python/, docs/python.md)
  voro++-dev # the columns' tessellation (app/studies/column_tessellation.cc: S_v, docs/microstructure.md)
  libhdf5-openmpi-dev) # checkpoints (app/checkpoint/checkpoint.cc): the HDF5 deal.II links
# The test suite also checks that ParaView reads the output (pvpython, about 1 GB with its
# libraries): installed with --test only.
[ "$mode" = test ] && packages+=(python3-paraview)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Open MPI refuses to run as root (CI) unless told it may.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none

build="$here/build"
# ccache hits across clones of the repository (CI builds a fresh clone in another folder)
export CCACHE_BASEDIR="$here"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
fi
cmake --build "$build" -j "$(nproc)"

if [ "$mode" = test ]; then
  cd "$build"
  ctest --output-on-failure -j "$(nproc)"
else
  "$build/app/dembridge" run "$here/examples/cantilever.prm" --output-dir "$build/example-output/cantilever"
fi
