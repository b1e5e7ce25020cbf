#!/usr/bin/env bash
# The full test suite: installs what is missing, builds, runs every test with CTest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
cd "${TSYNTH_BUILD_DIR:-$root/build}"
ctest -j "$(nproc)" --output-on-failure --timeout 600
