#!/usr/bin/env bash
# scripts/sanitize.sh [CTEST ARGS...]
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer: builds
# build-asan/ with -DDEMBRIDGE_SANITIZE=ON (every target, deal.II layers included; deal.II,
# PETSc and Open MPI themselves are not instrumented) and runs ctest there. Any undefined
# behaviour aborts its test (-fno-sanitize-recover=undefined); ASan aborts on the first memory
# error (out of bounds, use after free, double free). Leak checking is off by default: Open MPI's
# dlopen'ed components and Trilinos (linked through deal.II) leave start-up allocations whose
# stacks LeakSanitizer cannot unwind past the uninstrumented libraries (one or two frames, some
# in modules unloaded at exit), so they cannot be told from ours; SANITIZE_LEAKS=1 turns it on
# with scripts/lsan.supp (the DEM layer's tests, without MPI, run clean with it).
# Prints ctest's summary and writes the full log to build-asan/sanitize.log; exits with ctest's
# status. Extra arguments go to ctest (e.g. -R fem). About an hour on two cores, the build most
# of it; test time limits are five times the usual (tests/CMakeLists.txt).
# SANITIZE_JOBS=N: build and test jobs.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$here/build-asan"
jobs=${SANITIZE_JOBS:-$(nproc)}
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# why: the build runs the gtest binaries to list their tests, under the same sanitizers
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export ASAN_OPTIONS=detect_leaks=${SANITIZE_LEAKS:-0}:abort_on_error=1
export LSAN_OPTIONS=suppressions=$here/scripts/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEMBRIDGE_SANITIZE=ON \
    "${launcher[@]}" >/dev/null || exit 2
fi
cmake --build "$build" -j "$jobs" || { echo "sanitize.sh: build failed" >&2; exit 2; }
cd "$build" || exit 2
start=$(date +%s)
ctest -j "$jobs" --output-on-failure "$@" >"$build/sanitize.log" 2>&1
code=$?
echo "sanitize.sh: ctest exit $code in $(( $(date +%s) - start )) s; log $build/sanitize.log"
grep -E "tests passed|tests failed|^\s+[0-9]+ - " "$build/sanitize.log" | tail -40
grep -c "ERROR: AddressSanitizer\|runtime error:\|ERROR: LeakSanitizer" "$build/sanitize.log" |
  sed 's/^/sanitizer reports in the log: /'
exit $code
