#!/usr/bin/env python3
"""Local re-synthesis of an edit (tsynth synth --previous, Kernels/Synthesis/TileRecord.h):
its time against a full tiled synthesis of the same edited sketch, taken pair by pair
in the same run, and whether the two terrains are the same bits.

Cases, at 1024 x 1024 cells from the bundled Colorado DEM, in tiles of 256:
  wide ridges    two ridges 720 cells apart; the east one moved 24 cells
  Y, valley      the bundled Y of ridges; its south-west valley moved 24 cells
  drainage only  the bundled Y unchanged, --drainage breach added (the finishing alone)

Usage: bench_local_edit.py [--runs N] [build dir]
Prints per case the median seconds of each, their median ratio (re-synthesis / full),
how many of the tile passes were taken over, and "same bits" or "DIFFERENT" (exit 1).
"""
import argparse
import filecmp
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "Testing", "Python"))
import sketch_drawing  # noqa: E402

SIZE = 1024
TILE = 256
MOVE = 24  # cells the edit moves a stroke (12 pixels of the 512-pixel Y)


def wide_ridges(path, shift):
    canvas = sketch_drawing.Canvas(SIZE, SIZE)
    canvas.polyline([(150, 120), (180, 900)], sketch_drawing.RIDGE)
    canvas.polyline([(850 + shift, 120), (870 + shift, 900)], sketch_drawing.RIDGE)
    return canvas.save(path)


def y_with_valley_moved(path, shift):
    """The bundled Y's pixels with its south-west valley (the blue stroke left of x 150) moved."""
    import zlib
    import struct
    source = os.path.join(ROOT, "Data", "sketches", "strokes_y_ridges.png")
    width, height, rows = read_rgb_png(source, zlib, struct)
    canvas = sketch_drawing.Canvas(width, height)
    for y in range(height):
        for x in range(width):
            canvas.pixels[y][x] = rows[y][x]
    for y in range(height):
        for x in range(width):
            r, g, b = rows[y][x]
            if b > 128 and r < 100 and x < 150 and y > 290:
                canvas.pixels[y][x] = sketch_drawing.WHITE
    for y in range(height):
        for x in range(width):
            r, g, b = rows[y][x]
            if b > 128 and r < 100 and x < 150 and y > 290 and x + shift // 2 < width:
                canvas.pixels[y][x + shift // 2] = (r, g, b)
    return canvas.save(path)


def read_rgb_png(path, zlib, struct):
    """An 8-bit RGB PNG without interlacing, as rows of (r, g, b) (standard library only)."""
    with open(path, "rb") as f:
        data = f.read()
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour != 2:
                raise SystemExit(f"{path}: expected an 8-bit RGB PNG")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - 3] if i >= 3 else 0
            up = previous[i]
            corner = previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[3 * x:3 * x + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def synth(tsynth, sketch, out, *extra):
    report = out + ".report.json"
    start = time.perf_counter()
    result = subprocess.run([tsynth, "synth", "--exemplar", os.path.join(ROOT, "Data", "dems", "colorado.png"),
                             "--sketch", sketch, "--size", f"{SIZE}x{SIZE}", "-o", out, "--report", report,
                             "--no-progress", *extra], capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if result.returncode != 0:
        raise SystemExit(f"tsynth synth failed: {result.stderr.strip()}")
    with open(report) as f:
        return seconds, json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    parser.add_argument("--runs", type=int, default=3, help="pairs per case (default 3)")
    options = parser.parse_args()
    tsynth = os.path.join(options.build, "bin", "tsynth")
    different = False
    with tempfile.TemporaryDirectory(prefix="tsynth-edit-") as tmp:
        path = lambda name: os.path.join(tmp, name)  # noqa: E731
        cases = [("wide ridges", wide_ridges(path("wide0.png"), 0), wide_ridges(path("wide1.png"), MOVE), ()),
                 ("Y, valley", y_with_valley_moved(path("y0.png"), 0), y_with_valley_moved(path("y1.png"), MOVE), ()),
                 ("drainage only", y_with_valley_moved(path("d0.png"), 0), path("d0.png"), ("--drainage", "breach"))]
        for label, before, after, extra in cases:
            synth(tsynth, before, path("before.tif"), "--tile-size", str(TILE), "--keep-tiles")
            full, local, ratios, taken, same = [], [], [], [], True
            for _ in range(options.runs):
                f, _ = synth(tsynth, after, path("full.tif"), "--tile-size", str(TILE), *extra)
                e, report = synth(tsynth, after, path("edit.tif"), "--previous", path("before.tif"), *extra)
                full.append(f)
                local.append(e)
                ratios.append(e / f)
                taken.append((report["tiles_taken_over"], len(report["tiles"])))
                same &= filecmp.cmp(path("full.tif"), path("edit.tif"), shallow=False)
            different |= not same
            print(f"{label:14s} full {statistics.median(full):6.2f} s, re-synthesis {statistics.median(local):6.2f} s, "
                  f"ratio {statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f}); "
                  f"{taken[0][0]} of {taken[0][1]} tile passes taken over; "
                  f"{'same bits' if same else 'DIFFERENT'}")
            times = report["times_s"]
            print(f"{'':14s} re-synthesis stages: " + ", ".join(f"{k} {v:.2f}" for k, v in times.items()))
    return 1 if different else 0


if __name__ == "__main__":
    sys.exit(main())
