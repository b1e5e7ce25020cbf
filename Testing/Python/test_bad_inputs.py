"""A catalogue of bad inputs to every tsynth command (issue 14): each must end with a non-zero exit,
exactly one clear sentence on stderr naming what is wrong, no output file (not even a partial one)
and no hang. The bad files are generated in a temporary folder; the table below is the catalogue.

Argument tokens: "@name" is the fixture `name` made by make_fixtures() in the temporary folder,
"$dem"/"$strokes"/... are bundled data (DATA below), "^name" is an output path in the case's own
empty folder, which must still be empty when the command has failed. Everything else is passed as
it is.
"""
import base64
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

# A failing command must say so within this long (the slowest refusals read two DEMs and a sketch).
CASE_TIMEOUT_S = 120

# (id, arguments, exit status, regex the one stderr sentence must match)
CASES = [
    # Readers: truncated, corrupt, empty, zero-size, huge, NaN/inf, all-nodata -------------------
    ("tif-truncated", ["info", "@truncated.tif"], 1, r"truncated\.tif.*(truncated|corrupt|not a raster)"),
    ("tif-corrupt-strips", ["convert", "@corrupt.tif", "-o", "^out.tif"], 1,
     r"corrupt\.tif.*(truncated|corrupt)"),
    ("tif-header-only", ["render", "@header-only.tif", "-o", "^out.png"], 1,
     r"header-only\.tif.*(truncated|corrupt)"),
    ("png-truncated", ["convert", "@truncated.png", "-o", "^out.tif"], 1,
     r"truncated\.png.*(truncated|corrupt)"),
    ("png-bad-crc", ["info", "@badcrc.png"], 1, r"badcrc\.png is not a raster .*(invalid|CRC|corrupt)"),
    ("png-huge-header", ["info", "@huge.png"], 1, r"huge\.png is 1000000 x 1000000 cells: reading it needs about 10000 GB, more than"),
    ("tif-huge-header", ["convert", "@huge.tif", "-o", "^out.tif"], 1, r"huge\.tif.*memory"),
    ("empty-file", ["pits", "@empty.tif", "-o", "^out.tif"], 1, r"empty"),
    ("zero-cells-asc", ["info", "@zero.asc"], 1, r"zero\.asc.*(zero size|not a raster)"),
    ("one-pixel-exemplar", ["synth", "--exemplar", "@one.tif", "--sketch", "$strokes", "-o", "^out.tif"], 1,
     r"one\.tif.*(1 x 1|smaller than|too small)"),
    ("one-pixel-pits", ["pits", "@one.tif", "-o", "^out.tif"], 1, r"flat|one cell|1 x 1"),
    ("one-pixel-source", ["optimise", "--exemplar", "@one.tif", "--guide", "$grey", "-o", "^out.tif"], 1,
     r"source.*(flat|smaller|too small)"),
    ("all-nan-tif", ["render", "@allnan.tif", "-o", "^out.png"], 1, r"allnan\.tif.*no valid heights"),
    ("all-inf-tif", ["convert", "@allinf.tif", "-o", "^out.tif"], 1, r"allinf\.tif.*no valid heights"),
    ("all-nodata-tif", ["features", "@nodata.tif", "-o", "^out.vtp"], 1, r"nodata\.tif.*no valid heights"),
    ("all-nodata-asc", ["pits", "@nodata.asc", "-o", "^out.tif"], 1, r"no valid heights"),
    ("extreme-heights", ["pits", "@extreme.tif", "-o", "^out.tif"], 1, r"extreme\.tif.*heights? .*(beyond|m)"),
    ("synth-all-nan-exemplar", ["synth", "--exemplar", "@allnan.tif", "--sketch", "$strokes", "-o", "^out.tif"],
     1, r"allnan\.tif.*no valid heights"),
    ("directory-as-dem", ["evaluate", "@", "--exemplar", "$dem"], 1, r"is a directory"),
    ("text-as-dem", ["info", "@readme.tif"], 1, r"readme\.tif is not a raster"),
    ("fifo-as-dem", ["info", "@pipe.tif"], 1, r"pipe\.tif.*not a (regular file|raster)"),
    ("dev-zero-as-dem", ["info", "/dev/zero"], 1, r"/dev/zero.*not a (regular file|raster)"),
    # Odd rasters (issue 25) -----------------------------------------------------------------------
    ("complex-raster", ["info", "@complex.tif"], 1, r"complex\.tif stores complex values \(CFloat32\)"),
    ("complex-exemplar", ["synth", "--exemplar", "@complex.tif", "--sketch", "$strokes", "-o", "^out.tif"], 1,
     r"complex values"),
    ("one-valid-cell-exemplar", ["synth", "--exemplar", "@onecell.tif", "--sketch", "$strokes", "--patch", "32",
                                 "-o", "^out.tif"], 1,
     r"onecell\.tif holds no 32 x 32 window without nodata \(1 valid cells of 14400\)"),
    ("vti-nan-spacing", ["info", "@nan-spacing.vti"], 1, r"nan-spacing\.vti has Spacing \"nan nan 1\""),
    ("vtp-zlib-damaged", ["synth", "--exemplar", "$dem", "--sketch", "@zlib-damaged.vtp", "-o", "^out.tif"], 1,
     r"zlib-damaged\.vtp is damaged: some of its compressed data does not decompress"),
    ("vtp-zlib-damaged-features", ["features", "@zlib-damaged.vtp", "--sketch", "-o", "^out.vtp"], 1,
     r"zlib-damaged\.vtp is damaged"),
    ("profile-extra-column", ["distance", "--generators", "$distance", "--profiles", "@extra-column.csv",
                              "-o", "^out.tif"], 1, r"extra-column\.csv line 2: \"7\" is one column too many"),
    ("height-scale-beyond-any-terrain", ["distance", "--generators", "$distance", "--height-scale", "1e30",
                                         "-o", "^out.tif"], 1,
     r"Cannot write .*out\.tif: its heights reach .* beyond the \+-1e\+12 m"),
    ("optimise-source-smaller-than-scale", ["optimise", "--exemplar", "@small-slope.tif", "--guide", "$grey", "-o",
                                            "^out.tif"], 1, r"reduce the guide's landform scale\.$"),
    # Sidecars -----------------------------------------------------------------------------------
    ("sidecar-bad-json", ["info", "@badjson/dem.png"], 1, r"not valid JSON"),
    ("sidecar-wrong-unit", ["convert", "@badunit/dem.png", "-o", "^out.tif"], 1, r"z_unit.*\"m\" or \"ft\""),
    ("sidecar-negative-cell", ["render", "@badcell/dem.png", "-o", "^out.png"], 1,
     r"cell_size_m.*positive"),
    ("sidecar-range-reversed", ["info", "@badrange/dem.png"], 1, r"z_max.*greater than.*z_min"),
    ("sidecar-not-object", ["pits", "@badtype/dem.png", "-o", "^out.tif"], 1, r"JSON object"),
    ("sidecar-nan-cell", ["info", "@nancell/dem.png"], 1, r"nancell/dem\.json is not valid JSON"),
    ("sidecar-unreadable", ["info", "@dirsidecar/dem.png"], 1, r"Cannot read sidecar"),
    # Read options -------------------------------------------------------------------------------
    ("cell-inf", ["info", "$dem", "--cell", "inf"], 2, r"--cell.*positive"),
    ("cell-nan", ["convert", "$dem", "--cell", "nan", "-o", "^out.tif"], 2, r"--cell.*positive"),
    ("z-range-infinite", ["info", "$dem", "--z-range", "-inf,inf"], 2, r"--z-range"),
    # The Terrain Reader's ZMin/ZMax range (the read options table), as one sentence.
    ("z-range-beyond-earth", ["info", "$dem", "--z-range", "0,2e6"], 2,
     r"--z-range's MAX expects a number from -1000000 to 1000000, not 2000000\."),
    ("cell-beyond-earth", ["info", "$dem", "--cell", "2e7"], 2, r"--cell .*at most 10000000"),
    ("z-unit-unknown", ["info", "$dem", "--z-unit", "furlong"], 2, r"--z-unit must be auto, m or ft"),
    # render -------------------------------------------------------------------------------------
    ("render-size-overflow", ["render", "$dem", "--3d", "--size", "99999999999x5", "-o", "^out.png"], 2,
     r"--size.*16 and 8192"),
    ("render-size-negative", ["render", "$dem", "--3d", "--size", "-5x100", "-o", "^out.png"], 2,
     r"--size.*16 and 8192"),
    ("render-size-trailing", ["render", "$dem", "--3d", "--size", "100x100junk", "-o", "^out.png"], 2,
     r"--size.*16 and 8192"),
    ("render-altitude-nan", ["render", "$dem", "--altitude", "nan", "-o", "^out.png"], 2, r"--altitude"),
    ("render-azimuth-inf", ["render", "$dem", "--azimuth", "inf", "-o", "^out.png"], 2, r"--azimuth"),
    ("render-exaggeration-inf", ["render", "$dem", "--exaggeration", "inf", "-o", "^out.png"], 2,
     r"--exaggeration"),
    # Tiled export and synthesis (issue 22) ------------------------------------------------------
    ("synth-tile-too-small", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--tile-size", "100",
                              "-o", "^out.tif"], 2,
     r"Tiles of 100 cells are too small for patches of 80: a tile must be at least two patches wide \(160 cells\)"),
    ("tiles-png-not-engine-size", ["convert", "$dem", "--tile-size", "250", "-o", "^t.png"], 1,
     r"2\^k \+ 1 samples a side \(33 to 8193\), not 250: try 129 or 257"),
    ("tiles-raw-too-small", ["convert", "$dem", "--tile-size", "17", "-o", "^t.raw"], 1, r"not 17: try 33"),
    ("tiles-too-many", ["convert", "$dem", "--tile-size", "3", "-o", "^t.vrt"], 1,
     r"104976 files, more than 65536: choose larger tiles"),
    ("tiles-size-one", ["convert", "$dem", "--tile-size", "1", "-o", "^t.vrt"], 2, r"--tile-size"),
    ("tiles-vrt-without-size", ["convert", "$dem", "-o", "^t.vrt"], 2, r"give the tile size, --tile-size N"),
    ("tiles-into-a-tif", ["convert", "$dem", "--tile-size", "65", "-o", "^t.tif"], 2, r"-o OUT\.vrt"),
    ("tiles-16bit-with-nodata", ["convert", "@onecell.tif", "--tile-size", "65", "-o", "^t.png"], 1,
     r"14399 cells without data, which a 16-bit engine heightmap cannot mark"),
    # Output paths -------------------------------------------------------------------------------
    ("out-missing-folder", ["convert", "$dem", "-o", "^missing/out.tif"], 1, r"does not exist"),
    ("out-parent-is-file", ["pits", "$dem", "-o", "@readme.tif/out.tif"], 1, r"readme\.tif.*(not a folder|does not exist)"),
    ("out-in-proc", ["convert", "$dem", "-o", "/proc/tsynth-out.tif"], 1, r"Cannot write /proc/tsynth-out\.tif"),
    ("out-is-directory", ["convert", "$dem", "-o", "@folder.tif"], 1, r"folder\.tif: it is a folder"),
    ("render-out-missing-folder", ["render", "$dem", "-o", "^missing/out.png"], 1, r"does not exist"),
    ("features-controls-missing-folder",
     ["features", "$dem", "-o", "^tree.vtp", "--control-points", "^missing/cp.vtp"], 1, r"does not exist"),
    ("synth-report-missing-folder",
     ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "-o", "^out.tif", "--report", "^missing/r.json"], 1,
     r"does not exist"),
    ("synth-debug-dir-under-file",
     ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "-o", "^out.tif", "--debug-dir", "@readme.tif/dbg"], 1,
     r"readme\.tif.*(not a folder|debug)"),
    ("synth-out-in-proc", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "-o", "/proc/tsynth.tif"], 1,
     r"Cannot write /proc/tsynth\.tif"),
    ("pits-flow-missing-folder", ["pits", "$dem", "-o", "^out.tif", "--flow", "^missing/acc.tif"], 1,
     r"does not exist"),
    ("optimise-out-parent-is-file", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "-o", "@readme.tif/o.tif"],
     1, r"readme\.tif.*(not a folder|does not exist)"),
    ("distance-out-missing-folder", ["distance", "--generators", "$distance", "-o", "^missing/d.tif"], 1,
     r"does not exist"),
    # features -----------------------------------------------------------------------------------
    ("features-vtp-huge", ["features", "@huge.vtp", "--sketch", "-o", "^out.vtp"], 1, r"poly-lines.*(span|beyond)"),
    ("features-vtp-nan", ["features", "@nan.vtp", "--sketch", "-o", "^out.vtp"], 1, r"not a finite number"),
    ("features-vtp-negative", ["features", "@negative.vtp", "--sketch", "-o", "^out.vtp"], 1,
     r"poly-lines.*(west or south|span)"),
    ("features-vtp-not-vtk", ["features", "@readme.vtp", "--sketch", "-o", "^out.vtp"], 1,
     r"readme\.vtp is not a VTK poly-data file"),
    ("features-sketch-too-small", ["features", "@tiny-strokes.png", "--sketch", "-o", "^out.vtp"], 1,
     r"smaller than one patch"),
    ("features-patch-absurd", ["features", "$dem", "--patch", "1e9", "-o", "^out.vtp"], 2, r"--patch"),
    # synth --------------------------------------------------------------------------------------
    ("synth-size-overflow", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--size", "99999999999x5",
                             "-o", "^out.tif"], 2, r"--size .* beyond any machine"),
    ("synth-size-negative", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--size", "-5x100",
                             "-o", "^out.tif"], 2, r"--size expects WxH"),
    ("synth-size-zero", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--size", "0x0", "-o", "^out.tif"],
     2, r"--size expects WxH"),
    ("synth-size-below-patch", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--size", "20x20",
                                "-o", "^out.tif"], 1, r"smaller than one patch"),
    ("synth-patch-zero", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--patch", "0", "-o", "^out.tif"],
     2, r"--patch"),
    ("synth-patch-huge", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--patch", "100000",
                          "-o", "^out.tif"], 2, r"--patch"),
    ("synth-patch-odd", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--patch", "81", "-o", "^out.tif"],
     2, r"--patch must be a multiple of 4"),
    ("synth-memory-budget", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--max-memory", "0.001",
                             "-o", "^out.tif"], 1, r"needs about \d+ MB but the memory budget is 1 MB"),
    ("synth-mismatched-cells", ["synth", "--exemplar", "@fine.tif", "--exemplar", "$dem", "--sketch", "$strokes",
                                "-o", "^out.tif"], 1, r"needs about .* GB but the memory budget"),
    ("synth-empty-sketch", ["synth", "--exemplar", "$dem", "--sketch", "@blank.png", "-o", "^out.tif"], 1,
     r"(nothing|no (ridge|line|stroke|feature)).*(drawn|sketch)"),
    ("synth-vtp-huge", ["synth", "--exemplar", "$dem", "--sketch", "@huge.vtp", "-o", "^out.tif"], 1,
     r"poly-lines span"),
    ("synth-vtp-nan", ["synth", "--exemplar", "$dem", "--sketch", "@nan.vtp", "-o", "^out.tif"], 1,
     r"not a finite number"),
    ("synth-vtp-no-lines", ["synth", "--exemplar", "$dem", "--sketch", "@points.vtp", "-o", "^out.tif"], 1,
     r"no lines"),
    ("synth-vtp-short-featuretype", ["synth", "--exemplar", "$dem", "--sketch", "@shorttype.vtp", "-o", "^out.tif"],
     1, r"shorttype\.vtp is damaged: its FeatureType array holds fewer values than its 2 cells need"),
    ("synth-vtp-short-binary-array", ["synth", "--exemplar", "$dem", "--sketch", "@shorttype-bin.vtp",
                                      "-o", "^out.tif"], 1, r"FeatureType array holds fewer values"),
    ("synth-vtp-offsets-short", ["synth", "--exemplar", "$dem", "--sketch", "@offsets-short.vtp", "-o", "^out.tif"],
     1, r"offsets-short\.vtp is damaged: its Lines offsets hold fewer values than their 3 cells need"),
    ("synth-vtp-offsets-falling", ["synth", "--exemplar", "$dem", "--sketch", "@offsets-falling.vtp",
                                   "-o", "^out.tif"], 1, r"offsets-falling\.vtp is damaged: its Lines offsets fall"),
    ("synth-vtp-offsets-huge", ["synth", "--exemplar", "$dem", "--sketch", "@offsets-huge.vtp", "-o", "^out.tif"],
     1, r"connectivity holds fewer point ids than their offsets say \(4000000000\)"),
    ("synth-vtp-claims-1e15-points", ["synth", "--exemplar", "$dem", "--sketch", "@claims-points.vtp", "-o",
                                      "^out.tif"], 1, r"claims-points\.vtp is damaged: it claims 1000000000000000 points"),
    ("evaluate-vtp-connectivity-short", ["evaluate", "$dem", "--exemplar", "$dem", "--sketch",
                                         "@connectivity-short.vtp"], 1, r"connectivity holds fewer point ids"),
    ("distance-vtp-appended-falling", ["distance", "--generators", "@appended-falling.vtp", "-o", "^out.tif"], 1,
     r"appended-falling\.vtp is damaged: its Lines offsets fall"),
    ("features-vtp-appended-short-connectivity", ["features", "@appended-short-connectivity.vtp", "--sketch",
                                                  "-o", "^out.vtp"], 1, r"connectivity holds fewer point ids"),
    ("synth-vti-short-elevation", ["synth", "--exemplar", "@short.vti", "--sketch", "$strokes", "-o", "^out.tif"],
     1, r"short\.vti is damaged: its Elevation array holds fewer values than its 4096 points need"),
    ("info-vti-not-vtk", ["info", "@readme.vti"], 1, r"readme\.vti is not a VTK image file"),
    ("synth-landform-relief", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--landform-relief", "nan",
                               "-o", "^out.tif"], 2, r"--landform-relief"),
    ("synth-seed-negative", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--seed", "-1", "-o", "^out.tif"],
     2, r"--seed expects a whole number"),
    ("synth-regions-colour-image", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--regions", "$strokes",
                                    "-o", "^out.tif"], 1, r"strokes_y_ridges\.png has 3 bands"),
    ("synth-region-bad-map", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--regions", "@labels.png",
                              "--region", "x=y", "-o", "^out.tif"], 1, r"--region|region"),
    ("synth-region-missing-exemplar", ["synth", "--exemplar", "$dem", "--sketch", "$strokes", "--regions",
                                       "@labels.png", "--region", "1=7", "-o", "^out.tif"], 1, r"1=7: exemplar numbers run from 0 to 0"),
    # evaluate -----------------------------------------------------------------------------------
    ("evaluate-missing-terrain", ["evaluate", "@nope.tif", "--exemplar", "$dem"], 1, r"No such file"),
    ("evaluate-no-exemplar", ["evaluate", "$dem"], 2, r"needs an --exemplar"),
    ("evaluate-patch-absurd", ["evaluate", "$dem", "--exemplar", "$dem", "--patch", "-3"], 2, r"--patch"),
    ("evaluate-vtp-far", ["evaluate", "$dem", "--exemplar", "$dem", "--sketch", "@far.vtp"], 1,
     r"poly-lines span .* outside the output"),
    ("evaluate-vtp-short-array", ["evaluate", "$dem", "--exemplar", "$dem", "--sketch", "@shorttype.vtp"], 1,
     r"shorttype\.vtp is damaged: its FeatureType array holds fewer values than its 2 cells need"),
    # pits ---------------------------------------------------------------------------------------
    ("pits-flat", ["pits", "@flat.tif", "-o", "^out.tif"], 1, r"flat"),
    ("pits-sinks-wrong-size", ["pits", "$dem", "--sinks", "@one.tif", "-o", "^out.tif"], 1, r"1 x 1.*648 x 648"),
    ("pits-method-unknown", ["pits", "$dem", "--method", "pour", "-o", "^out.tif"], 2, r"fill.*breach.*hybrid"),
    ("pits-max-depth-nan", ["pits", "$dem", "--method", "hybrid", "--max-depth", "nan", "-o", "^out.tif"], 2,
     r"--max-depth"),
    ("pits-memory-budget", ["pits", "$dem", "--max-memory", "0.0001", "-o", "^out.tif"], 1,
     r"needs about \d+ MB but the memory budget is 0\.1 MB"),
    # optimise -----------------------------------------------------------------------------------
    ("optimise-size-overflow", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--size", "99999999999x5",
                                "-o", "^out.tif"], 2, r"--size .* beyond any machine"),
    ("optimise-size-negative", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--size", "-5x100",
                                "-o", "^out.tif"], 2, r"--size expects WxH"),
    ("optimise-patch-even", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--patch", "8", "-o", "^out.tif"],
     1, r"patch size must be odd"),
    ("optimise-alpha", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--alpha", "2", "-o", "^out.tif"], 2,
     r"--alpha expects a number from 0 to 1, not 2\."),
    ("optimise-levels-too-many", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--levels", "16",
                                  "-o", "^out.tif"], 1, r"pyramid levels"),
    ("optimise-flat-source", ["optimise", "--exemplar", "@flat.tif", "--guide", "$grey", "-o", "^out.tif"], 1,
     r"flat"),
    ("optimise-empty-guide", ["optimise", "--exemplar", "$dem", "--guide", "@blank.png", "-o", "^out.tif"], 1,
     r"(nothing|no (ridge|line|stroke|feature)).*(drawn|guide|sketch)"),
    ("optimise-guide-vtp-nan", ["optimise", "--exemplar", "$dem", "--guide", "@nan.vtp", "-o", "^out.tif"], 1,
     r"not a finite number"),
    ("optimise-memory-budget", ["optimise", "--exemplar", "$dem", "--guide", "$grey", "--max-memory", "0.001",
                                "-o", "^out.tif"], 1, r"needs about \d+ MB but the memory budget is 1 MB"),
    # distance -----------------------------------------------------------------------------------
    ("distance-no-generators", ["distance", "--generators", "@blank.png", "-o", "^out.tif"], 1, r"no generators|no ridge"),
    ("distance-profile-rising", ["distance", "--generators", "$distance", "--profiles", "@rising.csv",
                                 "-o", "^out.tif"], 1, r"profile.*(fall|monoton|rise)"),
    ("distance-profile-garbage", ["distance", "--generators", "$distance", "--profiles", "@garbage.csv",
                                  "-o", "^out.tif"], 1, r"garbage\.csv"),
    ("distance-profile-nan", ["distance", "--generators", "$distance", "--profiles", "@nanprofile.csv",
                              "-o", "^out.tif"], 1, r"nanprofile\.csv|finite|number"),
    ("distance-profile-empty", ["distance", "--generators", "$distance", "--profiles", "@emptyprofile.csv",
                                "-o", "^out.tif"], 1, r"emptyprofile\.csv|no profile|no rows|empty"),
    ("distance-vtp-far", ["distance", "--generators", "@far.vtp", "-o", "^out.tif"], 1, r"no generator"),
    ("distance-vtp-nan", ["distance", "--generators", "@nan.vtp", "-o", "^out.tif"], 1,
     r"point of poly-line 0 is not a finite number"),
    ("distance-vtp-not-vtk", ["distance", "--generators", "@readme.vtp", "-o", "^out.tif"], 1,
     r"readme\.vtp is not a VTK poly-data file"),
    ("distance-size-overflow", ["distance", "--generators", "@line.vtp", "--size", "99999999999x5",
                                "-o", "^out.tif"], 2, r"--size .* beyond any machine"),
    ("distance-size-negative", ["distance", "--generators", "@line.vtp", "--size", "-5x100", "-o", "^out.tif"], 2,
     r"--size expects WxH"),
    ("distance-size-with-image", ["distance", "--generators", "$distance", "--size", "64x64", "-o", "^out.tif"], 2,
     r"--size applies to poly-lines"),
    ("distance-mu-zero", ["distance", "--generators", "$distance", "--mu", "0", "-o", "^out.tif"], 2,
     r"--mu expects a number from 0\.001 to 100, not 0\."),
    ("distance-r-too-large", ["distance", "--generators", "$distance", "--r", "5", "-o", "^out.tif"], 1,
     r"rough|deviation|r "),
    ("distance-cell-nan", ["distance", "--generators", "$distance", "--cell", "nan", "-o", "^out.tif"], 2,
     r"--cell expects a number"),
    ("distance-labels-wrong-size", ["distance", "--generators", "$distance", "--profiles", "$profiles",
                                    "--labels", "@tiny-strokes.png", "-o", "^out.tif"], 1, r"label.*(size|\d+x\d+)"),
    ("distance-edge-weights-wrong-size", ["distance", "--generators", "$distance", "--edge-weights",
                                          "@tiny-strokes.png", "-o", "^out.tif"], 1, r"edge-weight image is 40x40"),
    ("distance-region-profile-missing", ["distance", "--generators", "$distance", "--region-profile", "3",
                                         "-o", "^out.tif"], 1, r"region profile 3 does not exist"),
    ("distance-memory-budget", ["distance", "--generators", "$distance", "--max-memory", "0.0001",
                                "-o", "^out.tif"], 1, r"needs about \d+ MB but the memory budget is 0\.1 MB"),
    # usage --------------------------------------------------------------------------------------
    ("unknown-command", ["synthesise"], 2, r"Unknown command \"synthesise\"\. See \"tsynth --help\""),
    ("option-without-value", ["info", "$dem", "--cell"], 2, r"--cell needs a value"),
]

