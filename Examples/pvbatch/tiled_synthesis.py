"""A tiled terrain synthesis on ParaView's MPI engine: every rank places its share of the tiles.

    mpiexec -np N pvbatch Examples/pvbatch/tiled_synthesis.py --exemplar DEM [--exemplar DEM ...] \\
        --sketch SKETCH --size WxH --tile-size T -o OUT.vrt|OUT.pvti [--file-tile-size F] [--patch P] [--seed S]

The Terrain Synthesis filter cuts the terrain into tiles of T x T cells (at least two patches) in a
fixed grid and places them in four colour classes; within a class, tile k goes to rank k mod N, and
after each class the ranks share what they placed (Kernels/Synthesis/Tiling.h). Every rank then
finishes the whole terrain and writes its own share of it:
- OUT.vrt: GeoTIFF tiles OUT_x<column>_y<row>.tif of F x F samples (--file-tile-size, default 1025)
  that share their edge rows and columns, each rank those of its share of the tile rows, with a
  NAME.json sidecar each, under a GDAL virtual mosaic that rank 0 writes (the Terrain Tile Writer;
  QGIS and gdal_translate read it);
- OUT.pvti: ParaView's parallel image format, one piece per rank in OUT/OUT_<rank>.vti.
The heights are those of `tsynth synth --tile-size T` with the same inputs, bit for bit, for any N
(Testing/Python/test_mpi.py checks N = 1, 2 and 3). Each rank prints how far it is ("rank 1 of 2:
fill, 60%") and, at the end, how long it placed tiles and waited for the others. Ctrl-C on mpiexec
stops every rank.

The sketch is read by its kind: poly-lines (.vtp), a DEM as target (.tif, .hgt, .asc, .vti, or a
.png with a NAME.json sidecar), else a stroke or grey sketch map (.png, .jpg). The plugin is looked
up in ./build (override with TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so). Under `mpiexec` as root,
Open MPI wants --allow-run-as-root (and --oversubscribe for more ranks than cores).
"""
import argparse
import glob
import os
import re
import shutil
import tempfile
import time

