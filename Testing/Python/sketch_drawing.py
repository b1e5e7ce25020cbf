"""Stroke-map sketches drawn by the tests themselves (standard library only).

A stroke map is an RGB picture on white: red strokes are ridges, blue strokes valleys.
Coordinates are pixels, x east, y down from the top (north) edge, as in the picture.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_cli import write_png  # noqa: E402

RIDGE = (230, 20, 20)
VALLEY = (20, 40, 230)
WHITE = (255, 255, 255)
# Stroke width in pixels: the bundled stroke sketches' pens are 6-8 pixels wide.
PEN = 6
# Points along a drawn curve, per pixel of its length: dense enough that stamped discs overlap.
SAMPLES_PER_PIXEL = 2


class Canvas:
    def __init__(self, width, height):
        self.width = width
        self.height = height
        self.pixels = [[WHITE] * width for _ in range(height)]

    def disc(self, cx, cy, radius, colour):
        for y in range(max(0, math.floor(cy - radius)), min(self.height, math.ceil(cy + radius) + 1)):
            for x in range(max(0, math.floor(cx - radius)), min(self.width, math.ceil(cx + radius) + 1)):
                if (x - cx) ** 2 + (y - cy) ** 2 <= radius * radius:
                    self.pixels[y][x] = colour

    def polyline(self, points, colour, pen=PEN):
        """Straight pieces between consecutive points; points may lie off the canvas."""
        for (x0, y0), (x1, y1) in zip(points, points[1:]):
            steps = max(1, math.ceil(SAMPLES_PER_PIXEL * math.hypot(x1 - x0, y1 - y0)))
            for k in range(steps + 1):
                t = k / steps
                self.disc(x0 + t * (x1 - x0), y0 + t * (y1 - y0), pen / 2.0, colour)

    def curve(self, f, t0, t1, colour, pieces=200, pen=PEN):
        """The curve t -> f(t) = (x, y) for t from t0 to t1, as `pieces` straight pieces."""
        self.polyline([f(t0 + (t1 - t0) * k / pieces) for k in range(pieces + 1)], colour, pen)

    def circle(self, cx, cy, radius, colour, pen=PEN):
        self.curve(lambda t: (cx + radius * math.cos(t), cy + radius * math.sin(t)), 0.0, 2.0 * math.pi,
                   colour, pieces=max(24, round(radius)), pen=pen)

    def save(self, path):
        write_png(path, self.width, self.height, lambda x, y: self.pixels[y][x])
        return path


# The sketches of the landform tests, on a SIZE x SIZE canvas (the thresholds of test_synth.py were
# measured at this size with --patch 40: strokes 2-7 patches long, parallel lines 2 patches apart).
SIZE = 320


def valley_tree():
    """A trunk valley leaving the map at the bottom (south) border, with four side valleys."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(160, 80), (165, 200), (160, SIZE + 10)], VALLEY)
    c.polyline([(50, 30), (110, 110), (163, 160)], VALLEY)
    c.polyline([(280, 40), (220, 120), (164, 180)], VALLEY)
    c.polyline([(30, 190), (100, 230), (162, 262)], VALLEY)
    c.polyline([(295, 200), (230, 240), (162, 285)], VALLEY)
    return c


def parallel_ridges():
    """Three slightly slanting ridges 90 pixels apart."""
    c = Canvas(SIZE, SIZE)
    for y in (70, 160, 250):
        c.polyline([(30, y - 10), (290, y + 10)], RIDGE)
    return c


def rings():
    """A ridge ring inside a valley ring, 70 pixels apart."""
    c = Canvas(SIZE, SIZE)
    c.circle(160, 160, 55, RIDGE)
    c.circle(160, 160, 125, VALLEY)
    return c


