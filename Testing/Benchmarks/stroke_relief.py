"""How boldly a terrain draws a stroke map's ridges: the crest minus the flank, against the texture.

For each terrain: the mean height on the red ridge strokes minus the mean 12-22 cells from them (away
from blue valleys), both on the terrain smoothed at sigma 2 cells, in metres; the texture as the
standard deviation of the terrain minus its sigma-6 smoothing; and their ratio. Compare ours, its
--debug-dir target.tif and patches.tif, and the peer's result on the same sketch: in stop 29 the
Everest letters gave target 1156 m, patches 506 m, ours 800 m, peer 1057 m (texture 126-136 m), which
located the lost relief in the final correction. Reports; asserts nothing.

    /usr/bin/python3 Testing/Benchmarks/stroke_relief.py SKETCH.png TERRAIN.tif [TERRAIN.tif ...]
"""
import sys

import numpy as np
from osgeo import gdal
from PIL import Image
from scipy import ndimage

FLANK_CELLS = (12, 22)  # about a third to a half of a patch-scale landform's half width
VALLEY_CLEARANCE = 10   # flank cells this close to a valley stroke are left out


def main(sketch_path, terrains):
    rgb = np.array(Image.open(sketch_path).convert("RGB")).astype(int)
    ridge = (rgb[..., 0] > 150) & (rgb[..., 1] < 100) & (rgb[..., 2] < 100)
    valley = (rgb[..., 2] > 150) & (rgb[..., 0] < 100)
    if not ridge.any():
        raise SystemExit("%s has no red ridge strokes." % sketch_path)
    to_ridge = ndimage.distance_transform_edt(~ridge)
    to_valley = ndimage.distance_transform_edt(~valley)
    flank = (to_ridge > FLANK_CELLS[0]) & (to_ridge < FLANK_CELLS[1]) & (to_valley > VALLEY_CLEARANCE)
    crest = to_ridge < 2
    for path in terrains:
        ds = gdal.Open(path)
        if ds is None:
            raise SystemExit("Cannot read %s." % path)
        z = ds.ReadAsArray().astype(float)
        if z.shape != ridge.shape:
            z = np.array(Image.fromarray(z).resize(ridge.shape[::-1]))
        smooth = ndimage.gaussian_filter(z, 2)
        drop = smooth[crest].mean() - smooth[flank].mean()
        texture = (z - ndimage.gaussian_filter(z, 6)).std()
        print("%s: crest minus flank %.0f m, texture %.0f m, ratio %.2f" % (path, drop, texture, drop / texture))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2:])
