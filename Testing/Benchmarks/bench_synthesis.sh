#!/usr/bin/env bash
# End-to-end synthesis speed with the per-stage split from --report, on OpenCL
# and on the CPU in the same run (the outputs must be identical).
#   default: a 1024 x 1024 terrain from one 648 x 648 exemplar (target: under 20 s
#            on this 2-core machine);
#   --large: 4096 x 4096 from five 648 x 648 exemplars (target: under 5 minutes,
#            peak memory under 3 GB), OpenCL only unless --both is given.
# Usage: bench_synthesis.sh [--large [--both]] [build dir]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
large=0
both=0
while [[ $# -gt 0 && "$1" == --* ]]; do
  case "$1" in
    --large) large=1 ;;
    --both) both=1 ;;
    *) echo "bench_synthesis.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
build="${1:-$root/build}"
shared="$root/../shared/data"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

if [[ $large -eq 1 ]]; then
  if [[ ! -d "$shared/dems" ]]; then
    echo "bench_synthesis.sh: --large needs ../shared/data beside the checkout" >&2
    exit 2
  fi
  args=()
  for dem in colorado alaska appalachians himalaya-everest andes-chile; do
    args+=(--exemplar "$shared/dems/$dem.png")
  done
  args+=(--sketch "$shared/sketches/strokes_valley_meander.png" --size 4096x4096)
  backends=(opencl)
  [[ $both -eq 1 ]] && backends=(opencl cpu)
  label="4096x4096 from five exemplars"
  tasse_gpu=0
else
  args=(--exemplar "$root/Data/dems/colorado.png" --sketch "$root/Data/sketches/strokes_y_ridges.png"
    --size 1024x1024)
  backends=(opencl cpu)
  label="1024x1024 from one exemplar"
  tasse_gpu=43
fi

echo "$label"
for backend in "${backends[@]}"; do
  start=$(date +%s.%N)
  /usr/bin/time -f "%M" -o "$tmp/rss-$backend" "$build/bin/tsynth" synth "${args[@]}" \
    --backend "$backend" -o "$tmp/out-$backend.tif" --report "$tmp/report-$backend.json" \
    --no-progress > /dev/null
  end=$(date +%s.%N)
  python3 - "$tmp/report-$backend.json" "$start" "$end" "$backend" "$(cat "$tmp/rss-$backend")" \
    "$tasse_gpu" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
wall = float(sys.argv[3]) - float(sys.argv[2])
t = r["times_s"]
fill = t["fill"]
fills = r["placements"] - r.get("feature_placements", 0)
print(f"{sys.argv[4]:>6}: {wall:6.1f} s end to end (read+prepare {t['prepare']:.2f}, matcher setup "
      f"{t['setup']:.2f}, features {t['features']:.2f}, fill {fill:.2f}); {r['placements']} patches, "
      f"{1e3 * fill / max(1, fills):.1f} ms per fill patch; peak memory "
      f"{int(sys.argv[5]) / 1048576:.2f} GB")
tasse = float(sys.argv[6])
if tasse > 0:
    print(f"        vs Tasse's GPU 43 s: {tasse / wall:.1f}x, his CPU 126 s: {126 / wall:.1f}x")
PY
done
if [[ ${#backends[@]} -eq 2 ]]; then
  cmp -s "$tmp/out-opencl.tif" "$tmp/out-cpu.tif" && echo "identical output on both backends" ||
    echo "OUTPUTS DIFFER"
fi
