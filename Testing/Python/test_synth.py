"""The synthesis end to end through the command line: landform quality bar, seeds, bad input."""
import filecmp
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402
import sketch_drawing  # noqa: E402
from test_cli import write_png  # noqa: E402


def write_polylines(path, points, elevation=None, types=(1, -1)):
    """An ASCII VTK poly-data sketch: pairs of points, one line each, with FeatureType."""
    n = len(points)
    pd = ('<PointData><DataArray type="Float32" Name="Elevation" format="ascii">%s</DataArray></PointData>'
          % " ".join(str(e) for e in elevation)) if elevation else ""
    with open(path, "w") as f:
        f.write("""<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
<PolyData><Piece NumberOfPoints="%d" NumberOfVerts="0" NumberOfLines="%d" NumberOfStrips="0" NumberOfPolys="0">
%s<CellData><DataArray type="Int32" Name="FeatureType" format="ascii">%s</DataArray></CellData>
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">%s</DataArray></Points>
<Lines><DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray></Lines>
</Piece></PolyData></VTKFile>
""" % (n, n // 2, pd, " ".join(str(t) for t in types[: n // 2]),
       " ".join("%r %r 0" % (float(x), float(y)) for x, y in points),
       " ".join(str(k) for k in range(n)), " ".join(str(2 * k + 2) for k in range(n // 2))))


def crop_dem(tmp, name, window):
    """A window (column, row, width, height) of a bundled DEM as a metres GeoTIFF."""
    full = os.path.join(tmp, name + ".full.tif")
    crop = os.path.join(tmp, name + ".crop.tif")
    subprocess.run([PATHS.tsynth, "convert", os.path.join(PATHS.bundled_data, "dems", name), "-o", full],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["gdal_translate", "-q", "-srcwin", *[str(v) for v in window], full, crop], check=True)
    return crop


def tsynth(*args, threads=None):
    """tsynth with its output captured; threads: OMP_NUM_THREADS for the run (None: the default)."""
    env = None if threads is None else dict(os.environ, OMP_NUM_THREADS=str(threads))
    return subprocess.run([PATHS.tsynth, *args], capture_output=True, text=True, timeout=600, env=env)


def synthesise(test, exemplar, sketch, out, *extra):
    """tsynth synth with a report; asserts success and returns (report, stderr)."""
    result = tsynth("synth", "--exemplar", exemplar, "--sketch", sketch, "-o", out, "--report", out + ".json",
                    "--no-progress", *extra)
    test.assertEqual(result.returncode, 0, result.stderr)
    with open(out + ".json") as f:
        return json.load(f), result.stderr


def evaluate(test, terrain, exemplar, sketch, *extra):
    result = tsynth("evaluate", terrain, "--exemplar", exemplar, "--sketch", sketch, "--json", *extra)
    test.assertEqual(result.returncode, 0, result.stderr)
    return json.loads(result.stdout)


def read_grid(path, tmp):
    """A raster's heights as rows of floats, the top (north) row first."""
    text = os.path.join(tmp, os.path.basename(path) + ".asc")
    subprocess.run(["gdal_translate", "-q", "-of", "AAIGrid", path, text], check=True)
    with open(text) as f:
        lines = [line.split() for line in f if line.strip()]
    return [[float(v) for v in line] for line in lines if not line[0][0].isalpha()]


# The bar on the bundled sketches (512 x 512, default patch): no visible seams (the 99.9th
# percentile of |Laplacian| at most 1.1 times the exemplar's) and the exemplar's slopes (slope-angle
# distance at most 0.1 of its mean slope).
MAX_SEAM_INDEX = 1.1
MAX_SLOPE_DISTANCE = 0.1

# Landform bars: the least value of each measure of LandformMetrics.h a terrain must reach. Each was
# measured on the terrains of seeds 0 to 10 (bundled sketches) or 0 to 2 (drawn ones) with Colorado and
# Mont Blanc, and set a quarter to a third below the least ratio and 0.02-0.15 below the least share,
# so that another seed passes too, while the baselines of tsynth evaluate (the exemplar tiled, random
# patches pasted: terrains that ignore the sketch) fail most of each bar (their shedding and order reach
# 0.87 and 0.91, which leaves those shares little room). The figures are tsynth evaluate's: the report
# divides its ratios by the exemplars' prominence on every PPA line the synthesis uses, evaluate by their
# major lines (the PPA defaults), so the report's ratios run 1.1 to 1.7 times evaluate's and pass the
# same bar with more room.
BUNDLED_BARS = {
    # Least measured: prominence 1.20, depth 2.31, order 0.968, descent 0.762, shedding 0.850 (Colorado
    # seed 9; 0.912 on the others). Drainage is not asked: the valleys end inside the map, where water
    # pools (0.23-0.55 measured).
    "strokes_y_ridges.png": {"ridge_prominence_ratio": 0.9, "valley_depth_ratio": 1.5,
                             "ridge_over_valley": 0.95, "valley_descent": 0.7, "ridge_shedding": 0.88},
    # Least measured: prominence 0.58, depth 1.96, order 0.994, drainage 0.33, descent 0.706, shedding
    # 0.896. The valley runs to within 20 pixels of the west and east borders: drainage 0.33-0.89, the
    # baselines' 0.03-0.12.
    "strokes_valley_meander.png": {"ridge_prominence_ratio": 0.45, "valley_depth_ratio": 1.5,
                                   "ridge_over_valley": 0.95, "valley_drainage": 0.25, "valley_descent": 0.65,
                                   "ridge_shedding": 0.88},
}

# Figures the report and tsynth evaluate compute alike (the ratios differ, see above).
SHARED_LANDFORM_FIGURES = ("ridge_prominence_m", "valley_depth_m", "ridge_over_valley", "valley_drainage",
                           "valley_descent", "ridge_shedding")
BASELINES = ("tiled_exemplar", "random_patches")


def assert_landform_bar(test, report, evaluated, bar):
    """The terrain reaches every figure of the bar, in the report and in tsynth evaluate; the report
    and evaluate agree; each baseline misses more than half of the bar."""
    ours = report["landform_quality"]
    theirs = evaluated["terrain"]["landforms"]
    for key in SHARED_LANDFORM_FIGURES:
        if ours[key] is None:
            test.assertIsNone(theirs[key], key)
        else:
            test.assertAlmostEqual(ours[key], theirs[key], delta=1e-6 * max(1.0, abs(ours[key])), msg=key)
    for key, least in bar.items():
        for source, figures in (("report", ours), ("evaluate", theirs)):
            test.assertIsNotNone(figures[key], "%s: no %s (%s)" % (source, key, figures["notes"]))
            test.assertGreaterEqual(figures[key], least, "%s: %s" % (source, key))
    for baseline in BASELINES:
        figures = evaluated[baseline]["landforms"]
        missed = [key for key, least in bar.items() if figures[key] is None or figures[key] < least]
        test.assertGreater(len(missed), len(bar) / 2, "the %s baseline passes the bar: %s" % (baseline, figures))


class BundledSketchTest(unittest.TestCase):
    """The bundled stroke sketches at their 512 x 512 with two exemplars of different character and the
    default patch: each synthesis runs once and serves every test of the class."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="tsynth-bundled-")
        cls.runs = {}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def run_case(self, exemplar, sketch, seed=None):
        """(terrain file, report, tsynth evaluate figures) of one synthesis; seed None: the default."""
        key = (exemplar, sketch, seed)
        if key not in self.runs:
            dem = os.path.join(PATHS.bundled_data, "dems", exemplar)
            drawing = os.path.join(PATHS.bundled_data, "sketches", sketch)
            out = os.path.join(self.tmp, "%s-%s-%s.tif" % (exemplar, sketch, seed))
            report, _ = synthesise(self, dem, drawing, out, *(() if seed is None else ("--seed", str(seed))))
            self.runs[key] = (out, report, evaluate(self, out, dem, drawing))
        return self.runs[key]

    def assert_quality_bar(self, exemplar, sketch, seed=None):
        _, report, evaluated = self.run_case(exemplar, sketch, seed)
        self.assertEqual(report["seed"], 0 if seed is None else seed)
        self.assertEqual(report["size"], [512, 512])
        self.assertGreater(report["feature_placements"], 10)
        q = report["quality"]
        self.assertLessEqual(q["seam_index"], MAX_SEAM_INDEX)
        self.assertLessEqual(q["slope_distance"], MAX_SLOPE_DISTANCE)
        assert_landform_bar(self, report, evaluated, BUNDLED_BARS[sketch])

    def test_quality_bar_on_both_stroke_sketches_with_two_exemplars(self):
        for exemplar in ("colorado.png", "alps-montblanc.png"):
            for sketch in BUNDLED_BARS:
                with self.subTest(exemplar=exemplar, sketch=sketch):
                    self.assert_quality_bar(exemplar, sketch)

    def test_another_seed_gives_another_terrain_that_passes_the_bar(self):
        # Seed 1 (measured: slope distance 0.063-0.092). Of the 44 terrains of seeds 0-10, five exceed the
        # slope bar, all on strokes_y_ridges (0.103-0.132: Colorado seeds 2, 6, 8, 9, Mont Blanc seed 3),
        # and one misses a landform figure (shedding 0.850, Colorado seed 9).
        for exemplar, sketch in (("colorado.png", "strokes_valley_meander.png"),
                                 ("alps-montblanc.png", "strokes_y_ridges.png")):
            with self.subTest(exemplar=exemplar, sketch=sketch):
                first = self.run_case(exemplar, sketch)[0]
                other = self.run_case(exemplar, sketch, 1)[0]
                self.assertFalse(filecmp.cmp(first, other, shallow=False))
                self.assert_quality_bar(exemplar, sketch, 1)


class DrawnSketchTest(unittest.TestCase):
    """Sketches the test draws (sketch_drawing.py), 320 x 320 with a 40-cell patch (the default seed)."""

    PATCH = "40"
    BOTH = ("colorado.png", "alps-montblanc.png")

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-drawn-")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def assert_landforms(self, draw, exemplars, bar):
        """Synthesises the drawing with each exemplar; returns the last run's stderr."""
        sketch = draw().save(os.path.join(self.tmp, draw.__name__ + ".png"))
        for exemplar in exemplars:
            with self.subTest(exemplar=exemplar):
                dem = os.path.join(PATHS.bundled_data, "dems", exemplar)
                out = os.path.join(self.tmp, exemplar + ".tif")
                report, stderr = synthesise(self, dem, sketch, out, "--patch", self.PATCH)
                self.assertEqual(report["size"], [sketch_drawing.SIZE, sketch_drawing.SIZE])
                self.assertLessEqual(report["quality"]["seam_index"], MAX_SEAM_INDEX)
                assert_landform_bar(self, report, evaluate(self, out, dem, sketch, "--patch", self.PATCH), bar)
        return stderr

    # Each bar is measured over seeds 0-2 with Colorado and Mont Blanc (least values in the comments;
    # the baselines' best in brackets), set as for BUNDLED_BARS.

    def test_valley_tree_drains_to_the_border(self):
        # depth 1.81 [-0.14], drainage 0.873 [0.174], descent 0.826 [0.607]
        self.assert_landforms(sketch_drawing.valley_tree, self.BOTH,
                              {"valley_depth_ratio": 1.4, "valley_drainage": 0.75, "valley_descent": 0.7})

    def test_parallel_ridges(self):
        # prominence 1.73 [-0.07], shedding 0.991 [0.780]
        self.assert_landforms(sketch_drawing.parallel_ridges, self.BOTH,
                              {"ridge_prominence_ratio": 1.3, "ridge_shedding": 0.93})

    def test_ridge_ring_inside_a_valley_ring(self):
        # prominence 1.91 [0.72], depth 2.44 [0.68], order 1.000 [0.675], shedding 0.980 [0.827]; the
        # valley ring is a loop whose floor rises to a divide, so neither descent nor drainage is asked
        # (0.50-0.92, 0.37-0.60).
        stderr = self.assert_landforms(sketch_drawing.rings, self.BOTH,
                                       {"ridge_prominence_ratio": 1.4, "valley_depth_ratio": 1.8,
                                        "ridge_over_valley": 0.97, "ridge_shedding": 0.93})
        self.assertIn("has a loop", stderr)

    def test_letters_t_and_s(self):
        # prominence 1.45 [0.19], shedding 0.975 [0.773]
        self.assert_landforms(sketch_drawing.letters, self.BOTH,
                              {"ridge_prominence_ratio": 1.1, "ridge_shedding": 0.92})

    def test_spiral_ridge(self):
        # Colorado: prominence 2.05 [0.68], shedding 0.996 [0.836]. Mont Blanc fails, see below.
        self.assert_landforms(sketch_drawing.spiral, ("colorado.png",),
                              {"ridge_prominence_ratio": 1.5, "ridge_shedding": 0.93})

    def test_spiral_ridge_with_mont_blanc_keeps_its_heights(self):
        # The default merge (new) once spread the seam's gradient mismatch over a fixed 20 cells: on
        # 40-cell patches with Mont Blanc the heights drifted to 112-8615 m (the exemplar spans
        # 454-4810 m) and the spiral became a scarp or a trench. The spread now scales with the
        # patch (a quarter); seeds 3, 6 and 7, which drifted worst, stay within the exemplar's range.
        sketch = sketch_drawing.spiral().save(os.path.join(self.tmp, "spiral.png"))
        dem = os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png")
        out = os.path.join(self.tmp, "spiral.tif")
        for seed in ("3", "6", "7"):
            report, _ = synthesise(self, dem, sketch, out, "--patch", self.PATCH, "--seed", seed)
            heights = tsynth("info", out, "--json")
            self.assertEqual(heights.returncode, 0, heights.stderr)
            self.assertLessEqual(json.loads(heights.stdout)["z_max_m"], 4810.0)
            self.assertGreaterEqual(report["landform_quality"]["ridge_prominence_ratio"], 1.5)

    def test_spiral_ridge_with_mont_blanc_on_default_patches_does_not_drift(self):
        # At the default 80-cell patches on 640 x 640 cells the new merge still drifted: each patch's
        # far side was carried off by its spread gradient correction and the next one fitted to it,
        # down to -5621 m (seed 4; seeds 1 and 3: -1646 and -3848 m) where the exemplar spans
        # 454-4810 m. With the free border anchored they stayed within 483-4143 m. Since the
        # correction is spread over a tenth of a patch (Tasse's code), not a quarter, no merge needs
        # the anchor here (the guard itself: Testing/Cxx/Merging/TestPatchMerger.cxx). Allowed: the
        # exemplar's range widened by a tenth of its span (436 m) each way.
        sketch = sketch_drawing.spiral().save(os.path.join(self.tmp, "spiral.png"))
        dem = os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png")
        out = os.path.join(self.tmp, "spiral.tif")
        low, high, slack = 454.0, 4810.0, 0.1 * (4810.0 - 454.0)
        for seed in ("1", "3", "4"):
            report, _ = synthesise(self, dem, sketch, out, "--size", "640x640", "--seed", seed)
            self.assertLess(report["anchored_merges"], 0.1 * report["placements"])
            heights = tsynth("info", out, "--json")
            self.assertEqual(heights.returncode, 0, heights.stderr)
            z = json.loads(heights.stdout)
            self.assertGreaterEqual(z["z_min_m"], low - slack, f"seed {seed}")
            self.assertLessEqual(z["z_max_m"], high + slack, f"seed {seed}")


class SynthTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-synth-")
        self.dems = os.path.join(PATHS.bundled_data, "dems")
        self.sketches = os.path.join(PATHS.bundled_data, "sketches")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def synth(self, exemplar, sketch, out, *extra, threads=None):
        report = out + ".json"
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, exemplar), "--sketch", sketch,
                        "-o", out, "--report", report, "--no-progress", *extra, threads=threads)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(report) as f:
            return json.load(f)

    def test_same_seed_gives_the_same_bits_on_opencl_and_cpu_and_another_seed_another_terrain(self):
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")

        def run(name, backend, *seed, threads=None):
            return self.synth("colorado.png", sketch, self.path(name), "--backend", backend, "--size", "320x320",
                              *seed, threads=threads)

        for tag, seed in (("default", ()), ("5", ("--seed", "5"))):
            with self.subTest(seed=tag):
                a = run("opencl-%s.tif" % tag, "opencl", *seed)
                b = run("cpu-%s.tif" % tag, "cpu", *seed)
                self.assertIn("opencl", a["backend"])
                self.assertEqual(b["backend"], "cpu")
                self.assertEqual(a["seed"], b["seed"])
                self.assertTrue(filecmp.cmp(self.path("opencl-%s.tif" % tag), self.path("cpu-%s.tif" % tag),
                                            shallow=False))
        again = run("cpu-5-again.tif", "cpu", "--seed", "5")
        self.assertTrue(filecmp.cmp(self.path("cpu-5.tif"), self.path("cpu-5-again.tif"), shallow=False))
        # The thread count (OpenMP's, which both backends use on the host) changes nothing either: one
        # thread, and three (the work split unevenly on two cores), against the default.
        for backend, threads in (("cpu", 1), ("cpu", 3), ("opencl", 1)):
            with self.subTest(backend=backend, threads=threads):
                name = "%s-5-threads%d.tif" % (backend, threads)
                run(name, backend, "--seed", "5", threads=threads)
                self.assertTrue(filecmp.cmp(self.path("cpu-5.tif"), self.path(name), shallow=False))
        with open(self.path("cpu-default.tif.json")) as f:
            first = json.load(f)
        self.assertEqual((first["seed"], again["seed"]), (0, 5))
        self.assertNotEqual(first["placement_list"], again["placement_list"])
        self.assertFalse(filecmp.cmp(self.path("cpu-default.tif"), self.path("cpu-5.tif"), shallow=False))

    def test_exemplar_cache_gives_the_same_terrain_and_a_damaged_entry_is_rebuilt(self):
        # What is computed from the exemplars alone is read back on the second run; the terrain is
        # the same bits as without a cache, and a damaged entry is said, rebuilt and never used.
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")
        cache = self.path("cache")

        def run(name, *cache_options):
            return self.synth("colorado.png", sketch, self.path(name), "--size", "320x320",
                              *cache_options)

        plain = run("plain.tif", "--no-cache")
        self.assertEqual(plain["exemplar_cache"]["directory"], "")
        first = run("first.tif", "--cache", cache)
        second = run("second.tif", "--cache", cache)
        self.assertFalse(first["exemplar_cache"]["hit"])
        self.assertTrue(second["exemplar_cache"]["hit"])
        entry = second["exemplar_cache"]["entry"]
        self.assertEqual(os.listdir(cache), [os.path.basename(entry)])
        for name in ("first.tif", "second.tif"):
            self.assertTrue(filecmp.cmp(self.path("plain.tif"), self.path(name), shallow=False), name)
        # Reading it back is faster than computing it (the same process's figures, one run each).
        self.assertLess(second["exemplar_cache"]["seconds"], plain["exemplar_cache"]["seconds"])

        with open(entry, "r+b") as f:  # one flipped byte in the middle of the entry
            f.seek(os.path.getsize(entry) // 2)
            byte = f.read(1)
            f.seek(-1, os.SEEK_CUR)
            f.write(bytes([byte[0] ^ 0xFF]))
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", sketch,
                        "--size", "320x320", "-o", self.path("damaged.tif"), "--report",
                        self.path("damaged-report.json"), "--no-progress", "--cache", cache)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("Exemplar cache: the cached entry", result.stderr)
        self.assertIn("checksum does not match", result.stderr)
        with open(self.path("damaged-report.json")) as f:
            self.assertFalse(json.load(f)["exemplar_cache"]["hit"])
        self.assertTrue(filecmp.cmp(self.path("plain.tif"), self.path("damaged.tif"), shallow=False))
        self.assertTrue(run("after.tif", "--cache", cache)["exemplar_cache"]["hit"])

        both = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", sketch,
                      "-o", self.path("both.tif"), "--cache", cache, "--no-cache")
        self.assertNotEqual(both.returncode, 0)
        self.assertIn("--cache and --no-cache contradict each other", both.stderr)
        self.assertFalse(os.path.exists(self.path("both.tif")))

    def test_a_tiled_report_times_every_tile_of_each_pass(self):
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")
        report = self.synth("colorado.png", sketch, self.path("tiled.tif"), "--size", "320x320",
                            "--tile-size", "160")  # 2 x 2 tiles of two patches
        tiles = report["tiles"]
        self.assertEqual(sorted((t["column"], t["row"], t["pass"]) for t in tiles),
                         sorted((c, r, p) for c in (0, 1) for r in (0, 1) for p in ("features", "fill")))
        self.assertEqual(sorted({(t["column"] % 2, t["row"] % 2): t["colour"] for t in tiles}.values()),
                         [0, 1, 2, 3])
        self.assertTrue(all(t["seconds"] > 0 and t["cpu_seconds"] >= 0 for t in tiles), tiles)
        fill = sum(t["seconds"] for t in tiles if t["pass"] == "fill")
        times = report["times_s"]
        self.assertLess(fill, times["fill"] + times["setup"] + 1e-6, (tiles, times))
        untiled = self.synth("colorado.png", sketch, self.path("untiled.tif"), "--size", "320x320")
        self.assertNotIn("tiles", untiled)

    def test_an_edit_resynthesised_from_the_previous_tile_record_is_a_full_synthesis(self):
        # Two ridges far apart on 384 x 256 cells; the edit moves the east one 10 cells.
        def draw(name, shift):
            canvas = sketch_drawing.Canvas(384, 256)
            canvas.polyline([(50, 40), (60, 215)], sketch_drawing.RIDGE, pen=3)
            canvas.polyline([(320 + shift, 40), (330 + shift, 215)], sketch_drawing.RIDGE, pen=3)
            return canvas.save(self.path(name))
        before, after = draw("before.png", 0), draw("after.png", 10)
        grid = ("--patch", "32", "--backend", "cpu")
        self.synth("colorado.png", before, self.path("v1.tif"), *grid, "--tile-size", "64", "--keep-tiles")
        self.assertTrue(os.path.exists(self.path("v1.tiles")))
        full = self.synth("colorado.png", after, self.path("full.tif"), *grid, "--tile-size", "64")
        self.assertFalse(os.path.exists(self.path("full.tiles")))
        # The tile size comes from v1's record; the result is the full synthesis' bits (a preview
        # first, at its own patch size, neither takes from the record nor keeps one).
        edited = self.synth("colorado.png", after, self.path("v2.tif"), *grid, "--previous", self.path("v1.tif"),
                            "--preview", self.path("v2-preview.tif"))
        self.assertFalse(os.path.exists(self.path("v2-preview.tiles")))
        self.assertTrue(filecmp.cmp(self.path("full.tif"), self.path("v2.tif"), shallow=False))
        self.assertTrue(os.path.exists(self.path("v2.tiles")))
        passes = len(edited["tiles"])
        self.assertEqual(passes, len(full["tiles"]))
        self.assertGreaterEqual(edited["tiles_taken_over"], passes // 3, edited["tiles"])
        self.assertLess(edited["tiles_taken_over"], passes)
        self.assertEqual(edited["tiles_taken_over"], sum(t["taken_over"] for t in edited["tiles"]))
        # Refused, each in one sentence, with nothing written: another seed than the record's (given
        # as --seed=3: a given option is never overridden by the record),
        # a record that is not there, -o onto the previous terrain's record, a record without tiles.
        for extra, out, words in ((("--previous", self.path("v1.tif"), "--seed=3"), "seed.tif", "seed 0"),
                                  (("--previous", self.path("full.tif")), "none.tif", "--keep-tiles"),
                                  (("--previous", self.path("v1.tif")), "v1.png", "tile record"),
                                  (("--keep-tiles",), "untiled.tif", "--tile-size")):
            with self.subTest(extra=extra):
                result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", after,
                                "-o", self.path(out), "--no-progress", *grid, *extra)
                self.assertNotEqual(result.returncode, 0)
                self.assertIn(words, result.stderr)
                self.assertEqual(result.stderr.strip().count("\n"), 0, result.stderr)
                self.assertFalse(os.path.exists(self.path(out)))
        # A damaged record is refused, never used.
        with open(self.path("v2.tiles"), "r+b") as f:
            f.seek(4000)
            byte = f.read(1)
            f.seek(4000)
            f.write(bytes([byte[0] ^ 0x20]))
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", after,
                        "-o", self.path("v3.tif"), "--no-progress", *grid, "--previous", self.path("v2.tif"))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("damaged", result.stderr)
        self.assertFalse(os.path.exists(self.path("v3.tif")))

    def test_preview_comes_first_draws_the_sketch_and_leaves_the_terrain_unchanged(self):
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")
        colorado = os.path.join(self.dems, "colorado.png")
        plain = self.synth("colorado.png", sketch, self.path("plain.tif"))
        report = self.synth("colorado.png", sketch, self.path("whole.tif"), "--preview", self.path("preview.tif"))
        # The terrain is the same bits with or without a preview first.
        self.assertTrue(filecmp.cmp(self.path("plain.tif"), self.path("whole.tif"), shallow=False))
        preview = report["preview"]
        self.assertEqual(preview["size"], [129, 129])  # 512 cells of 90 m on cells of 360 m
        self.assertEqual(preview["cell_size_m"], [360.0, 360.0])
        self.assertEqual(preview["patch_size"], 20)
        whole_seconds = sum(plain["times_s"].values())
        self.assertLess(preview["seconds"], 0.5 * whole_seconds, (preview, plain["times_s"]))
        # Its own stages: each one measured, together within its wall-clock seconds.
        stages = preview["times_s"]
        self.assertEqual(set(stages), {"prepare", "setup", "features", "fill", "finish"})
        self.assertGreater(stages["prepare"], 0.0, stages)
        self.assertGreater(stages["fill"], 0.0, stages)
        self.assertGreater(stages["features"], 0.0, stages)
        self.assertLessEqual(sum(stages.values()), preview["seconds"], (stages, preview["seconds"]))
        # It draws the same sketch: most of the strokes' length is legible in it, as in the terrain
        # (a random patchwork scores about 0.1).
        result = tsynth("evaluate", self.path("preview.tif"), "--exemplar", colorado, "--sketch", sketch, "--json")
        self.assertEqual(result.returncode, 0, result.stderr)
        legible = json.loads(result.stdout)["terrain"]["legibility"]["legible_share"]
        self.assertGreater(legible, 0.6)

        # Refused before any work: a patch with no coarser level, a preview over an input or the output.
        for extra, message, status in ((["--patch", "28", "--preview", self.path("p.tif")], "at least 32", 2),
                                       (["--preview", sketch], "same file as --sketch", 1),
                                       (["--preview", self.path("same.tif")], "same file as -o", 1)):
            result = tsynth("synth", "--exemplar", colorado, "--sketch", sketch, "-o", self.path("same.tif"),
                            "--no-progress", *extra)
            self.assertEqual(result.returncode, status, result.stderr)
            self.assertIn(message, result.stderr)
            self.assertFalse(os.path.exists(self.path("same.tif")))
            self.assertFalse(os.path.exists(self.path("p.tif")))

    def test_ctrl_c_after_the_preview_leaves_the_preview_complete(self):
        import signal
        out = self.path("interrupted.tif")
        preview = self.path("preview.tif")
        p = subprocess.Popen([PATHS.tsynth, "synth", "--exemplar", os.path.join(self.dems, "colorado.png"),
                              "--sketch", os.path.join(self.sketches, "strokes_valley_tree.png"),
                              "--size", "1024x1024", "--no-progress", "--preview", preview, "-o", out],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = p.stdout.readline()  # written once the preview file is complete
        self.assertTrue(line.startswith("Preview: 257 x 257 cells"), line)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=120)
        self.assertEqual(p.returncode, 130, err)
        self.assertIn("only the preview %s was written (complete)" % preview, err)
        self.assertFalse(os.path.exists(out))
        info = tsynth("info", preview)
        self.assertEqual(info.returncode, 0, info.stderr)
        self.assertIn("257 x 257", info.stdout)

    def test_lambda_grey_sketch_keeps_ring_and_lambda(self):
        sketch = os.path.join(self.sketches, "lambda_circle_grey.png")
        colorado = os.path.join(self.dems, "colorado.png")
        report = self.synth("colorado.png", sketch, self.path("lambda.tif"))
        self.assertEqual(report["sketch_kind"], "grey sketch")
        self.assertLessEqual(report["quality"]["seam_index"], MAX_SEAM_INDEX)
        # The ring and the lambda's three strokes stand as mountain ridges. Measured with Colorado
        # (Mont Blanc) over seeds 0-2: prominence 2.40-2.62 (2.41-2.45) of the exemplar's own ridges,
        # shedding 0.93-0.96 (0.94-0.96); the baselines 0.66 and 0.85 at most.
        figures = evaluate(self, self.path("lambda.tif"), colorado, sketch)
        assert_landform_bar(self, report, figures, {"ridge_prominence_ratio": 1.8, "ridge_shedding": 0.88})
        self.assertAlmostEqual(figures["terrain"]["ridge_fidelity"], report["quality"]["ridge_fidelity"], places=3)
        self.assertGreater(figures["random_patches"]["seam_index"], 2.0)
        # Against two exemplars the references are pooled: the Alps' sharper relief
        # raises the curvature reference, so the same terrain scores a lower seam index.
        pooled = tsynth("evaluate", self.path("lambda.tif"), "--exemplar",
                        os.path.join(self.dems, "colorado.png"), "--exemplar",
                        os.path.join(self.dems, "alps-montblanc.png"), "--json")
        self.assertEqual(pooled.returncode, 0, pooled.stderr)
        both = json.loads(pooled.stdout)["terrain"]
        self.assertLess(both["seam_index"], 0.9 * figures["terrain"]["seam_index"])
        self.assertNotAlmostEqual(both["slope_distance"], figures["terrain"]["slope_distance"], places=2)

    def test_polyline_elevations_are_met(self):
        # A ridge at 3500 m to 3000 m and a valley at 2000 m, drawn in metres on colorado's
        # 90 m cells: cells (20, 100)-(180, 100) and (10, 190)-(190, 150), in an output reaching
        # half a default patch (40 cells) past them.
        vtp = self.path("lines.vtp")
        write_polylines(vtp, [(20 * 90, 100 * 90), (180 * 90, 100 * 90), (10 * 90, 190 * 90), (190 * 90, 150 * 90)],
                        elevation=[3500, 3000, 2000, 2000])
        out = self.path("lines.tif")
        report = self.synth("colorado.png", vtp, out)
        self.assertEqual(report["sketch_kind"], "poly-lines")
        size = 191 + 80 // 2
        self.assertEqual(report["size"], [size, size])

        def height(column, row_from_south):
            line = size - 1 - row_from_south  # GDAL counts lines from the top
            r = subprocess.run(["gdallocationinfo", "-valonly", out, str(column), str(line)],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            return float(r.stdout.strip())

        # On the constrained ridge: 3500 m at x = 20, 3000 m at x = 180, linear between.
        for column, expected in ((20, 3500.0), (100, 3250.0), (180, 3000.0)):
            self.assertAlmostEqual(height(column, 100), expected, delta=1.0)
        self.assertAlmostEqual(height(100, 170), 2000.0, delta=1.0)

    def test_features_of_a_dem_are_a_sketch_of_the_same_dem(self):
        # tsynth features writes metres in the raster frame and the grid it was found on:
        # used as a sketch it gives an output of the DEM's size and cell size.
        dem = crop_dem(self.tmp, "colorado.png", (200, 200, 192, 160))
        features = self.path("features.vtp")
        done = tsynth("features", dem, "-o", features, "--both")
        self.assertEqual(done.returncode, 0, done.stderr)
        result = tsynth("synth", "--exemplar", dem, "--sketch", features, "--patch", "32",
                        "-o", self.path("again.tif"), "--report", self.path("again-report.json"), "--no-progress")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.path("again-report.json")) as f:
            report = json.load(f)
        self.assertEqual(report["sketch_kind"], "poly-lines")
        self.assertEqual(report["size"], [192, 160])
        self.assertEqual(report["cell_size_m"], [90.0, 90.0])
        self.assertGreater(report["feature_placements"], 20)
        # At half the cell size the same ground needs twice the cells a side.
        result = tsynth("synth", "--exemplar", dem, "--sketch", features, "--patch", "32", "--cell", "45",
                        "-o", self.path("fine.tif"), "--report", self.path("fine-report.json"), "--no-progress",
                        "--max-memory", "0.001")
        self.assertEqual(result.returncode, 1)
        self.assertIn("384 x 320 cells", result.stderr)  # refused by the budget, after sizing

    def test_crowded_feature_sites_are_spaced_and_a_drawing_with_room_keeps_its_own(self):
        # A DEM target's own ridge and valley tree has lines about 10 cells apart: a feature site
        # within a quarter patch of one already placed is left to that patch (about 2.6 times fewer
        # feature patches on 648 x 648 targets, the same band-pass correlation). So are a drawing's
        # whose lines are closer than patches draw (0.6 patches).
        def closest_feature_corners(report):
            corners = [(p[4], p[5]) for p in report["placement_list"] if p[1] == 1]
            return len(corners), min(math.hypot(a[0] - b[0], a[1] - b[1])
                                     for i, a in enumerate(corners) for b in corners[:i])

        colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        # Corners are the centres rounded to cells: up to a diagonal cell closer than the centres.
        def spacing_for(patch):
            return 0.25 * patch - math.sqrt(2)

        spaced = spacing_for(80)
        target = crop_dem(self.tmp, "mount_jackson_crop601.tif", (100, 100, 320, 320))
        report, _ = synthesise(self, colorado, target, self.path("dem.tif"))
        self.assertEqual(report["patch_size"], 32)  # a DEM target's own default
        count, closest = closest_feature_corners(report)
        self.assertGreater(count, 10)
        self.assertGreaterEqual(closest, spacing_for(32))

        def draw(name, ridge):
            path = self.path(name)
            write_png(path, 320, 320, lambda x, y: (255, 0, 0) if ridge(x, y) else (255, 255, 255))
            return path

        # Two ridges 12 pixels apart, finer than 80-cell patches draw (and said so).
        close = draw("close.png", lambda x, y: 40 <= x < 280 and (150 <= y < 152 or 162 <= y < 164))
        report, stderr = synthesise(self, colorado, close, self.path("close.tif"))
        self.assertIn("cells apart, closer than 80-cell patches draw", stderr)
        self.assertGreaterEqual(closest_feature_corners(report)[1], spaced)
        # A fork whose arms part at 40 degrees: its strokes have room, and the sites on the arms
        # beside the junction, closer than a quarter patch, each get their patch.
        def fork(x, y):
            arm = abs(abs(x - 160) - 0.36 * (300 - y)) < 1.5 and 20 <= y < 300
            return arm or (abs(x - 160) < 1.5 and 300 <= y < 310)
        report, stderr = synthesise(self, colorado, draw("fork.png", fork), self.path("fork.tif"))
        self.assertNotIn("patches draw", stderr)
        self.assertLess(closest_feature_corners(report)[1], spaced)

    def test_polylines_in_cells_or_degrees_are_refused_with_a_sentence(self):
        cells = self.path("cells.vtp")
        write_polylines(cells, [(20, 100), (180, 100), (10, 190), (190, 150)])
        out = self.path("never.tif")
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", cells,
                        "-o", out, "--no-progress")
        self.assertEqual(result.returncode, 1)
        self.assertIn("span 180 x 90 m", result.stderr)
        self.assertIn("are they in cells", result.stderr)
        self.assertIn("--size", result.stderr)
        self.assertEqual(result.stderr.count("\n"), 1)  # one sentence on one line
        degrees = self.path("degrees.vtp")
        write_polylines(degrees, [(-105.2, 39.1), (-104.9, 39.3)], types=(1,))
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", degrees,
                        "-o", out, "--no-progress")
        self.assertEqual(result.returncode, 1)
        self.assertIn("west or south of the raster frame", result.stderr)
        self.assertFalse(os.path.exists(out))

    def test_memory_budget_is_applied_to_the_reported_estimate(self):
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")
        common = ("--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", sketch,
                  "--size", "160x160", "--patch", "32", "--no-progress")
        report = self.synth("colorado.png", sketch, self.path("fits.tif"), "--size", "160x160", "--patch", "32")
        estimate = report["memory_estimate_gb"]
        self.assertGreater(estimate, 0.1)  # the program and a 648 x 648 exemplar's tables
        self.assertLess(estimate, 1.0)
        out = self.path("refused.tif")
        refused = tsynth("synth", *common, "-o", out, "--max-memory", "%.6f" % (0.99 * estimate))
        self.assertEqual(refused.returncode, 1)
        self.assertIn("needs about %d MB" % round(estimate * 1000), refused.stderr)
        self.assertIn("raise --max-memory", refused.stderr)
        self.assertFalse(os.path.exists(out))
        fits = tsynth("synth", *common, "-o", out, "--max-memory", "%.6f" % (1.01 * estimate))
        self.assertEqual(fits.returncode, 0, fits.stderr)

    def test_report_is_valid_json_with_quotes_in_paths_and_records_the_seed(self):
        out = self.path('a "quoted" \\ name.tif')
        report = self.synth("colorado.png", os.path.join(self.sketches, "strokes_y_ridges.png"), out,
                            "--size", "160x160", "--patch", "32", "--seed", "18446744073709551615")
        self.assertEqual(report["output"], out)
        self.assertEqual(report["seed"], 18446744073709551615)
        self.assertEqual(report["size"], [160, 160])
        self.assertEqual(len(report["placement_list"]), report["placements"])

    def test_bad_seed_and_size_are_usage_errors(self):
        base = ("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch",
                os.path.join(self.sketches, "strokes_y_ridges.png"), "-o", self.path("never.tif"))
        for seed in ("-1", "1.5", "abc", "18446744073709551616"):
            result = tsynth(*base, "--seed", seed)
            self.assertEqual(result.returncode, 2, seed)
            self.assertIn("--seed expects a whole number", result.stderr)
        for size, message in (("99999999999x2", "beyond any machine"), ("2000000x2", "beyond any machine"),
                              ("160", "expects WxH"), ("160x", "expects WxH"), ("0x160", "expects WxH"),
                              ("160x160x2", "expects WxH")):
            result = tsynth(*base, "--size", size)
            self.assertEqual(result.returncode, 2, size)
            self.assertIn(message, result.stderr, size)
        self.assertFalse(os.path.exists(self.path("never.tif")))

    def test_style_regions_choose_the_exemplars(self):
        labels = self.path("labels.asc")
        with open(labels, "w") as f:
            f.write("ncols 8\nnrows 8\nxllcorner 0\nyllcorner 0\ncellsize 1\n")
            f.write("0 0 0 0 1 1 1 1\n" * 8)  # west: label 0, east: label 1
        out = self.path("regions.tif")
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"),
                        "--exemplar", os.path.join(self.dems, "alps-montblanc.png"),
                        "--sketch", os.path.join(self.sketches, "strokes_y_ridges.png"), "--size", "320x320",
                        "--regions", labels, "--region", "0=1", "--region", "1=0",
                        "-o", out, "--report", out + ".json", "--no-progress")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(out + ".json") as f:
            placements = json.load(f)["placement_list"]
        west = {p[2] for p in placements if p[4] + 40 < 150}
        east = {p[2] for p in placements if p[4] + 40 > 170}
        self.assertEqual(west, {1})  # --region 0=1: the west is served by the alps
        self.assertEqual(east, {0})
        # A label with no exemplar is refused before any work.
        bad = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"),
                     "--sketch", os.path.join(self.sketches, "strokes_y_ridges.png"),
                     "--regions", labels, "-o", self.path("bad.tif"), "--no-progress")
        self.assertEqual(bad.returncode, 1)
        self.assertIn("has no exemplar", bad.stderr)
        self.assertFalse(os.path.exists(self.path("bad.tif")))

    def test_strokes_shorter_than_a_patch_get_a_warning_and_a_terrain(self):
        sketch = sketch_drawing.short_strokes().save(self.path("short.png"))
        colorado = os.path.join(self.dems, "colorado.png")
        report, stderr = synthesise(self, colorado, sketch, self.path("short.tif"))
        self.assertIn("shorter than one patch (80 cells)", stderr)
        self.assertIn("--patch", stderr)
        self.assertEqual(report["size"], [192, 192])
        self.assertGreater(report["feature_placements"], 0)
        # At a 40-cell patch the strokes (45-58 pixels) are longer than one: no warning.
        _, stderr = synthesise(self, colorado, sketch, self.path("finer.tif"), "--patch", "40")
        self.assertNotIn("shorter than one patch", stderr)

    def test_strokes_touching_the_border(self):
        sketch = sketch_drawing.border_strokes().save(self.path("border.png"))
        colorado = os.path.join(self.dems, "colorado.png")
        out = self.path("border.tif")
        report, stderr = synthesise(self, colorado, sketch, out, "--patch", "40", "--debug-dir", self.path("debug"))
        self.assertNotIn("warning", stderr)
        self.assertEqual(report["size"], [256, 256])
        # Measured over seeds 0-2 (baselines' best in brackets): prominence 1.87 [0.42], depth 2.26
        # [2.16], order 1.000 [0.910], drainage 0.849 [0.163] (the valley leaves the map on both
        # sides), descent 0.80 [0.60], shedding 0.961 [0.868].
        assert_landform_bar(self, report, evaluate(self, out, colorado, sketch, "--patch", "40"),
                            {"ridge_prominence_ratio": 1.4, "valley_depth_ratio": 1.7, "ridge_over_valley": 0.97,
                             "valley_drainage": 0.7, "valley_descent": 0.7, "ridge_shedding": 0.9})
        # The target does not taper the ridges where they leave the map: their prominence over the land
        # 40 cells to each side, along the last 10 cells (a quarter patch), is that of their middles
        # (measured 0.97-1.00 of it; before commit 2fa860d the west end had 0.43).
        target = read_grid(os.path.join(self.path("debug"), "target.tif"), self.tmp)
        row, column, side, edge = 80, 128, 40, 10  # the west-east ridge's row, the north ridge's column

        def across_row(x):
            crest = max(target[y][x] for y in range(row - 2, row + 3))
            return crest - (target[row - side][x] + target[row + side][x]) / 2

        def across_column(y):
            crest = max(target[y][column - 2:column + 3])
            return crest - (target[y][column - side] + target[y][column + side]) / 2

        middle = statistics.median(across_row(x) for x in range(side, 256 - side))
        for name, x_range in (("west", range(edge)), ("east", range(256 - edge, 256))):
            self.assertGreater(statistics.median(across_row(x) for x in x_range), 0.9 * middle, name)
        north = statistics.median(across_column(y) for y in range(edge))
        self.assertGreater(north, 0.9 * statistics.median(across_column(y) for y in range(side // 2, row - side // 2)))

    def test_a_closed_valley_loop_gets_a_warning_and_a_terrain(self):
        sketch = sketch_drawing.valley_loop().save(self.path("loop.png"))
        report, stderr = synthesise(self, os.path.join(self.dems, "colorado.png"), sketch, self.path("loop.tif"),
                                    "--patch", "40")
        self.assertIn("valley network has a loop", stderr)
        self.assertEqual(report["size"], [192, 192])
        self.assertIsNotNone(report["landform_quality"]["valley_depth_m"])

    def test_ctrl_c_stops_promptly_and_writes_nothing(self):
        import signal
        import time
        out = self.path("interrupted.tif")
        sketch = os.path.join(PATHS.bundled_data, "sketches", "strokes_valley_tree.png")
        command = [PATHS.tsynth, "synth", "--exemplar", os.path.join(self.dems, "colorado.png"),
                   "--sketch", sketch, "--size", "1024x1024", "--no-progress"]
        whole_out = self.path("whole.tif")
        whole = harness.seconds_to_run(lambda: subprocess.run(command + ["-o", whole_out], check=True,
                                                              capture_output=True))
        os.remove(whole_out)
        p = subprocess.Popen(command + ["-o", out, "--report", out + ".json"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(0.4 * whole)  # into the placements
        self.assertIsNone(p.poll(), "the synthesis ended before it could be interrupted")
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=60 + whole)
        harness.assert_stopped_promptly(self, "tsynth synth", time.monotonic() - sent, whole)
        self.assertEqual(p.returncode, 130, err)
        self.assertIn("nothing was written", err)
        self.assertEqual([f for f in os.listdir(self.tmp) if "interrupted" in f], [])

    def test_bad_input(self):
        blank = self.path("blank.png")
        write_png(blank, 200, 200, lambda x, y: (255, 255, 255))
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", blank,
                        "-o", self.path("blank.tif"), "--no-progress")
        # Nothing drawn is refused (issue 14) rather than a terrain that ignores the sketch.
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("The sketch has nothing drawn", result.stderr)
        self.assertFalse(os.path.exists(self.path("blank.tif")))

        small = self.path("small.asc")
        with open(small, "w") as f:
            f.write("ncols 40\nnrows 40\nxllcorner 0\nyllcorner 0\ncellsize 90\n")
            f.write(("100 " * 40 + "\n") * 40)
        out = self.path("never.tif")
        result = tsynth("synth", "--exemplar", small, "--sketch", os.path.join(self.sketches, "strokes_y_ridges.png"),
                        "-o", out, "--no-progress")
        self.assertEqual(result.returncode, 1)
        self.assertIn("smaller than one patch", result.stderr)
        self.assertFalse(os.path.exists(out))

        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch",
                        os.path.join(self.sketches, "strokes_y_ridges.png"), "-o", out, "--size", "300000x300000")
        self.assertEqual(result.returncode, 1)
        self.assertIn("GB", result.stderr)
        self.assertFalse(os.path.exists(out))

        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch",
                        os.path.join(self.sketches, "strokes_y_ridges.png"), "-o", out, "--merge", "glue")
        self.assertEqual(result.returncode, 2)
        self.assertFalse(os.path.exists(out))
        self.assertEqual(tsynth("synth", "--help").returncode, 0)


if __name__ == "__main__":
    harness.run(__name__)
