#!/usr/bin/env bash
# The main job on bundled data: installs what is missing, builds, and synthesises a terrain from a
# bundled exemplar DEM and stroke sketch, then renders it as a shaded map and a 3D view into ./out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
tsynth="${TSYNTH_BUILD_DIR:-$root/build}/bin/tsynth"
mkdir -p "$root/out"
"$tsynth" synth --exemplar "$root/Data/dems/colorado.png" \
  --sketch "$root/Data/sketches/strokes_y_ridges.png" \
  -o "$root/out/terrain.tif" --report "$root/out/report.json"
"$tsynth" render "$root/out/terrain.tif" -o "$root/out/terrain.png"
"$tsynth" render "$root/out/terrain.tif" --3d -o "$root/out/terrain-3d.png"
echo "Terrain: $root/out/terrain.tif; pictures: $root/out/terrain.png (map), $root/out/terrain-3d.png (3D view);"
echo "figures: $root/out/report.json"
