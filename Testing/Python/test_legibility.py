"""Issue 20: the sketch reads off the terrain. Drawn sketches whose strokes are closer together than a
patch (a branching valley network between bounding ridges, block letters in a ring valley, rings, a
grid), each with two exemplars, must be legible at each stroke's own scale (LegibilityOptions: the
share of stroke length whose cross-section, out to half the spacing to the facing stroke, stands out
of the exemplars' own relief at that half width); a DEM target must be followed at its own scales at
least as well as Tasse's code follows it; strokes finer than the patches draw get a warning."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402
import sketch_drawing  # noqa: E402
from test_synth import crop_dem, evaluate, synthesise  # noqa: E402

PATCH = "40"  # the drawings are 320 x 320 (sketch_drawing.SIZE)
BOTH = ("colorado.png", "alps-montblanc.png")

# Least legible shares (whole stroke length, ridges, valleys) each drawing must reach with both
# exemplars. Measured over seeds 0-2 (the least in the comment, then the previous landing's best, whose
# tsynth ignored the stroke spacing: that landing fails each bar); each bar is set a little below the
# least so that another seed passes too. Testing/Benchmarks/legibility_vs_landing.py scores any other
# tsynth against these bars (the previous landing: 21 of 24 runs fail, only the grid on Colorado passes).
BARS = {
    # least 0.64 (ridges 0.88, valleys 0.53); previous landing's best 0.57 (valleys 0.44)
    "valley_network": {"all": 0.6, "valley": 0.5},
    # least 0.82 (ridges 0.73, valleys 0.85); previous 0.72 (valleys 0.70)
    "letters_in_a_ring": {"all": 0.78, "valley": 0.8},
    # least 0.92 (ridges 0.97, valleys 0.89); previous 0.74 (valleys 0.66)
    "rings": {"all": 0.85, "valley": 0.85},
    # least 0.88 (ridges 0.89, valleys 0.80); previous 0.96 with Colorado but 0.89 (ridges 0.82) with
    # Mont Blanc: the grid already read well, and still does
    "grid": {"all": 0.85, "ridge": 0.86},
}


class LegibilityTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-legibility-")
        self.dems = os.path.join(PATHS.bundled_data, "dems")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def synthesise(self, exemplar, sketch, out, *extra):
        return synthesise(self, exemplar, sketch, out, *extra)

    def evaluate(self, terrain, exemplar, sketch, *extra):
        return evaluate(self, terrain, exemplar, sketch, *extra)

    def assert_legible(self, draw):
        sketch = draw().save(os.path.join(self.tmp, draw.__name__ + ".png"))
        bar = BARS[draw.__name__]
        for exemplar in BOTH:
            with self.subTest(exemplar=exemplar):
                dem = os.path.join(self.dems, exemplar)
                out = os.path.join(self.tmp, exemplar + ".tif")
                report, _ = self.synthesise(dem, sketch, out, "--patch", PATCH)
                ours = report["legibility"]
                figures = {"all": ours["legible_share"], "ridge": ours["ridge"]["legible_share"],
                           "valley": ours["valley"]["legible_share"]}
                for kind, least in bar.items():
                    self.assertGreaterEqual(figures[kind], least, "%s: %s" % (kind, ours))
                # tsynth evaluate reads the same from the file, and the random-patch baseline (the
                # exemplar pasted at random: no sketch in it) reads far less.
                evaluated = self.evaluate(out, dem, sketch, "--patch", PATCH)
                self.assertAlmostEqual(evaluated["terrain"]["legibility"]["legible_share"],
                                       ours["legible_share"], delta=1e-6)
                self.assertLess(evaluated["random_patches"]["legibility"]["legible_share"],
                                ours["legible_share"] - 0.3)
                # The patches carry their own ridges and valleys onto the strokes before any
                # correction: their PPA lines lie within a few cells of the drawn ones (measured on
                # 40-cell patches: median 1.0 cells, 90th percentile 1.0-2.0; on the letters with
                # 80-cell patches and Everest 2.0 and 3.7, against 5.0 and 8.2 when the seam cost
                # alone chose among 8 candidates).
                offsets = report["feature_line_offset_cells"]
                self.assertLessEqual(offsets["median"], 1.5)
                self.assertLessEqual(offsets["p90"], 3.0)
                self.assertGreater(report["legibility_before_corrections"]["legible_share"],
                                   evaluated["random_patches"]["legibility"]["legible_share"])

    def test_valley_network_between_bounding_ridges(self):
        self.assert_legible(sketch_drawing.valley_network)

    def test_letters_in_a_ring_valley(self):
        self.assert_legible(sketch_drawing.letters_in_a_ring)

    def test_rings(self):
        self.assert_legible(sketch_drawing.rings)

    def test_grid_stays_legible(self):
        self.assert_legible(sketch_drawing.grid)

    def test_block_letters_carved_as_valleys_read_at_default_patches_and_drain(self):
        # H and I carved as valleys on the README's 512 x 512 frame at the default 80-cell patches,
        # where the strokes (120-140 cells apart) are narrower than the correction's blur used to
        # draw: seed 0 reads 0.46 (Colorado) and 0.50 (Mont Blanc), the least over seeds 0-2 is 0.28
        # (Colorado, seed 1: by eye too the faintest H of the six). Those figures are the measure's
        # since it asks a stroke to stand out of the terrain's own land as well as the exemplars',
        # along a run at least its half width long; the measure before read the same terrains at
        # 0.64, 0.67 and 0.55 at least (and 3e034fb's, which drew each landform blurred at its own
        # scale, at 0.48 and 0.54 for seed 0). Each letter is a valley network whose outlet lies
        # inside the map: its water is led out of that closed basin (valley drainage 0.58-0.88 over
        # seeds 0-2; the previous landing 0.44 on Colorado seed 0).
        sketch = sketch_drawing.carved_letters().save(os.path.join(self.tmp, "carved_letters.png"))
        for exemplar in BOTH:
            with self.subTest(exemplar=exemplar):
                out = os.path.join(self.tmp, exemplar + ".tif")
                report, _ = self.synthesise(os.path.join(self.dems, exemplar), sketch, out)
                self.assertGreaterEqual(report["legibility"]["legible_share"], 0.25, report["legibility"])
                self.assertGreaterEqual(report["landform_quality"]["valley_drainage"], 0.55)

    def test_strokes_closer_than_the_patches_draw_get_a_warning_naming_the_spacing_and_patch(self):
        # Ridges 15 pixels apart: 40-cell patches draw strokes 24 cells apart at the finest (the final
        # correction goes down to a tenth of a patch, and follows three times that each side).
        c = sketch_drawing.Canvas(sketch_drawing.SIZE, sketch_drawing.SIZE)
        for y in range(20, 310, 15):
            c.polyline([(10, y), (310, y)], sketch_drawing.RIDGE, pen=4)
        sketch = c.save(os.path.join(self.tmp, "fine.png"))
        dem = os.path.join(self.dems, "colorado.png")
        _, stderr = self.synthesise(dem, sketch, os.path.join(self.tmp, "fine.tif"), "--patch", PATCH)
        found = re.search(r"strokes are about (\d+) cells apart, closer than 40-cell patches draw: "
                          r"they will read faintly; give a patch of (\d+) cells", stderr)
        self.assertIsNotNone(found, stderr)
        spacing, patch = int(found.group(1)), int(found.group(2))
        self.assertLessEqual(abs(spacing - 15), 1)  # drawn 15 apart, read off skeletons of 4-pixel pens
        # The largest patch (a multiple of 4) whose finest correction, 0.6 of it, fits that spacing.
        self.assertEqual(patch, int(spacing / 0.6) // 4 * 4)
        # The drawings above leave their strokes room: no such warning.
        sketch = sketch_drawing.valley_network().save(os.path.join(self.tmp, "network.png"))
        _, stderr = self.synthesise(dem, sketch, os.path.join(self.tmp, "network.tif"), "--patch", PATCH)
        self.assertNotIn("cells apart", stderr)


# Band-pass correlation (sigma 2, 4, 8, 16, 32 cells) with the target of Tasse's code (the peer) on a
# 320 x 320 window of the bundled Mount Jackson DEM as the target, 80-cell patches, measured with
# ../shared/peers/tasse/run.sh and tsynth evaluate (README, "Legibility"). Ours, with its own default
# patch for a DEM target (32 cells), must reach at least the peer's at every scale once corrected, and
# before the corrections at the finer two.
PEER_CORRELATION = {
    "colorado.png": (0.06, 0.18, 0.40, 0.69, 0.84),
    "alps-montblanc.png": (0.06, 0.20, 0.46, 0.81, 0.93),
}


class DemTargetTest(unittest.TestCase):
    def test_a_dem_target_is_followed_at_its_own_scales_at_least_as_well_as_by_the_peer(self):
        tmp = tempfile.mkdtemp(prefix="tsynth-dem-target-")
        try:
            target = crop_dem(tmp, "mount_jackson_crop601.tif", (100, 100, 320, 320))
            for exemplar, peer in PEER_CORRELATION.items():
                with self.subTest(exemplar=exemplar):
                    out = os.path.join(tmp, exemplar + ".tif")
                    report, stderr = synthesise(
                        self, os.path.join(PATHS.bundled_data, "dems", exemplar), target, out)
                    # A DEM target gets 32-cell patches unless told otherwise (80 for drawings), and
                    # its ridges and valleys, about 10 cells apart, are finer still: it says so.
                    self.assertEqual(report["patch_size"], 32)
                    self.assertIn("cells apart, finer than 32-cell patches follow: the finest of them "
                                  "will read faintly; give a patch of 16 cells", stderr)
                    final = [c["correlation"] for c in report["target_correlation"]]
                    before = [c["correlation"] for c in report["target_correlation_before_corrections"]]
                    self.assertEqual([c["sigma_cells"] for c in report["target_correlation"]], [2, 4, 8, 16, 32])
                    for ours, theirs in zip(final, peer):
                        self.assertGreaterEqual(ours, theirs)
                    for ours, theirs in zip(before[:2], peer[:2]):
                        self.assertGreaterEqual(ours, theirs)
        finally:
            shutil.rmtree(tmp)


class SketchOverlay(unittest.TestCase):
    """Examples/legibility/overlay.py draws a stroke map's outlines over hillshades, side by side."""

    SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "legibility",
                          "overlay.py")

    def write_rgb(self, path, rgb):
        from osgeo import gdal
        d = gdal.GetDriverByName("MEM").Create("", rgb.shape[2], rgb.shape[1], 3, gdal.GDT_Byte)
        for i in range(3):
            d.GetRasterBand(i + 1).WriteArray(rgb[i])
        gdal.GetDriverByName("PNG").CreateCopy(path, d)

    def overlay(self, *args):
        return subprocess.run([sys.executable, self.SCRIPT, *args], capture_output=True, text=True)

    def test_outlines_lie_on_the_strokes_edges_over_each_hillshade(self):
        import numpy as np
        from osgeo import gdal
        tmp = tempfile.mkdtemp()
        try:
            sketch = np.full((3, 40, 60), 255, np.uint8)
            sketch[:, 10:20, 5:55] = np.array([230, 20, 20], np.uint8)[:, None, None]  # a red ridge bar
            sketch[:, 22:38, 20:30] = np.array([20, 20, 230], np.uint8)[:, None, None]  # a blue valley bar
            shade = np.full((3, 80, 120), 128, np.uint8)  # twice the sketch's size, mid grey
            self.write_rgb(os.path.join(tmp, "sketch.png"), sketch)
            self.write_rgb(os.path.join(tmp, "shade.png"), shade)
            out = os.path.join(tmp, "out.png")
            done = self.overlay(out, os.path.join(tmp, "sketch.png"), os.path.join(tmp, "shade.png"),
                                os.path.join(tmp, "shade.png"))
            self.assertEqual(done.returncode, 0, done.stderr)
            sheet = gdal.Open(out).ReadAsArray()
            self.assertEqual(sheet.shape, (3, 40, 2 * 60 + 8))
            for left in (0, 68):
                panel = sheet[:, :, left:left + 60]
                red = (panel[0] == 255) & (panel[1] == 0)
                blue = (panel[2] == 255) & (panel[0] == 0)
                # Two cells deep along each edge of the 10 x 50 bar: 2 * (50 + 10) * 2 - 16 cells.
                self.assertEqual(int(red.sum()), 2 * (50 + 10) * 2 - 16)
                self.assertTrue(red[10, 5] and red[11, 6] and not red[12, 7] and not red[15, 30])
                self.assertTrue(blue[22, 20] and not blue[30, 25])
                grey = ~red & ~blue
                self.assertTrue((panel[:, grey] == 128).all())
            self.assertTrue((sheet[:, :, 60:68] == 255).all())  # the gutter
        finally:
            shutil.rmtree(tmp)

    def test_refuses_a_sketch_without_strokes_and_an_output_that_is_an_input(self):
        import numpy as np
        tmp = tempfile.mkdtemp()
        try:
            grey = os.path.join(tmp, "grey.png")
            self.write_rgb(grey, np.full((3, 20, 20), 90, np.uint8))
            done = self.overlay(os.path.join(tmp, "out.png"), grey, grey)
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("not a stroke map", done.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "out.png")))
            done = self.overlay(grey, grey, grey)
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("is one of the inputs", done.stderr)
        finally:
            shutil.rmtree(tmp)


if __name__ == "__main__":
    harness.run(__name__)
