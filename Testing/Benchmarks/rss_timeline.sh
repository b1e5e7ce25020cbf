#!/usr/bin/env bash
# Resident memory of a command over time, to see which stage sets its peak.
#   bash Testing/Benchmarks/rss_timeline.sh LOG -- tsynth synth ... --report R.json
# Writes "milliseconds kB" every 0.25 s to LOG and prints the peak and when it came; compare the
# time with the report's times_s, or let rss_stages.py REPORT LOG print each stage's peak.
# At 4096^2 from five exemplars in tiles of 1024 the placement held 1.5 GB, the target's set-up
# peaked at 2.6 GB (10 s) and the finishing at 2.7 GB (160 s). Untiled, after the landform target
# and smoothLarge kept fewer planes: set-up 2.16 GB (12 s), placement 1.88 GB, finishing 2.54 GB.
# In tiles of 1024 once smoothLarge kept no plane of weights for fields without nodata: the
# exemplars' preparation and the target 2.24 GB (12 s), placement 1.54 GB, finishing 2.0 GB, the
# figures beside the writing 2.41 GB (the peak, 151 s of 152). Once the target's and the drainage's
# planes were let go as soon as read and freed memory went back between stages (returnFreedMemory):
# set-up 1.71 GB (the peak, 13 s), placement 1.43 GB, finishing 1.56 GB, figures 1.56 GB.
# Once the target kept no plane for a missing kind of line and the pool went with the placement:
# set-up 1.45 GB (the peak, 9 s), placement 1.43 GB, finishing 1.43 GB, figures 1.40 GB.
set -euo pipefail
log=$1
shift
[ "${1:-}" = "--" ] && shift
: > "$log"
"$@" > /dev/null 2>&1 &
pid=$!
start=$(date +%s%N)
while kill -0 "$pid" 2> /dev/null; do
  kb=$(awk '/VmRSS/ {print $2}' "/proc/$pid/status" 2> /dev/null || true)
  [ -n "$kb" ] && echo "$((($(date +%s%N) - start) / 1000000)) $kb" >> "$log"
  sleep 0.25
done
wait "$pid" || { echo "the command failed" >&2; exit 1; }
awk '{ if ($2 > m) { m = $2; t = $1 } } END { printf "peak %.0f MB at %.1f s\n", m / 1024, t / 1000 }' "$log"
