"""How long an edit waits for the background refinement it stops (Preview First).

Run with pvpython (the plugin is loaded from the build):
    pvpython Testing/Benchmarks/bench_refinement_stop.py [build dir] [--size N]
A ridge drawn as a Terrain Sketch Lines poly-line over Colorado is edited, then edited again after
a growing pause (0.05 to 2 s), so that the second edit meets the first one's whole synthesis at
every stage (set-up, target, matcher, features, fill). For each pause, the wait for the stop is
the second update's time minus that of a preview with nothing to stop, measured in the same run. Timings are reported, never asserted.
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
options = parser.parse_args()

sys.path.insert(0, os.path.join(options.build, "lib", "python3.11", "site-packages"))
from paraview import simple  # noqa: E402

simple.LoadPlugin(os.path.join(options.build, "lib", "paraview-plugins", "TerrainSynthesis",
                               "TerrainSynthesis.so"), remote=False)
import terrainsynthesis  # noqa: E402,F401

PAUSES_S = (0.05, 0.2, 0.4, 0.6, 0.8, 1.0, 1.3, 1.6, 2.0)
exemplar = simple.TerrainReader(FileName=os.path.join(ROOT, "Data", "dems", "colorado.png"))
line = simple.PolyLineSource(Points=[15000, 29000, 0, 22000, 30000, 0, 29000, 29000, 0,
                                     36000, 30000, 0, 43000, 29000, 0])
ridge = simple.TerrainSketchLines(Input=line, FeatureType="Ridge")
live = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=ridge,
                               OutputSize=[options.size, options.size], PreviewFirst=1)
synthesis = live.GetClientSideObject()
edits = 0


def edit():
    """Moves the middle point and updates; returns the update's seconds."""
    global edits
    edits += 1
    points = list(line.Points)
    points[7] = 30000 + 300 * edits
    line.Points = points
    start = time.monotonic()
    live.UpdatePipeline()
    return time.monotonic() - start


edit()  # fills the exemplar cache at both levels, untimed
synthesis.WaitForRefinement()
alone = []
for _ in range(3):  # a preview with nothing to stop
    synthesis.WaitForRefinement()
    alone.append(edit())
baseline = statistics.median(alone)
print("%d x %d cells from Colorado: a preview with nothing to stop takes %.3f s (median of 3)"
      % (options.size, options.size, baseline))
waits = []
for pause in PAUSES_S:
    synthesis.WaitForRefinement()
    edit()
    time.sleep(pause)
    waits.append(max(0.0, edit() - baseline))
    print("  edit %.2f s into the refinement: waited %.3f s for it to stop" % (pause, waits[-1]))
print("  longest wait %.3f s; median %.3f s" % (max(waits), statistics.median(waits)))
