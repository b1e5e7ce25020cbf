#!/usr/bin/env bash
# Builds TerrainSynthesis the way a ParaView build with PARAVIEW_EXTERNAL_PLUGIN_DIRS does
# (Testing/ExternalPlugin), then checks the plugin it makes in pvpython against the
# project's own build.
#   build_external_plugin.sh SOURCE_DIR SCRATCH_DIR PVPYTHON TSYNTH DEM
set -euo pipefail
source="$1"; scratch="$2"; pvpython="$3"; tsynth="$4"; dem="$5"
rm -rf "$scratch"
# paraview_plugin_build gives the plugin the binary folder <host build>/<path from the host's
# source to the plugin>, here <host build>/../.., so the host builds two levels down.
host="$scratch/host/build"
mkdir -p "$host"
cmake -S "$source/Testing/ExternalPlugin" -B "$host" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPARAVIEW_EXTERNAL_PLUGIN_DIRS="$source" > "$scratch/configure.log" 2>&1 ||
  { cat "$scratch/configure.log"; exit 1; }
grep -q "built as an external plugin of this ParaView" "$scratch/configure.log" ||
  { echo "the plugin was not configured through its external-plugin entry"; exit 1; }
cmake --build "$host" > "$scratch/build.log" 2>&1 || { tail -40 "$scratch/build.log"; exit 1; }
plugin="$host/lib/paraview-plugins/TerrainSynthesis/TerrainSynthesis.so"
test -f "$plugin" || { echo "no plugin at $plugin"; exit 1; }
"$tsynth" pits "$dem" -o "$scratch/reference.tif" > /dev/null
"$pvpython" "$(dirname "$0")/Python/check_external_plugin.py" "$plugin" "$dem" "$scratch/reference.tif"
