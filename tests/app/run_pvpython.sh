#!/bin/sh
# Runs a ParaView check with pvpython, looked up when the test runs (not when CMake configured
# the build: scripts/setup.sh --test installs ParaView after build/ may have been configured).
# Exit code 77 (ctest: skipped) only if no pvpython is found; otherwise pvpython's own.
# Usage: run_pvpython.sh SCRIPT [ARGS...]
pv=$(command -v pvpython 2>/dev/null)
if [ -z "$pv" ]; then
  for candidate in /usr/bin/pvpython /usr/local/bin/pvpython /opt/paraview/bin/pvpython; do
    if [ -x "$candidate" ]; then
      pv=$candidate
      break
    fi
  done
fi
if [ -z "$pv" ]; then
  echo "pvpython not found (apt-get install python3-paraview): skipped"
  exit 77
fi
echo "pvpython: $pv"
exec "$pv" "$@"
