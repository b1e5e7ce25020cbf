#!/bin/bash
# Makes the distance-synthesis examples (tsynth distance, Rusnell 2009) and their
# pictures. Usage: bash render.sh [BUILD_DIR]   (default ../../build)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../../build}/bin/tsynth"
out="${OUT:-$here}"   # the pictures
tmp="$(mktemp -d)"      # the terrains (large: not kept in the repository)
trap 'rm -rf "$tmp"' EXIT
cd "$here"
/usr/bin/python3 make_inputs.py
run() { # name, then tsynth distance options
  local name="$1"
  shift
  "$bin" distance --no-progress -o "$tmp/$name.tif" "$@"
  "$bin" render "$tmp/$name.tif" -o "$out/$name-3d.png" --3d --size 800x500
  # A 256-colour palette keeps each picture small enough for the repository.
  /usr/bin/python3 -c "from PIL import Image; import sys; \
Image.open(sys.argv[1]).convert('RGB').quantize(256).save(sys.argv[1], optimize=True)" "$out/$name-3d.png"
}
# A range: two crest profiles by stroke colour, 60 dendritic ridges off the strokes.
run mountain_range --generators mountain_range_strokes.png --profiles mountain_profiles.csv --ridges 60
# Crater rings (rim profile 1 outside, bowl profile 2 inside, exclusive) and hills.
run crater_field --generators crater_field_strokes.png --profiles crater_profiles.csv --region-profile 2
# The same three ridges with a V profile blended sharply (b = 15) and a U profile (b = 3).
run valley_v --generators valley_pair_strokes.png --profiles valley_v_profile.csv --b 15
run valley_u --generators valley_pair_strokes.png --profiles valley_u_profile.csv --b 3