# Odd but valid inputs: each must succeed (exit 0, only warnings on stderr, its outputs written).
# (id, arguments, outputs it must write)
EDGE_CASES = [
    ("info-one-pixel", ["info", "@one.tif"], []),
    ("render-some-inf-heights", ["render", "@someinf.tif", "-o", "^out.png"], ["out.png"]),
    ("features-strokes-on-border", ["features", "@border.png", "--sketch", "-o", "^tree.vtp"], ["tree.vtp"]),
    ("synth-strokes-on-border", ["synth", "--exemplar", "$dem", "--sketch", "@border.png", "--patch", "32",
                                 "-o", "^out.tif"], ["out.tif"]),
    ("optimise-strokes-on-border", ["optimise", "--exemplar", "$dem", "--guide", "@border.png", "-o", "^out.tif"],
     ["out.tif"]),
    ("distance-strokes-on-border", ["distance", "--generators", "@border.png", "-o", "^out.tif"], ["out.tif"]),
    # Lines from inside the grid to 1e300 m: only what lies on the grid is used, in bounded time.
    ("evaluate-vtp-reaching-1e300", ["evaluate", "$dem", "--exemplar", "$dem", "--sketch", "@huge.vtp"], []),
    ("distance-vtp-reaching-1e300", ["distance", "--generators", "@huge.vtp", "-o", "^out.tif"], ["out.tif"]),
    ("synth-vtp-reaching-1e300-with-size", ["synth", "--exemplar", "$dem", "--sketch", "@huge.vtp", "--size",
                                            "128x128", "--patch", "32", "-o", "^out.tif"], ["out.tif"]),
    # The appended-data fixture undamaged: what the damaged ones are refused for is their damage.
    ("distance-vtp-appended", ["distance", "--generators", "@appended.vtp", "-o", "^out.tif"], ["out.tif"]),
]