def letters():
    """A T and an S in ridge strokes."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(40, 60), (150, 60)], RIDGE)
    c.polyline([(95, 60), (95, 265)], RIDGE)
    r = 52  # the S: two arcs of radius r, the upper one open to the right, the lower to the left

    def arc(cy, start, end):
        c.curve(lambda t: (235 + r * math.cos(t), cy - r * math.sin(t)), math.radians(start), math.radians(end),
                RIDGE)

    arc(112, 20, 270)
    arc(216, 90, -160)
    return c


def spiral():
    """One ridge winding 1.5 times round the centre, its turns 80 pixels apart."""
    c = Canvas(SIZE, SIZE)
    turns, r0, r1 = 1.5, 20.0, 140.0
    end = 2.0 * math.pi * turns

    def at(t):
        r = r0 + (r1 - r0) * t / end
        return (160 + r * math.cos(t), 160 - r * math.sin(t))

    c.curve(at, 0.0, end, RIDGE, pieces=400)
    return c


def border_strokes():
    """256 x 256: a ridge from the west to the east border 80 pixels below the top, a ridge from the
    top border down to it, and a valley from the west to the east border near the bottom."""
    c = Canvas(256, 256)
    c.polyline([(-5, 80), (260, 80)], RIDGE)
    c.polyline([(128, -5), (128, 140)], RIDGE)
    c.polyline([(-5, 190), (260, 200)], VALLEY)
    return c


def short_strokes():
    """192 x 192: two ridges and a valley, each at most 58 pixels long."""
    c = Canvas(192, 192)
    c.polyline([(30, 40), (80, 60)], RIDGE)
    c.polyline([(40, 150), (60, 110)], RIDGE)
    c.polyline([(120, 120), (150, 170)], VALLEY)
    return c


def valley_loop():
    """192 x 192: a closed valley ring of radius 55."""
    c = Canvas(192, 192)
    c.circle(96, 96, 55, VALLEY)
    return c


# The legibility sketches (issue 20): strokes closer together than a patch, as a person draws them
# to get them back as land. Drawn on a 512-pixel frame (the README's comparison, Examples/legibility)
# and scaled to `size`: the tests draw them at 320 x 320 for 40-cell patches.
LEGIBILITY_FRAME = 512


def _scaled(points, size):
    s = size / LEGIBILITY_FRAME
    return [(x * s, y * s) for x, y in points]


def valley_network(size=SIZE):
    """A trunk valley running out through the south border, ten side valleys 40-50 pixels apart (of
    512) leaving it at a slant, and a bounding ridge each side."""
    c = Canvas(size, size)
    c.polyline(_scaled([(60, 20), (40, 200), (60, 380), (100, 500)], size), RIDGE)
    c.polyline(_scaled([(450, 20), (470, 200), (450, 380), (410, 500)], size), RIDGE)
    c.polyline(_scaled([(255, 40), (250, 150), (260, 260), (250, 380), (256, 515)], size), VALLEY)
    for y0, side, length in ((80, -1, 150), (120, 1, 160), (170, -1, 170), (210, 1, 170), (260, -1, 160),
                             (300, 1, 165), (350, -1, 150), (390, 1, 145), (430, -1, 120), (460, 1, 110)):
        x1 = 253 + side * length
        c.polyline(_scaled([(253, y0), ((253 + x1) / 2, y0 - 18), (x1, y0 - 55)], size), VALLEY)
    return c


def letters_in_a_ring(size=SIZE):
    """Block letters T and S in ridge strokes inside a ring valley."""
    c = Canvas(size, size)
    s = size / LEGIBILITY_FRAME
    c.circle(256 * s, 256 * s, 230 * s, VALLEY)
    c.polyline(_scaled([(110, 150), (240, 150)], size), RIDGE)
    c.polyline(_scaled([(175, 150), (175, 370)], size), RIDGE)
    c.polyline(_scaled([(400, 150), (290, 150), (290, 260), (400, 260), (400, 370), (290, 370)], size), RIDGE)
    return c


def carved_letters(size=LEGIBILITY_FRAME):
    """Block letters H and I carved as valleys, nothing else drawn: each letter is a valley network
    whose outlet lies inside the map (a closed basin unless its water is led out)."""
    c = Canvas(size, size)
    for line in ([(110, 130), (110, 380)], [(230, 130), (230, 380)], [(110, 255), (230, 255)],
                 [(330, 130), (410, 130)], [(370, 130), (370, 380)], [(330, 380), (410, 380)]):
        c.polyline(_scaled(line, size), VALLEY)
    return c


def grid():
    """Ridges and valleys in turn, 40 pixels apart, across the whole map."""
    c = Canvas(SIZE, SIZE)
    for k, y in enumerate(range(40, SIZE, 40)):
        c.polyline([(-5, y), (SIZE + 5, y)], RIDGE if k % 2 == 0 else VALLEY)
    return c
