#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, builds Examples/cxx against it with
# find_package(TerrainSynthesis), and runs the program on a bundled DEM; then the installed tsynth
# (info, and render --3d through its module).
#   install_and_build_example.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR DEM
set -euo pipefail
build="$1"; source="$2"; scratch="$3"; dem="$4"
rm -rf "$scratch"
mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
cmake -S "$source/Examples/cxx" -B "$scratch/example" -G Ninja \
  -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_BUILD_TYPE=Release > "$scratch/configure.log"
cmake --build "$scratch/example" > "$scratch/build.log"
# The program's exit status counts (set -e), and so do its figures: the bundled Colorado DEM
# has 679 pits, and none may remain.
"$scratch/example/drain_dem" "$dem" "$scratch/drained.tif" | tee "$scratch/run.log"
grep -Eq "^pits before 679, after 0; [0-9]+ cells lowered" "$scratch/run.log" ||
  { echo "unexpected figures from drain_dem"; exit 1; }
test -s "$scratch/drained.tif"
# The installed command line: the launcher finds tsynth-main beside it, which finds its libraries.
"$scratch/prefix/bin/tsynth" info "$dem" > "$scratch/info.log"
grep -q "648 x 648 cells" "$scratch/info.log" || { echo "the installed tsynth did not run"; exit 1; }
# ... and render --3d's module, which the installed tsynth-main loads from the prefix's library folder.
"$scratch/prefix/bin/tsynth" render "$dem" --3d --size 160x120 -o "$scratch/view.png" > "$scratch/render.log"
test -s "$scratch/view.png" || { echo "the installed tsynth did not draw the 3D view"; exit 1; }