DATA = {
    "$dem": ("dems", "colorado.png"),
    "$strokes": ("sketches", "strokes_y_ridges.png"),
    "$grey": ("sketches", "lambda_circle_grey.png"),
}
# Not under Data/: the distance examples.
EXAMPLES = {
    "$distance": ("distance", "valley_pair_strokes.png"),
    "$profiles": ("distance", "mountain_profiles.csv"),
}

# Anything of these in stderr is a crash or garbage, never a sentence for a user.
FORBIDDEN = re.compile(r"Traceback|terminate called|Sanitizer|runtime error|Segmentation|core dumped|"
                       r"unexpected failure|std::|basic_string|what\(\)|Assertion|ERROR: In |"
                       r"ERROR \d+:|Warning \d+:|ERR\||\.tsynth-")


def png_bytes(width, height, rows, colour_type=2, bit_depth=8):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + row for row in rows)
    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def rgb_png(path, width, height, pixel):
    rows = [bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height)]
    with open(path, "wb") as f:
        f.write(png_bytes(width, height, rows))


def float_tiff(path, width, height, value, nodata=None):
    """A baseline little-endian float32 TIFF, one strip; value(x, y) gives the height."""
    pixels = b"".join(struct.pack("<f", value(x, y)) for y in range(height) for x in range(width))
    entries = [(256, 4, 1, width), (257, 4, 1, height), (258, 3, 1, 32), (259, 3, 1, 1), (262, 3, 1, 1),
               (273, 4, 1, 0), (277, 3, 1, 1), (278, 4, 1, height), (279, 4, 1, len(pixels)), (339, 3, 1, 3)]
    extra = b""
    if nodata is not None:
        text = (nodata + "\0").encode()
        entries.append((42113, 2, len(text), 0))
        extra = text
    entries.sort()
    ifd_size = 2 + 12 * len(entries) + 4
    data_offset = 8 + ifd_size
    extra_offset = data_offset + len(pixels)
    ifd = struct.pack("<H", len(entries))
    for tag, kind, count, value_ in entries:
        if tag == 273:
            value_ = data_offset
        if tag == 42113:
            value_ = extra_offset
        if kind == 3:
            ifd += struct.pack("<HHIHH", tag, kind, count, value_, 0)
        else:
            ifd += struct.pack("<HHII", tag, kind, count, value_)
    ifd += struct.pack("<I", 0)
    with open(path, "wb") as f:
        f.write(b"II*\x00" + struct.pack("<I", 8) + ifd + pixels + extra)


