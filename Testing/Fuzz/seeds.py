#!/usr/bin/python3
"""Writes the hand-made seed inputs of the fuzz targets into OUT/<target>/.

The corpora in corpus/ started from these and grew by fuzzing (merged with
-merge=1); run this only to start a corpus afresh: python3 seeds.py OUT
(Debian's /usr/bin/python3, which has numpy, PIL and GDAL's bindings).
"""
import io
import json
import math
import os
import struct
import sys
import tempfile

import numpy as np
from osgeo import gdal, osr
from PIL import Image

gdal.UseExceptions()
SIDECAR_FLAG = 0x80
# The heightfield_reader's file names, as FuzzHeightfieldReader.cxx lists them.
NAMES = ["input.tif", "input.png", "input.asc", "N45E006.hgt", "input.xyz", "input.dem",
         "input.jpg", "input.gif", "input.bmp", "input.img", "input.bil", "input.vrt"]


def write(out, target, name, data):
    folder = os.path.join(out, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def raster_bytes(driver, array, gdal_type, options=(), nodata=None, geo=True, epsg=4326):
    """A small raster written by GDAL and read back as bytes."""
    with tempfile.TemporaryDirectory() as d:
        ext = {"GTiff": "tif", "PNG": "png", "HFA": "img", "netCDF": "nc", "AAIGrid": "asc",
               "XYZ": "xyz", "JPEG": "jpg", "GIF": "gif", "BMP": "bmp"}[driver]
        path = os.path.join(d, "x." + ext)
        bands = 1 if array.ndim == 2 else array.shape[0]
        h, w = array.shape[-2:]
        mem = gdal.GetDriverByName("MEM").Create("", w, h, bands, gdal_type)
        for b in range(bands):
            band = mem.GetRasterBand(b + 1)
            band.WriteArray(array if bands == 1 else array[b])
            if nodata is not None:
                band.SetNoDataValue(nodata)
        if geo:
            mem.SetGeoTransform([6.0, 1 / 1200.0, 0, 45.0, 0, -1 / 1200.0])
            srs = osr.SpatialReference()
            srs.ImportFromEPSG(epsg)
            mem.SetProjection(srs.ExportToWkt())
        gdal.GetDriverByName(driver).CreateCopy(path, mem, options=list(options))
        with open(path, "rb") as f:
            return f.read()


def heightfield_seeds(out):
    y, x = np.mgrid[0:12, 0:12]
    hills = (100 + 40 * np.sin(x / 2.0) * np.cos(y / 3.0)).astype(np.float32)
    seeds = {
        "tif_float32": (0, raster_bytes("GTiff", hills, gdal.GDT_Float32)),
        "tif_int16_nodata_deflate": (0, raster_bytes(
            "GTiff", hills.astype(np.int16), gdal.GDT_Int16, ["COMPRESS=DEFLATE"], nodata=-9999,
            epsg=32632)),
        "tif_tiled_uint16": (0, raster_bytes(
            "GTiff", (hills * 100).astype(np.uint16), gdal.GDT_UInt16,
            ["TILED=YES", "BLOCKXSIZE=16", "BLOCKYSIZE=16"], geo=False)),
        "png_grey8": (1, raster_bytes("PNG", hills.astype(np.uint8), gdal.GDT_Byte, geo=False)),
        "png_rgb": (1, raster_bytes("PNG", np.stack([hills.astype(np.uint8)] * 3), gdal.GDT_Byte,
                                    geo=False)),
        "asc_nodata": (2, b"ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 30\n"
                          b"NODATA_value -9999\n1 2 3 4\n5 -9999 7 8\n9 10 11 12\n"),
        "asc_huge_header": (2, b"ncols 100000\nnrows 100000\nxllcorner 0\nyllcorner 0\n"
                               b"cellsize 30\n1 2 3 4\n"),
        "xyz": (4, b"0 0 10\n30 0 11\n60 0 12\n0 30 13\n30 30 14\n60 30 15\n"),
        "jpg": (6, raster_bytes("JPEG", hills.astype(np.uint8), gdal.GDT_Byte, geo=False)),
        "gif_palette": (7, raster_bytes("GIF", hills.astype(np.uint8), gdal.GDT_Byte, geo=False)),
        "bmp": (8, raster_bytes("BMP", hills.astype(np.uint8), gdal.GDT_Byte, geo=False)),
        "vrt_huge": (11, b'<VRTDataset rasterXSize="200000" rasterYSize="200000">'
                         b'<VRTRasterBand dataType="Float32" band="1"></VRTRasterBand>'
                         b'</VRTDataset>'),
    }
    for name, (selector, data) in seeds.items():
        write(out, "heightfield_reader", name, bytes([selector]) + data)
    # A 16-bit PNG with a sidecar cut off its end.
    sidecar = json.dumps({"z_unit": "ft", "cell_size_m": [30, 25], "z_min": 100, "z_max": 900,
                          "nodata": 0}).encode()
    png16 = raster_bytes("PNG", (hills * 300).astype(np.uint16), gdal.GDT_UInt16, geo=False)
    write(out, "heightfield_reader", "png16_sidecar",
          bytes([1 | SIDECAR_FLAG, len(sidecar)]) + png16 + sidecar)


def sidecar_seeds(out):
    docs = {
        "full": {"z_unit": "ft", "cell_size_m": 30.0, "z_min": -10, "z_max": 4000, "nodata": 0},
        "xy_cells": {"z_unit": "metres", "cell_size_m": [12.5, 25]},
        "range_only": {"z_min": 0.5, "z_max": 0.75},
        "bad_unit": {"z_unit": "furlong"},
        "bad_cell": {"cell_size_m": [1, 2, 3]},
    }
    for name, doc in docs.items():
        write(out, "sidecar", name, json.dumps(doc).encode())
    write(out, "sidecar", "not_json", b'{"z_unit": "m",')
    write(out, "sidecar", "big_number", b'{"nodata": 1e999}')
    write(out, "sidecar", "array", b"[1, 2, {\"z_min\": 3}]")


def sketch_image(width, height, channels, pixels):
    return bytes([width - 2, height - 2, channels - 1]) + pixels


def sketch_seeds(out):
    w = h = 40
    rgb = np.full((h, w, 3), 255, np.uint8)
    for t in range(w):
        rgb[t, t] = [230, 20, 20]  # a red ridge on the diagonal
        rgb[max(0, t - 1), t] = [230, 20, 20]
        rgb[h // 2, t] = [20, 20, 230]  # a blue valley across
    # Bytes: patch (1 + b % 16), upscale (1 + b % 2), then the image.
    write(out, "sketch", "strokes_rgb", bytes([15, 0]) + sketch_image(w, h, 3, rgb.tobytes()))
    rgba = np.concatenate([rgb, np.full((h, w, 1), 255, np.uint8)], axis=2)
    write(out, "sketch", "strokes_rgba_upscaled",
          bytes([7, 1]) + sketch_image(w, h, 4, rgba.tobytes()))
    y, x = np.mgrid[0:32, 0:32]
    grey = np.where(np.abs(x - y) < 3, 220, 40).astype(np.uint8)
    write(out, "sketch", "grey_ridge", bytes([15, 0]) + sketch_image(32, 32, 1, grey.tobytes()))
    ga = np.stack([grey, np.full_like(grey, 255)], axis=2)
    write(out, "sketch", "grey_alpha", bytes([3, 1]) + sketch_image(32, 32, 2, ga.tobytes()))
    write(out, "sketch", "tiny", bytes([0, 0, 0, 0, 2, 200, 10, 10]))


def ppa_field(width, height, heights, codes=None):
    """Bytes: half profile, significance, presmoothing, width, height, cell exponents, cells."""
    body = bytearray()
    for k, z in enumerate(heights):
        code = 4 if codes is None or codes[k] is None else codes[k]
        if code >= 4:
            v = int(round(z * 16)) + 32768
            code, value = v >> 8, v & 0xFF
            code = max(code, 4)
        else:
            value = 0
        body += bytes([code, value])
    return bytes([2, 1, 1, width - 2, height - 2, 5, 5]) + bytes(body)


def ppa_seeds(out):
    w = h = 24
    ridge = [100 + 50 * math.cos((i - j) / 4.0) for j in range(h) for i in range(w)]
    write(out, "ppa", "ridges", ppa_field(w, h, ridge))
    codes = [None] * (w * h)
    for k in range(0, w * h, 7):
        codes[k] = 0  # nodata
    codes[50], codes[51], codes[52] = 1, 2, 3  # NaN, +inf, -inf left valid
    write(out, "ppa", "ridges_nodata_nan_inf", ppa_field(w, h, ridge, codes))
    flat = [5.0] * (16 * 16)
    write(out, "ppa", "flat", ppa_field(16, 16, flat))
    cone = [200 - 3 * math.hypot(i - 20, j - 20) for j in range(40) for i in range(40)]
    write(out, "ppa", "cone", ppa_field(40, 40, cone))


VTP_HEAD = b"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
"""


def vtp_lines(points, connectivity, offsets, types, elevation=None, grid=None):
    """An ASCII .vtp with poly-line cells, FeatureType per cell, optional Elevation and frame."""
    def nums(values):
        return " ".join(repr(v) for v in values).encode()
    doc = VTP_HEAD
    if grid is not None:
        doc += (b'    <FieldData>\n      <DataArray type="Int32" Name="GridSize" '
                b'NumberOfTuples="2" format="ascii">' + nums(grid[0]) + b"</DataArray>\n"
                b'      <DataArray type="Float64" Name="CellSize" NumberOfTuples="2" '
                b'format="ascii">' + nums(grid[1]) + b"</DataArray>\n    </FieldData>\n")
    doc += (b'    <Piece NumberOfPoints="%d" NumberOfVerts="0" NumberOfLines="%d" '
            b'NumberOfStrips="0" NumberOfPolys="0">\n' % (len(points) // 3, len(offsets)))
    if elevation is not None:
        doc += (b'      <PointData><DataArray type="Float32" Name="Elevation" format="ascii">'
                + nums(elevation) + b"</DataArray></PointData>\n")
    doc += (b'      <CellData><DataArray type="Int32" Name="FeatureType" format="ascii">'
            + nums(types) + b"</DataArray></CellData>\n")
    doc += (b'      <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">'
            + nums(points) + b"</DataArray></Points>\n")
    doc += (b'      <Lines><DataArray type="Int64" Name="connectivity" format="ascii">'
            + nums(connectivity) + b"</DataArray>\n"
            b'      <DataArray type="Int64" Name="offsets" format="ascii">' + nums(offsets)
            + b"</DataArray></Lines>\n")
    return doc + b"    </Piece>\n  </PolyData>\n</VTKFile>\n"


def polyline_seeds(out):
    # A Y of ridges (metres, 30 m cells) meeting at a branch, and a valley.
    y_points = [600, 100, 0, 600, 900, 0, 200, 1500, 0, 1000, 1500, 0, 200, 300, 0, 1100, 400, 0]
    write(out, "polylines", "y_ridges_valley",
          vtp_lines(y_points, [0, 1, 2, 1, 3, 4, 5], [2, 3, 5, 7], [1, 1, 1, -1]))
    write(out, "polylines", "framed_elevation",
          vtp_lines([0, 0, 0, 900, 900, 0, 1800, 0, 0], [0, 1, 2], [3], [1],
                    elevation=[100.0, float("nan"), 300.0], grid=([64, 64], [30.0, 30.0])))
    square = [300, 300, 0, 900, 300, 0, 900, 900, 0, 300, 900, 0]
    write(out, "polylines", "closed_loop",
          vtp_lines(square, [0, 1, 2, 3, 0], [5], [-1]))
    # Generator lines of tsynth distance: per-point costs and a profile per cell.
    write(out, "polylines", "distance_generators",
          vtp_lines(y_points, [0, 1, 2, 1, 3, 4, 5], [2, 3, 5, 7], [1, 1, 1, -1]).replace(
              b"<CellData>", b'<CellData><DataArray type="Int32" Name="Profile" format="ascii">'
              b"0 1 -1 2</DataArray>").replace(
              b"</CellData>", b'</CellData>\n      <PointData><DataArray type="Float32" '
              b'Name="Cost" format="ascii">1 2 nan 4 5 6</DataArray></PointData>'))
    write(out, "polylines", "no_feature_type",
          vtp_lines(y_points[:9], [0, 1, 2], [3], []).replace(
              b'<CellData><DataArray type="Int32" Name="FeatureType" format="ascii">'
              b"</DataArray></CellData>\n", b""))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "seeds"
    heightfield_seeds(out)
    sidecar_seeds(out)
    sketch_seeds(out)
    ppa_seeds(out)
    polyline_seeds(out)
    print("seeds written to", out)


if __name__ == "__main__":
    main()
