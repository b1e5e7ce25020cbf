#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, builds Examples/cxx against it with
# find_package(TerrainSynthesis), and runs the program on a bundled DEM.
#   install_and_build_example.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR DEM
set -euo pipefail
build="$1"; source="$2"; scratch="$3"; dem="$4"
rm -rf "$scratch"
mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
cmake -S "$source/Examples/cxx" -B "$scratch/example" -G Ninja \
  -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_BUILD_TYPE=Release > "$scratch/configure.log"
cmake --build "$scratch/example" > "$scratch/build.log"
"$scratch/example/drain_dem" "$dem" "$scratch/drained.tif"
test -s "$scratch/drained.tif"
