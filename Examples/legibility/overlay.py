#!/usr/bin/env python3
"""overlay.py OUT.png SKETCH.png HILLSHADE.png... : each hillshade with the outline of the stroke map's
strokes drawn over it (red ridges, blue valleys), side by side, so one sees whether a terrain's ridges
and valleys lie on the strokes or between them. The hillshades (`tsynth render --grey`) are sampled to
the sketch's size. GDAL's and numpy's Python bindings only, as compose.py."""
import sys

import numpy as np
from osgeo import gdal

GUTTER = 8
OUTLINE = 2  # cells: how far into a stroke its outline reaches
RIDGE = (255, 0, 0)
VALLEY = (0, 80, 255)


def fail(message):
    sys.exit("overlay.py: " + message)


def read_rgb(path):
    d = gdal.Open(path)
    if d is None:
        fail(f"cannot read {path}.")
    a = d.ReadAsArray()
    return np.stack([a] * 3) if a.ndim == 2 else a[:3]


def strokes(sketch):
    """The stroke map's ridge and valley cells, by the colours DESIGN.md gives."""
    r, g, b = (sketch[i].astype(int) for i in range(3))
    ridge = (r >= 200) & (g <= 80) & (b <= 80)
    valley = (b >= 200) & (r <= 80) & (g <= 80)
    return ridge, valley


def outline(mask):
    """The cells of a mask within OUTLINE cells of its edge (4-neighbour erosion)."""
    inner = mask.copy()
    for _ in range(OUTLINE):
        shrunk = inner.copy()
        shrunk[1:, :] &= inner[:-1, :]
        shrunk[:-1, :] &= inner[1:, :]
        shrunk[:, 1:] &= inner[:, :-1]
        shrunk[:, :-1] &= inner[:, 1:]
        shrunk[0, :] = shrunk[-1, :] = False
        shrunk[:, 0] = shrunk[:, -1] = False
        inner = shrunk
    return mask & ~inner


def sampled(image, height, width):
    """The image at height x width, nearest cell."""
    rows = np.arange(height) * image.shape[1] // height
    cols = np.arange(width) * image.shape[2] // width
    return image[:, rows][:, :, cols]


def main():
    if len(sys.argv) < 4:
        fail("usage: overlay.py OUT.png SKETCH.png HILLSHADE.png...")
    out, sketch_path, shades = sys.argv[1], sys.argv[2], sys.argv[3:]
    if out in [sketch_path] + shades:
        fail(f"{out} is one of the inputs; give another output name.")
    ridge, valley = strokes(read_rgb(sketch_path))
    if not ridge.any() and not valley.any():
        fail(f"{sketch_path} has no red or blue strokes: it is not a stroke map.")
    h, w = ridge.shape
    panels = []
    for path in shades:
        panel = sampled(read_rgb(path), h, w).copy()
        for mask, colour in ((outline(ridge), RIDGE), (outline(valley), VALLEY)):
            for i in range(3):
                panel[i][mask] = colour[i]
        panels.append(panel)
    sheet = np.full((3, h, len(panels) * (w + GUTTER) - GUTTER), 255, np.uint8)
    for k, panel in enumerate(panels):
        sheet[:, :, k * (w + GUTTER): k * (w + GUTTER) + w] = panel
    mem = gdal.GetDriverByName("MEM").Create("", sheet.shape[2], h, 3, gdal.GDT_Byte)
    for i in range(3):
        mem.GetRasterBand(i + 1).WriteArray(sheet[i])
    if gdal.GetDriverByName("PNG").CreateCopy(out, mem) is None:
        fail(f"cannot write {out}.")


if __name__ == "__main__":
    main()
