"""Tests of the tsynth command line: values, pictures, round trips and error handling."""
import json
import re
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS, gl_preload_environment  # noqa: E402


def tsynth(*args, env=None):
    return subprocess.run([PATHS.tsynth, *args], capture_output=True, text=True, timeout=240, env=env)


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        raise AssertionError("%s is not a PNG" % path)
    return struct.unpack(">II", head[16:24])


def write_png(path, width, height, pixel):
    """A plain 8-bit RGB PNG; pixel(x, y) gives (r, g, b), y = 0 at the top."""
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows)))
        f.write(chunk(b"IEND", b""))


def vtp_counts(path):
    """Number of points and lines in a .vtp written by tsynth (from its XML header)."""
    with open(path, "rb") as f:
        head = f.read(4096).decode("latin-1")
    match = re.search(r'<Piece NumberOfPoints="(\d+)"[^>]*NumberOfLines="(\d+)"', head)
    if not match:
        raise AssertionError("no Piece header in %s" % path)
    return int(match.group(1)), int(match.group(2))


def info(path, *extra):
    result = tsynth("info", path, "--json", *extra)
    if result.returncode != 0:
        raise AssertionError(result.stderr)
    return json.loads(result.stdout)


class CliTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-cli-")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def dem(self, name):
        """A real DEM: Data/dems' copy when there is one, else ../shared's; skips the test when
        only ../shared has it and ../shared is not beside the checkout."""
        for folder in (PATHS.bundled_data, PATHS.shared_data):
            path = os.path.join(folder, "dems", name)
            if os.path.exists(path):
                return path
        self.skipTest("%s is absent: ../shared/data is not beside the checkout" % name)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def assert_clean_failure(self, result, code, phrase, output=None):
        self.assertEqual(result.returncode, code, result.stderr)
        lines = [line for line in result.stderr.splitlines() if line.strip()]
        self.assertEqual(len(lines), 1, "expected one sentence, got: %r" % result.stderr)
        self.assertIn(phrase, lines[0])
        if output is not None:
            self.assertFalse(os.path.exists(output), "a failed command left %s behind" % output)
        leftovers = [n for n in os.listdir(self.tmp) if ".tmp-" in n]
        self.assertEqual(leftovers, [])

    # Interruption -------------------------------------------------------------------------

    @harness.skip_if_instrumented("reading the DEM takes longer than the 2 s wait before Ctrl-C")
    def test_ctrl_c_stops_long_commands_and_leaves_no_file(self):
        """pits and features stop promptly with exit 130; render dies by the signal. None leaves
        its output or a temporary behind."""
        import signal
        import time
        from osgeo import gdal
        import numpy as np
        z = gdal.Open(os.path.join(PATHS.bundled_data, "dems", "colorado.png")).ReadAsArray()
        tile = np.block([[z, z[:, ::-1]], [z[::-1, :], z[::-1, ::-1]]]).astype(np.float32)
        for _ in range(2):
            tile = np.block([[tile, tile[:, ::-1]], [tile[::-1, :], tile[::-1, ::-1]]])
        big = self.path("big.tif")  # 5184^2 cells: each command below takes seconds on it
        ds = gdal.GetDriverByName("GTiff").Create(big, tile.shape[1], tile.shape[0], 1,
                                                  gdal.GDT_Float32)
        ds.SetGeoTransform((0.0, 30.0, 0.0, 0.0, 0.0, -30.0))
        ds.GetRasterBand(1).WriteArray(tile)
        ds = None
        cases = [("pits", ["pits", big, "-o", self.path("out.tif"), "--flow",
                           self.path("flow.tif")], 130),
                 ("features", ["features", big, "-o", self.path("out.vtp")], 130),
                 ("render", ["render", big, "-o", self.path("out.png")], -signal.SIGINT)]
        for name, args, code in cases:
            with self.subTest(command=name):
                whole = harness.seconds_to_run(lambda: subprocess.run(
                    [PATHS.tsynth] + args, check=True, capture_output=True))
                for n in os.listdir(self.tmp):
                    if n != "big.tif":
                        os.remove(os.path.join(self.tmp, n))
                p = subprocess.Popen([PATHS.tsynth] + args, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
                time.sleep(0.5 * whole)  # past reading the DEM, into the computation
                self.assertIsNone(p.poll(), "%s ended before it could be interrupted" % name)
                sent = time.monotonic()
                p.send_signal(signal.SIGINT)
                _, err = p.communicate(timeout=60 + whole)
                harness.assert_stopped_promptly(self, "tsynth " + name, time.monotonic() - sent, whole)
                self.assertEqual(p.returncode, code, err)
                if code == 130:
                    self.assertIn("nothing was written", err)
                self.assertEqual(sorted(n for n in os.listdir(self.tmp) if n != "big.tif"), [])

    # Values -------------------------------------------------------------------------------

    def test_info_reads_units_and_cell_sizes(self):
        alaska = info(self.dem("alaska.png"))
        self.assertEqual(alaska["source_z_unit"], "ft")
        self.assertAlmostEqual(alaska["z_max_m"], 6180.0, delta=10.0)
        self.assertEqual(alaska["cell_size_m"], [90.0, 90.0])
        alps = info(self.dem("alps-montblanc.png"))
        self.assertAlmostEqual(alps["z_min_m"], 454.0, places=2)
        self.assertAlmostEqual(alps["z_max_m"], 4810.0, places=2)
        jackson = info(self.dem("mount_jackson_n39_w107_3arc.tif"))
        self.assertTrue(jackson["geographic"])
        self.assertAlmostEqual(jackson["cell_size_m"][0], 71.5, delta=0.5)
        self.assertAlmostEqual(jackson["cell_size_m"][1], 92.5, delta=0.3)
        self.assertEqual(jackson["crs"], "WGS 84")

    def test_info_options_override_the_sidecar(self):
        alaska = info(self.dem("alaska.png"), "--z-unit", "m", "--cell", "30,45")
        self.assertAlmostEqual(alaska["z_max_m"], 6180.0 / 0.3048, delta=40.0)
        self.assertEqual(alaska["cell_size_m"], [30.0, 45.0])

    def test_info_text_is_readable(self):
        result = tsynth("info", self.dem("alaska.png"))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("648 x 648 cells", result.stdout)
        self.assertIn("Stored in:  feet (sidecar)", result.stdout)

    def test_bundled_data_is_readable(self):
        for name in sorted(os.listdir(os.path.join(PATHS.bundled_data, "dems"))):
            if name.endswith((".png", ".tif")):
                with self.subTest(name=name):
                    data = info(os.path.join(PATHS.bundled_data, "dems", name))
                    self.assertGreater(data["z_max_m"], data["z_min_m"])
                    self.assertNotEqual(data["cell_size_source"].split(" ")[0], "unknown")

    # Pictures -----------------------------------------------------------------------------

    def test_render_map_has_one_pixel_per_cell(self):
        out = self.path("alps.png")
        result = tsynth("render", self.dem("alps-montblanc.png"), "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(png_size(out), (647, 647))

    def test_render_3d_view(self):
        out = self.path("jackson3d.png")
        result = tsynth("render", self.dem("mount_jackson_n39_w107_3arc.tif"),
                        "-o", out, "--3d", "--size", "320x200", env=gl_preload_environment())
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(png_size(out), (320, 200))
        self.assertGreater(os.path.getsize(out), 20000)  # a picture, not a blank frame

    # Round trips --------------------------------------------------------------------------

    def test_convert_round_trips_through_every_format(self):
        source = self.dem("mount_jackson_n39_w107_3arc.tif")
        original = info(source)
        for ext in ("tif", "png", "vti"):
            with self.subTest(ext=ext):
                out = self.path("jackson." + ext)
                result = tsynth("convert", source, "-o", out)
                self.assertEqual(result.returncode, 0, result.stderr)
                back = info(out)
                self.assertEqual((back["width"], back["height"]), (1201, 1201))
                self.assertAlmostEqual(back["cell_size_m"][0], original["cell_size_m"][0], places=6)
                self.assertAlmostEqual(back["cell_size_m"][1], original["cell_size_m"][1], places=6)
                tolerance = 0.02 if ext == "png" else 1e-6
                self.assertAlmostEqual(back["z_min_m"], original["z_min_m"], delta=tolerance)
                self.assertAlmostEqual(back["z_max_m"], original["z_max_m"], delta=tolerance)
        self.assertTrue(os.path.exists(self.path("jackson.json")))
        self.assertTrue(info(self.path("jackson.tif"))["geographic"])

    def test_convert_cuts_tiles_that_share_their_edges(self):
        source = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        whole = info(source)
        mosaic = self.path("tiles.vrt")
        for attempt in ("first", "again over the first"):
            with self.subTest(attempt=attempt):
                result = tsynth("convert", source, "--tile-size", "257", "-o", mosaic)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn("Wrote 9 tiles of 257 x 257 samples (3 x 3)", result.stdout)
        back = info(mosaic)
        self.assertEqual((back["width"], back["height"]), (whole["width"], whole["height"]))
        self.assertAlmostEqual(back["z_min_m"], whole["z_min_m"], delta=1e-3)
        self.assertAlmostEqual(back["z_max_m"], whole["z_max_m"], delta=1e-3)
        corner = info(self.path("tiles_x2_y2.tif"))
        self.assertEqual((corner["width"], corner["height"]), (648 - 512, 648 - 512))
        with open(self.path("tiles_x1_y0.json")) as f:
            self.assertEqual(json.load(f)["tile"]["first_sample"], [256, 0])

        result = tsynth("convert", source, "--tile-size", "257", "-o", self.path("ue.png"))
        self.assertEqual(result.returncode, 0, result.stderr)
        ranges = []
        for row in range(3):
            for column in range(3):
                name = self.path("ue_x%d_y%d" % (column, row))
                self.assertEqual(png_size(name + ".png"), (257, 257))
                with open(name + ".json") as f:
                    side = json.load(f)
                ranges.append((side["z_min"], side["z_max"]))
                self.assertAlmostEqual(side["unity"]["size_m"][1], side["z_max"] - side["z_min"])
        self.assertEqual(len(set(ranges)), 1, "the tiles do not share one height scale")
        self.assertAlmostEqual(ranges[0][0], whole["z_min_m"], delta=1e-3)

        result = tsynth("convert", source, "--tile-size", "129", "-o", self.path("un.raw"))
        self.assertEqual(result.returncode, 0, result.stderr)
        raws = sorted(n for n in os.listdir(self.tmp) if n.endswith(".raw"))
        self.assertEqual(len(raws), 36)
        self.assertEqual(os.path.getsize(self.path("un_0_0.raw")), 129 * 129 * 2)
        with open(self.path("un_0_5.json")) as f:
            north_west = json.load(f)
        self.assertEqual(north_west["tile"]["first_sample"], [0, 0])
        self.assertEqual(north_west["row_order"], "south first")

    # Features -----------------------------------------------------------------------------

    def test_features_of_a_dem(self):
        out = self.path("ridges.vtp")
        controls = self.path("controls.vtp")
        dem = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        result = tsynth("features", dem, "-o", out, "--control-points", controls,
                        "--features", "ridges")
        self.assertEqual(result.returncode, 0, result.stderr)
        match = re.search(r"Features: (\d+) nodes \((\d+) branch, (\d+) end", result.stdout)
        self.assertIsNotNone(match, result.stdout)
        nodes, branches, ends = (int(g) for g in match.groups())
        self.assertGreater(branches, 20)
        self.assertGreater(ends, 20)
        points, lines = vtp_counts(out)
        self.assertGreater(points, nodes)
        self.assertGreater(lines, 50)
        self.assertGreater(vtp_counts(controls)[0], nodes)  # one control point per chain end
        valleys = tsynth("features", dem, "-o", self.path("valleys.vtp"), "--valleys")
        self.assertEqual(valleys.returncode, 0, valleys.stderr)
        # By default both kinds, as the Terrain Feature Extractor: the ridges' and the valleys'
        # nodes together (--valleys is short for --features valleys).
        both = tsynth("features", dem, "-o", self.path("both.vtp"))
        self.assertEqual(both.returncode, 0, both.stderr)
        valley_nodes = int(re.search(r"Features: (\d+) nodes", valleys.stdout).group(1))
        self.assertIn("Features: %d nodes" % (nodes + valley_nodes), both.stdout)
        # The significance test (default 0.02 of the 1762 m relief) removes minor lines;
        # --significance 0 is plain PPA (768 nodes on this DEM, 486 at 0.05).
        drop = re.search(r"Significance: features stand ([0-9.]+) m", result.stdout)
        self.assertIsNotNone(drop, result.stdout)
        self.assertAlmostEqual(float(drop.group(1)), 0.02 * 1762.1, delta=0.5)
        plain = tsynth("features", dem, "-o", self.path("plain.vtp"), "--significance", "0",
                       "--features", "ridges")
        self.assertEqual(plain.returncode, 0, plain.stderr)
        self.assertNotIn("Significance:", plain.stdout)
        self.assertIn("Features: 768 nodes", plain.stdout)
        strict = tsynth("features", dem, "-o", self.path("strict.vtp"), "--features", "ridges",
                        "--significance", "0.05",
                        "--significance-noise", "0", "--significance-radius", "20")
        self.assertEqual(strict.returncode, 0, strict.stderr)
        self.assertIn("Features: 486 nodes", strict.stdout)
        self.assertLess(486, nodes)
        self.assertLess(nodes, 768)

    def test_features_of_sketches(self):
        sketches = os.path.join(PATHS.bundled_data, "sketches")
        y = tsynth("features", os.path.join(sketches, "strokes_y_ridges.png"), "--sketch",
                   "-o", self.path("y.vtp"))
        self.assertEqual(y.returncode, 0, y.stderr)
        self.assertIn("8 nodes (1 branch, 7 end, 0 loop anchors), 5 chains in 3 trees", y.stdout)
        grey = tsynth("features", os.path.join(sketches, "lambda_circle_grey.png"), "--sketch",
                      "-o", self.path("lambda.vtp"))
        self.assertEqual(grey.returncode, 0, grey.stderr)
        self.assertIn("(1 branch, 5 end", grey.stdout)
        hint = tsynth("features", os.path.join(sketches, "lambda_circle_grey.png"),
                      "-o", self.path("dem.vtp"))
        self.assert_clean_failure(hint, 1, "--sketch", self.path("dem.vtp"))

    def test_features_bad_input(self):
        flat = self.path("flat.asc")
        with open(flat, "w") as f:
            f.write("ncols 100\nnrows 100\nxllcorner 0\nyllcorner 0\ncellsize 30\n")
            f.write(("500 " * 100 + "\n") * 100)
        out = self.path("flat.vtp")
        result = tsynth("features", flat, "-o", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("flat", result.stderr)
        self.assertEqual(vtp_counts(out), (0, 0))  # an empty tree, honestly

        blank = self.path("blank.png")
        write_png(blank, 128, 128, lambda x, y: (255, 255, 255))
        result = tsynth("features", blank, "--sketch", "-o", self.path("blank.vtp"))
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("no features", result.stderr)
        self.assertEqual(vtp_counts(self.path("blank.vtp")), (0, 0))

        small = self.path("small.png")
        write_png(small, 40, 40, lambda x, y: (230, 20, 20) if x == y else (255, 255, 255))
        self.assert_clean_failure(tsynth("features", small, "--sketch", "-o", self.path("s.vtp")),
                                  1, "smaller than one patch", self.path("s.vtp"))

        photo = self.path("photo.png")
        write_png(photo, 128, 128, lambda x, y: (x * 2, 200, 255 - y))
        self.assert_clean_failure(tsynth("features", photo, "--sketch", "-o", self.path("p.vtp")),
                                  1, "not a stroke map", self.path("p.vtp"))

        dem = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("x.txt")), 2, ".vtp")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("v.vtp"), "--valleys", "--both"),
                                  2, "--both")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("v.vtp"), "--min-branch", "2.5"),
                                  2, "whole number")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("v.vtp"), "--significance", "2"),
                                  2, "--significance expects a number from 0 to 1, not 2.")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("v.vtp"),
                                         "--significance-noise", "-1"), 2,
                                  "--significance-noise expects a number from 0 to 100, not -1.")
        self.assert_clean_failure(tsynth("features", dem, "-o", self.path("v.vtp"),
                                         "--significance-radius", "0"), 2, "whole number")

    # Bad input ----------------------------------------------------------------------------

    def test_missing_file(self):
        out = self.path("out.png")
        self.assert_clean_failure(tsynth("render", self.path("nope.tif"), "-o", out), 1,
                                  "No such file", out)
        self.assert_clean_failure(tsynth("info", self.path("nope.tif")), 1, "No such file")

    def test_non_raster_file(self):
        text = self.path("readme.tif")
        with open(text, "w") as f:
            f.write("hello, I am text\n")
        out = self.path("out.tif")
        self.assert_clean_failure(tsynth("convert", text, "-o", out), 1, "is not a raster", out)

    def test_unreadable_corrupt_file(self):
        corrupt = self.path("corrupt.png")
        with open(self.dem("alaska.png"), "rb") as f:
            data = f.read()
        with open(corrupt, "wb") as f:
            f.write(data[:4000])  # a valid header and a fraction of the pixels
        out = self.path("out.png")
        self.assert_clean_failure(tsynth("render", corrupt, "-o", out), 1, corrupt, out)

    def test_directory_and_empty_file(self):
        self.assert_clean_failure(tsynth("info", self.tmp), 1, "is a directory")
        empty = self.path("empty.tif")
        open(empty, "w").close()
        self.assert_clean_failure(tsynth("info", empty), 1, "empty")

    def test_all_nodata_raster(self):
        grid = self.path("void.asc")
        with open(grid, "w") as f:
            f.write("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                    "NODATA_value -9999\n-9999 -9999\n-9999 -9999\n")
        out = self.path("void.png")
        self.assert_clean_failure(tsynth("render", grid, "-o", out), 1, "no valid heights", out)

    def test_bad_sidecar_json(self):
        dem = self.path("alaska.png")
        shutil.copy(self.dem("alaska.png"), dem)
        with open(self.path("alaska.json"), "w") as f:
            f.write('{"z_unit": "ft", "cell_size_m": }')
        out = self.path("out.tif")
        self.assert_clean_failure(tsynth("convert", dem, "-o", out), 1, "not valid JSON", out)
        # --no-sidecar gets past it.
        self.assertEqual(tsynth("info", dem, "--no-sidecar").returncode, 0)

    def test_output_problems(self):
        dem = self.dem("alaska.png")
        missing = self.path("no-such-folder/out.tif")
        self.assert_clean_failure(tsynth("convert", dem, "-o", missing), 1, "does not exist")
        self.assert_clean_failure(tsynth("convert", dem, "-o", self.path("out.xyz")), 2, ".tif")
        self.assert_clean_failure(tsynth("render", dem), 2, "-o OUT.png")
        self.assert_clean_failure(tsynth("render", dem, "-o", self.path("x.jpg")), 2, ".png")

    def test_usage_errors(self):
        self.assert_clean_failure(tsynth("frobnicate"), 2, "Unknown command")
        self.assert_clean_failure(tsynth("info"), 2, "needs a DEM")
        self.assert_clean_failure(tsynth("info", "a.tif", "--bogus"), 2, "Unknown option --bogus")
        self.assert_clean_failure(tsynth("info", "a.tif", "--cell", "-4"), 2, "--cell")
        self.assert_clean_failure(tsynth("info", "a.tif", "--z-unit", "yd"), 2, "--z-unit")

    # The launcher (Apps/Launcher.cxx) ------------------------------------------------------

    def test_synth_loads_the_program_once(self):
        """tsynth synth starts with its runtime settings in place: the dynamic loader initialises
        the project's kernels once (a synth that set them itself and re-ran loaded everything
        twice, 0.15 s each here)."""
        env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GLIBC_TUNABLES")}
        env["LD_DEBUG"] = "files"
        result = tsynth("synth", "--exemplar", self.path("absent.png"), "--sketch",
                        self.path("absent-sketch.png"), "-o", self.path("out.tif"), env=env)
        self.assertEqual(result.returncode, 1, result.stderr[-2000:])
        inits = [line for line in result.stderr.splitlines()
                 if "calling init:" in line and "libtsynth_kernels.so" in line]
        self.assertEqual(len(inits), 1, "the kernels were initialised %d times" % len(inits))

    def test_synth_runs_with_its_settings_and_keeps_the_users(self):
        """The synthesis process (tsynth-main, same pid) has passive OpenMP waiting and huge pages
        in its environment, unless the user set them: then the user's values stand."""
        import signal
        import time
        sketch = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        base = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GLIBC_TUNABLES")}
        cases = [("unset", base, {"OMP_WAIT_POLICY": "passive",
                                  "GLIBC_TUNABLES": "glibc.malloc.hugetlb=1"}),
                 ("given", dict(base, OMP_WAIT_POLICY="active",
                                GLIBC_TUNABLES="glibc.malloc.hugetlb=0"),
                  {"OMP_WAIT_POLICY": "active", "GLIBC_TUNABLES": "glibc.malloc.hugetlb=0"})]
        for name, env, expected in cases:
            with self.subTest(environment=name):
                process = subprocess.Popen(
                    [PATHS.tsynth, "synth", "--exemplar", self.dem("colorado.png"), "--sketch",
                     sketch, "--size", "1024x1024", "-o", self.path("out-%s.tif" % name)],
                    env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                found = None
                deadline = time.monotonic() + 60
                while found is None and process.poll() is None and time.monotonic() < deadline:
                    try:
                        with open("/proc/%d/maps" % process.pid) as maps:
                            loaded = "libtsynth_kernels.so" in maps.read()
                        if loaded:
                            with open("/proc/%d/environ" % process.pid, "rb") as f:
                                found = dict(item.decode().split("=", 1)
                                             for item in f.read().split(b"\0") if b"=" in item)
                    except OSError:
                        pass
                    time.sleep(0.005)
                process.send_signal(signal.SIGINT)
                process.communicate(timeout=120)
                self.assertIsNotNone(found, "the synthesis process was never seen running")
                for key, value in expected.items():
                    self.assertEqual(found.get(key), value, key)

    def test_only_render_3d_loads_vtk_rendering(self):
        """VTK's rendering libraries (and X11, GL) are in render --3d's module, not loaded by the
        other commands: tsynth info does not load them."""
        env = dict(os.environ, LD_DEBUG="files")
        result = tsynth("info", self.dem("colorado.png"), env=env)
        self.assertEqual(result.returncode, 0, result.stderr[-2000:])
        loaded = [line for line in result.stderr.splitlines() if "file=" in line]
        self.assertTrue(any("libtsynth_kernels.so" in line for line in loaded))
        self.assertFalse([line for line in loaded if "libvtkRenderingOpenGL2" in line])

    def test_launcher_without_the_program_says_so(self):
        """The launcher alone, without tsynth-main beside it: one sentence, exit 1."""
        alone = self.path("tsynth")
        shutil.copy(PATHS.tsynth, alone)
        result = subprocess.run([alone, "info", "x.tif"], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 1)
        lines = [line for line in result.stderr.splitlines() if line.strip()]
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertIn("cannot start", lines[0])
        self.assertIn("tsynth-main", lines[0])

    def test_help(self):
        for command in ("info", "render", "convert", "features"):
            result = tsynth(command, "--help")
            self.assertEqual(result.returncode, 0)
            self.assertIn("Usage: tsynth " + command, result.stdout)
        self.assertEqual(tsynth("--help").returncode, 0)


if __name__ == "__main__":
    harness.run(__name__)
