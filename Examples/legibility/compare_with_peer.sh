#!/usr/bin/env bash
# The README's legibility comparison: each sketch of draw_sketches.py and a real DEM used as the
# target, synthesised by tsynth and by Tasse's 2012 code (the peer) with two exemplars, all shown as
# grey hillshades at the same size, with the legibility measure of tsynth evaluate for each.
#
#   bash Examples/legibility/compare_with_peer.sh PEER_WORKDIR OUT_DIR
#
# PEER_WORKDIR is where ../shared/peers/tasse/build.sh built the peer (fetch github:ftasse/
# TerrainSynthesisGPU first); ../shared/data must be beside the checkout. Writes OUT_DIR/NAME.png
# (sketch | ours and the peer's per exemplar) and OUT_DIR/legibility.md. About 15 minutes on two
# cores, most of it the peer's (one thread).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
peer="${1:?usage: compare_with_peer.sh PEER_WORKDIR OUT_DIR}"
out="${2:?usage: compare_with_peer.sh PEER_WORKDIR OUT_DIR}"
tsynth="${TSYNTH:-$root/build/bin/tsynth}"
# Debian's python3, which has GDAL's and numpy's bindings (a pyenv or venv python3 may not).
py=/usr/bin/python3
[ -x "$py" ] || py=python3
shared="$root/../shared"
exemplars=(himalaya-everest colorado)
mkdir -p "$out/runs"
"$py" "$root/Examples/legibility/draw_sketches.py" "$out/sketches" > /dev/null
# The DEM target: Norway's fjords, a valley network cut into rugged land.
"$tsynth" convert "$shared/data/dems/norway.png" -o "$out/sketches/dem_norway.tif" > /dev/null

shade() { "$tsynth" render "$1" --grey --azimuth 315 -o "$2" > /dev/null; }
legible() { # terrain exemplar sketch -> "share (ridges, valleys); flanks; weakest stroke" or, for a DEM target, band-pass correlations
  "$tsynth" evaluate "$1" --exemplar "$2" --sketch "$3" --json 2> /dev/null | "$py" -c '
import json, sys
t = json.load(sys.stdin)["terrain"]
if "target_correlation" in t:
    print("correlation " + " ".join("%.2f" % c["correlation"] for c in t["target_correlation"]))
else:
    l = t["legibility"]
    f = lambda v: "-" if v is None else "%.2f" % v
    print("%s (ridges %s, valleys %s); flanks %s; weakest %s" % (
        f(l["legible_share"]), f(l["ridge"]["legible_share"]), f(l["valley"]["legible_share"]),
        f(l["flank_agreement"]), f(l["weakest_stroke_share"])))'
}

{
  echo "| sketch | exemplar | ours: legible share; flank agreement; weakest stroke | peer: the same | ours, peer: time (s) |"
  echo "|---|---|---|---|---|"
} > "$out/legibility.md"
for sketch in "$out"/sketches/*; do
  name="$(basename "${sketch%.*}")"
  tiles=("$sketch")
  if [[ "$sketch" == *.tif ]]; then # a DEM target is shown as the others are
    shade "$sketch" "$out/runs/$name.target.png"
    tiles=("$out/runs/$name.target.png")
  fi
  for ex in "${exemplars[@]}"; do
    dem="$shared/data/dems/$ex.png"
    run="$out/runs/${name}__$ex"
    start=$(date +%s.%N)
    "$tsynth" synth --exemplar "$dem" --sketch "$sketch" -o "$run.ours.tif" --no-progress > "$run.ours.log" 2>&1
    mid=$(date +%s.%N)
    bash "$shared/peers/tasse/run.sh" "$peer" "$dem" "$sketch" "$run.peer.tif" > "$run.peer.log" 2>&1
    end=$(date +%s.%N)
    shade "$run.ours.tif" "$run.ours.png"
    shade "$run.peer.tif" "$run.peer.png"
    tiles+=("$run.ours.png" "$run.peer.png")
    printf '| %s | %s | %s | %s | %.1f, %.1f |\n' "$name" "$ex" "$(legible "$run.ours.tif" "$dem" "$sketch")" \
      "$(legible "$run.peer.tif" "$dem" "$sketch")" "$(echo "$mid - $start" | bc)" "$(echo "$end - $mid" | bc)" \
      >> "$out/legibility.md"
  done
  "$py" "$root/Examples/legibility/compose.py" "$out/$name.png" "${tiles[@]}"
  echo "wrote $out/$name.png"
done
cat "$out/legibility.md"
