#!/usr/bin/env python3
"""Straight steps along lines of a terrain, such as a tiled synthesis's tile edges.

    /usr/bin/python3 Testing/Benchmarks/tile_edges.py TERRAIN.tif [TERRAIN.tif ...]

For every column line (and row line), the mean |height step| across it over blocks of 64 cells,
divided by the median of the 8 lines beside it. A tile edge where patches meet in a cliff stands out
as a line several times steeper than its neighbours (9.9 on a 256^2 test terrain before the tiles'
inner border, 1.2-2.2 on untiled terrains). Prints, per terrain, the worst ratio, its line and block,
and the 99.9th percentile, for columns and rows. Needs numpy, scipy and GDAL's Python bindings.
"""
import sys

import numpy as np
from osgeo import gdal
from scipy.ndimage import median_filter

BLOCK = 64  # cells along a line per figure: a short cliff is not averaged away
NEIGHBOURS = 9  # the line and 4 each side


def worst_line(z, axis):
    d = np.abs(np.diff(z, axis=axis))
    if axis == 0:
        d = d.T  # lines as columns of d
    blocks = d.shape[0] // BLOCK
    means = d[:blocks * BLOCK].reshape(blocks, BLOCK, -1).mean(axis=1)  # block x line
    ratio = means / np.maximum(median_filter(means, size=(1, NEIGHBOURS), mode="nearest"), 1e-6)
    block, line = np.unravel_index(np.argmax(ratio), ratio.shape)
    return float(ratio.max()), int(line), int(block) * BLOCK, float(np.percentile(ratio, 99.9))


for path in sys.argv[1:]:
    z = gdal.Open(path).ReadAsArray().astype(float)
    for name, axis in (("columns", 1), ("rows", 0)):
        worst, line, start, p999 = worst_line(z, axis)
        print("%s %s: worst %.2f at line %d (cells %d-%d), 99.9th percentile %.2f"
              % (path, name, worst, line, start, start + BLOCK - 1, p999))
