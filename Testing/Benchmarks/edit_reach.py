#!/usr/bin/env python3
"""How far a moved stroke reaches in the synthesis target: the obstacle to local re-synthesis
(tsynth synth --previous takes a tile over only where its part of the target is the same bits).

For each edit of bench_local_edit.py (two lone ridges 720 cells apart, the east one moved; the
bundled Y with its south-west valley moved), at 1024 x 1024 cells from the bundled Colorado DEM,
the target planes of `tsynth synth --placements 1 --debug-dir` before and after the edit are
compared: the share of cells whose target height changes at all, by more than 1 cm and by more
than 1 m, how many of the 16 tiles of 256 cells those touch, and the share whose confidence
changes. With --pictures DIR it also writes DIR/NAME-reach.png: white unchanged, light grey
changed, darker by more than 1 cm, 1 m and 30 m.

    /usr/bin/python3 Testing/Benchmarks/edit_reach.py [--tsynth build/bin/tsynth] [--pictures DIR]

December 2026 (bb762c6): the ridge edit changes 21% of the cells (8 tiles: the ridge's own
landform band, which crosses them); the valley edit 52% (36% by more than 1 m, 12 tiles): far from
every line the target blends the nearest ridge's base and the nearest valley's rim by inverse
squared distance, so a valley changes the land wherever it is the nearest. Reports; asserts
nothing. Needs Debian's python3 (GDAL's and numpy's bindings).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
from osgeo import gdal

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(root, "Testing", "Python"))
import bench_local_edit as edits  # noqa: E402

TILE = 256
CENTIMETRE = 0.01
METRE = 1.0
FAR = 30.0  # metres: the darkest shade of the pictures
EDITS = (("wide-ridges", edits.wide_ridges), ("y-valley", edits.y_with_valley_moved))


def target_planes(tsynth, sketch, folder):
    subprocess.run([tsynth, "synth", "--exemplar", os.path.join(root, "Data", "dems", "colorado.png"),
                    "--sketch", sketch, "--size", "%dx%d" % (edits.SIZE, edits.SIZE),
                    "--placements", "1", "--debug-dir", folder, "-o", folder + ".tif",
                    "--no-progress"], check=True, capture_output=True)
    return [gdal.Open(os.path.join(folder, name)).ReadAsArray().astype(np.float64)
            for name in ("target.tif", "target-confidence.tif")]


def tiles_touched(mask):
    return sum(bool(mask[j:j + TILE, i:i + TILE].any())
               for j in range(0, mask.shape[0], TILE) for i in range(0, mask.shape[1], TILE))


def write_picture(change, path):
    shade = np.full(change.shape, 255, np.uint8)
    for limit, grey in ((0.0, 200), (CENTIMETRE, 150), (METRE, 90), (FAR, 0)):
        shade[change > limit] = grey
    image = gdal.GetDriverByName("MEM").Create("", change.shape[1], change.shape[0], 1, gdal.GDT_Byte)
    image.GetRasterBand(1).WriteArray(shade)
    gdal.GetDriverByName("PNG").CreateCopy(path, image)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tsynth", default=os.path.join(root, "build", "bin", "tsynth"))
    parser.add_argument("--pictures", help="folder for NAME-reach.png")
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for name, draw in EDITS:
            planes = []
            for shift in (0, edits.MOVE):
                sketch = os.path.join(tmp, "%s-%d.png" % (name, shift))
                draw(sketch, shift)
                planes.append(target_planes(a.tsynth, sketch, os.path.join(tmp, "%s-%d" % (name, shift))))
            (before, confidence_before), (after, confidence_after) = planes
            change = np.abs(after - before)
            print("%-12s target changed on %4.1f%% of cells (> 1 cm %4.1f%%, > 1 m %4.1f%%), largest %.0f m; "
                  "tiles of %d touched %d (> 1 cm %d) of %d; confidence changed on %4.1f%%"
                  % (name, 100 * (change > 0).mean(), 100 * (change > CENTIMETRE).mean(),
                     100 * (change > METRE).mean(), change.max(), TILE, tiles_touched(change > 0),
                     tiles_touched(change > CENTIMETRE), (edits.SIZE // TILE) ** 2,
                     100 * (np.abs(confidence_after - confidence_before) > 0).mean()))
            if a.pictures:
                os.makedirs(a.pictures, exist_ok=True)
                write_picture(change, os.path.join(a.pictures, name + "-reach.png"))


if __name__ == "__main__":
    main()
