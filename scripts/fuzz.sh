#!/usr/bin/env bash
# Fuzzes one target with libFuzzer (clang, ASan, UBSan) and merges what it
# found into Testing/Fuzz/corpus/TARGET/. See Testing/Fuzz/README.md.
#   scripts/fuzz.sh TARGET [SECONDS]     TARGET: heightfield_reader sidecar sketch polylines ppa
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
dict=()
[ -f "$root/Testing/Fuzz/$target.dict" ] && dict=(-dict="$root/Testing/Fuzz/$target.dict")
status=0
"$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
  "${dict[@]}" -artifact_prefix="$artifacts/" "$work" "$corpus" || status=$?
# The smallest set of inputs with the same coverage; regression-* files (inputs
# that once crashed) always stay.
merged="$(mktemp -d)"
"$fuzzer" -merge=1 -rss_limit_mb=2048 -timeout=10 "$merged" "$corpus" "$work" > /dev/null 2>&1 || true
if [ -n "$(ls -A "$merged")" ]; then
  find "$corpus" -maxdepth 1 -type f -name 'regression-*' -exec cp {} "$merged/" \;
  find "$corpus" -maxdepth 1 -type f -delete
  cp "$merged"/* "$corpus/"
else
  echo "fuzz.sh: the merge failed; the corpus is left as it was" >&2
fi
rm -rf "$merged"
echo "fuzz.sh: $target corpus: $(ls "$corpus" | wc -l) files, $(du -sk "$corpus" | cut -f1) KB"
exit "$status"
