"""ParaView on 2 MPI ranks: how long File > Save Data takes after the view has shown the terrain.

Run with python3 (it starts the server and a pvpython client itself):
    python3 Testing/Benchmarks/bench_pvserver_save.py [build dir] [--size N] [--ranks N]
`mpiexec -np N pvserver` is started on a free port; a pvpython client, as the GUI would, updates
a tiled Terrain Synthesis (the view asks each rank for its piece) and then saves it as a GDAL
mosaic with the Terrain tiles writer (which asks for its tile rows: another extent). The filter
keeps its whole outputs while a rank holds a piece, so the save cuts the rows from them rather than
synthesising again. Printed: both times, their ratio (same run: the figure that counts on a shared
machine) and how many syntheses each rank ran. Timings are reported, never asserted.
"""
import argparse
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
parser.add_argument("--size", type=int, default=768, help="output cells a side (default 768)")
parser.add_argument("--ranks", type=int, default=2, help="server ranks (default 2)")
options = parser.parse_args()

CLIENT = """
import time
from paraview import simple
simple.Connect("localhost", %(port)d)
simple.LoadPlugin(%(plugin)r, remote=True)
exemplar = simple.TerrainReader(FileName=%(exemplar)r)
sketch = simple.TerrainSketchReader(FileName=%(sketch)r, ExemplarFileName=%(exemplar)r)
synthesis = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[%(size)d, %(size)d],
                                    Seed=3, TileSize=256, Backend="CPU")
start = time.monotonic()
synthesis.UpdatePipeline()
shown = time.monotonic()
simple.SaveData(%(out)r, proxy=synthesis, TileSize=257)
saved = time.monotonic()
print("view update %%.2f s, Save Data %%.2f s, ratio %%.3f" %% (shown - start, saved - shown,
      (saved - shown) / (shown - start)), flush=True)
"""

plugin = os.path.join(options.build, "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so")
if not os.path.isfile(plugin):
    sys.exit("bench_pvserver_save.py: no plugin at %s: build first (scripts/build.sh)" % plugin)
# pvpython may run as an MPI singleton: its Open MPI variables would make the ranks join it.
env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
with socket.socket() as probe:
    probe.bind(("localhost", 0))
    port = probe.getsockname()[1]
folder = tempfile.mkdtemp(prefix="tsynth-bench-save-")
server = subprocess.Popen([shutil.which("mpiexec"), "--allow-run-as-root", "--oversubscribe", "-np",
                           str(options.ranks), shutil.which("pvserver"), "--server-port=%d" % port],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
try:
    for line in server.stdout:
        if "Accepting connection" in line:
            break
    client = os.path.join(folder, "client.py")
    with open(client, "w") as f:
        f.write(CLIENT % dict(port=port, plugin=plugin, size=options.size,
                              exemplar=os.path.join(ROOT, "Data", "dems", "colorado.png"),
                              sketch=os.path.join(ROOT, "Data", "sketches", "strokes_y_ridges.png"),
                              out=os.path.join(folder, "terrain.vrt")))
    run = subprocess.run([shutil.which("pvpython"), client], capture_output=True, text=True, env=env)
    if run.returncode != 0:
        sys.exit(run.stdout + run.stderr)
finally:
    server.terminate()
    served = server.communicate(timeout=60)[0]
    shutil.rmtree(folder, ignore_errors=True)
print("%d x %d in tiles of 256 on %d ranks: %s" % (options.size, options.size, options.ranks,
                                                   run.stdout.strip()))
print("syntheses per rank: %d (1: the save was cut from the view's synthesis)"
      % len(re.findall(r"rank 0 of %d: \d+ feature" % options.ranks, served)))
