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
import sketch_drawing  # noqa: E402
from sketch_drawing import Canvas, RIDGE, VALLEY  # noqa: E402

SIZE = 512


def valley_network():
    return sketch_drawing.valley_network(SIZE)


def letters():
    return sketch_drawing.letters_in_a_ring(SIZE)


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


def carved_letters():
    return sketch_drawing.carved_letters(SIZE)


def isolated():
    """Four short strokes far apart: a ridge, a ring valley, a valley and a bent ridge."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(70, 90), (190, 120)], RIDGE)
    c.circle(380, 130, 45, VALLEY)
    c.polyline([(120, 330), (160, 440)], VALLEY)
    c.polyline([(300, 400), (360, 330), (440, 380)], RIDGE)
    return c


def dashes():
    """Short strokes 30-120 pixels long, well under a patch and a little over: three ridges, three
    valleys, a V of valleys and a ridge beside a valley."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(40, 100), (70, 100)], RIDGE)
    c.polyline([(150, 80), (200, 120)], RIDGE)
    c.polyline([(300, 60), (400, 120)], RIDGE)
    c.polyline([(50, 330), (75, 360)], VALLEY)
    c.polyline([(160, 300), (160, 360)], VALLEY)
    c.polyline([(300, 380), (400, 330)], VALLEY)
    c.polyline([(420, 200), (460, 260), (490, 200)], VALLEY)
    c.polyline([(80, 200), (180, 230)], RIDGE)
    c.polyline([(90, 240), (190, 270)], VALLEY)
    return c


def ts_over_valleys():
    """A T and an S as ridges above a branching valley network, one valley's spur reaching up
    towards the T's stem: short letters beside long valleys, where a lost letter hides."""
    c = Canvas(SIZE, SIZE)
    c.polyline([(60, 470), (200, 380), (300, 300), (440, 120)], VALLEY)
    c.polyline([(200, 380), (120, 250), (90, 140)], VALLEY)
    c.polyline([(300, 300), (380, 360), (470, 420)], VALLEY)
    c.polyline([(120, 250), (200, 200)], VALLEY)
    c.polyline([(60, 60), (200, 60)], RIDGE)
    c.polyline([(130, 60), (130, 190)], RIDGE)

    def arc(cy, start, end):  # the S: two arcs of ellipses 100 x 80 pixels, degrees clockwise from east
        c.curve(lambda t: (310 + 50 * math.cos(t), cy + 40 * math.sin(t)), math.radians(start), math.radians(end),
                RIDGE)

    arc(70, 315, 90)
    arc(150, -90, 135)
    return c


def dendrite_and_letters():
    """A trunk valley with seven branches (two branching again) draining south, the letters T and S
    as ridges beside it, and a lone ridge 70 pixels long. Drawn at 640 x 640 in December 2026 and
    run over Colorado (scaled here to 512): ours legible over 0.79 of the stroke length, Tasse's code
    over 0.28 (tsynth evaluate); in the hillshades ours drew every branch and both letters, the peer
    neither letter."""
    c = Canvas(SIZE, SIZE)

    def line(points, colour):
        c.polyline([(x * SIZE / 640, y * SIZE / 640) for x, y in points], colour)

    line([(200, 635), (210, 540), (190, 450), (215, 360), (200, 270), (220, 180), (205, 90)], VALLEY)
    for branch in ([(210, 540), (120, 500), (60, 440)], [(190, 450), (280, 420), (340, 360)],
                   [(215, 360), (130, 320), (90, 250)], [(200, 270), (290, 230), (330, 160)],
                   [(220, 180), (140, 130), (110, 60)], [(120, 500), (100, 560), (70, 600)],
                   [(280, 420), (300, 480), (350, 510)]):
        line(branch, VALLEY)
    line([(400, 120), (560, 120)], RIDGE)
    line([(480, 120), (480, 300)], RIDGE)
    line([(600, 360), (440, 360), (440, 450), (600, 450), (600, 540), (430, 540)], RIDGE)
    line([(330, 580), (400, 600)], RIDGE)
    return c


SKETCHES = (valley_network, letters, rings, herringbone, carved_letters, isolated, dashes, ts_over_valleys,
            dendrite_and_letters)

if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    for draw in SKETCHES:
        path = draw().save(os.path.join(out, draw.__name__ + ".png"))
        print("wrote", path)
