"""The synthesis end to end through the command line: quality bar, determinism, bad input."""
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402
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


def tsynth(*args):
    return subprocess.run([PATHS.tsynth, *args], capture_output=True, text=True, timeout=600)


class SynthTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-synth-")
        self.dems = os.path.join(PATHS.bundled_data, "dems")
        self.sketches = os.path.join(PATHS.shared_data, "sketches")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def synth(self, exemplar, sketch, out, *extra):
        report = out + ".json"
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, exemplar), "--sketch", sketch,
                        "-o", out, "--report", report, "--no-progress", *extra)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(report) as f:
            return json.load(f)

    def test_quality_bar_on_both_stroke_sketches_with_two_exemplars(self):
        for exemplar in ("colorado.png", "alps-montblanc.png"):
            for sketch in ("strokes_y_ridges.png", "strokes_valley_meander.png"):
                with self.subTest(exemplar=exemplar, sketch=sketch):
                    report = self.synth(exemplar, os.path.join(self.sketches, sketch),
                                        self.path(exemplar + sketch + ".tif"))
                    q = report["quality"]
                    self.assertEqual(report["size"], [512, 512])
                    self.assertGreater(report["feature_placements"], 10)
                    self.assertGreaterEqual(q["ridge_fidelity"], 0.85)
                    self.assertGreaterEqual(q["valley_fidelity"], 0.85)
                    self.assertLessEqual(q["seam_index"], 1.3)
                    self.assertLessEqual(q["slope_distance"], 0.15)

    def test_same_result_on_opencl_and_cpu(self):
        sketch = os.path.join(self.sketches, "strokes_y_ridges.png")
        a = self.synth("colorado.png", sketch, self.path("opencl.tif"), "--backend", "opencl", "--size", "320x320")
        b = self.synth("colorado.png", sketch, self.path("cpu.tif"), "--backend", "cpu", "--size", "320x320")
        self.assertIn("opencl", a["backend"])
        self.assertEqual(b["backend"], "cpu")
        self.assertTrue(filecmp.cmp(self.path("opencl.tif"), self.path("cpu.tif"), shallow=False))
        again = self.synth("colorado.png", sketch, self.path("cpu2.tif"), "--backend", "cpu", "--size", "320x320")
        self.assertEqual(again["placements"], b["placements"])
        self.assertTrue(filecmp.cmp(self.path("cpu.tif"), self.path("cpu2.tif"), shallow=False))

    def test_lambda_grey_sketch_keeps_ring_and_lambda(self):
        sketch = os.path.join(self.sketches, "lambda_circle_grey.png")
        report = self.synth("colorado.png", sketch, self.path("lambda.tif"))
        self.assertEqual(report["sketch_kind"], "grey sketch")
        # Fidelity along the sketch's own lines: the ring and the lambda's three strokes.
        self.assertGreaterEqual(report["quality"]["ridge_fidelity"], 0.85)
        evaluated = tsynth("evaluate", self.path("lambda.tif"), "--exemplar",
                           os.path.join(self.dems, "colorado.png"), "--sketch", sketch, "--json")
        self.assertEqual(evaluated.returncode, 0, evaluated.stderr)
        figures = json.loads(evaluated.stdout)
        self.assertAlmostEqual(figures["terrain"]["ridge_fidelity"], report["quality"]["ridge_fidelity"], places=3)
        # The baselines do not follow the sketch.
        self.assertLess(figures["tiled_exemplar"]["ridge_fidelity"], 0.6)
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
        # 90 m cells: cells (20, 100)-(180, 100) and (10, 190)-(190, 150).
        vtp = self.path("lines.vtp")
        write_polylines(vtp, [(20 * 90, 100 * 90), (180 * 90, 100 * 90), (10 * 90, 190 * 90), (190 * 90, 150 * 90)],
                        elevation=[3500, 3000, 2000, 2000])
        out = self.path("lines.tif")
        report = self.synth("colorado.png", vtp, out)
        self.assertEqual(report["sketch_kind"], "poly-lines")
        self.assertEqual(report["size"], [191, 191])

        def height(column, row_from_south):
            line = 191 - 1 - row_from_south  # GDAL counts lines from the top
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
                        "-o", self.path("again.tif"), "--report", self.path("again.json"), "--no-progress")
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.path("again.json")) as f:
            report = json.load(f)
        self.assertEqual(report["sketch_kind"], "poly-lines")
        self.assertEqual(report["size"], [192, 160])
        self.assertEqual(report["cell_size_m"], [90.0, 90.0])
        self.assertGreater(report["feature_placements"], 20)
        # At half the cell size the same ground needs twice the cells a side.
        result = tsynth("synth", "--exemplar", dem, "--sketch", features, "--patch", "32", "--cell", "45",
                        "-o", self.path("fine.tif"), "--report", self.path("fine.json"), "--no-progress",
                        "--max-memory", "0.001")
        self.assertEqual(result.returncode, 1)
        self.assertIn("384 x 320 cells", result.stderr)  # refused by the budget, after sizing

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

    def test_bad_input(self):
        blank = self.path("blank.png")
        write_png(blank, 200, 200, lambda x, y: (255, 255, 255))
        result = tsynth("synth", "--exemplar", os.path.join(self.dems, "colorado.png"), "--sketch", blank,
                        "-o", self.path("blank.tif"), "--no-progress")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("no features", result.stderr)
        self.assertTrue(os.path.exists(self.path("blank.tif")))

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
