"""Runs an example script and checks the picture it writes (pvpython: vtk and numpy are there).

    pvpython run_example.py OUT.png MIN_SPREAD [--blue FRACTION] -- COMMAND...

Fails unless COMMAND exits 0 and OUT.png then exists, is fresh, and shows a picture: the
standard deviation of its grey levels is at least MIN_SPREAD (a blank or failed render is
nearly uniform) and, with --blue, at least FRACTION of its pixels are mostly blue (streams).
"""
import os
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def main():
    split = sys.argv.index("--")
    options, command = sys.argv[1:split], sys.argv[split + 1:]
    picture, min_spread = options[0], float(options[1])
    blue = float(options[options.index("--blue") + 1]) if "--blue" in options else None
    if os.path.exists(picture):
        os.remove(picture)
    status = subprocess.call(command)
    if status != 0:
        sys.exit("example failed with exit status %d" % status)
    if not os.path.exists(picture):
        sys.exit("example wrote no picture %s" % picture)
    reader = vtkPNGReader()
    reader.SetFileName(picture)
    reader.Update()
    image = reader.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)
    grey = pixels[:, :3].mean(axis=1)
    spread = grey.std()
    print("picture %s: %d x %d, grey spread %.1f" % ((picture,) + image.GetDimensions()[:2] + (spread,)))
    if spread < min_spread:
        sys.exit("the picture is nearly uniform (spread %.1f < %.1f)" % (spread, min_spread))
    if blue is not None:
        r, g, b = pixels[:, 0], pixels[:, 1], pixels[:, 2]
        share = float(np.mean((b > 150) & (b > r + 60) & (b > g + 30)))
        print("blue share %.4f" % share)
        if share < blue:
            sys.exit("too few blue pixels: %.4f < %.4f" % (share, blue))


if __name__ == "__main__":
    main()
