"""Ripples along slanted strokes: the target's corrugation beside a line and the slot down a valley floor.

A stroke's cells make a staircase along any slanted line. Two defects followed it, both visible in a
grey hillshade zoomed 3-4 times: the target's flanks rippled with the distance to the staircase (stripes
across the flanks), and the drainage's last cuts made a one-cell slot down each valley line (a dotted
line along the floor). This draws a 512 x 512 stroke map of slanted lines (a ridge and a valley at
slopes 0.4 and 0.5, a short valley at 0.5), synthesises it with each build given (--debug-dir for the
target) and prints, per build:
  ripple at d   the largest departure of the target, sampled every quarter cell along a parallel d
                cells beside the valley, from its own 4-cell running mean (metres);
  floor step    the 90th percentile, over the valleys' line cells, of the lowest 8-neighbour off the line
                minus the line cell, on the synthesised terrain (metres): a slot's depth.
and each figure's ratio to the first build's, taken in the same run. Reports; asserts nothing.

    /usr/bin/python3 Testing/Benchmarks/line_ripple.py [--exemplar DEM] TSYNTH [TSYNTH ...]

Measured with Mont Blanc, c3aed4e then be16aa0: ripple at 1, 2, 3 and 5 cells 8.06, 7.43, 5.46 and 6.47 m
against 3.66, 2.34, 2.26 and 2.16 m (ratios 0.32-0.45); floor step 5.88 against 0.14 m. About 5 s a build.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
from osgeo import gdal

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "Testing", "Python"))
from sketch_drawing import Canvas, RIDGE, VALLEY  # noqa: E402

SIZE = 512
# The valleys measured: (from, to) in pixels, x east, y down, as drawn.
VALLEYS = (((60, 300), (460, 460)), ((300, 60), (420, 120)))
RIDGE_LINE = ((60, 60), (260, 140))
OFFSETS = (1, 2, 3, 5)        # cells beside the valley
RUNNING_MEAN_CELLS = 4.0      # the ripple is what a running mean this long leaves
SAMPLES_PER_CELL = 4
# The floor step is this percentile over the line cells: most are not cut at all, the slot shows
# where the drainage had to cut.
SLOT_PERCENTILE = 90


def draw(path):
    c = Canvas(SIZE, SIZE)
    c.polyline(list(RIDGE_LINE), RIDGE)
    for a, b in VALLEYS:
        c.polyline([a, b], VALLEY)
    return c.save(path)


def bilinear(z, x, y):
    i, j = int(np.floor(x)), int(np.floor(y))
    fx, fy = x - i, y - j
    return (z[j, i] * (1 - fx) * (1 - fy) + z[j, i + 1] * fx * (1 - fy)
            + z[j + 1, i] * (1 - fx) * fy + z[j + 1, i + 1] * fx * fy)


def ripple(z, a, b, offset):
    """Largest departure from the running mean along the parallel `offset` cells beside a..b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = np.linalg.norm(b - a)
    along = (b - a) / length
    normal = np.array([-along[1], along[0]])
    steps = np.arange(0.2 * length, 0.8 * length, 1.0 / SAMPLES_PER_CELL)
    values = np.array([bilinear(z, *(a + s * along + offset * normal)) for s in steps])
    n = int(RUNNING_MEAN_CELLS * SAMPLES_PER_CELL) + 1
    mean = np.convolve(values, np.ones(n) / n, mode="valid")
    return float(np.abs(values[n // 2: n // 2 + len(mean)] - mean).max())


def floor_step(z, a, b):
    """SLOT_PERCENTILE over the valley's cells of the lowest off-line 8-neighbour minus the cell."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    steps = int(np.ceil(2 * np.linalg.norm(b - a)))
    line = {(int(round(a[0] + t * (b[0] - a[0]))), int(round(a[1] + t * (b[1] - a[1]))))
            for t in np.linspace(0.1, 0.9, steps)}
    rises = []
    for i, j in line:
        around = [z[j + dj, i + di] for dj in (-1, 0, 1) for di in (-1, 0, 1)
                  if (i + di, j + dj) not in line]
        rises.append(min(around) - z[j, i])
    return float(np.percentile(rises, SLOT_PERCENTILE))


def measure(tsynth, exemplar, sketch, tmp, label):
    out = os.path.join(tmp, label + ".tif")
    debug = os.path.join(tmp, label + "-debug")
    subprocess.run([tsynth, "synth", "--exemplar", exemplar, "--sketch", sketch, "-o", out,
                    "--debug-dir", debug, "--no-progress"], check=True, capture_output=True)
    target = gdal.Open(os.path.join(debug, "target.tif")).ReadAsArray().astype(float)
    terrain = gdal.Open(out).ReadAsArray().astype(float)
    figures = {}
    for d in OFFSETS:
        figures["ripple at %d" % d] = max(ripple(target, a, b, d) for a, b in VALLEYS)
    figures["floor step"] = float(np.mean([floor_step(terrain, a, b) for a, b in VALLEYS]))
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("builds", nargs="+", help="tsynth binaries; the first is the reference")
    parser.add_argument("--exemplar", default=os.path.join(ROOT, "..", "shared", "data", "dems",
                                                           "alps-montblanc.png"))
    args = parser.parse_args()
    if not os.path.exists(args.exemplar):
        raise SystemExit("line_ripple: no exemplar at %s (give --exemplar DEM)" % args.exemplar)
    with tempfile.TemporaryDirectory(prefix="tsynth-ripple-") as tmp:
        sketch = draw(os.path.join(tmp, "slanted.png"))
        results = [measure(b, args.exemplar, sketch, tmp, "build%d" % k) for k, b in enumerate(args.builds)]
    names = list(results[0])
    print("%-13s" % "figure" + "".join("%14s" % ("build %d" % k) for k in range(len(results))))
    for name in names:
        row = "%-13s" % name
        for r in results:
            ratio = r[name] / results[0][name] if results[0][name] else float("nan")
            row += "%8.2f (%4.2f)" % (r[name], ratio)
        print(row)
    print("(metres; in brackets, the ratio to build 0 in this run)")


if __name__ == "__main__":
    main()
