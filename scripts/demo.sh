#!/usr/bin/env bash
# The main job on bundled data: installs what is missing, builds, and renders a bundled DEM
# as a hillshade map and a 3D view into ./out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
tsynth="${TSYNTH_BUILD_DIR:-$root/build}/bin/tsynth"
dem="$root/Data/dems/alps-montblanc.png"
mkdir -p "$root/out"
"$tsynth" info "$dem"
"$tsynth" render "$dem" -o "$root/out/alps-montblanc.png"
"$tsynth" render "$dem" --3d -o "$root/out/alps-montblanc-3d.png"
echo "Pictures: $root/out/alps-montblanc.png (map) and $root/out/alps-montblanc-3d.png (3D view)"
