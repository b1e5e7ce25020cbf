"""The Patch Matcher chained to the Candidate Builder: what a moved Site costs.

Run with pvpython (the plugin is loaded from the build):
    pvpython Testing/Benchmarks/bench_matcher_chain.py [build dir] [--exemplar DEM] [--moves N]
A user steps the matcher's Site over a target. A matcher on its own builds the candidate pool
again at every step; one whose Candidate Pool is the Candidate Builder's table reads it (the
builder runs once, upstream, and is not re-run when only the Site changes). Both are timed in
the same run, step by step, on the CPU backend; the ratio of their medians is the figure that
counts on a shared machine. The matches of the two are compared at every step (they must be the
same). Timings are reported, never asserted.
"""
import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
parser.add_argument("--exemplar", default=os.path.join(ROOT, "Data", "dems", "colorado.png"))
parser.add_argument("--moves", type=int, default=6, help="Site positions timed (default 6)")
options = parser.parse_args()

sys.path.insert(0, os.path.join(options.build, "lib", "python3.11", "site-packages"))
from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

simple.LoadPlugin(os.path.join(options.build, "lib", "paraview-plugins", "TerrainSynthesis",
                               "TerrainSynthesis.so"), remote=False)

reader = simple.TerrainReader(FileName=options.exemplar)
reader.UpdatePipeline()
bounds = reader.GetDataInformation().GetBounds()
builder = simple.TerrainCandidateBuilder(Input=[reader])
start = time.perf_counter()
builder.UpdatePipeline()
build_s = time.perf_counter() - start
rows = builder.GetDataInformation().GetNumberOfRows()
common = dict(Input=reader, Exemplars=[reader], Mode=0, Backend=2)
own = simple.TerrainPatchMatcher(**common)
chained = simple.TerrainPatchMatcher(CandidatePool=builder, **common)


def step(matcher, site):
    matcher.Site = site
    t0 = time.perf_counter()
    matcher.UpdatePipeline()
    seconds = time.perf_counter() - t0
    table = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
    return seconds, vtk_to_numpy(table.GetColumnByName("Cost")).tolist()


own_s, chained_s = [], []
for k in range(options.moves):
    f = (k + 1) / (options.moves + 1)
    site = [bounds[0] + f * (bounds[1] - bounds[0]), bounds[2] + (1 - f) * (bounds[3] - bounds[2])]
    a, costs_a = step(own, site)
    b, costs_b = step(chained, site)
    if costs_a != costs_b:
        sys.exit("the chained matcher matched differently at %s" % site)
    own_s.append(a)
    chained_s.append(b)
print("exemplar %s: %d candidate variants, built once in %.2f s"
      % (os.path.basename(options.exemplar), rows, build_s))
print("matcher per Site, median of %d: own pool %.3f s, chained %.3f s; ratio own/chained %.2f"
      % (options.moves, statistics.median(own_s), statistics.median(chained_s),
         statistics.median(own_s) / statistics.median(chained_s)))
print("matches identical at every Site")
