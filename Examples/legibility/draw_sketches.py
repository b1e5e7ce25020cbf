#!/usr/bin/env python3
"""The stroke sketches of the README's legibility comparison (red ridges, blue valleys on white),
512 x 512: thin, branching and isolated strokes closer together than a patch, as a person draws
them to get them back as land.

    python3 Examples/legibility/draw_sketches.py OUT_DIR
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Testing", "Python"))
from sketch_drawing import Canvas, RIDGE, VALLEY  # noqa: E402

SIZE = 512


def valley_network():
    """A trunk valley running out through the south border, ten side valleys 40-50 pixels apart,
    and a bounding ridge each side."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(60, 20), (40, 200), (60, 380), (100, 500)], RIDGE)
    c.polyline([(450, 20), (470, 200), (450, 380), (410, 500)], RIDGE)
    c.polyline([(255, 40), (250, 150), (260, 260), (250, 380), (256, 515)], VALLEY)
    for y0, side, length in ((80, -1, 150), (120, 1, 160), (170, -1, 170), (210, 1, 170), (260, -1, 160),
                             (300, 1, 165), (350, -1, 150), (390, 1, 145), (430, -1, 120), (460, 1, 110)):
        x1 = 253 + side * length
        c.polyline([(253, y0), ((253 + x1) / 2, y0 - 18), (x1, y0 - 55)], VALLEY)
    return c


def letters():
    """Block letters T and S drawn as ridges inside a ring valley."""
    c = Canvas(SIZE, SIZE)
    c.circle(256, 256, 230, VALLEY)
    c.polyline([(110, 150), (240, 150)], RIDGE)
    c.polyline([(175, 150), (175, 370)], RIDGE)
    c.polyline([(400, 150), (290, 150), (290, 260), (400, 260), (400, 370), (290, 370)], RIDGE)
    return c


def rings():
    """A ridge ring inside a valley ring."""
    c = Canvas(SIZE, SIZE)
    c.circle(256, 256, 120, RIDGE)
    c.circle(256, 256, 200, VALLEY)
    return c


def herringbone():
    """A main crest with spurs leaving it every 80 pixels and valleys between the spurs."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(30, 256), (482, 256)], RIDGE)
    for x in range(60, 440, 80):
        c.polyline([(x, 256), (x + 40, 120)], RIDGE)
        c.polyline([(x, 256), (x + 40, 392)], RIDGE)
        c.polyline([(x + 40, 230), (x + 80, 100)], VALLEY)
        c.polyline([(x + 40, 282), (x + 80, 412)], VALLEY)
    return c


SKETCHES = (valley_network, letters, rings, herringbone)

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    for draw in SKETCHES:
        path = draw().save(os.path.join(out, draw.__name__ + ".png"))
        print("wrote", path)