from paraview import servermanager as sm
from paraview import simple

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PLUGIN = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(ROOT, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
DEM_EXTENSIONS = (".tif", ".tiff", ".hgt", ".asc", ".vti")


def arguments():
    p = argparse.ArgumentParser(description="Tiled terrain synthesis on ParaView's MPI engine.")
    p.add_argument("--exemplar", action="append", required=True, help="a DEM to copy terrain from (repeat)")
    p.add_argument("--sketch", required=True, help="stroke or grey map, poly-lines (.vtp) or a DEM")
    p.add_argument("--size", required=True, help="output size in cells, WxH")
    p.add_argument("--tile-size", type=int, required=True, help="tile side in cells (at least two patches)")
    p.add_argument("--patch", type=int, default=80, help="patch size in cells (default 80)")
    p.add_argument("--seed", type=int, default=0, help="the seed (default 0)")
    p.add_argument("-o", "--output", required=True,
                   help="OUT.vrt (GeoTIFF tiles under a GDAL mosaic) or OUT.pvti (ParaView's parallel image)")
    p.add_argument("--file-tile-size", type=int, default=1025,
                   help="samples a side of OUT.vrt's GeoTIFF tiles, which share their edges (default 1025)")
    a = p.parse_args()
    try:
        width, height = (int(v) for v in a.size.lower().split("x"))
    except ValueError:
        p.error("--size expects WxH in cells, such as 2048x2048, not %s" % a.size)
    if not a.output.lower().endswith((".pvti", ".vrt")):
        p.error("the output is a GDAL mosaic of GeoTIFF tiles or ParaView's parallel image format: "
                "-o OUT.vrt or -o OUT.pvti, not %s" % a.output)
    if a.file_tile_size < 2:
        p.error("--file-tile-size must be at least 2 samples, not %d" % a.file_tile_size)
    for path in a.exemplar + [a.sketch]:
        if not os.path.isfile(path):
            p.error("%s does not exist" % path)
    a.width, a.height = width, height
    return a


def sketch_reader(path, exemplar):
    ext = os.path.splitext(path)[1].lower()
    if ext == ".vtp":
        return simple.XMLPolyDataReader(FileName=[path])
    if ext in DEM_EXTENSIONS or os.path.isfile(os.path.splitext(path)[0] + ".json"):
        return simple.TerrainReader(FileName=path)
    # The sketch's pixels laid on the exemplar's cells, as tsynth synth does.
    return simple.TerrainSketchReader(FileName=path, ExemplarFileName=exemplar)


def sweep_stopped_runs(folder, stem):
    """Removes the temporary folders of earlier runs to this output that were stopped (Ctrl-C on
    mpiexec ends every rank at once, before it can clean up): each is named after the process that
    made it, and one whose process is gone is left over."""
    for path in glob.glob(os.path.join(folder, ".%s.tmp-*" % glob.escape(stem))):
        made_by = re.match(r"\.tmp-(\d+)-", os.path.basename(path)[len(stem) + 1:])
        if made_by is None or not os.path.isdir(path):
            continue
        if not running(int(made_by.group(1))):
            shutil.rmtree(path, ignore_errors=True)


def running(pid):
    """Whether process `pid` lives: a zombie does not (in a container whose first process reaps no
    orphans, a rank ended by Ctrl-C stays one, and os.kill(pid, 0) still finds it)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        pass  # gone, or no /proc here
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # another user's live run
    return True


def write_pieces(synthesis, path, ranks):
    """OUT.pvti and one piece per rank in OUT/, by ParaView's parallel image writer."""
    simple.SaveData(path, proxy=synthesis, ChooseArraysToWrite=1, PointDataArrays=["Elevation"])
    # Gathered from every rank after its write: no rank is still writing its piece.
    synthesis.GetDataInformation().GetNumberOfPoints()
    return "%d piece%s" % (ranks, "" if ranks == 1 else "s")


def write_mosaic(synthesis, path, tile):
    """OUT.vrt over GeoTIFF tiles, each rank writing its share of the tile rows (Terrain Tile Writer).
    Its tiles are published only when every rank's are written; a failure on any rank is an error."""
    # Made directly, not by simple.SaveData or CreateWriter: those first ask the synthesis for its
    # data information, which would run it once for ParaView's pieces before the writer asks for
    # its tile rows (a second synthesis).
    writer = sm.writers.TerrainTileWriter(Input=synthesis, FileName=path, TileSize=tile)
    writer.UpdatePipeline()  # returns when every rank has written its tiles, or failed
    tiles = [n for n in os.listdir(os.path.dirname(path)) if n.endswith(".tif")]
    if not os.path.isfile(path) or not tiles:
        raise SystemExit("tiled_synthesis.py: the tiles of %s were not written (see the error above)"
                         % os.path.basename(path))
    return "%d GeoTIFF tile%s" % (len(tiles), "" if len(tiles) == 1 else "s")


def main():
    a = arguments()
    simple.LoadPlugin(PLUGIN, remote=True)
    ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
    exemplars = [simple.TerrainReader(FileName=path) for path in a.exemplar]
    synthesis = simple.TerrainSynthesis(Exemplars=exemplars, Sketch=sketch_reader(a.sketch, a.exemplar[0]),
                                        OutputSize=[a.width, a.height], PatchSize=a.patch,
                                        Seed=a.seed, TileSize=a.tile_size, Backend="CPU")
    print("Synthesising %d x %d cells in tiles of %d on %d rank%s ..." % (
        a.width, a.height, a.tile_size, ranks, "" if ranks == 1 else "s"), flush=True)
    start = time.time()
    # Written aside, under the final names inside a temporary folder, then moved into place: a run
    # that fails or is stopped leaves no half-written mosaic under OUT.pvti. Ctrl-C on mpiexec stops
    # every rank within about a second (Open MPI sends them SIGTERM); the next run to the same
    # output removes the folder such a run leaves.
    folder, name = os.path.split(os.path.abspath(a.output))
    stem = os.path.splitext(name)[0]
    sweep_stopped_runs(folder, stem)
    aside = tempfile.mkdtemp(prefix=".%s.tmp-%d-" % (stem, os.getpid()), dir=folder)
    try:
        if name.lower().endswith(".vrt"):
            written = write_mosaic(synthesis, os.path.join(aside, name), a.file_tile_size)
        else:
            written = write_pieces(synthesis, os.path.join(aside, name), ranks)
        for entry in sorted(os.listdir(aside)):
            target = os.path.join(folder, entry)
            if os.path.isdir(target):
                shutil.rmtree(target)
            os.replace(os.path.join(aside, entry), target)
    finally:
        shutil.rmtree(aside, ignore_errors=True)
    print("Wrote %s (%s) in %.1f s" % (a.output, written, time.time() - start), flush=True)


# Not sys.exit(): pvbatch must return from the script to finalise MPI on every rank.
main()
