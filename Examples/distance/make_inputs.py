#!/usr/bin/python3
"""Makes the stroke maps and profile tables of the distance-synthesis examples
(tsynth distance, Rusnell 2009). Run with a Python that has PIL and numpy."""
import math
from PIL import Image, ImageDraw

SIZE = 512
RIDGE = (255, 0, 0)       # profile 1 in (R, G, B) order: the main crests
SPUR = (220, 0, 0)        # profile 0: the lower spurs


def blank():
    return Image.new("RGB", (SIZE, SIZE), (255, 255, 255))


def polyline(draw, points, colour, width=3):
    draw.line(points, fill=colour, width=width, joint="curve")


def mountain_range():
    im = blank()
    d = ImageDraw.Draw(im)
    main = [(40 + t * 4.3, 380 - 240 * t / 100 + 30 * math.sin(t / 12.0)) for t in range(0, 101)]
    polyline(d, main, RIDGE)
    for (x, y, dx, dy) in [(120, 330, -50, -90), (200, 300, 40, 110), (300, 250, -70, -100),
                           (370, 200, 60, 120), (450, 150, -30, -100), (250, 270, 90, 60)]:
        polyline(d, [(x, y), (x + dx * 0.6, y + dy * 0.5), (x + dx, y + dy)], SPUR)
    im.save("mountain_range_strokes.png")


def crater_field():
    im = blank()
    d = ImageDraw.Draw(im)
    for (cx, cy, r) in [(180, 200, 90), (380, 330, 60), (360, 110, 35), (110, 420, 40)]:
        d.ellipse([cx - r, cy - r, cx + r, cy + r], outline=RIDGE, width=3)
    for (x, y) in [(450, 470), (60, 60), (470, 220), (260, 460)]:
        d.ellipse([x - 3, y - 3, x + 3, y + 3], fill=SPUR)
    im.save("crater_field_strokes.png")


def valley_pair():
    im = blank()
    d = ImageDraw.Draw(im)
    for x in (70, 250, 440):
        polyline(d, [(x + 25 * math.sin(y / 70.0), y) for y in range(20, 500, 10)], RIDGE)
    im.save("valley_pair_strokes.png")


def write_csv(name, rows):
    with open(name, "w") as f:
        f.write("distance,height,profile\n")
        for r in rows:
            f.write("%g,%g,%d\n" % r)


def profiles():
    # Mountains: 0 rounded spurs, 1 sharp main crest with long flanks.
    write_csv("mountain_profiles.csv",
              [(0, 1.0, 0), (30, 0.8, 0), (70, 0.35, 0), (110, 0.0, 0),
               (0, 1.0, 1), (15, 0.75, 1), (60, 0.35, 1), (160, 0.0, 1)])
    # Craters: 0 hills, 1 rim outside (steep then a long apron), 2 the bowl inside.
    write_csv("crater_profiles.csv",
              [(0, 1.0, 0), (20, 0.7, 0), (60, 0.0, 0),
               (0, 1.0, 1), (8, 0.6, 1), (40, 0.25, 1), (120, 0.0, 1),
               (0, 1.0, 2), (10, 0.45, 2), (25, 0.32, 2), (200, 0.0, 2)])
    # Valleys: V straight flanks to a crease; U steep walls and a round floor.
    write_csv("valley_v_profile.csv", [(0, 1.0, 0), (100, 0.0, 0)])
    write_csv("valley_u_profile.csv", [(0, 1.0, 0), (15, 0.9, 0), (45, 0.35, 0), (70, 0.08, 0), (100, 0.0, 0)])


if __name__ == "__main__":
    mountain_range()
    crater_field()
    valley_pair()
    profiles()
