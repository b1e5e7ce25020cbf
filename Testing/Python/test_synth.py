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
        # An ASCII VTK poly-data sketch: a ridge at 3500 m to 3000 m, a valley at 2000 m.
        vtp = self.path("lines.vtp")
        with open(vtp, "w") as f:
            f.write("""<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
<PolyData><Piece NumberOfPoints="4" NumberOfVerts="0" NumberOfLines="2" NumberOfStrips="0" NumberOfPolys="0">
<PointData><DataArray type="Float32" Name="Elevation" format="ascii">3500 3000 2000 2000</DataArray></PointData>
<CellData><DataArray type="Int32" Name="FeatureType" format="ascii">1 -1</DataArray></CellData>
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">20 100 0 180 100 0 10 190 0 190 150 0</DataArray></Points>
<Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">2 4</DataArray></Lines>
</Piece></PolyData></VTKFile>
""")
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
