"""How busy is the land between the strokes? The band-pass relief G(8) - G(32) (Gaussian sigmas in
cells: the relief between about 1 and 3 km at 90 m cells) of terrains, as a standard deviation over
the cells farther than half a patch from every stroke and over the cells nearer, beside the
exemplar's own. A sketched landform reads against its surroundings: where ours stood 185 m away
from the strokes against the peer's 115 m and the exemplar's 130 m, the lone ridges the peer drew
were lost in ours (bbfa754 brought it to 100 m).

    /usr/bin/python3 Testing/Benchmarks/background_relief.py --sketch SKETCH.png --exemplar DEM \\
        TERRAIN.tif [TERRAIN.tif ...] [--patch 80]

The sketch is a stroke map (red ridges, blue valleys) on the terrains' grid. Reports; asserts
nothing. Needs Debian's python3 (GDAL, numpy, scipy, PIL).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
from osgeo import gdal
from PIL import Image
from scipy import ndimage

FINE, COARSE = 8.0, 32.0  # band-pass sigmas, cells


def heights(path, tsynth):
    """Heights in metres; PNG DEMs go through tsynth convert so their units and sidecars count."""
    if path.lower().endswith(".png"):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "h.tif")
            subprocess.run([tsynth, "convert", path, "-o", out], check=True, capture_output=True)
            return gdal.Open(out).ReadAsArray().astype(float)
    data = gdal.Open(path)
    if data is None:
        raise SystemExit("cannot read %s" % path)
    return data.ReadAsArray().astype(float)


def band(z):
    return ndimage.gaussian_filter(z, FINE) - ndimage.gaussian_filter(z, COARSE)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sketch", required=True)
    parser.add_argument("--exemplar", required=True)
    parser.add_argument("--patch", type=int, default=80)
    parser.add_argument("--tsynth", default=os.path.join(here, "..", "..", "build", "bin", "tsynth"))
    parser.add_argument("terrains", nargs="+")
    a = parser.parse_args()
    rgb = np.asarray(Image.open(a.sketch).convert("RGB")).astype(int)
    red = (rgb[:, :, 0] >= 200) & (rgb[:, :, 1] <= 80) & (rgb[:, :, 2] <= 80)
    blue = (rgb[:, :, 2] >= 200) & (rgb[:, :, 0] <= 80) & (rgb[:, :, 1] <= 80)
    strokes = red | blue
    if not strokes.any():
        raise SystemExit("%s has no red or blue strokes" % a.sketch)
    away = ndimage.distance_transform_edt(~strokes) >= a.patch / 2
    ex = band(heights(a.exemplar, a.tsynth))
    margin = int(2 * COARSE)
    exemplar = ex[margin:-margin, margin:-margin].std()
    print("exemplar %s: band-pass relief %.0f m" % (os.path.basename(a.exemplar), exemplar))
    print("%-40s %8s %8s %10s" % ("terrain", "away", "near", "away/ex"))
    for path in a.terrains:
        b = band(heights(path, a.tsynth))
        if b.shape != strokes.shape:
            raise SystemExit("%s is %s cells, the sketch %s" % (path, b.shape, strokes.shape))
        far = b[away].std() if away.any() else float("nan")
        print("%-40s %8.0f %8.0f %10.2f" % (os.path.basename(path)[-40:], far, b[~away].std(), far / exemplar))
    return 0


if __name__ == "__main__":
    sys.exit(main())
