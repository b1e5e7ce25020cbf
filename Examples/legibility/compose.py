#!/usr/bin/env python3
"""compose.py [--tile N] OUT.png TILE.png... : the tiles side by side, each shrunk by the least whole factor
that fits it in N pixels a side (256), with a white gutter between them (GDAL's and numpy's Python bindings,
which Debian's gdal-bin and python3-numpy bring)."""
import sys

import numpy as np
from osgeo import gdal

TILE = 256
GUTTER = 6


def tile(path, side):
    d = gdal.Open(path)
    a = d.ReadAsArray()
    a = np.stack([a] * 3) if a.ndim == 2 else a[:3]
    h, w = a.shape[1:]
    f = max(1, -(-max(h, w) // side))  # a whole factor that fits: never crops
    a = a[:, : h // f * f, : w // f * f].reshape(3, h // f, f, w // f, f).mean(axis=(2, 4))
    out = np.full((3, side, side), 255.0)
    out[:, : a.shape[1], : a.shape[2]] = a[:, :side, :side]
    return out


def main():
    args = sys.argv[1:]
    side = TILE
    if args[:1] == ["--tile"]:
        side, args = int(args[1]), args[2:]
    tiles = [tile(p, side) for p in args[1:]]
    width = len(tiles) * side + (len(tiles) - 1) * GUTTER
    canvas = np.full((3, side, width), 255.0)
    for k, t in enumerate(tiles):
        canvas[:, :, k * (side + GUTTER): k * (side + GUTTER) + side] = t
    mem = gdal.GetDriverByName("MEM").Create("", width, side, 3, gdal.GDT_Byte)
    for b in range(3):
        mem.GetRasterBand(b + 1).WriteArray(np.clip(canvas[b], 0, 255).round().astype(np.uint8))
    if gdal.GetDriverByName("PNG").CreateCopy(args[0], mem) is None:
        sys.exit("compose.py: cannot write " + args[0])


if __name__ == "__main__":
    main()