def tiff(path, width, height, bits, sample_format, pixels, tags=()):
    """A little-endian baseline TIFF of one strip and one sample per pixel (SampleFormat 1 unsigned,
    2 signed, 3 float, 6 complex float), with extra tags as (tag, type, values): type 3 SHORT or
    12 DOUBLE, the values written after the pixels."""
    entries = [(256, 4, [width]), (257, 4, [height]), (258, 3, [bits]), (259, 3, [1]), (262, 3, [1]),
               (273, 4, None), (277, 3, [1]), (278, 4, [height]), (279, 4, [len(pixels)]),
               (339, 3, [sample_format])] + list(tags)
    entries.sort(key=lambda e: e[0])
    ifd_size = 2 + 12 * len(entries) + 4
    data_offset = 8 + ifd_size
    extra = b""
    ifd = struct.pack("<H", len(entries))
    for tag, kind, values in entries:
        if tag == 273:
            ifd += struct.pack("<HHII", tag, 4, 1, data_offset)
            continue
        packed = b"".join(struct.pack({3: "<H", 4: "<I", 12: "<d"}[kind], v) for v in values)
        if len(packed) <= 4:
            ifd += struct.pack("<HHI", tag, kind, len(values)) + packed.ljust(4, b"\0")
        else:
            offset = data_offset + len(pixels) + len(extra)
            ifd += struct.pack("<HHII", tag, kind, len(values), offset)
            extra += packed
    ifd += struct.pack("<I", 0)
    with open(path, "wb") as f:
        f.write(b"II*\x00" + struct.pack("<I", 8) + ifd + pixels + extra)


def geotiff(path, geokeys, scale=(30.0, 30.0, 0.0)):
    """A 64 x 64 float32 GeoTIFF (UTM-like tie point) with the given GeoKeyDirectory shorts."""
    pixels = b"".join(struct.pack("<f", 1000.0 + 3.0 * x + 2.0 * y) for y in range(64) for x in range(64))
    tiff(path, 64, 64, 32, 3, pixels, [(33550, 12, list(scale)),
                                       (33922, 12, [0.0, 0.0, 0.0, 500000.0, 4500000.0, 0.0]),
                                       (34735, 3, geokeys)])


# GeoKeyDirectory: version 1.1.0, then (key, location, count, value): projected model, pixel is
# area, ProjectedCSTypeGeoKey = the EPSG code.
def projected_geokeys(epsg):
    return [1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, epsg]


def sidecar(path, text):
    with open(os.path.splitext(path)[0] + ".json", "w") as f:
        f.write(text)


def vtp(path, points, lines, feature_types=None, raw_points=None):
    """A VTK XML poly-data file; points are written in binary (base64) so NaN survives."""
    coords = raw_points if raw_points is not None else b"".join(struct.pack("<3d", *p) for p in points)
    n = len(coords) // 24

    def binary(data):
        return base64.b64encode(struct.pack("<I", len(data)) + data).decode()

    connectivity = " ".join(str(i) for line in lines for i in line)
    offsets, total = [], 0
    for line in lines:
        total += len(line)
        offsets.append(str(total))
    cell_data = ""
    if feature_types is not None:
        cell_data = ('<CellData><DataArray type="Int32" Name="FeatureType" format="ascii">%s</DataArray>'
                     '</CellData>' % " ".join(str(t) for t in feature_types))
    line_block = ""
    if lines:
        line_block = ('<Lines><DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>'
                      '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray></Lines>'
                      % (connectivity, " ".join(offsets)))
    verts = ""
    if not lines:
        verts = ('<Verts><DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>'
                 '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray></Verts>'
                 % (" ".join(str(i) for i in range(n)), " ".join(str(i + 1) for i in range(n))))
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">'
                '<PolyData><Piece NumberOfPoints="%d" NumberOfVerts="%d" NumberOfLines="%d" NumberOfStrips="0" '
                'NumberOfPolys="0">%s<Points><DataArray type="Float64" NumberOfComponents="3" format="binary">'
                '%s</DataArray></Points>%s%s</Piece></PolyData></VTKFile>\n'
                % (n, 0 if lines else n, len(lines), cell_data, binary(coords), verts, line_block))


def vtp_appended(path, points, connectivity, offsets, feature_types, connectivity_bytes=None):
    """A VTK XML poly-data file of one piece with every array in raw appended data (UInt32 block sizes);
    connectivity_bytes, if given, is the size its block claims."""
    blocks, arrays = b"", {}
    for name, data in (("points", b"".join(struct.pack("<3d", *p) for p in points)),
                       ("types", struct.pack("<%di" % len(feature_types), *feature_types)),
                       ("connectivity", struct.pack("<%dq" % len(connectivity), *connectivity)),
                       ("offsets", struct.pack("<%dq" % len(offsets), *offsets))):
        size = connectivity_bytes if name == "connectivity" and connectivity_bytes is not None else len(data)
        arrays[name] = len(blocks)
        blocks += struct.pack("<I", size) + data
    with open(path, "wb") as f:
        f.write(('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">'
                 '<PolyData><Piece NumberOfPoints="%d" NumberOfVerts="0" NumberOfLines="%d" NumberOfStrips="0" '
                 'NumberOfPolys="0"><CellData><DataArray type="Int32" Name="FeatureType" format="appended" '
                 'offset="%d"/></CellData><Points><DataArray type="Float64" NumberOfComponents="3" '
                 'format="appended" offset="%d"/></Points><Lines><DataArray type="Int64" Name="connectivity" '
                 'format="appended" offset="%d"/><DataArray type="Int64" Name="offsets" format="appended" '
                 'offset="%d"/></Lines></Piece></PolyData><AppendedData encoding="raw">_'
                 % (len(points), len(feature_types), arrays["types"], arrays["points"], arrays["connectivity"],
                    arrays["offsets"])).encode())
        f.write(blocks)
        f.write(b"</AppendedData></VTKFile>\n")


