"""The synthesis given the Candidate Builder's pool (stages.pvsm) against the synthesis alone.

Run with pvpython (the plugin is loaded from the build):
    pvpython Testing/Benchmarks/bench_stage_chain.py [build dir] [--runs N] [--size N] [--no-cache]
Both Terrain Synthesis filters run on Data/dems/colorado.png and strokes_y_ridges.png with the
CPU backend, alternately, each re-run by a change of Seed (so nothing is cached between runs
but the exemplar cache both share); the builder runs once, upstream, as in a pipeline where only
the synthesis' properties change. The medians and their ratio are printed; the terrains of the
two are compared at every run (they must be the same). Timings are reported, never asserted.
"""
import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
parser.add_argument("--runs", type=int, default=4, help="runs of each (default 4)")
parser.add_argument("--size", type=int, default=512, help="output cells a side (default 512)")
parser.add_argument("--no-cache", action="store_true",
                    help="both syntheses without the exemplar cache: each prepares the exemplars; "
                         "given a pool, it builds none of its own")
options = parser.parse_args()

sys.path.insert(0, os.path.join(options.build, "lib", "python3.11", "site-packages"))
from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

simple.LoadPlugin(os.path.join(options.build, "lib", "paraview-plugins", "TerrainSynthesis",
                               "TerrainSynthesis.so"), remote=False)
dem = simple.TerrainReader(FileName=os.path.join(ROOT, "Data", "dems", "colorado.png"))
sketch = simple.PNGSeriesReader(FileNames=[os.path.join(ROOT, "Data", "sketches", "strokes_y_ridges.png")])
builder = simple.TerrainCandidateBuilder(Input=[dem])
t0 = time.perf_counter()
builder.UpdatePipeline()
build_s = time.perf_counter() - t0
common = dict(Exemplars=[dem], Sketch=sketch, Backend=2, OutputSize=[options.size, options.size],
              UseExemplarCache=0 if options.no_cache else 1)
alone = simple.TerrainSynthesis(**common)
chained = simple.TerrainSynthesis(CandidatePool=builder, **common)


def run(synth, seed):
    synth.Seed = seed
    start = time.perf_counter()
    synth.UpdatePipeline()
    seconds = time.perf_counter() - start
    return seconds, vtk_to_numpy(sm.Fetch(synth).GetPointData().GetArray("Elevation")).copy()


run(alone, 0)  # fills the exemplar cache, untimed
times = {"alone": [], "chained": []}
for seed in range(1, options.runs + 1):
    a, za = run(alone, seed)
    b, zb = run(chained, seed)
    if not (za == zb).all():
        sys.exit("seed %d: the chained synthesis made other heights" % seed)
    times["alone"].append(a)
    times["chained"].append(b)
ma, mb = statistics.median(times["alone"]), statistics.median(times["chained"])
print("pool built once upstream in %.2f s" % build_s)
print("synthesis %d^2%s, median of %d: alone %.3f s, with the builder's pool %.3f s; chained/alone %.3f"
      % (options.size, " without the exemplar cache" if options.no_cache else "", options.runs, ma, mb,
         mb / ma))
print("terrains identical at every seed")
