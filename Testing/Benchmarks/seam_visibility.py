"""Seam figures of synthesised terrains, from their seams (`tsynth synth --debug-dir D`: D/seams.tif).

An instrument under construction, kept so that its figures can be reproduced and extended. With
the fill's windows 0.75 patch apart (not 0.5) the seams follow the windows' straight edges and one
shows in the hillshade as a straight line, yet none of these three figures tells the two apart
(1024 x 1024 from Colorado, y_ridges, seed 0; 0.5 against 0.75):
  laplacian   mean |Laplacian| on seam cells over that 3-8 cells from them   0.994 against 1.007
  straight    share of seam cells in straight runs of STRAIGHT cells (a run
              may wander one row or column)                                  0.082 against 0.099
  crease      second derivative across each seam, averaged along it over
              ALONG cells, RMS, over the same seams moved 6 cells           0.839 against 0.845
The straight seams are boundaries between two patches' textures, not creases: the eye sees them
because they are long and straight. A measure that sees that is still to be made; the sweep's
seam index (the 99th-percentile |Laplacian| against the exemplar's) does not either.

    /usr/bin/python3 Testing/Benchmarks/seam_visibility.py TERRAIN.tif D/seams.tif [TERRAIN D/seams ...]

Reports; asserts nothing. Needs Debian's python3 (GDAL, numpy, scipy).
"""
import sys

import numpy as np
from osgeo import gdal
from scipy import ndimage

NEAR, FAR = 3, 8  # cells: "beside the seams" for the Laplacian figure
STRAIGHT = 30  # cells: a straight run at least this long
ALONG = 8  # cells each way: the crease is averaged along the seam over this reach
ACROSS = 2.0  # cells: the crease's second difference is taken this far either side
SHIFT = 6  # cells: the seams moved this far give the crease's reference


def load(path):
    return gdal.Open(path).ReadAsArray().astype(float)


def laplacian(z):
    lap = np.zeros_like(z)
    lap[1:-1, 1:-1] = np.abs(z[1:-1, 2:] + z[1:-1, :-2] + z[2:, 1:-1] + z[:-2, 1:-1] - 4 * z[1:-1, 1:-1])
    return lap


def laplacian_ratio(z, seams):
    distance = ndimage.distance_transform_edt(~seams)
    lap = laplacian(z)
    return lap[seams].mean() / lap[(distance >= NEAR) & (distance <= FAR)].mean()


def long_runs(mask):
    """Cells in runs of at least STRAIGHT along each row."""
    out = np.zeros_like(mask)
    for r, row in enumerate(mask):
        edges = np.flatnonzero(np.diff(np.concatenate(([0], row.astype(np.int8), [0]))))
        for start, stop in zip(edges[::2], edges[1::2]):
            if stop - start >= STRAIGHT:
                out[r, start:stop] = True
    return out


def straight_share(seams):
    wander_rows = ndimage.binary_dilation(seams, structure=np.ones((3, 1), bool))
    wander_cols = ndimage.binary_dilation(seams, structure=np.ones((1, 3), bool))
    straight = (long_runs(wander_rows) | long_runs(wander_cols.T).T) & seams
    return straight.sum() / seams.sum()


def aligned_crease(z, lines):
    """RMS over the line cells of the second difference across the line, averaged along it."""
    box = lambda a: ndimage.uniform_filter(a, 2 * ALONG + 1, mode="constant")
    ys, xs = np.nonzero(lines)
    m = lines.astype(float)
    y, x = np.mgrid[0:z.shape[0], 0:z.shape[1]].astype(float)
    n = np.maximum(box(m), 1e-9)
    cx, cy = box(m * x) / n, box(m * y) / n
    vxx, vyy, vxy = box(m * x * x) / n - cx * cx, box(m * y * y) / n - cy * cy, box(m * x * y) / n - cx * cy
    angle = 0.5 * np.arctan2(2 * vxy, vxx - vyy)[ys, xs]  # the line's direction per cell
    nx, ny = -np.sin(angle), np.cos(angle)
    a = ndimage.map_coordinates(z, [ys + ny * ACROSS, xs + nx * ACROSS], order=1, mode="nearest")
    b = ndimage.map_coordinates(z, [ys - ny * ACROSS, xs - nx * ACROSS], order=1, mode="nearest")
    crease = np.zeros_like(z)
    crease[ys, xs] = (a + b - 2 * z[ys, xs]) / ACROSS ** 2
    along = box(crease) / n
    return np.sqrt(np.mean(along[ys, xs] ** 2))


def crease_ratio(z, seams):
    moved = [np.roll(seams, (dy, dx), (0, 1)) & ~seams
             for dy, dx in ((0, SHIFT), (SHIFT, 0), (0, -SHIFT), (-SHIFT, 0))]
    return aligned_crease(z, seams) / np.mean([aligned_crease(z, m) for m in moved])


def main(args):
    if not args or len(args) % 2:
        raise SystemExit(__doc__)
    print("%-40s %7s %10s %9s %7s" % ("terrain", "seams", "laplacian", "straight", "crease"))
    for terrain, seam_file in zip(args[::2], args[1::2]):
        z, seams = load(terrain), load(seam_file) > 0
        if seams.shape != z.shape or not seams.any():
            raise SystemExit("%s: no seams on the terrain's grid" % seam_file)
        print("%-40s %7.3f %10.3f %9.3f %7.3f" % (terrain, seams.mean(), laplacian_ratio(z, seams),
                                                   straight_share(seams), crease_ratio(z, seams)))


if __name__ == "__main__":
    main(sys.argv[1:])