def make_fixtures(d, bundled):
    join = lambda *p: os.path.join(d, *p)  # noqa: E731
    colorado = os.path.join(bundled, "dems", "colorado.png")
    jackson = os.path.join(bundled, "dems", "mount_jackson_crop601.tif")
    with open(jackson, "rb") as f:
        tif = f.read()
    with open(colorado, "rb") as f:
        png = f.read()
    with open(join("truncated.tif"), "wb") as f:
        f.write(tif[:len(tif) // 3])
    corrupt = bytearray(tif)
    for k in range(len(corrupt) // 2, len(corrupt) - 1000, 7):
        corrupt[k] = 0xFF
    with open(join("corrupt.tif"), "wb") as f:
        f.write(bytes(corrupt))
    with open(join("header-only.tif"), "wb") as f:
        f.write(tif[:16384])
    with open(join("truncated.png"), "wb") as f:
        f.write(png[:len(png) // 2])
    bad = bytearray(png)
    bad[40] ^= 0x55  # inside IHDR/first chunk: its CRC no longer matches
    bad[len(bad) // 2] ^= 0x55
    with open(join("badcrc.png"), "wb") as f:
        f.write(bytes(bad))
    with open(join("huge.png"), "wb") as f:  # a header claiming 10^12 grey pixels
        f.write(png_bytes(1000000, 1000000, [], colour_type=0)[:33] + png_bytes(1, 1, [b"\x00"], colour_type=0)[33:])
    float_tiff(join("huge.tif"), 1, 1, lambda x, y: 1.0)
    with open(join("huge.tif"), "r+b") as f:  # then widen the header to 10^6 x 10^6
        data = bytearray(f.read())
        ifd = 8
        for e in range(struct.unpack_from("<H", data, ifd)[0]):
            at = ifd + 2 + 12 * e
            if struct.unpack_from("<H", data, at)[0] in (256, 257, 278):
                struct.pack_into("<I", data, at + 8, 1000000)
        f.seek(0)
        f.write(bytes(data))
    open(join("empty.tif"), "w").close()
    with open(join("zero.asc"), "w") as f:
        f.write("ncols 0\nnrows 0\nxllcorner 0\nyllcorner 0\ncellsize 30\n")
    float_tiff(join("one.tif"), 1, 1, lambda x, y: 1000.0)
    sidecar(join("one.tif"), '{"cell_size_m": 90}')
    nan = float("nan")
    float_tiff(join("allnan.tif"), 64, 64, lambda x, y: nan)
    sidecar(join("allnan.tif"), '{"cell_size_m": 90}')
    float_tiff(join("allinf.tif"), 64, 64, lambda x, y: float("inf") if (x + y) % 2 else -float("inf"))
    sidecar(join("allinf.tif"), '{"cell_size_m": 90}')
    float_tiff(join("nodata.tif"), 64, 64, lambda x, y: -9999.0, nodata="-9999")
    sidecar(join("nodata.tif"), '{"cell_size_m": 90}')
    with open(join("nodata.asc"), "w") as f:
        f.write("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 30\nNODATA_value -1\n-1 -1 -1\n-1 -1 -1\n")
    float_tiff(join("extreme.tif"), 64, 64, lambda x, y: 3.0e38 if (x * 7 + y * 3) % 5 == 0 else -3.0e38)
    sidecar(join("extreme.tif"), '{"cell_size_m": 90}')
    float_tiff(join("flat.tif"), 200, 200, lambda x, y: 1234.0)
    sidecar(join("flat.tif"), '{"cell_size_m": 90}')
    # 0.01 m cells: the second exemplar (90 m) would be resampled to 58320 x 58320 cells.
    float_tiff(join("fine.tif"), 200, 200, lambda x, y: 0.001 * ((x * 37 + y * 91) % 17))
    sidecar(join("fine.tif"), '{"cell_size_m": 0.01}')
    with open(join("readme.tif"), "w") as f:
        f.write("hello, I am text\n")
    shutil.copy(join("readme.tif"), join("readme.vtp"))
    shutil.copy(join("readme.tif"), join("readme.vti"))
    os.mkfifo(join("pipe.tif"))
    os.mkdir(join("folder.tif"))
    for name, text in (("badjson", '{"z_unit": "ft", "cell_size_m": }'),
                       ("badunit", '{"z_unit": "furlongs"}'),
                       ("badcell", '{"cell_size_m": -90}'),
                       ("badrange", '{"z_min": 100, "z_max": 50}'),
                       ("badtype", '[1, 2, 3]'),
                       ("nancell", '{"cell_size_m": NaN}'),
                       ("dirsidecar", None)):
        os.mkdir(join(name))
        shutil.copy(colorado, join(name, "dem.png"))
        if text is None:
            os.mkdir(join(name, "dem.json"))  # a sidecar that cannot be read
        else:
            sidecar(join(name, "dem.png"), text)
    rgb_png(join("blank.png"), 256, 256, lambda x, y: (255, 255, 255))
    with open(join("labels.png"), "wb") as f:  # two style regions, grey 8-bit
        f.write(png_bytes(128, 128, [bytes(0 if x < 64 else 1 for x in range(128))] * 128, colour_type=0))
    # A ridge along the top row and a valley down the right-hand column, touching the border.
    rgb_png(join("border.png"), 256, 256,
            lambda x, y: (230, 20, 20) if y == 0 and x < 200 else (20, 20, 230) if x == 255 and y > 40
            else (255, 255, 255))
    float_tiff(join("someinf.tif"), 64, 64, lambda x, y: float("inf") if x == y else 100.0 + x * 3 + y)
    sidecar(join("someinf.tif"), '{"cell_size_m": 90}')
    rgb_png(join("tiny-strokes.png"), 40, 40, lambda x, y: (230, 20, 20) if x == y else (255, 255, 255))
    vtp(join("huge.vtp"), [(0, 0, 0), (1e300, 1e300, 0), (10, 10, 0), (2e300, 5, 0)], [[0, 1], [2, 3]], [1, -1])
    vtp(join("nan.vtp"), None, [[0, 1, 2]], [1],
        raw_points=struct.pack("<9d", 100, 100, 0, nan, 2000, 0, 3000, 3000, 0))
    vtp(join("negative.vtp"), [(-5000, -5000, 0), (-100, -200, 0)], [[0, 1]], [1])
    vtp(join("points.vtp"), [(100, 100, 0), (200, 200, 0)], [], None)
    vtp(join("shorttype.vtp"), [(1000, 1000, 0), (20000, 20000, 0), (1000, 20000, 0), (20000, 1000, 0)],
        [[0, 1], [2, 3]], [1])
    vtp(join("line.vtp"), [(500, 2000, 0), (3500, 2000, 0)], [[0, 1]], [1])
    vtp(join("far.vtp"), [(1e300, 1e300, 0), (2e300, 1e300, 0)], [[0, 1]], [1])
    with open(join("shorttype.vtp")) as f:  # the same, its FeatureType array in binary
        text = f.read()
    short = base64.b64encode(struct.pack("<I", 4) + struct.pack("<i", 1)).decode()
    with open(join("shorttype-bin.vtp"), "w") as f:
        f.write(text.replace('format="ascii">1</DataArray></CellData>',
                             'format="binary">%s</DataArray></CellData>' % short))
    # Cell arrays that disagree with their counts: line.vtp's single line [0, 1], offsets "2", altered.
    with open(join("line.vtp")) as f:
        line = f.read()
    lines = ('<DataArray type="Int64" Name="connectivity" format="ascii">0 1</DataArray>'
             '<DataArray type="Int64" Name="offsets" format="ascii">2</DataArray>')
    for name, count, connectivity, offsets in (("offsets-short", 3, "0 1", "2"),
                                               ("offsets-falling", 2, "0 1 1 0", "2 1"),
                                               ("offsets-huge", 1, "0 1", "4000000000"),
                                               ("connectivity-short", 1, "0", "2")):
        with open(join(name + ".vtp"), "w") as f:
            f.write(line.replace('NumberOfLines="1"', 'NumberOfLines="%d"' % count)
                    .replace('format="ascii">1</DataArray></CellData>',
                             'format="ascii">%s</DataArray></CellData>' % " ".join(["1"] * count))
                    .replace(lines, lines.replace(">0 1<", ">%s<" % connectivity).replace(">2<", ">%s<" % offsets)))
    with open(join("claims-points.vtp"), "w") as f:
        f.write(line.replace('NumberOfPoints="2"', 'NumberOfPoints="1000000000000000"'))
    ends = [(500, 2000, 0), (3500, 2000, 0), (500, 3000, 0), (3500, 3000, 0)]
    vtp_appended(join("appended.vtp"), ends, [0, 1, 2, 3], [2, 4], [1, -1])
    vtp_appended(join("appended-falling.vtp"), ends, [0, 1, 2, 3], [4, 2], [1, -1])
    vtp_appended(join("appended-short-connectivity.vtp"), ends, [0, 1, 2, 3], [2, 4], [1, -1], connectivity_bytes=16)
    with open(join("short.vti"), "w") as f:  # 64 x 64 points, an Elevation array of 10 values
        f.write('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">'
                '<ImageData WholeExtent="0 63 0 63 0 0" Origin="0 0 0" Spacing="90 90 1">'
                '<Piece Extent="0 63 0 63 0 0"><PointData Scalars="Elevation">'
                '<DataArray type="Float32" Name="Elevation" format="ascii">%s</DataArray>'
                '</PointData><CellData/></Piece></ImageData></VTKFile>\n' % " ".join(["100"] * 10))
    with open(join("rising.csv"), "w") as f:
        f.write("0,1\n5,0.5\n7,0.8\n")
    with open(join("garbage.csv"), "w") as f:
        f.write("distance,height\nthis,is\nnot,numbers\n")
    with open(join("nanprofile.csv"), "w") as f:
        f.write("0,1\n5,nan\n10,0\n")
    open(join("emptyprofile.csv"), "w").close()
    # Odd rasters (issue 25): signed bytes, complex values, one valid cell, unusual georeferencing.
    signed = [(x * 7 + y * 3) % 200 - 100 for y in range(80) for x in range(80)]
    tiff(join("int8.tif"), 80, 80, 8, 2, struct.pack("<%db" % len(signed), *signed))
    tiff(join("complex.tif"), 32, 32, 64, 6, struct.pack("<%df" % (2 * 32 * 32), *([1.0, 2.0] * 32 * 32)))
    float_tiff(join("onecell.tif"), 120, 120, lambda x, y: 5.0 if (x, y) == (60, 60) else float("nan"), "nan")
    float_tiff(join("small-slope.tif"), 12, 12, lambda x, y: 100.0 + 3.0 * x + 5.0 * y)
    geotiff(join("geo-ok.tif"), projected_geokeys(32613))
    geotiff(join("geo-unknown-epsg.tif"), projected_geokeys(30999))
    geotiff(join("geo-corrupt-keys.tif"), [1, 1, 0, 900, 1024, 0, 1, 1])
    geotiff(join("geo-negative-scale.tif"), projected_geokeys(32613), scale=(30.0, -30.0, 0.0))
    with open(join("extra-column.csv"), "w") as f:
        f.write("distance,height,profile\n0,1,0,7\n5,0.5,0,7\n")


def make_written_fixtures(d, bundled):
    """Damaged copies of files tsynth writes: a .vti with a NaN spacing, a .vtp whose zlib blocks are
    damaged."""
    colorado = os.path.join(bundled, "dems", "colorado.png")
    vti = os.path.join(d, "written.vti")
    vtp_path = os.path.join(d, "written.vtp")
    for args in (["convert", colorado, "-o", vti], ["features", colorado, "-o", vtp_path]):
        r = subprocess.run([PATHS.tsynth] + args, capture_output=True)
        assert r.returncode == 0, r.stderr
    with open(vti) as f:
        text = f.read()
    with open(os.path.join(d, "nan-spacing.vti"), "w") as f:
        f.write(re.sub(r'Spacing="[^"]*"', 'Spacing="nan nan 1"', text, count=1))
    with open(vtp_path, "rb") as f:
        data = f.read()
    payload = re.search(rb'format="binary"[^>]*>\s*([A-Za-z0-9+/=]{200,})', data)
    middle = (payload.start(1) + payload.end(1)) // 2
    with open(os.path.join(d, "zlib-damaged.vtp"), "wb") as f:
        f.write(data[:middle] + b"QUJD" * 8 + data[middle + 32:])


class BadInputTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="tsynth-bad-")
        make_fixtures(cls.tmp, PATHS.bundled_data)
        make_written_fixtures(cls.tmp, PATHS.bundled_data)
        examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples")
        cls.data = {k: os.path.join(PATHS.bundled_data, *v) for k, v in DATA.items()}
        cls.data.update({k: os.path.join(examples, *v) for k, v in EXAMPLES.items()})

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def arguments(self, args, out_dir):
        out = []
        for a in args:
            if a.startswith("@"):
                out.append(os.path.join(self.tmp, a[1:]) if len(a) > 1 else self.tmp)
            elif a.startswith("^"):
                out.append(os.path.join(out_dir, a[1:]))
            else:
                out.append(self.data.get(a, a))
        return out

    def check_case(self, case_id, args, status, pattern):
        out_dir = os.path.join(self.tmp, "out-" + case_id)
        os.mkdir(out_dir)
        try:
            r = subprocess.run([PATHS.tsynth] + self.arguments(args, out_dir), capture_output=True,
                               text=True, errors="replace", timeout=CASE_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self.fail("hung for more than %d s" % CASE_TIMEOUT_S)
        lines = [line for line in r.stderr.splitlines() if line.strip()]
        self.assertGreater(r.returncode, 0, "exit %d (a signal if negative); stderr %r" % (r.returncode, r.stderr))
        self.assertIsNone(FORBIDDEN.search(r.stderr), r.stderr)
        self.assertEqual(len(lines), 1, "expected one sentence, got %r" % r.stderr)
        sentence = lines[0]
        self.assertTrue(sentence.startswith("tsynth: ") and sentence.rstrip().endswith("."), sentence)
        self.assertTrue(all(32 <= ord(c) < 127 for c in sentence), "not plain text: %r" % sentence)
        if os.environ.get("TSYNTH_BAD_INPUT_VERBOSE"):
            print("\n%-34s %d %s" % (case_id, r.returncode, sentence))
        self.assertRegex(sentence, pattern)
        self.assertEqual(r.returncode, status, sentence)
        self.assertNotIn("Wrote ", r.stdout)
        self.assertEqual(os.listdir(out_dir), [], "a failed command left files behind")
        self.assertFalse(os.path.exists("/proc/tsynth-out.tif"))

    def run_tsynth(self, args):
        return subprocess.run([PATHS.tsynth] + args, capture_output=True, timeout=CASE_TIMEOUT_S)

    def test_report_is_valid_json_whatever_the_paths(self):
        """The report is written with nlohmann: quotes, backslashes, a newline and a byte that is not
        UTF-8 in the paths still give valid JSON (the byte replaced), never an error after the
        terrain was written."""
        folder = os.path.join(self.tmp, 'we"ird\\dir')
        os.mkdir(folder)
        out = os.path.join(folder, "o\nut.tif").encode() + b"\xe9.tif"
        report = os.path.join(folder, 'r"\\.json')
        strokes = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        r = self.run_tsynth([b"synth", b"--exemplar", self.data["$dem"].encode(), b"--sketch", strokes.encode(),
                             b"--size", b"128x128", b"--patch", b"32", b"-o", out, b"--report", report.encode(),
                             b"--no-progress"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(report, encoding="utf-8") as f:
            doc = json.load(f)
        self.assertEqual(doc["output"], out.decode("utf-8", errors="replace"))
        self.assertEqual(doc["sketch"], strokes)
        self.assertTrue(os.path.exists(out))

    def test_info_json_keeps_every_character_of_the_path(self):
        name = os.path.join(self.tmp, 'a"b\\c\nd.png')
        shutil.copy(self.data["$dem"], name)
        shutil.copy(os.path.splitext(self.data["$dem"])[0] + ".json", os.path.splitext(name)[0] + ".json")
        r = self.run_tsynth([b"info", name.encode(), b"--json"])
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout.decode("utf-8"))
        self.assertEqual(doc["file"], name)  # the newline too (it used to become a space)
        self.assertEqual((doc["width"], doc["height"]), (648, 648))

    def test_a_flat_exemplar_gives_null_figures_with_a_reason(self):
        """Seam index and slope distance have no scale on a flat exemplar: null with a note, never the 0
        that read as a perfect score; evaluate's text shows "-"."""
        out = os.path.join(self.tmp, "flat-out.tif")
        report = os.path.join(self.tmp, "flat-report.json")
        strokes = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        flat = os.path.join(self.tmp, "flat.tif")
        r = self.run_tsynth(["synth", "--exemplar", flat, "--sketch", strokes, "--size", "128x128", "--patch", "32",
                             "-o", out, "--report", report, "--no-progress"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(report) as f:
            quality = json.load(f)["quality"]
        self.assertIsNone(quality["seam_index"])
        self.assertIsNone(quality["slope_distance"])
        self.assertIn("flat", quality["notes"]["seamIndex"])
        self.assertIn("flat", quality["notes"]["slopeDistance"])
        self.assertGreater(quality["pit_density"], 0.0)  # still measured: it needs no exemplar scale
        r = self.run_tsynth(["evaluate", out, "--exemplar", flat, "--json"])
        self.assertEqual(r.returncode, 0, r.stderr)
        figures = json.loads(r.stdout)["terrain"]
        self.assertIsNone(figures["seam_index"])
        self.assertIsNone(figures["ridge_fidelity"])  # no sketch given
        self.assertEqual(figures["notes"]["ridgeFidelity"], "no sketch given")
        text = self.run_tsynth(["evaluate", out, "--exemplar", flat]).stdout.decode()
        self.assertRegex(text.splitlines()[0], r"seam   -    slope   -  ")

    def test_odd_but_valid_inputs_succeed(self):
        for case_id, args, outputs in EDGE_CASES:
            with self.subTest(case=case_id):
                out_dir = os.path.join(self.tmp, "edge-" + case_id)
                os.mkdir(out_dir)
                try:
                    r = subprocess.run([PATHS.tsynth] + self.arguments(args, out_dir), capture_output=True,
                                       text=True, errors="replace", timeout=CASE_TIMEOUT_S)
                except subprocess.TimeoutExpired:
                    self.fail("hung for more than %d s" % CASE_TIMEOUT_S)
                self.assertEqual(r.returncode, 0, r.stderr)
                others = [line for line in r.stderr.splitlines()
                          if line.strip() and not line.startswith("tsynth: warning: ")]
                self.assertEqual(others, [], r.stderr)
                self.assertIsNone(FORBIDDEN.search(r.stderr), r.stderr)
                self.assertEqual(sorted(os.listdir(out_dir)), sorted(outputs))

    def test_unusual_georeferencing_reads_with_one_warning(self):
        """GDAL's own "Warning 1:" lines never reach the user: an unknown EPSG code, damaged GeoTIFF
        keys and a negative pixel scale read with one tsynth warning naming the file; a sound file
        reads with none."""
        for name, warned in (("geo-ok.tif", False), ("geo-unknown-epsg.tif", True),
                             ("geo-corrupt-keys.tif", True), ("geo-negative-scale.tif", True)):
            with self.subTest(file=name):
                r = subprocess.run([PATHS.tsynth, "info", os.path.join(self.tmp, name), "--json"],
                                   capture_output=True, text=True, timeout=CASE_TIMEOUT_S)
                self.assertEqual(r.returncode, 0, r.stderr)
                lines = [line for line in r.stderr.splitlines() if line.strip()]
                self.assertIsNone(FORBIDDEN.search(r.stderr), r.stderr)
                self.assertEqual(len(lines), 1 if warned else 0, r.stderr)
                if warned:
                    self.assertRegex(lines[0], r"^tsynth: warning: .*%s: GDAL read it with \d warning" % re.escape(name))
                self.assertEqual(json.loads(r.stdout)["width"], 64)

    def test_signed_bytes_are_read_signed(self):
        r = subprocess.run([PATHS.tsynth, "info", os.path.join(self.tmp, "int8.tif"), "--json"],
                           capture_output=True, text=True, timeout=CASE_TIMEOUT_S)
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        self.assertEqual(doc["data_type"], "Int8")
        self.assertEqual((doc["z_min_m"], doc["z_max_m"]), (-100.0, 99.0))

    def test_catalogue(self):
        self.assertGreaterEqual(len(CASES), 40)
        self.assertEqual(len({c[0] for c in CASES}), len(CASES), "case ids must be unique")
        commands = {c[1][0] for c in CASES}
        for command in ("info", "render", "convert", "features", "synth", "evaluate", "pits", "optimise",
                        "distance"):
            self.assertIn(command, commands)
        only = os.environ.get("TSYNTH_BAD_INPUT_CASES")  # a comma-separated subset, for debugging
        for case_id, args, status, pattern in CASES:
            if only and case_id not in only.split(","):
                continue
            with self.subTest(case=case_id):
                self.check_case(case_id, args, status, pattern)



# Issue 25, "nothing lost": an output never replaces an input or another output, a failed write
# (a full disk at any byte) leaves no file and says so, a signal leaves no file, and names of any
# legal length work. Each case runs in its own folder of inputs; every file there must be unchanged
# (byte for byte) after a refusal, and no new file (a temporary included) may appear.

# The write-fault shim (Testing/Fault/WriteFault.cxx), from CTest's environment.
SHIM = os.environ.get("TSYNTH_WRITE_FAULT_SHIM", "")
# The longest file name Linux file systems take (NAME_MAX).
NAME_MAX = 255
STROKES = ("sketches", "strokes_y_ridges.png")
# A small synthesis: enough for every output the command writes, quick even under the sanitizers.
SMALL_SYNTH = ["--size", "128x128", "--patch", "32", "--no-progress"]

# (id, arguments, regex of the one sentence). Tokens: "dem.png" and the rest are the case folder's
# files (make_case_folder); "$strokes" the bundled stroke map. Exit status 1 for all.
SAME_FILE_CASES = [
    ("render-onto-itself", ["render", "dem.png", "-o", "dem.png"], r"-o dem\.png: it is the same file as the DEM"),
    ("synth-onto-exemplar", ["synth", "--exemplar", "t/dem.tif", "--sketch", "$strokes", "-o", "t/dem.tif"]
     + SMALL_SYNTH, r"-o t/dem\.tif: it is the same file as --exemplar t/dem\.tif"),
    ("synth-onto-sketch", ["synth", "--exemplar", "dem.png", "--sketch", "strokes.png", "-o", "strokes.png"]
     + SMALL_SYNTH, r"same file as --sketch strokes\.png"),
    ("pits-flow-is-output", ["pits", "t/dem.tif", "-o", "o.tif", "--flow", "o.tif"],
     r"--flow o\.tif: it is the same file as -o o\.tif"),
    ("pits-streams-is-input", ["pits", "t/dem.tif", "-o", "o.tif", "--streams", "t/dem.tif"],
     r"--streams t/dem\.tif: it is the same file as the DEM"),
    ("report-is-png-sidecar", ["synth", "--exemplar", "dem.png", "--sketch", "$strokes", "-o", "r.png",
                               "--report", "r.json"] + SMALL_SYNTH,
     r"--report r\.json: it is the same file as the sidecar of -o r\.png"),
    ("report-is-exemplar-sidecar", ["synth", "--exemplar", "dem.png", "--sketch", "$strokes", "-o", "r.tif",
                                    "--report", "dem.json"] + SMALL_SYNTH,
     r"--report dem\.json: it is the same file as the sidecar of --exemplar dem\.png"),
    ("report-where-the-tif-sidecar-goes", ["synth", "--exemplar", "dem.png", "--sketch", "$strokes", "-o", "r.tif",
                                           "--report", "r.json"] + SMALL_SYNTH,
     r"--report r\.json: readers of -o r\.tif would take it for that terrain's sidecar"),
    ("debug-dir-holds-output", ["synth", "--exemplar", "dem.png", "--sketch", "$strokes", "-o", "dbg/patches.tif",
                                "--debug-dir", "dbg"] + SMALL_SYNTH,
     r"--debug-dir dbg/patches\.tif: it is the same file as -o dbg/patches\.tif"),
    ("debug-dir-holds-exemplar", ["synth", "--exemplar", "dbg/target.tif", "--sketch", "$strokes", "-o", "o.tif",
                                  "--debug-dir", "dbg"] + SMALL_SYNTH,
     r"--debug-dir dbg/target\.tif: it is the same file as --exemplar dbg/target\.tif"),
    ("convert-png-onto-input-sidecar", ["convert", "u/dem.tif", "-o", "u/dem.png"],
     r"sidecar of -o u/dem\.png.*same file as the sidecar of the DEM u/dem\.tif"),
    ("convert-through-symlink", ["convert", "t/dem.tif", "-o", "link.tif"], r"-o link\.tif: it is the same file as the DEM"),
    ("convert-through-dotdot", ["convert", "t/dem.tif", "-o", "t/../t/dem.tif"], r"same file as the DEM t/dem\.tif"),
    ("convert-onto-hard-link", ["convert", "t/dem.tif", "-o", "hard.tif"], r"-o hard\.tif: it is the same file as the DEM"),
    ("convert-onto-symlinked-folder", ["convert", "t/dem.tif", "-o", "tl/dem.tif"], r"same file as the DEM t/dem\.tif"),
    ("features-output-is-control-points", ["features", "t/dem.tif", "-o", "f.vtp", "--control-points", "f.vtp"],
     r"--control-points f\.vtp: it is the same file as -o f\.vtp"),
    ("features-onto-its-sketch", ["features", "lines.vtp", "--sketch", "-o", "lines.vtp"],
     r"-o lines\.vtp: it is the same file as the sketch"),
    ("optimise-onto-guide", ["optimise", "--exemplar", "dem.png", "--guide", "t/dem.tif", "-o", "t/dem.tif"],
     r"same file as --guide t/dem\.tif"),
    ("distance-onto-generators", ["distance", "--generators", "strokes.png", "-o", "strokes.png"],
     r"same file as --generators strokes\.png"),
    ("output-is-dev-null", ["convert", "t/dem.tif", "-o", "null.tif"], r"null\.tif: it is a device, which an output never replaces"),
    ("output-is-fifo", ["render", "t/dem.tif", "-o", "fifo.png"], r"fifo\.png: it is a pipe \(FIFO\)"),
    ("output-is-folder", ["convert", "t/dem.tif", "-o", "folder.tif"], r"folder\.tif: it is a folder"),
    ("tif-beside-a-foreign-sidecar", ["convert", "dem.png", "-o", "dem.tif"],
     r"-o dem\.tif: dem\.json beside it would be read as its sidecar"),
]


def file_digest(path):
    import hashlib
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def snapshot(folder):
    """Every regular file under folder (symlinks and special files by what they are) and its bytes."""
    state = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            rel = os.path.relpath(path, folder)
            if os.path.islink(path):
                state[rel] = "link:" + os.readlink(path)
            elif os.path.isfile(path):
                state[rel] = file_digest(path)
            else:
                state[rel] = "special" if not os.path.isdir(path) else "folder"
    return state


def can_mount_tmpfs():
    probe = tempfile.mkdtemp(prefix="tsynth-tmpfs-probe-")
    try:
        ok = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", probe],
                            capture_output=True).returncode == 0
        if ok:
            subprocess.run(["umount", probe], capture_output=True)
        return ok
    except OSError:
        return False
    finally:
        os.rmdir(probe)


class NothingLostTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="tsynth-lost-")
        cls.dem = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        cls.strokes = os.path.join(PATHS.bundled_data, *STROKES)
        cls.tif = os.path.join(cls.tmp, "dem.tif")
        r = subprocess.run([PATHS.tsynth, "convert", cls.dem, "-o", cls.tif], capture_output=True)
        assert r.returncode == 0, r.stderr

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def make_case_folder(self, name):
        d = os.path.join(self.tmp, name)
        os.makedirs(os.path.join(d, "t"))
        os.makedirs(os.path.join(d, "u"))
        os.makedirs(os.path.join(d, "dbg"))
        os.makedirs(os.path.join(d, "folder.tif"))
        shutil.copy(self.dem, os.path.join(d, "dem.png"))
        shutil.copy(os.path.splitext(self.dem)[0] + ".json", os.path.join(d, "dem.json"))
        shutil.copy(self.tif, os.path.join(d, "t", "dem.tif"))
        shutil.copy(self.tif, os.path.join(d, "u", "dem.tif"))
        with open(os.path.join(d, "u", "dem.json"), "w") as f:
            f.write('{"cell_size_m": [30, 30]}\n')
        shutil.copy(self.tif, os.path.join(d, "dbg", "target.tif"))
        shutil.copy(self.strokes, os.path.join(d, "strokes.png"))
        vtp(os.path.join(d, "lines.vtp"), [(100.0, 100.0, 0.0), (3000.0, 3000.0, 0.0)], [[0, 1]],
            feature_types=[1])
        os.symlink(os.path.join("t", "dem.tif"), os.path.join(d, "link.tif"))
        os.symlink("t", os.path.join(d, "tl"))
        os.link(os.path.join(d, "t", "dem.tif"), os.path.join(d, "hard.tif"))
        os.symlink("/dev/null", os.path.join(d, "null.tif"))
        os.mkfifo(os.path.join(d, "fifo.png"))
        return d

    def run_in(self, folder, args, env=None, stdout=subprocess.PIPE):
        args = [self.strokes if a == "$strokes" else a for a in args]
        return subprocess.run([PATHS.tsynth] + args, cwd=folder, stdout=stdout, stderr=subprocess.PIPE,
                              text=True, errors="replace", timeout=CASE_TIMEOUT_S, env=env)

    def assert_one_sentence(self, r, pattern):
        lines = [line for line in r.stderr.splitlines() if line.strip()]
        self.assertNotEqual(r.returncode, 0, r.stderr)
        self.assertIsNone(FORBIDDEN.search(r.stderr), r.stderr)
        self.assertEqual(len(lines), 1, "expected one sentence, got %r" % r.stderr)
        self.assertTrue(lines[0].startswith("tsynth: ") and lines[0].endswith("."), lines[0])
        self.assertNotIn(".tsynth-", lines[0], "names a temporary, not the user's file")
        self.assertRegex(lines[0], pattern)

    def test_an_output_never_replaces_an_input_or_another_output(self):
        self.assertGreaterEqual(len(SAME_FILE_CASES), 20)
        for case_id, args, pattern in SAME_FILE_CASES:
            with self.subTest(case=case_id):
                folder = self.make_case_folder("same-" + case_id)
                before = snapshot(folder)
                r = self.run_in(folder, args)
                self.assert_one_sentence(r, pattern)
                self.assertEqual(r.returncode, 1, r.stderr)
                self.assertEqual(snapshot(folder), before, "a refused command changed the folder")
        self.assertTrue(os.path.exists("/dev/null") and not os.path.isfile("/dev/null"))

    def test_names_of_any_legal_length_are_written(self):
        folder = os.path.join(self.tmp, "long-names")
        os.mkdir(folder)
        for name in ("a" * (NAME_MAX - 4) + ".tif", "b" * (NAME_MAX - 5) + ".png", "c" * (NAME_MAX - 4) + ".vti"):
            with self.subTest(length=len(name), ext=name[-4:]):
                r = self.run_in(folder, ["convert", self.tif, "-o", name])
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertTrue(os.path.isfile(os.path.join(folder, name)))
        self.assertEqual([n for n in os.listdir(folder) if n.startswith(".")], [])

    def outputs_of(self, kind):
        """A command writing `kind` into the current folder: its arguments and the files it makes."""
        synth = ["synth", "--exemplar", self.tif, "--sketch", self.strokes] + SMALL_SYNTH
        return {
            "tif": (["convert", self.tif, "-o", "o.tif"], ["o.tif"]),
            "png": (["convert", self.tif, "-o", "o.png"], ["o.json", "o.png"]),
            "vti": (["convert", self.tif, "-o", "o.vti"], ["o.vti"]),
            "vtp": (["features", self.tif, "-o", "o.vtp", "--control-points", "c.vtp"], ["c.vtp", "o.vtp"]),
            "picture": (["render", self.tif, "-o", "o.png"], ["o.png"]),
            "synth": (synth + ["-o", "o.png", "--report", "r.json", "--debug-dir", "dbg"],
                      ["dbg", "o.json", "o.png", "r.json"]),
        }[kind]

    def written_bytes(self, kind):
        folder = tempfile.mkdtemp(dir=self.tmp, prefix="sizes-")
        args, files = self.outputs_of(kind)
        r = self.run_in(folder, args)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(folder)), files)
        total = 0
        for root, _, names in os.walk(folder):
            total += sum(os.path.getsize(os.path.join(root, n)) for n in names)
        return total

    @unittest.skipIf(harness.INSTRUMENTED, "the shim is preloaded before ASan's runtime, which ASan refuses")
    def test_a_write_failing_at_any_byte_leaves_nothing(self):
        """The write-fault shim fails every write to tsynth's temporaries past byte N, as a disk that
        fills up there: for N from the first byte to the last of every format and of a command that
        writes several files, one sentence saying the disk is full, exit 1, and no file at all."""
        self.assertTrue(SHIM and os.path.exists(SHIM), "TSYNTH_WRITE_FAULT_SHIM is not set by CTest")
        cases = 0
        for kind in ("tif", "png", "vti", "vtp", "picture", "synth"):
            total = self.written_bytes(kind)
            for limit in sorted({0, 1, 100, 4096, total // 3, total // 2, total - 4096, total - 1}):
                if limit < 0:
                    continue
                with self.subTest(kind=kind, fail_after=limit, of=total):
                    folder = tempfile.mkdtemp(dir=self.tmp, prefix="fault-%s-%d-" % (kind, limit))
                    env = dict(os.environ, LD_PRELOAD=SHIM, TSYNTH_FAULT_FAIL_AFTER=str(limit))
                    r = self.run_in(folder, self.outputs_of(kind)[0], env=env)
                    self.assert_one_sentence(r, r"Cannot write .*: No space left on device\.$")
                    self.assertEqual(r.returncode, 1)
                    self.assertEqual(os.listdir(folder), [], "a failed write left files behind")
                    cases += 1
        self.assertGreaterEqual(cases, 40)

    @unittest.skipUnless(os.geteuid() == 0 and can_mount_tmpfs(), "mounting a small tmpfs needs root")
    def test_a_full_disk_leaves_nothing(self):
        """On a real full file system (a tmpfs of a few pages): every format, and a PNG that fits
        while its sidecar does not."""
        mount = tempfile.mkdtemp(dir=self.tmp, prefix="tmpfs-")
        def remount(kilobytes):
            subprocess.run(["umount", mount], capture_output=True)
            subprocess.run(["mount", "-t", "tmpfs", "-o", "size=%dk" % kilobytes, "tmpfs", mount], check=True)
        try:
            for kind in ("tif", "png", "vti", "vtp", "synth"):
                with self.subTest(kind=kind):
                    remount(64)
                    r = self.run_in(mount, self.outputs_of(kind)[0])
                    self.assert_one_sentence(r, r"Cannot write .*: No space left on device\.$")
                    self.assertEqual(os.listdir(mount), [])
            # The PNG alone, then a tmpfs of exactly its pages: the sidecar finds no room.
            remount(4096)
            self.assertEqual(self.run_in(mount, ["convert", self.tif, "-o", "o.png"]).returncode, 0)
            pages = (os.path.getsize(os.path.join(mount, "o.png")) + 4095) // 4096
            remount(4 * pages)
            r = self.run_in(mount, ["convert", self.tif, "-o", "o.png"])
            self.assert_one_sentence(r, r"Cannot write o\.json: No space left on device\.$")
            self.assertEqual(os.listdir(mount), [], "the PNG was left without its sidecar")
        finally:
            subprocess.run(["umount", mount], capture_output=True)

    def test_a_full_standard_output_fails_and_publishes_nothing(self):
        folder = tempfile.mkdtemp(dir=self.tmp, prefix="stdout-")
        for args in (["info", self.tif, "--json"], ["evaluate", self.tif, "--exemplar", self.tif, "--json"],
                     ["convert", self.tif, "-o", "o.tif"]):
            with self.subTest(command=args[0]):
                with open("/dev/full", "w") as full:
                    r = self.run_in(folder, args, stdout=full)
                self.assert_one_sentence(r, r"Cannot write to standard output")
                self.assertEqual(r.returncode, 1)
                self.assertEqual(os.listdir(folder), [])

    def test_3d_view_with_a_display_nobody_answers(self):
        """DISPLAY naming no X server used to abort (SIGABRT) inside VTK: now one warning, and the
        view is rendered under xvfb-run as without a DISPLAY."""
        number = next(n for n in range(4000, 5000) if not os.path.exists("/tmp/.X11-unix/X%d" % n))
        folder = tempfile.mkdtemp(dir=self.tmp, prefix="display-")
        env = dict(harness.gl_preload_environment() or os.environ, DISPLAY=":%d" % number)
        r = self.run_in(folder, ["render", "--3d", self.tif, "-o", "view.png", "--size", "160x120"], env=env)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = [line for line in r.stderr.splitlines() if line.strip()]
        self.assertEqual(lines, ["tsynth: warning: no X server answers at DISPLAY=:%d; rendering under "
                                 "xvfb-run instead." % number])
        self.assertGreater(os.path.getsize(os.path.join(folder, "view.png")), 1000)

    def signal_mid_write(self, args, pause_file, sig):
        """Runs args with the shim pausing at the first write of temporary number pause_file, sends
        sig once it is there, and returns the result and the folder."""
        import signal
        import time
        folder = tempfile.mkdtemp(dir=self.tmp, prefix="signal-")
        marker = os.path.join(self.tmp, "marker-%d" % os.getpid())
        if os.path.exists(marker):
            os.remove(marker)
        env = dict(os.environ, LD_PRELOAD=SHIM, TSYNTH_FAULT_PAUSE_FILE=str(pause_file),
                   TSYNTH_FAULT_MARKER=marker)
        args = [self.strokes if a == "$strokes" else a for a in args]
        p = subprocess.Popen([PATHS.tsynth] + args, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=env)
        deadline = time.monotonic() + CASE_TIMEOUT_S
        while not os.path.exists(marker) and p.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)
        self.assertTrue(os.path.exists(marker), "the command never reached temporary %d" % pause_file)
        p.send_signal(sig)
        out, err = p.communicate(timeout=CASE_TIMEOUT_S)
        os.remove(marker)
        return p.returncode, err, folder

    @unittest.skipIf(harness.INSTRUMENTED, "the shim is preloaded before ASan's runtime, which ASan refuses")
    def test_a_signal_while_writing_leaves_nothing(self):
        """A stop signal (SIGHUP, SIGTERM, SIGINT, SIGQUIT) in the middle of any file of a command's
        outputs, the first or one after others are complete, leaves no file: a long command (synth)
        stops cleanly with 128 + the signal, a short one (convert) and any other terminating signal
        (SIGUSR1, SIGPIPE) remove the temporaries and end as the signal would."""
        import signal
        self.assertTrue(SHIM and os.path.exists(SHIM), "TSYNTH_WRITE_FAULT_SHIM is not set by CTest")
        synth = ["synth", "--exemplar", self.tif, "--sketch", "$strokes"] + SMALL_SYNTH + [
            "-o", "o.png", "--report", "r.json", "--debug-dir", "dbg"]
        convert = ["convert", self.tif, "-o", "o.png"]
        for args, pause_file, sig, status in (
                (convert, 1, signal.SIGHUP, -signal.SIGHUP),
                (convert, 2, signal.SIGTERM, -signal.SIGTERM),  # the PNG complete, its sidecar not
                (synth, 1, signal.SIGTERM, 128 + signal.SIGTERM),
                (synth, 3, signal.SIGINT, 128 + signal.SIGINT),    # the terrain and sidecar complete
                (synth, 6, signal.SIGQUIT, 128 + signal.SIGQUIT),  # inside the debug folder
                (synth, 4, signal.SIGUSR1, -signal.SIGUSR1),
                (convert, 2, signal.SIGPIPE, -signal.SIGPIPE)):
            with self.subTest(command=args[0], file=pause_file, signal=sig.name):
                code, err, folder = self.signal_mid_write(args, pause_file, sig)
                self.assertEqual(code, status, err)
                self.assertIsNone(FORBIDDEN.search(err), err)
                self.assertEqual(os.listdir(folder), [], "a signalled command left files behind")


if __name__ == "__main__":
    harness.run(__name__)
