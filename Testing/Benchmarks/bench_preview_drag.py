"""Drawing in ParaView with Preview First: how long each edit of a sketch line takes to show.

Run with pvpython (the plugin is loaded from the build):
    pvpython Testing/Benchmarks/bench_preview_drag.py [build dir] [--size N] [--edits N]
A ridge drawn as a Terrain Sketch Lines poly-line over Colorado is moved, one point at a time,
every second (so each edit meets the whole synthesis of the previous one under way and stops it),
and the time UpdatePipeline takes to show the preview is recorded. The same filter with Preview
First off then makes the whole terrain once: the ratio of the two, taken in the same run, is the
figure that counts on a shared machine. Timings are reported, never asserted.
"""
import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
parser.add_argument("--size", type=int, default=1024, help="output cells a side (default 1024)")
parser.add_argument("--edits", type=int, default=8, help="edits timed (default 8)")
options = parser.parse_args()

sys.path.insert(0, os.path.join(options.build, "lib", "python3.11", "site-packages"))
from paraview import simple  # noqa: E402

simple.LoadPlugin(os.path.join(options.build, "lib", "paraview-plugins", "TerrainSynthesis",
                               "TerrainSynthesis.so"), remote=False)
import terrainsynthesis  # noqa: E402,F401

PAUSE_S = 1.0  # between edits: the refinement is well under way when the next edit comes
exemplar = simple.TerrainReader(FileName=os.path.join(ROOT, "Data", "dems", "colorado.png"))
line = simple.PolyLineSource(Points=[15000, 29000, 0, 22000, 30000, 0, 29000, 29000, 0,
                                     36000, 30000, 0, 43000, 29000, 0])
ridge = simple.TerrainSketchLines(Input=line, FeatureType="Ridge")
live = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=ridge,
                               OutputSize=[options.size, options.size], PreviewFirst=1)
synthesis = live.GetClientSideObject()
live.UpdatePipeline()  # fills the exemplar cache at both levels, untimed
synthesis.WaitForRefinement()
shown = []
for k in range(options.edits):
    points = list(line.Points)
    points[7] = 30000 + 600 * (k + 1)  # the middle point's y, metres
    line.Points = points
    start = time.monotonic()
    live.UpdatePipeline()
    shown.append(time.monotonic() - start)
    assert synthesis.GetOutputLevel() == "preview"
    time.sleep(PAUSE_S)
synthesis.WaitForRefinement()
live.PreviewFirst = 0
start = time.monotonic()
live.UpdatePipeline()
whole = time.monotonic() - start
print("%d x %d cells from Colorado, one sketched ridge, %d edits:" % (options.size, options.size,
                                                                     options.edits))
print("  preview shown after an edit: median %.3f s (each: %s)"
      % (statistics.median(shown), ", ".join("%.2f" % s for s in shown)))
print("  whole synthesis: %.2f s; preview / whole %.3f" % (whole, statistics.median(shown) / whole))
