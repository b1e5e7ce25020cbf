#!/usr/bin/env bash
# Configures (once) and builds TerrainSynthesis in ./build with Ninja.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TSYNTH_BUILD_DIR:-$root/build}"
if [ ! -f "$build/build.ninja" ]; then
  # Debian's python3 is the one ParaView was built with (not a pyenv or venv one).
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3
fi
cmake --build "$build" -j "$(nproc)"
