#!/usr/bin/env bash
# Whether this build's terrains are a baseline build's to the bit, on cases
# that reach the matcher's different paths: a drawing at 1024^2, a DEM target
# with and without the vertical offset and at another patch size, five
# exemplars, a DEM's own feature tree (on auto and on the CPU backend). For a
# change meant to be faster only: every case must say "same".
# Usage: compare_outputs.sh BASELINE_BUILD [BUILD]   (BUILD defaults to ./build)
# Needs ../shared/data for the five-exemplar and tree cases.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [ $# -lt 1 ] || [ ! -x "$1/bin/tsynth" ]; then
  echo "compare_outputs: give a baseline build directory holding bin/tsynth." >&2
  exit 2
fi
old="$1/bin/tsynth"
new="${2:-$root/build}/bin/tsynth"
if [ ! -x "$new" ]; then
  echo "compare_outputs: $new is not built." >&2
  exit 2
fi
data="$root/Data"
shared="$root/../shared/data"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
status=0

compare() {
  local name=$1
  shift
  if ! "$old" synth "$@" -o "$out/$name.old.tif" --no-progress --no-cache >/dev/null 2>"$out/err"; then
    echo "$name: the baseline failed: $(tail -1 "$out/err")"
    status=1
    return
  fi
  if ! "$new" synth "$@" -o "$out/$name.new.tif" --no-progress --no-cache >/dev/null 2>"$out/err"; then
    echo "$name: this build failed: $(tail -1 "$out/err")"
    status=1
    return
  fi
  if cmp -s "$out/$name.old.tif" "$out/$name.new.tif"; then
    echo "$name: same"
  else
    echo "$name: DIFFERENT"
    status=1
  fi
}

colorado="$data/dems/colorado.png"
montblanc="$data/dems/alps-montblanc.png"
compare y-1024 --exemplar "$colorado" --sketch "$data/sketches/strokes_y_ridges.png" --size 1024x1024
compare montblanc-no-offset-seed3 --exemplar "$colorado" --sketch "$montblanc" --no-vertical-offset --seed 3
compare montblanc-patch48 --exemplar "$colorado" --sketch "$montblanc" --patch 48
if [ -d "$shared/dems" ]; then
  five=()
  for dem in colorado alaska appalachians himalaya-everest andes-chile; do
    five+=(--exemplar "$shared/dems/$dem.png")
  done
  compare five-768 "${five[@]}" --sketch "$shared/sketches/strokes_valley_meander.png" --size 768x768
  if "$new" features "$shared/dems/mount_jackson_n39_w107_3arc.tif" --both -o "$out/tree.vtp" \
    >/dev/null 2>&1; then
    compare tree --exemplar "$colorado" --sketch "$out/tree.vtp"
    compare tree-cpu-seed7 --exemplar "$colorado" --sketch "$out/tree.vtp" --backend cpu --seed 7
  else
    echo "tree: tsynth features failed"
    status=1
  fi
else
  echo "(no ../shared/data: the five-exemplar and tree cases are left out)"
fi
exit "$status"
