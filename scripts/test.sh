#!/usr/bin/env bash
# The full test suite: installs what is missing, builds, runs every test with CTest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
cd "${TSYNTH_BUILD_DIR:-$root/build}"
# One virtual X server for the tests that render (3D views, pvpython examples), started once:
# an xvfb-run per test races for display numbers and fails now and then under load. -noreset
# keeps the server up when its last client leaves: a server resetting between two tests refuses
# the next one's connection ("bad X server connection").
if [ -z "${DISPLAY:-}" ]; then
  for n in $(seq 90 140); do
    if [ ! -e "/tmp/.X$n-lock" ] && [ ! -e "/tmp/.X11-unix/X$n" ]; then display=":$n"; break; fi
  done
  Xvfb "$display" -screen 0 1920x1200x24 -nolisten tcp -noreset > /dev/null 2>&1 &
  xvfb=$!
  trap 'kill "$xvfb" 2> /dev/null || true' EXIT
  for _ in $(seq 100); do [ -e "/tmp/.X11-unix/X${display#:}" ] && break; sleep 0.1; done
  export DISPLAY="$display"
fi
ctest -j "$(nproc)" --output-on-failure --timeout 900
