#!/usr/bin/env bash
# Fuzzes one target with libFuzzer (clang, ASan, UBSan) and merges what it
# found into Testing/Fuzz/corpus/TARGET/. See Testing/Fuzz/README.md.
#   scripts/fuzz.sh TARGET [SECONDS]     TARGET: heightfield_reader sidecar sketch polylines ppa
#                                        SECONDS 0: only pick the corpus again
# The build lives in ./build-fuzz (TSYNTH_FUZZ_BUILD_DIR moves it); new inputs and
# crashes go to BUILD/fuzz-work/TARGET and BUILD/fuzz-artifacts/TARGET.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TSYNTH_FUZZ_BUILD_DIR:-$root/build-fuzz}"
target="${1:?usage: scripts/fuzz.sh TARGET [SECONDS]}"
seconds="${2:-600}"
corpus="$root/Testing/Fuzz/corpus/$target"
[ -d "$corpus" ] || { echo "fuzz.sh: no corpus folder $corpus (unknown target?)" >&2; exit 2; }
if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DTSYNTH_FUZZ=ON \
    -DPython3_EXECUTABLE=/usr/bin/python3
fi
cmake --build "$build" --target "tsynth_fuzz_$target"
fuzzer="$build/bin/tsynth_fuzz_$target"
work="$build/fuzz-work/$target"
artifacts="$build/fuzz-artifacts/$target"
mkdir -p "$work" "$artifacts"
# One core: OpenMP loops in the kernels run on one thread.
export OMP_NUM_THREADS=1
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
# Leaks of other projects' libraries, listed with what leaks.
export LSAN_OPTIONS="suppressions=$root/Testing/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
dict=()
[ -f "$root/Testing/Fuzz/$target.dict" ] && dict=(-dict="$root/Testing/Fuzz/$target.dict")
status=0
if [ "$seconds" -gt 0 ]; then
  "$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    "${dict[@]}" -artifact_prefix="$artifacts/" "$work" "$corpus" || status=$?
fi
# The full corpus (the inputs with new coverage edges, -merge=1) stays in
# $work for the next run; the committed one is a regression suite of at most
# $committed of them, picked greedily by coverage (pick_corpus.py), and every
# regression-* file (an input that once crashed).
committed=48
merged="$(mktemp -d)"
control="$merged.control"
mkdir "$merged/all" "$merged/picked"
"$fuzzer" -merge=1 -use_counters=0 -merge_control_file="$control" -rss_limit_mb=2048 \
  -artifact_prefix="$artifacts/merge-" \
  -timeout=10 "$merged/all" "$corpus" "$work" > /dev/null 2>&1 || true
if [ -n "$(ls -A "$merged/all")" ]; then
  /usr/bin/python3 "$root/Testing/Fuzz/pick_corpus.py" "$control" "$merged/picked" "$committed"
  find "$corpus" -maxdepth 1 -type f -name 'regression-*' -exec cp {} "$merged/picked/" \;
  find "$corpus" "$work" -maxdepth 1 -type f -delete
  cp "$merged/picked"/* "$corpus/"
  cp "$merged/all"/* "$work/"
else
  echo "fuzz.sh: the merge failed; the corpus is left as it was" >&2
fi
rm -rf "$merged" "$control"
echo "fuzz.sh: $target corpus: $(ls "$corpus" | wc -l) files, $(cat "$corpus"/* | wc -c) bytes"
exit "$status"
