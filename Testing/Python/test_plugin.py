"""pvpython tests: the plugin loads, its proxies and wrapped classes run on real DEMs."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

import numpy as np  # noqa: E402
from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402


# Marked lines and feature trees are shown this many pixels wide (Plugin/TerrainLineWidths.xml).
THICK_LINE_WIDTH = 3.0


def point_array(data, name):
    array = data.GetPointData().GetArray(name)
    if array is None:
        raise AssertionError("missing point array %s" % name)
    return vtk_to_numpy(array)


def horn_slope_degrees(z, cx, cy):
    """Reference slope on interior cells, written independently of the C++ code."""
    a, b, c = z[2:, :-2], z[2:, 1:-1], z[2:, 2:]
    d, f = z[1:-1, :-2], z[1:-1, 2:]
    g, h, i = z[:-2, :-2], z[:-2, 1:-1], z[:-2, 2:]
    p = ((c + 2 * f + i) - (a + 2 * d + g)) / (8 * cx)
    q = ((a + 2 * b + c) - (g + 2 * h + i)) / (8 * cy)
    return np.degrees(np.arctan(np.hypot(p, q)))


def image_from(z, spacing, origin=(0.0, 0.0), arrays=None):
    """A 2D vtkImageData with point arrays from numpy (rows = y)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk

    ny, nx = z.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    image.SetSpacing(spacing[0], spacing[1], 1.0)
    image.SetOrigin(origin[0], origin[1], 0.0)
    elevation = numpy_to_vtk(np.ascontiguousarray(z.ravel(), dtype=np.float32), deep=1)
    elevation.SetName("Elevation")
    image.GetPointData().SetScalars(elevation)
    for name, values in (arrays or {}).items():
        a = numpy_to_vtk(np.ascontiguousarray(values.ravel()), deep=1)
        a.SetName(name)
        image.GetPointData().AddArray(a)
    return image


def producer(image):
    source = simple.PVTrivialProducer()
    source.GetClientSideObject().SetOutput(image)
    source.UpdatePipeline()
    return source


def dem_array(path):
    reader = simple.TerrainReader(FileName=path)
    data = sm.Fetch(reader)
    nx, ny, _ = data.GetDimensions()
    return point_array(data, "Elevation").reshape(ny, nx).astype(np.float64), data.GetSpacing()


class PluginTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        simple.LoadPlugin(PATHS.plugin, remote=False)
        cls.alps = os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png")

    def test_reader_proxy_reads_metres_and_cell_size(self):
        reader = simple.TerrainReader(FileName=self.alps)
        reader.UpdatePipeline()
        data = sm.Fetch(reader)
        self.assertEqual(data.GetDimensions(), (647, 647, 1))
        self.assertAlmostEqual(data.GetSpacing()[0], 92.74, places=6)
        z = point_array(data, "Elevation")
        self.assertAlmostEqual(float(z.min()), 454.0, places=2)
        self.assertAlmostEqual(float(z.max()), 4810.0, places=2)

    def test_tile_writer_writes_tiles_that_give_the_heights_back(self):
        folder = tempfile.mkdtemp(prefix="tsynth-tiles-")
        try:
            reader = simple.TerrainReader(FileName=self.alps)
            mosaic = os.path.join(folder, "alps.vrt")
            writer = sm.writers.TerrainTileWriter(Input=reader, FileName=mosaic, TileSize=257)
            writer.UpdatePipeline()
            tiles = sorted(n for n in os.listdir(folder) if n.endswith(".tif"))
            self.assertEqual(len(tiles), 9)  # 647 samples: tiles from 0, 256 and 512
            self.assertEqual(len([n for n in os.listdir(folder) if n.endswith(".json")]), 9)
            original = point_array(sm.Fetch(reader), "Elevation")
            back = point_array(sm.Fetch(simple.TerrainReader(FileName=mosaic)), "Elevation")
            np.testing.assert_array_equal(back, original)

            engine = os.path.join(folder, "alps.png")
            refused = sm.writers.TerrainTileWriter(Input=reader, FileName=engine, TileSize=250)
            refused.UpdatePipeline()  # says why (2^k + 1 samples) and writes nothing
            self.assertFalse([n for n in os.listdir(folder) if n.endswith(".png")])
            accepted = sm.writers.TerrainTileWriter(Input=reader, FileName=engine, TileSize=129)
            accepted.UpdatePipeline()
            self.assertEqual(len([n for n in os.listdir(folder) if n.endswith(".png")]), 36)
        finally:
            shutil.rmtree(folder)

    def test_reader_to_hillshade_arrays_and_ranges(self):
        reader = simple.TerrainReader(FileName=self.alps)
        shade = simple.TerrainHillshade(Input=reader)
        shade.UpdatePipeline()
        data = sm.Fetch(shade)
        nx, ny, _ = data.GetDimensions()
        cx, cy, _ = data.GetSpacing()
        hill = point_array(data, "Hillshade")
        slope = point_array(data, "Slope").reshape(ny, nx)
        z = point_array(data, "Elevation").reshape(ny, nx).astype(np.float64)
        self.assertGreaterEqual(float(hill.min()), 0.0)
        self.assertLessEqual(float(hill.max()), 1.0)
        self.assertGreater(float(hill.std()), 0.05)  # real relief, not a flat grey
        np.testing.assert_allclose(slope[1:-1, 1:-1], horn_slope_degrees(z, cx, cy), atol=1e-3)
        self.assertGreater(float(slope.max()), 40.0)  # Mont Blanc massif cliffs
        self.assertLess(float(slope.max()), 90.0)

    def test_single_light_from_opposite_sides_inverts_shading(self):
        reader = simple.TerrainReader(FileName=self.alps)
        west = simple.TerrainHillshade(Input=reader, Multidirectional=0, Azimuth=270.0)
        east = simple.TerrainHillshade(Input=reader, Multidirectional=0, Azimuth=90.0)
        hw = point_array(sm.Fetch(west), "Hillshade")
        he = point_array(sm.Fetch(east), "Hillshade")
        correlation = np.corrcoef(hw, he)[0, 1]
        self.assertLess(correlation, -0.5)

    def test_wrapped_classes_give_the_same_result_as_the_proxies(self):
        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainHillshade, vtkTerrainReader

        reader = vtkTerrainReader()
        reader.SetFileName(self.alps)
        shade = vtkTerrainHillshade()
        shade.SetInputConnection(reader.GetOutputPort())
        shade.Update()
        direct = point_array(shade.GetOutput(), "Hillshade")
        proxy = simple.TerrainHillshade(Input=simple.TerrainReader(FileName=self.alps))
        np.testing.assert_array_equal(direct, point_array(sm.Fetch(proxy), "Hillshade"))

    def test_vti_written_by_tsynth_opens_in_paraview(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "alps.vti")
            subprocess.run([PATHS.tsynth, "convert", self.alps, "-o", out], check=True,
                           stdout=subprocess.DEVNULL)
            opened = simple.OpenDataFile(out)
            self.assertIsNotNone(opened)
            opened.UpdatePipeline()
            data = sm.Fetch(opened)
            self.assertEqual(data.GetDimensions(), (647, 647, 1))
            z = point_array(data, "Elevation")
            self.assertAlmostEqual(float(z.max()), 4810.0, places=2)

    def test_reader_factory_opens_an_esri_grid_with_the_plugin(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "tiny.asc")
            with open(path, "w") as f:
                f.write("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                        "NODATA_value -9999\n1 2 3\n4 -9999 6\n")
            reader = simple.OpenDataFile(path)
            self.assertEqual(reader.GetXMLName(), "TerrainReader")
            reader.UpdatePipeline()
            data = sm.Fetch(reader)
            valid = point_array(data, "Valid")
            self.assertEqual(int(valid.sum()), 5)
            self.assertEqual(data.GetSpacing()[0], 10.0)

    # Feature trees ------------------------------------------------------------------------

    def check_tree_arrays(self, data):
        """The DESIGN.md arrays exist and agree with each other."""
        kind = point_array(data, "NodeKind")
        degree = point_array(data, "Degree")
        for name in ("Elevation", "BFSRank", "ComponentId"):
            point_array(data, name)
        feature_type = vtk_to_numpy(data.GetCellData().GetArray("FeatureType"))
        self.assertTrue(set(np.unique(feature_type)) <= {-1, 1})
        self.assertIsNotNone(data.GetCellData().GetArray("ChainId"))
        order = vtk_to_numpy(data.GetFieldData().GetArray("BFSOrder"))
        nodes = np.flatnonzero(kind != 0)
        # Every end or branch node is in the breadth-first order exactly once.
        self.assertTrue(set(nodes.tolist()) <= set(order.tolist()))
        self.assertEqual(len(order), len(set(order.tolist())))
        np.testing.assert_array_equal(degree[kind == 1], 1)
        self.assertTrue(np.all(degree[kind == 2] >= 3))
        return kind, degree, feature_type

    def test_feature_extractor_on_a_real_dem(self):
        reader = simple.TerrainReader(FileName=self.alps)
        features = simple.TerrainFeatureExtractor(Input=reader, Features=2)
        features.UpdatePipeline()
        tree = sm.Fetch(features, arg1=None, arg2=None, idx=0)
        kind, degree, feature_type = self.check_tree_arrays(tree)
        self.assertGreater(int((kind == 2).sum()), 20)  # a mountain massif branches
        self.assertGreater(int((feature_type == 1).sum()), 50)
        self.assertGreater(int((feature_type == -1).sum()), 50)
        # Coordinates are metres inside the DEM (647 cells of 92.74 m).
        bounds = tree.GetBounds()
        self.assertGreaterEqual(bounds[0], 0.0)
        self.assertLessEqual(bounds[1], 646 * 92.74 + 1e-6)
        # Ridge nodes stand higher than valley nodes on average.
        elevation = point_array(tree, "Elevation")
        self.assertGreater(float(elevation.max()), 3000.0)
        controls = sm.Fetch(features, arg1=None, arg2=None, idx=1)
        self.assertGreater(controls.GetNumberOfPoints(), 100)
        # Significance (default 0.02 of the relief) drops minor lines; 0 gives plain PPA,
        # with more chains (measured 1137 vs 847 on this DEM's ridges and valleys).
        self.assertAlmostEqual(features.Significance, 0.02)
        plain = simple.TerrainFeatureExtractor(Input=reader, Features=2, Significance=0.0)
        plain.UpdatePipeline()
        plain_tree = sm.Fetch(plain, arg1=None, arg2=None, idx=0)
        self.assertGreater(plain_tree.GetNumberOfLines(), 1.2 * tree.GetNumberOfLines())

    def test_sketch_features_from_a_stroke_map(self):
        png = simple.PNGSeriesReader(FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        features = simple.TerrainSketchFeatures(Input=png)
        features.UpdatePipeline()
        tree = sm.Fetch(features, arg1=None, arg2=None, idx=0)
        kind, degree, feature_type = self.check_tree_arrays(tree)
        self.assertEqual(int((kind == 2).sum()), 1)  # the Y's fork
        self.assertEqual(int((kind == 1).sum()), 7)  # 3 ridge ends, 4 valley ends
        self.assertEqual(sorted(np.unique(feature_type).tolist()), [-1, 1])

    def test_sketch_reader_lays_the_sketch_on_the_exemplars_grid(self):
        """The Terrain Sketch Reader gives the sketch the exemplar's cells, so it lies under the
        terrain made from it, and synthesises the same terrain as ParaView's PNG reader."""
        strokes = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        exemplar = simple.TerrainReader(FileName=colorado)
        sketch = simple.TerrainSketchReader(FileName=strokes, ExemplarFileName=colorado)
        sketch.UpdatePipeline()
        image = sm.Fetch(sketch)
        self.assertEqual(image.GetDimensions(), (512, 512, 1))
        self.assertEqual(image.GetSpacing()[:2], (90.0, 90.0))  # colorado.json's cell size
        self.assertEqual(image.GetOrigin(), (0.0, 0.0, 0.0))
        png = sm.Fetch(simple.PNGSeriesReader(FileNames=[strokes]))
        self.assertEqual(png.GetSpacing()[0], 1.0)  # the speck this reader replaces
        np.testing.assert_array_equal(vtk_to_numpy(image.GetPointData().GetArray("Sketch")),
                                      vtk_to_numpy(png.GetPointData().GetScalars()))

        def terrain(sketch_source):
            synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch_source,
                                            OutputSize=[128, 128], PatchSize=32, Backend=2)
            synth.UpdatePipeline()
            return sm.Fetch(synth, arg1=None, arg2=None, idx=0)

        ours = terrain(sketch)
        self.assertEqual(ours.GetSpacing(), image.GetSpacing())
        np.testing.assert_array_equal(
            point_array(ours, "Elevation"),
            point_array(terrain(simple.PNGSeriesReader(FileNames=[strokes])), "Elevation"))
        # The sketch's feature tree comes out in metres on the same grid.
        features = simple.TerrainSketchFeatures(Input=sketch)
        features.UpdatePipeline()
        bounds = sm.Fetch(features, arg1=None, arg2=None, idx=0).GetBounds()
        self.assertGreater(bounds[1], 0.5 * 511 * 90.0)
        self.assertLessEqual(bounds[1], 511 * 90.0 + 1e-6)
        # CellSize overrides; a DEM target reads as heights; poly-lines are pointed elsewhere.
        sketch.CellSize = 30.0
        sketch.UpdatePipeline()
        self.assertEqual(sm.Fetch(sketch).GetSpacing()[:2], (30.0, 30.0))
        dem = simple.TerrainSketchReader(FileName=self.alps, ExemplarFileName=colorado)
        dem.UpdatePipeline()
        heights = point_array(sm.Fetch(dem), "Elevation")
        self.assertEqual(sm.Fetch(dem).GetSpacing()[0], 90.0)
        np.testing.assert_array_equal(heights, dem_array(self.alps)[0].ravel())
        with tempfile.TemporaryDirectory() as tmp:
            lines = os.path.join(tmp, "lines.vtp")
            open(lines, "w").close()
            refused = simple.TerrainSketchReader(FileName=lines)
            refused.UpdatePipeline()
            self.assertEqual(sm.Fetch(refused).GetNumberOfPoints(), 0)

    def test_sketch_features_from_polylines_with_elevation(self):
        from vtkmodules.vtkCommonCore import vtkFloatArray, vtkIntArray, vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
        from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

        points = vtkPoints()
        for x, y in [(0, 0), (0, 900), (-600, 1800), (600, 1800), (2000, 0), (2000, 1800)]:
            points.InsertNextPoint(x + 3000.0, y + 100.0, 0.0)
        lines = vtkCellArray()
        for ids in ([0, 1], [1, 2], [1, 3], [4, 5]):
            lines.InsertNextCell(len(ids))
            for i in ids:
                lines.InsertCellPoint(i)
        poly = vtkPolyData()
        poly.SetPoints(points)
        poly.SetLines(lines)
        kinds = vtkIntArray()
        kinds.SetName("FeatureType")
        for v in (1, 1, 1, -1):
            kinds.InsertNextValue(v)
        poly.GetCellData().AddArray(kinds)
        heights = vtkFloatArray()
        heights.SetName("Elevation")
        for v in (1500, 2500, 1800, 1800, 900, 600):
            heights.InsertNextValue(v)
        poly.GetPointData().AddArray(heights)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "lines.vtp")
            writer = vtkXMLPolyDataWriter()
            writer.SetInputData(poly)
            writer.SetFileName(path)
            writer.SetDataModeToBinary()
            writer.Write()
            drawn = simple.OpenDataFile(path)
            features = simple.TerrainSketchFeatures(Input=drawn, CellSize=90.0)
            features.UpdatePipeline()
            tree = sm.Fetch(features, arg1=None, arg2=None, idx=0)
        kind, degree, feature_type = self.check_tree_arrays(tree)
        self.assertEqual(int((kind == 2).sum()), 1)
        self.assertEqual(int((kind == 1).sum()), 5)
        constraint = point_array(tree, "ElevationConstraint")
        branch = int(np.flatnonzero(kind == 2)[0])
        self.assertEqual(float(constraint[branch]), 2500.0)
        x, y, _ = tree.GetPoint(branch)
        self.assertAlmostEqual(x, 3000.0, places=6)
        self.assertAlmostEqual(y, 1000.0, places=6)

    def test_features_vtp_written_by_tsynth_opens_in_paraview(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "ridges.vtp")
            dem = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
            subprocess.run([PATHS.tsynth, "features", dem, "-o", out, "--features", "ridges"],
                           check=True, stdout=subprocess.DEVNULL)
            opened = simple.OpenDataFile(out)
            opened.UpdatePipeline()
            tree = sm.Fetch(opened)
            kind, degree, feature_type = self.check_tree_arrays(tree)
            np.testing.assert_array_equal(feature_type, 1)
            self.assertGreater(tree.GetNumberOfCells(), 100)

    # Matching --------------------------------------------------------------------------------

    def test_candidate_builder_table(self):
        reader = simple.TerrainReader(FileName=self.alps)
        builder = simple.TerrainCandidateBuilder(Input=[reader], PatchSize=64)
        builder.UpdatePipeline()
        table = sm.Fetch(builder)
        rows = table.GetNumberOfRows()
        self.assertGreater(rows, 1000)
        self.assertEqual(rows % 10, 0)  # every site in 10 variants
        variant = vtk_to_numpy(table.GetColumnByName("Variant"))
        self.assertEqual(sorted(np.unique(variant).tolist()), list(range(10)))
        x = vtk_to_numpy(table.GetColumnByName("X"))
        y = vtk_to_numpy(table.GetColumnByName("Y"))
        # Sites keep half a rotated patch (46 cells) away from the edges.
        self.assertGreaterEqual(float(x.min()), 45 * 92.74)
        self.assertLessEqual(float(x.max()), (646 - 45) * 92.74)
        self.assertGreaterEqual(float(y.min()), 45 * 92.74)
        kinds = set(np.unique(vtk_to_numpy(table.GetColumnByName("Kind"))).tolist())
        self.assertEqual(kinds, {0, 1, 2})

    def test_patch_matcher_finds_the_target_in_its_own_exemplar(self):
        reader = simple.TerrainReader(FileName=self.alps)
        site = [300 * 92.74, 320 * 92.74]
        for mode in (0, 1):
            matcher = simple.TerrainPatchMatcher(Input=reader, Exemplars=[reader], Mode=mode,
                                                 Site=site, PatchSize=64, K=4)
            matcher.UpdatePipeline()
            table = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
            self.assertGreaterEqual(table.GetNumberOfRows(), 1)
            variant = int(table.GetColumnByName("Variant").GetValue(0))
            cost = float(table.GetColumnByName("Cost").GetValue(0))
            x = float(table.GetColumnByName("X").GetValue(0))
            y = float(table.GetColumnByName("Y").GetValue(0))
            # The target is the exemplar: the best match is the place itself, unrotated. In
            # feature mode the target's site is found on its significant lines and the
            # candidates' on every line (as the synthesis does): their arms differ a little.
            self.assertEqual(variant, 0, "mode %d" % mode)
            self.assertLess(cost, 1e-3 if mode == 1 else 0.05, "mode %d" % mode)
            if mode == 1:
                # An even-sized window around a cell centres half a cell before it.
                self.assertAlmostEqual(x, site[0] - 0.5 * 92.74, delta=1.0)
                self.assertAlmostEqual(y, site[1] - 0.5 * 92.74, delta=1.0)
            else:
                self.assertLess(abs(x - site[0]), 32 * 92.74)  # the nearest feature site
            costmap = sm.Fetch(matcher, arg1=None, arg2=None, idx=1)
            self.assertEqual(costmap.GetDimensions(), (647, 647, 1))
            values = point_array(costmap, "MatchCost")
            self.assertGreater(int(np.isfinite(values).sum()), 100)
            self.assertAlmostEqual(float(np.nanmin(values)), cost, delta=max(1e-6, 1e-3 * abs(cost)) + 1e-3)

    def test_patch_matcher_takes_the_candidate_builders_table(self):
        # The two stages chained: the matcher given the builder's table matches exactly as
        # the matcher that builds its own pool; emptying the property builds it again.
        reader = simple.TerrainReader(FileName=self.alps)
        builder = simple.TerrainCandidateBuilder(Input=[reader], PatchSize=64)
        site = [300 * 92.74, 320 * 92.74]
        options = dict(Input=reader, Exemplars=[reader], Mode=0, Site=site, PatchSize=64, K=4,
                       Backend=2)
        own = simple.TerrainPatchMatcher(**options)
        chained = simple.TerrainPatchMatcher(CandidatePool=builder, **options)

        def costs(matcher):
            matcher.UpdatePipeline()
            table = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
            return [vtk_to_numpy(table.GetColumnByName(c)).copy()
                    for c in ("Variant", "X", "Y", "Cost")]

        expected = costs(own)
        self.assertGreaterEqual(len(expected[3]), 4)
        for a, b in zip(expected, costs(chained)):
            np.testing.assert_array_equal(a, b)
        # A pool of another patch size is refused, with the sizes named.
        from vtkmodules.vtkCommonCore import vtkCommand
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING
        builder.PatchSize = 80
        errors = []

        @calldata_type(VTK_STRING)
        def on_error(_caller, _event, text):
            errors.append(text)

        chained.GetClientSideObject().AddObserver(vtkCommand.ErrorEvent, on_error)
        chained.UpdatePipeline()
        self.assertTrue(any("built for patches of 80 cells, not 64" in e for e in errors), errors)
        chained.CandidatePool = None
        for a, b in zip(expected, costs(chained)):
            np.testing.assert_array_equal(a, b)

    def test_matcher_extractor_and_merger_chain(self):
        # Builder -> Matcher -> Extractor -> Merger in ParaView's proxies: the self-match at a
        # place of the exemplar's own ridges, cut and merged back, leaves the terrain as it was.
        reader = simple.TerrainReader(FileName=self.alps)
        builder = simple.TerrainCandidateBuilder(Input=[reader], PatchSize=64)
        builder.UpdatePipeline()
        pool = sm.Fetch(builder)
        site = [pool.GetColumnByName("X").GetValue(300), pool.GetColumnByName("Y").GetValue(300)]
        # Dense mode: the window itself is the best match, exactly.
        matcher = simple.TerrainPatchMatcher(Input=reader, Exemplars=[reader], CandidatePool=builder,
                                             Mode=1, Site=site, PatchSize=64, K=4, Backend=2)
        extractor = simple.TerrainPatchExtractor(Input=reader, Exemplars=[reader],
                                                 Matches=simple.OutputPort(matcher, 0))
        merger = simple.TerrainGraphCutMerger(Input=reader, Patch=extractor)
        merger.UpdatePipeline()
        patch = sm.Fetch(extractor)
        self.assertEqual(patch.GetDimensions(), (64, 64, 1))
        matches = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
        cell = matches.GetFieldData().GetArray("PatchCell")
        self.assertAlmostEqual(patch.GetOrigin()[0], cell.GetValue(0) * 92.74, delta=0.5)
        self.assertAlmostEqual(patch.GetOrigin()[1], cell.GetValue(1) * 92.74, delta=0.5)
        self.assertEqual(patch.GetFieldData().GetArray("VerticalOffset").GetValue(0), 0.0)
        self.assertEqual(int(point_array(patch, "Core").sum()), 0)  # a dense match owns nothing
        z, _ = dem_array(self.alps)
        merged = point_array(sm.Fetch(merger), "Elevation").reshape(z.shape)
        self.assertLess(float(np.abs(merged - z).max()), 1e-3)
        # The second best, shifted onto the terrain's level, is cut too.
        extractor.Rank = 1
        extractor.UpdatePipeline()
        self.assertNotEqual(sm.Fetch(extractor).GetFieldData().GetArray("VerticalOffset").GetValue(0),
                            0.0)

    def test_patch_matcher_with_two_exemplars_and_the_cpu_backend(self):
        alps = simple.TerrainReader(FileName=self.alps)
        colorado = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        matcher = simple.TerrainPatchMatcher(Input=alps, Exemplars=[colorado, alps], Mode=0,
                                             Site=[300 * 92.74, 320 * 92.74], PatchSize=64, K=3,
                                             Backend=2)
        matcher.UpdatePipeline()
        table = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
        exemplars = vtk_to_numpy(table.GetColumnByName("Exemplar"))
        self.assertEqual(sorted(exemplars.tolist()), [0, 0, 0, 1, 1, 1])  # K per exemplar
        costs = vtk_to_numpy(table.GetColumnByName("Cost"))
        self.assertTrue(np.all(np.diff(costs) >= 0))
        self.assertEqual(int(exemplars[0]), 1)  # the alps match themselves best

    # Merging ---------------------------------------------------------------------------------

    def test_patch_placed_back_leaves_the_terrain_unchanged(self):
        z, spacing = dem_array(self.alps)
        filled = np.zeros(z.shape, dtype=np.uint8)
        filled[:, :300] = 1
        terrain = producer(image_from(z, spacing, arrays={"Filled": filled}))
        patch_z = z[250:346, 250:346]
        patch = producer(image_from(patch_z, spacing, origin=(250 * spacing[0], 250 * spacing[1])))
        for mode in (0, 1, 2, 3):
            merged = simple.TerrainGraphCutMerger(Input=terrain, Patch=patch, Mode=mode)
            merged.UpdatePipeline()
            data = sm.Fetch(merged)
            out = point_array(data, "Elevation").reshape(z.shape)
            now = point_array(data, "Filled").reshape(z.shape)
            self.assertTrue(np.all(now[250:346, 250:346] == 1), "mode %d" % mode)
            np.testing.assert_allclose(out[now == 1], z[now == 1], rtol=0, atol=1e-3,
                                       err_msg="mode %d" % mode)

    def test_new_mode_hides_the_seam_that_cut_leaves(self):
        terrain_z, spacing = dem_array(os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        alps_z, _ = dem_array(self.alps)
        filled = np.zeros(terrain_z.shape, dtype=np.uint8)
        filled[:, :300] = 1
        terrain = producer(image_from(terrain_z, spacing, arrays={"Filled": filled}))
        patch = producer(image_from(alps_z[200:296, 200:296], spacing,
                                    origin=(260 * spacing[0], 200 * spacing[1])))
        steps = {}
        for mode in (0, 3):
            merged = simple.TerrainGraphCutMerger(Input=terrain, Patch=patch, Mode=mode, PatchIdValue=7)
            merged.UpdatePipeline()
            data = sm.Fetch(merged)
            out = point_array(data, "Elevation").reshape(terrain_z.shape)
            seam = point_array(data, "SeamMask").reshape(terrain_z.shape)
            ids = point_array(data, "PatchId").reshape(terrain_z.shape)
            self.assertGreater(int(seam.sum()), 50)
            self.assertGreater(int((ids == 7).sum()), 96 * 50)
            self.assertGreater(float(data.GetFieldData().GetArray("CutCost").GetValue(0)), 0.0)
            # Height steps between horizontal neighbours on the seam.
            rows, cols = np.nonzero(seam[:, :-1])
            steps[mode] = np.percentile(np.abs(out[rows, cols + 1] - out[rows, cols]), 95)
        own = np.percentile(np.abs(np.diff(terrain_z, axis=1)), 99)
        self.assertGreater(steps[0], 3 * own)  # the cut alone leaves a cliff
        self.assertLess(steps[3], own)         # the gradient-domain merge removes it

    def test_poisson_solver_clones_one_dem_into_another(self):
        dst_z, spacing = dem_array(os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        src_z, _ = dem_array(self.alps)
        dst_z = dst_z[100:300, 100:300]
        src_z = src_z[300:500, 300:500] + 2000.0
        yy, xx = np.mgrid[0:200, 0:200]
        mask = ((xx - 100) ** 2 + (yy - 100) ** 2 < 60 ** 2).astype(np.uint8)
        destination = producer(image_from(dst_z, spacing))
        source = producer(image_from(src_z, spacing, arrays={"Mask": mask}))
        solver = simple.TerrainPoissonSolver(Input=destination, Source=source, Mode=0)
        solver.UpdatePipeline()
        data = sm.Fetch(solver)
        out = point_array(data, "Elevation").reshape(200, 200).astype(np.float64)
        np.testing.assert_array_equal(out[mask == 0], dst_z[mask == 0].astype(np.float32))

        def laplacian(a):
            return a[1:-1, 2:] + a[1:-1, :-2] + a[2:, 1:-1] + a[:-2, 1:-1] - 4 * a[1:-1, 1:-1]
        inside = mask[1:-1, 1:-1] == 1
        scale = np.abs(laplacian(src_z)[inside]).max()
        self.assertLess(np.abs(laplacian(out) - laplacian(src_z))[inside].max(), 1e-3 * scale)
        # No step at the edge: the 2000 m offset is gone next to the boundary.
        ring = (mask == 1) & ((xx - 100) ** 2 + (yy - 100) ** 2 > 58 ** 2)
        self.assertLess(abs(float(np.mean(out[ring] - dst_z[ring]))), 100.0)

    def test_mask_and_known_arrays_are_chosen_by_name(self):
        full, spacing = dem_array(self.alps)
        z = full[200:328, 200:328]
        exemplar = producer(image_from(full[350:550, 350:550], spacing))
        yy, xx = np.mgrid[0:128, 0:128]
        disc = ((xx - 64) ** 2 + (yy - 64) ** 2 < 30 ** 2).astype(np.uint8)
        destination = producer(image_from(z, spacing))
        lifted = full[350:478, 350:478] + 500.0  # other relief, so where it lands shows

        def clone(arrays, **properties):
            source = producer(image_from(lifted, spacing, arrays=arrays))
            solver = simple.TerrainPoissonSolver(Input=destination, Source=source, Mode=0,
                                                 **properties)
            solver.UpdatePipeline()
            return point_array(sm.Fetch(solver), "Elevation").copy()

        by_default = clone({"Mask": disc})
        renamed = clone({"Region": disc, "Mask": np.ones_like(disc)}, MaskArray="Region")
        np.testing.assert_array_equal(renamed, by_default)
        whole = clone({"Region": disc})  # the default "Mask" is absent: the whole source
        self.assertGreater(int(np.count_nonzero(whole != by_default)), 1000)
        mistyped = simple.TerrainPoissonSolver(
            Input=destination, Source=producer(image_from(lifted, spacing, arrays={"Region": disc})),
            Mode=0, MaskArray="Regoin")
        mistyped.UpdatePipeline()
        self.assertEqual(sm.Fetch(mistyped).GetNumberOfPoints(), 0)

        site = [64 * spacing[0], 64 * spacing[1]]

        def best_cost(arrays, **properties):
            target = producer(image_from(z, spacing, arrays=arrays))
            matcher = simple.TerrainPatchMatcher(Input=target, Exemplars=[exemplar], Mode=1,
                                                 Site=site, PatchSize=32, K=1, **properties)
            matcher.UpdatePipeline()
            table = sm.Fetch(matcher, arg1=None, arg2=None, idx=0)
            return float(table.GetColumnByName("Cost").GetValue(0)) if table.GetNumberOfRows() else None

        half = (xx < 64).astype(np.uint8)
        known = best_cost({"Known": half})
        chosen = best_cost({"Done": half, "Known": np.ones_like(half)}, KnownArray="Done")
        self.assertEqual(chosen, known)
        self.assertNotEqual(best_cost({"Known": np.ones_like(half)}), known)  # the choice counts
        self.assertIsNone(best_cost({"Done": half}, KnownArray="Dnoe"))

    def test_array_selections_name_elevation_on_their_own_input(self):
        """A heights selection starts at Elevation (not ParaView's "0 (?)"), and one on a second
        input reads that input. The selections keep port 0 (a port-1 selection crashes ParaView
        5.11's vtkPVPostFilter), so the filters look the name up on their second input: read
        through the selection's port, picking the source's Elevation cloned the destination."""
        full, spacing = dem_array(self.alps)
        dst_z = full[100:228, 100:228]
        lifted = full[300:428, 300:428] + 500.0
        destination = producer(image_from(dst_z, spacing))
        source = producer(image_from(lifted, spacing))
        destination.UpdatePipeline()
        source.UpdatePipeline()

        def elements(proxy, name):
            prop = proxy.GetProperty(name)
            return [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]

        made = {
            "TerrainHillshade": (simple.TerrainHillshade(Input=destination),
                                 {"SelectInputScalars": "0"}),
            "TerrainSynthesis": (simple.TerrainSynthesis(Exemplars=[destination], Sketch=source),
                                 {"SelectExemplarScalars": "0"}),
            "TerrainGraphCutMerger": (simple.TerrainGraphCutMerger(Input=destination, Patch=source),
                                      {"SelectInputScalars": "0", "SelectPatchScalars": "1"}),
            "TerrainPoissonSolver": (simple.TerrainPoissonSolver(Input=destination, Source=source),
                                     {"SelectInputScalars": "0", "SelectSourceScalars": "1"}),
            "TerrainPitRemoval": (simple.TerrainPitRemoval(Input=destination, Sinks=source),
                                  {"SelectInputScalars": "0", "SelectSinkScalars": "1"}),
        }
        for filter_name, (proxy, selections) in made.items():
            for name, index in selections.items():
                e = elements(proxy, name)
                self.assertEqual((e[0], e[1], e[4]), (index, "0", "Elevation"),
                                 "%s %s: %s" % (filter_name, name, e))
            proxy.UpdatePipeline()  # runs (the pit removal with every cell a sink) without a crash

        yy, xx = np.mgrid[0:128, 0:128]
        disc = ((xx - 64) ** 2 + (yy - 64) ** 2 < 30 ** 2).astype(np.uint8)
        masked = producer(image_from(lifted, spacing, arrays={"Mask": disc}))

        def clone(**properties):
            solver = simple.TerrainPoissonSolver(Input=destination, Source=masked, Mode=0, **properties)
            solver.UpdatePipeline()
            return point_array(sm.Fetch(solver), "Elevation").reshape(128, 128).copy()

        by_default = clone()
        picked = clone(SourceHeights=["POINTS", "Elevation"])  # what picking it in the panel does
        np.testing.assert_array_equal(picked, by_default)
        inside = disc == 1
        self.assertGreater(float(np.abs(picked[inside] - dst_z[inside]).max()), 100.0,
                           "the source's relief is cloned in, not the destination's own")

    def test_array_selections_read_elevation_when_made_before_their_input_ran(self):
        """Made in pvpython on a reader that has not run yet, a heights selection names Elevation
        (ParaView set it to the empty array list's "0"; the NoDefault hint keeps the XML's
        Elevation), and the filters run on it."""
        colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        strokes = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")

        def reader():
            return simple.TerrainReader(FileName=colorado)  # not updated: no arrays known yet

        def elements(proxy, name):
            prop = proxy.GetProperty(name)
            return [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]

        sketch = simple.TerrainSketchReader(FileName=strokes, ExemplarFileName=colorado)
        made = {
            "TerrainSynthesis": (simple.TerrainSynthesis(Exemplars=[reader()], Sketch=sketch, OutputSize=[128, 128],
                                                         PatchSize=32, Backend="CPU"),
                                 ["SelectExemplarScalars"]),
            "TerrainFeatureExtractor": (simple.TerrainFeatureExtractor(Input=reader()), ["SelectInputScalars"]),
            "TerrainHillshade": (simple.TerrainHillshade(Input=reader()), ["SelectInputScalars"]),
            "TerrainCandidateBuilder": (simple.TerrainCandidateBuilder(Input=[reader()], PatchSize=64),
                                        ["SelectExemplarScalars"]),
            "TerrainPatchMatcher": (simple.TerrainPatchMatcher(Input=reader(), Exemplars=[reader()], PatchSize=32,
                                                               Backend=2),
                                    ["SelectInputScalars", "SelectExemplarScalars"]),
            "TerrainGraphCutMerger": (simple.TerrainGraphCutMerger(Input=reader(), Patch=reader()),
                                      ["SelectInputScalars", "SelectPatchScalars"]),
            "TerrainPoissonSolver": (simple.TerrainPoissonSolver(Input=reader(), Source=reader()),
                                     ["SelectInputScalars", "SelectSourceScalars"]),
            "TerrainPitRemoval": (simple.TerrainPitRemoval(Input=reader(), Sinks=reader()),
                                  ["SelectInputScalars", "SelectSinkScalars"]),
            "TerrainOptimisation": (simple.TerrainOptimisation(Source=reader(), Guide=sketch, OutputSize=[64, 64]),
                                    ["SelectInputScalars"]),
        }
        for filter_name, (proxy, selections) in made.items():
            for name in selections:
                self.assertEqual(elements(proxy, name)[3:], ["0", "Elevation"], "%s %s" % (filter_name, name))
        # They run: the synthesis and the feature tree from the exemplar's heights.
        synth, _ = made["TerrainSynthesis"]
        synth.UpdatePipeline()
        terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        self.assertEqual(terrain.GetDimensions(), (128, 128, 1))
        z = point_array(terrain, "Elevation")
        self.assertFalse(np.isnan(z).any())
        self.assertGreater(float(z.max() - z.min()), 500.0)  # Colorado's relief, not a flat field
        features, _ = made["TerrainFeatureExtractor"]
        features.UpdatePipeline()
        self.assertGreater(sm.Fetch(features).GetNumberOfLines(), 100)

    def test_exemplar_heights_are_chosen_by_name(self):
        full, spacing = dem_array(self.alps)
        a, b = full[:256, :256], full[300:556, 300:556]
        both = producer(image_from(a, spacing, arrays={"Other": b.astype(np.float32)}))
        only_b = producer(image_from(b, spacing))

        def table(exemplar, **properties):
            builder = simple.TerrainCandidateBuilder(Input=[exemplar], PatchSize=64, **properties)
            builder.UpdatePipeline()
            t = sm.Fetch(builder)
            return {t.GetColumnName(c): vtk_to_numpy(t.GetColumn(c)).copy()
                    for c in range(t.GetNumberOfColumns())}

        chosen = table(both, ExemplarHeights=["POINTS", "Other"])
        reference = table(only_b)
        self.assertEqual(sorted(chosen), sorted(reference))
        for name in reference:
            np.testing.assert_array_equal(chosen[name], reference[name], err_msg=name)
        default = table(both)
        self.assertNotEqual(len(default["X"]), 0)
        self.assertFalse(len(default["X"]) == len(reference["X"]) and
                         np.array_equal(default["X"], reference["X"]), "the choice changed nothing")

    def test_arrays_of_the_wrong_length_fail_the_request_with_a_sentence(self):
        from vtkmodules.vtkCommonCore import vtkCommand
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING

        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainPoissonSolver

        z = np.full((50, 60), 100.0)
        short = numpy_to_vtk(np.ones(10, dtype=np.uint8), deep=1)
        short.SetName("Mask")
        destination = image_from(z, (90.0, 90.0))
        source = image_from(z + 5.0, (90.0, 90.0))
        source.GetPointData().AddArray(short)
        gradient = numpy_to_vtk(np.zeros((10, 2)), deep=1)
        gradient.SetName("Gradient")
        guided = image_from(z, (90.0, 90.0), arrays={"Mask": np.ones(z.shape, dtype=np.uint8)})
        guided.GetPointData().AddArray(gradient)
        cases = [(0, destination, source, "The Mask array has 10 values for 3000 points"),
                 (1, guided, None, "The Gradient array has 10 values for 3000 points")]
        for mode, dst, src, message in cases:
            solver = vtkTerrainPoissonSolver()
            solver.SetMode(mode)
            solver.SetInputData(0, dst)
            if src is not None:
                solver.SetInputData(1, src)
            errors = []

            @calldata_type(VTK_STRING)
            def on_error(_caller, _event, text):
                errors.append(text)

            solver.AddObserver(vtkCommand.ErrorEvent, on_error)
            solver.Update()
            self.assertEqual(solver.GetOutput().GetNumberOfPoints(), 0, message)
            self.assertTrue(any(message in e for e in errors), errors)

    def test_patch_matcher_refuses_a_target_smaller_than_a_patch(self):
        z, spacing = dem_array(self.alps)
        small = producer(image_from(z[:40, :40], spacing))
        exemplar = simple.TerrainReader(FileName=self.alps)
        matcher = simple.TerrainPatchMatcher(Input=small, Exemplars=[exemplar], PatchSize=64)
        matcher.UpdatePipeline()
        self.assertEqual(sm.Fetch(matcher, arg1=None, arg2=None, idx=0).GetNumberOfRows(), 0)

    # Synthesis -------------------------------------------------------------------------------

    def test_synthesis_filter_follows_a_stroke_sketch(self):
        exemplar = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        sketch = simple.PNGSeriesReader(FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[256, 256])
        synth.UpdatePipeline()
        terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        self.assertEqual(terrain.GetDimensions(), (256, 256, 1))
        self.assertEqual(terrain.GetSpacing()[0], 90.0)
        z = point_array(terrain, "Elevation")
        self.assertFalse(np.isnan(z).any())
        ids = point_array(terrain, "PatchId")
        self.assertTrue(np.all(ids >= 0))  # every cell comes from a placement
        self.assertGreater(int(point_array(terrain, "SeamMask").sum()), 100)
        placements = sm.Fetch(synth, arg1=None, arg2=None, idx=1)
        rows = placements.GetNumberOfRows()
        self.assertEqual(rows, int(ids.max()) + 1)
        feature = vtk_to_numpy(placements.GetColumnByName("Feature"))
        self.assertGreater(int(feature.sum()), 5)
        # The sketch's Y: the trunk (x = 256 of 512 sketch pixels) stands above its flanks.
        grid = z.reshape(256, 256)
        trunk = grid[30:100, 124:132].mean()
        flanks = 0.5 * (grid[30:100, 100:108].mean() + grid[30:100, 148:156].mean())
        self.assertGreater(trunk, flanks)

    def test_preview_first_shows_a_preview_then_the_whole_synthesis_bit_for_bit(self):
        sys.path.insert(0, PATHS.python_dir)
        import terrainsynthesis  # noqa: F401  (the client-side objects' own methods)
        exemplar = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        sketch = simple.PNGSeriesReader(FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        settings = dict(Exemplars=[exemplar], Sketch=sketch, OutputSize=[256, 256], UseExemplarCache=0)
        plain = simple.TerrainSynthesis(**settings)
        plain.UpdatePipeline()
        whole = sm.Fetch(plain, arg1=None, arg2=None, idx=0)
        self.assertEqual(plain.GetClientSideObject().GetOutputLevel(), "final")

        live = simple.TerrainSynthesis(PreviewFirst=1, **settings)
        self.assertIsNotNone(live.SMProxy.GetHints().FindNestedElementByName("LiveSource"),
                             "ParaView's GUI polls GetNeedsUpdate only with the LiveSource hint")
        live.UpdatePipeline()
        filter_ = live.GetClientSideObject()
        self.assertEqual(filter_.GetOutputLevel(), "preview")
        preview = sm.Fetch(live, arg1=None, arg2=None, idx=0)
        # On the terrain's grid, heights only, in the exemplar's range.
        self.assertEqual(preview.GetDimensions(), whole.GetDimensions())
        self.assertEqual(preview.GetSpacing(), whole.GetSpacing())
        self.assertIsNone(preview.GetPointData().GetArray("PatchId"))
        z_preview = point_array(preview, "Elevation")
        z_whole = point_array(whole, "Elevation")
        self.assertFalse(np.isnan(z_preview).any())
        self.assertLess(abs(np.median(z_preview) - np.median(z_whole)), 0.25 * np.ptp(z_whole))
        self.assertFalse(np.array_equal(z_preview, z_whole))
        self.assertEqual(live.GetDataInformation(0).GetNumberOfPoints(), 256 * 256)
        self.assertEqual(live.GetDataInformation(1).GetNumberOfRows(), 0)  # no placements yet

        filter_.WaitForRefinement()
        self.assertTrue(filter_.GetNeedsUpdate())
        self.assertFalse(filter_.GetNeedsUpdate(), "a refinement is announced once")
        live.SMProxy.MarkModified(live.SMProxy)  # as ParaView's live-source poll does
        live.UpdatePipeline()
        self.assertEqual(filter_.GetOutputLevel(), "final")
        final = sm.Fetch(live, arg1=None, arg2=None, idx=0)
        for name in ("Elevation", "PatchId", "SeamMask"):
            self.assertTrue(np.array_equal(point_array(final, name), point_array(whole, name)), name)
        self.assertEqual(sm.Fetch(live, arg1=None, arg2=None, idx=1).GetNumberOfRows(),
                         sm.Fetch(plain, arg1=None, arg2=None, idx=1).GetNumberOfRows())

        # Another seed: a preview again, then that seed's whole synthesis.
        live.Seed = 3
        live.UpdatePipeline()
        self.assertEqual(filter_.GetOutputLevel(), "preview")
        filter_.WaitForRefinement()
        self.assertTrue(filter_.GetNeedsUpdate())
        live.SMProxy.MarkModified(live.SMProxy)
        live.UpdatePipeline()
        self.assertEqual(filter_.GetOutputLevel(), "final")
        plain.Seed = 3
        plain.UpdatePipeline()
        self.assertTrue(np.array_equal(point_array(sm.Fetch(live, arg1=None, arg2=None, idx=0), "Elevation"),
                                       point_array(sm.Fetch(plain, arg1=None, arg2=None, idx=0), "Elevation")))

        # A patch with no coarser level: the whole synthesis at once (and a warning).
        live.PatchSize = 28
        live.UpdatePipeline()
        self.assertEqual(filter_.GetOutputLevel(), "final")
        self.assertFalse(filter_.GetNeedsUpdate())
        self.assertIsNotNone(sm.Fetch(live, arg1=None, arg2=None, idx=0).GetPointData().GetArray("PatchId"))

    def test_an_edit_stops_the_refinement_under_way_and_keeps_the_preview(self):
        sys.path.insert(0, PATHS.python_dir)
        import terrainsynthesis  # noqa: F401
        exemplar = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        sketch = simple.PNGSeriesReader(FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        live = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[1024, 1024],
                                       PreviewFirst=1, UseExemplarCache=0)
        live.UpdatePipeline()
        filter_ = live.GetClientSideObject()
        self.assertEqual(filter_.GetOutputLevel(), "preview")
        # An edit while the whole synthesis (seconds) runs: a new preview, no stale result.
        live.Seed = 5
        started = harness.seconds_to_run(live.UpdatePipeline)
        self.assertEqual(filter_.GetOutputLevel(), "preview")
        self.assertFalse(filter_.GetNeedsUpdate())
        # Switched off: the whole synthesis at once, and nothing left running.
        live.PreviewFirst = 0
        whole = harness.seconds_to_run(live.UpdatePipeline)
        self.assertEqual(filter_.GetOutputLevel(), "final")
        self.assertFalse(filter_.GetNeedsUpdate())
        # The edit was answered by a preview in a fraction of the whole synthesis' time.
        self.assertLess(started, 0.5 * whole, "preview %.2f s, whole %.2f s" % (started, whole))

    def test_gdal_raster_reader_images_are_read_as_the_terrain_reader_reads_them(self):
        """ParaView's GDAL Raster Reader (what File > Open preselects for a GeoTIFF) puts the
        heights on cells and hides nodata: the filters read them as the Terrain Reader's points,
        so the synthesis of either is the same terrain, bit for bit."""
        from osgeo import gdal
        z, _ = dem_array(os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        z = z[:200, :240].astype(np.float32)[::-1]  # north-up rows for GDAL
        z[10:30, 40:70] = -9999.0  # a nodata block
        folder = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, folder)
        path = os.path.join(folder, "projected.tif")
        ds = gdal.GetDriverByName("GTiff").Create(path, 240, 200, 1, gdal.GDT_Float32)
        ds.SetGeoTransform((500000.0, 90.0, 0.0, 4400000.0, 0.0, -90.0))
        band = ds.GetRasterBand(1)
        band.SetNoDataValue(-9999.0)
        band.WriteArray(z)
        ds = None
        sketch = simple.PNGSeriesReader(
            FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        terrains = []
        shades = []
        for reader in (simple.TerrainReader(FileName=path), simple.GDALRasterReader(FileName=path)):
            shade = simple.TerrainHillshade(Input=reader)
            shade.UpdatePipeline()
            data = sm.Fetch(shade)
            self.assertEqual(data.GetDimensions(), (240, 200, 1), reader.GetXMLName())
            shades.append(point_array(data, "Hillshade"))
            synth = simple.TerrainSynthesis(Exemplars=[reader], Sketch=sketch, PatchSize=32,
                                            OutputSize=[96, 96], Backend=2)
            synth.UpdatePipeline()
            terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
            self.assertEqual(terrain.GetDimensions(), (96, 96, 1))
            self.assertEqual(terrain.GetSpacing()[0], 90.0)
            terrains.append(point_array(terrain, "Elevation"))
        self.assertFalse(np.isnan(terrains[0]).any())
        np.testing.assert_array_equal(terrains[0], terrains[1])
        np.testing.assert_array_equal(shades[0], shades[1])
        # Nodata stayed nodata: the hidden block has no shade, the rest has.
        hidden = np.isnan(shades[1].reshape(200, 240)[170:190, 40:70])
        self.assertTrue(hidden.all())
        self.assertLess(int(np.isnan(shades[1]).sum()), 20 * 30 + 2 * (20 + 30) + 4)

    def test_loading_the_plugin_sets_terrain_colour_maps_and_the_dem_reader(self):
        """Once loaded, ParaView colours the plugin's arrays as terrain is read (grey hillshade,
        a terrain map for heights, categories for patches and feature kinds) and File > Open
        reads DEM files with the Terrain Reader (its 'Supported Files' default)."""
        import paraview.modules.vtkRemotingServerManager as rsm
        settings = rsm.vtkSMSettings.GetInstance()
        key = ".settings.RepresentedArrayListSettings.ReaderDetails"
        self.assertEqual(settings.GetSettingAsString(key, 2, ""), "TerrainReader")
        self.assertIn("*.tif", settings.GetSettingAsString(key, 0, "").split())
        self.assertNotIn("*.png", settings.GetSettingAsString(key, 0, "").split())  # sketches
        exemplar = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        sketch = simple.PNGSeriesReader(
            FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[128, 128],
                                        PatchSize=32)
        shade = simple.TerrainHillshade(Input=synth)
        view = simple.CreateRenderView()
        shown = simple.Show(shade, view)
        simple.ColorBy(shown, ("POINTS", "Hillshade"))
        shown.RescaleTransferFunctionToDataRange(True)
        grey = np.array(simple.GetColorTransferFunction("Hillshade").RGBPoints).reshape(-1, 4)
        np.testing.assert_array_equal(grey[:, 1], grey[:, 2])  # r = g = b: grey
        np.testing.assert_array_equal(grey[:, 1], grey[:, 3])
        self.assertEqual((grey[0, 1], grey[-1, 1]), (0.0, 1.0))  # dark in shadow, white lit
        simple.ColorBy(shown, ("POINTS", "Elevation"))
        shown.RescaleTransferFunctionToDataRange(True)
        heights = np.array(simple.GetColorTransferFunction("Elevation").RGBPoints).reshape(-1, 4)
        self.assertGreater(heights[0, 2], heights[0, 1])  # low land green
        self.assertEqual(tuple(heights[-1, 1:]), (1.0, 1.0, 1.0))  # snow on top
        for name, values in (("PatchColour", [str(c) for c in range(12)]), ("FeatureType", ["1", "-1"])):
            lut = simple.GetColorTransferFunction(name)
            self.assertEqual(lut.InterpretValuesAsCategories, 1, name)
            self.assertEqual(list(lut.Annotations)[0::2], values, name)
            colours = np.array(lut.IndexedColors).reshape(-1, 3)
            self.assertEqual(len({tuple(c) for c in colours}), len(values), name)
        # The colours a categorical map draws differ wherever two patches touch.
        terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        ids = point_array(terrain, "PatchId").reshape(128, 128)
        colour = point_array(terrain, "PatchColour").reshape(128, 128)
        for a, b, ca, cb in ((ids[:, 1:], ids[:, :-1], colour[:, 1:], colour[:, :-1]),
                             (ids[1:], ids[:-1], colour[1:], colour[:-1])):
            touching = a != b
            self.assertGreater(int(touching.sum()), 100)
            self.assertFalse(np.any(ca[touching] == cb[touching]))
        simple.Delete(view)

    def test_synthesis_filter_with_style_regions(self):
        colorado = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        alps = simple.TerrainReader(FileName=self.alps)
        sketch = simple.PNGSeriesReader(FileNames=[os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")])
        labels = np.zeros((16, 16), dtype=np.float32)
        labels[:, 8:] = 1.0  # west label 0, east label 1
        regions = producer(image_from(labels, (1.0, 1.0)))
        synth = simple.TerrainSynthesis(Exemplars=[colorado, alps], Sketch=sketch, Regions=regions,
                                        RegionMaps=["0=1", "1=0"], OutputSize=[256, 256])
        synth.UpdatePipeline()
        placements = sm.Fetch(synth, arg1=None, arg2=None, idx=1)
        column = vtk_to_numpy(placements.GetColumnByName("Column"))
        exemplar = vtk_to_numpy(placements.GetColumnByName("Exemplar"))
        self.assertEqual(set(exemplar[column + 40 < 118].tolist()), {1})
        self.assertEqual(set(exemplar[column + 40 > 138].tolist()), {0})

    # Distance-based synthesis ----------------------------------------------------------------

    def test_distance_source_matches_tsynth_distance(self):
        examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "distance")
        strokes = os.path.join(examples, "valley_pair_strokes.png")
        profiles = os.path.join(examples, "valley_v_profile.csv")
        sketch = simple.PNGSeriesReader(FileNames=[strokes])
        table = simple.CSVReader(FileName=[profiles])
        source = simple.TerrainDistanceSynthesis(Generators=sketch, Profiles=table, BlendBias=15.0,
                                              Seed=5)
        source.UpdatePipeline()
        terrain = sm.Fetch(source)
        self.assertEqual(terrain.GetDimensions(), (512, 512, 1))
        self.assertEqual(terrain.GetSpacing()[0], 10.0)
        z = point_array(terrain, "Elevation").reshape(512, 512)
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "v.tif")
            subprocess.run([PATHS.tsynth, "distance", "--generators", strokes, "--profiles", profiles,
                            "--b", "15", "--seed", "5", "-o", out, "--no-progress"],
                           check=True, capture_output=True)
            cli = point_array(sm.Fetch(simple.TerrainReader(FileName=out)), "Elevation").reshape(512, 512)
        np.testing.assert_array_equal(z, cli)  # the same kernel behind both front ends
        # The middle stroke (x = 250 of 512, row 256 from the top) stands above the V between.
        row = 511 - 256
        self.assertGreater(z[row, 245:256].max(), z[row, 150:170].min() + 50.0)
        # The file name property gives the same terrain as the table.
        by_file = simple.TerrainDistanceSynthesis(Generators=sketch, ProfileFileName=profiles,
                                               BlendBias=15.0, Seed=5)
        by_file.UpdatePipeline()
        np.testing.assert_array_equal(point_array(sm.Fetch(by_file), "Elevation").reshape(512, 512), z)
        # Both at once is refused rather than one silently ignored.
        source.ProfileFileName = profiles
        source.UpdatePipeline()
        self.assertEqual(sm.Fetch(source).GetNumberOfPoints(), 0)

    def test_distance_source_reports_bad_profiles(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "bad.csv")
            with open(bad, "w") as f:
                f.write("0,1\n5,0.5\n7,0.8\n")
            sketch = simple.PNGSeriesReader(FileNames=[os.path.join(
                os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "distance",
                "valley_pair_strokes.png")])
            source = simple.TerrainDistanceSynthesis(Generators=sketch, ProfileFileName=bad)
            source.UpdatePipeline()
            self.assertEqual(sm.Fetch(source).GetNumberOfPoints(), 0)

    def test_every_xml_property_has_its_setter_getter_and_default(self):
        """A typo in a command, or an XML default that drifted from the class's, fails here."""
        import glob
        import xml.etree.ElementTree as ET

        sys.path.insert(0, PATHS.python_dir)
        import terrainsynthesis

        plugin_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Plugin")
        checked = 0
        for path in sorted(glob.glob(os.path.join(plugin_dir, "*.xml"))):
            for proxy in ET.parse(path).getroot().iter("SourceProxy"):
                obj = getattr(terrainsynthesis, proxy.get("class"))()
                for prop in proxy:
                    command = prop.get("command")
                    if not prop.tag.endswith("VectorProperty") or command is None:
                        continue
                    with self.subTest(xml=os.path.basename(path), property=prop.get("name")):
                        self.assertTrue(hasattr(obj, command), command)
                        for extra in ("clean_command",):
                            if prop.get(extra):
                                self.assertTrue(hasattr(obj, prop.get(extra)), prop.get(extra))
                        if command == "SetInputArrayToProcess" or not command.startswith("Set"):
                            continue
                        getter = "Get" + command[3:]
                        self.assertTrue(hasattr(obj, getter), getter)
                        default = prop.get("default_values")
                        if default is None or prop.tag == "StringVectorProperty":
                            continue
                        expected = [float(v) for v in default.split()]
                        value = getattr(obj, getter)()
                        actual = [float(v) for v in (value if isinstance(value, tuple) else (value,))]
                        for e, a in zip(expected, actual):
                            self.assertAlmostEqual(e, a, places=6, msg=getter)
                        checked += 1
        self.assertGreater(checked, 40)

    def test_every_xml_documents_its_filter_and_bounds_its_numbers(self):
        """Help with a cited year, a domain on every numeric property, and each range enforced by
        the class too: a value past either end comes back as that end, except the patch sizes,
        which the request refuses with a sentence (test_bad_filter_inputs) and the setter keeps
        as typed, so the panel never shows a size other than the one used."""
        import glob
        import re
        import xml.etree.ElementTree as ET

        sys.path.insert(0, PATHS.python_dir)
        import terrainsynthesis

        plugin_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Plugin")
        domains = ("IntRangeDomain", "DoubleRangeDomain", "BooleanDomain", "EnumerationDomain",
                   "BoundsDomain", "FileListDomain", "ArrayListDomain")
        clamped = 0
        for path in sorted(glob.glob(os.path.join(plugin_dir, "*.xml"))):
            for proxy in ET.parse(path).getroot().iter("SourceProxy"):
                name = os.path.basename(path)
                doc = proxy.find("Documentation")
                self.assertIsNotNone(doc, name)
                self.assertTrue(doc.get("short_help") and doc.get("long_help"), name)
                if proxy.get("class") != "vtkTerrainReader":  # the only one without a paper
                    self.assertRegex(doc.get("long_help") + doc.text, r"(19|20)\d\d", name)
                obj = getattr(terrainsynthesis, proxy.get("class"))()
                for prop in proxy:
                    if prop.tag not in ("IntVectorProperty", "DoubleVectorProperty"):
                        continue
                    with self.subTest(xml=name, property=prop.get("name")):
                        found = [d for d in prop if d.tag in domains]
                        self.assertTrue(found, "no domain")
                        if prop.get("name") == "PatchSize" and proxy.get("name") != "TerrainOptimisation":
                            # The synthesis' 0 chooses the patch for the sketch (80, or 32 for a DEM).
                            lowest = "0" if proxy.get("name") == "TerrainSynthesis" else "16"
                            self.assertEqual((found[0].get("min"), found[0].get("max")), (lowest, "512"))
                        domain = found[0]
                        if (domain.tag not in ("IntRangeDomain", "DoubleRangeDomain")
                                or prop.get("number_of_elements") != "1"
                                or domain.get("min") is None or domain.get("max") is None):
                            continue
                        lo, hi = float(domain.get("min")), float(domain.get("max"))
                        setter = getattr(obj, prop.get("command"))
                        getter = getattr(obj, "Get" + prop.get("command")[3:])
                        cast = int if domain.tag == "IntRangeDomain" else float
                        if prop.get("name") == "PatchSize":
                            for typed in (int(lo) - 1, int(hi) + 1):
                                setter(typed)
                                self.assertEqual(getter(), typed, "a patch size was clamped")
                            continue
                        if hi < 2147483647:
                            setter(cast(hi + 1))
                            self.assertAlmostEqual(getter(), hi, places=6)
                        setter(cast(lo - 1))
                        self.assertAlmostEqual(getter(), lo, places=6)
                        clamped += 1
        self.assertGreater(clamped, 35)

    def test_sketch_features_help_opens_sketches_with_the_sketch_reader(self):
        """The README opens a sketch with the Terrain Sketch Reader (on the exemplar's grid); the
        filter's own help said ParaView's PNG reader, whose 1 m pixels put it at the corner."""
        import xml.etree.ElementTree as ET
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Plugin",
                            "TerrainSketchFeatures.xml")
        help_text = " ".join(ET.parse(path).getroot().find(".//SourceProxy/Documentation").text.split())
        self.assertIn("Open sketch images with the Terrain Sketch Reader", help_text)
        self.assertNotIn("with ParaView's own PNG reader", help_text)

    def test_abort_stops_the_synthesis_promptly_with_an_empty_output(self):
        import time
        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainReader, vtkTerrainSynthesis
        from vtkmodules.vtkIOImage import vtkPNGReader

        exemplar = vtkTerrainReader()
        exemplar.SetFileName(os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        sketch = vtkPNGReader()
        sketch.SetFileName(os.path.join(PATHS.bundled_data, "sketches", "strokes_valley_tree.png"))
        exemplar.Update()
        sketch.Update()

        def synthesis():
            synth = vtkTerrainSynthesis()
            synth.AddInputConnection(0, exemplar.GetOutputPort())
            synth.SetSketchConnection(sketch.GetOutputPort())
            synth.SetOutputSize(1024, 1024)
            return synth

        whole = harness.seconds_to_run(synthesis().Update)
        synth = synthesis()
        stopped_at = []

        def abort_at_a_quarter(caller, _event):
            if caller.GetProgress() > 0.25 and not stopped_at:
                stopped_at.append(time.monotonic())
                caller.SetAbortExecute(1)

        synth.AddObserver("ProgressEvent", abort_at_a_quarter)
        synth.Update()
        self.assertTrue(stopped_at, "no progress was reported")
        harness.assert_stopped_promptly(self, "the synthesis", time.monotonic() - stopped_at[0], whole)
        self.assertEqual(synth.GetTerrain().GetNumberOfPoints(), 0)

    def test_abort_stops_the_long_filters_promptly_with_an_empty_output(self):
        import time
        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import (vtkTerrainFeatureExtractor, vtkTerrainPitRemoval,
                                      vtkTerrainPoissonSolver)

        # Colorado mirrored 8 x 8 times (5184^2 cells): each filter takes seconds on it.
        z, spacing = dem_array(os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        tile = np.block([[z, z[:, ::-1]], [z[::-1, :], z[::-1, ::-1]]])
        for _ in range(2):
            tile = np.block([[tile, tile[:, ::-1]], [tile[::-1, :], tile[::-1, ::-1]]])
        big = image_from(tile, spacing, arrays={"Mask": np.ones(tile.shape, dtype=np.uint8)})
        gradient = numpy_to_vtk(np.zeros((tile.size, 2)), deep=1)
        gradient.SetName("Gradient")
        big.GetPointData().AddArray(gradient)
        pits = vtkTerrainPitRemoval()
        features = vtkTerrainFeatureExtractor()
        poisson = vtkTerrainPoissonSolver()
        poisson.SetMode(1)  # integrate the (flat) slopes over the whole terrain
        poisson.SetTolerance(1e-12)
        for name, filter_, start in (("pit removal", pits, 0.1), ("features", features, 0.0),
                                     ("poisson", poisson, 0.1)):
            with self.subTest(filter=name):
                filter_.SetInputData(big)
                whole = harness.seconds_to_run(filter_.Update)
                filter_.Modified()
                stopped_at = []

                def abort_once(caller, _event, start=start, stopped_at=stopped_at):
                    if caller.GetProgress() >= start and not stopped_at:
                        stopped_at.append(time.monotonic())
                        caller.SetAbortExecute(1)

                errors = []
                filter_.AddObserver("ProgressEvent", abort_once)
                filter_.AddObserver("ErrorEvent", lambda *_args, errors=errors: errors.append(1))
                filter_.Update()
                self.assertEqual(errors, [], "the filter failed instead of stopping")
                self.assertTrue(stopped_at, "no progress was reported")
                harness.assert_stopped_promptly(self, name, time.monotonic() - stopped_at[0], whole)
                self.assertEqual(filter_.GetOutputDataObject(0).GetNumberOfPoints(), 0)

    def test_sketch_lines_mark_drawn_lines_for_the_synthesis(self):
        ridge = simple.PolyLineSource(Points=[900.0, 900.0, 3500.0, 9000.0, 9000.0, 3900.0])
        marked = sm.Fetch(simple.TerrainSketchLines(Input=ridge, ElevationMode="From Z"))
        self.assertEqual(marked.GetNumberOfLines(), 1)
        np.testing.assert_array_equal(vtk_to_numpy(marked.GetCellData().GetArray("FeatureType")), [1])
        elevation = point_array(marked, "Elevation")
        self.assertEqual(elevation[0], 3500.0)
        self.assertEqual(elevation[-1], 3900.0)
        z = vtk_to_numpy(marked.GetPoints().GetData())[:, 2]
        self.assertTrue(np.all(z == 0.0))  # laid flat on the raster plane
        valley = sm.Fetch(simple.TerrainSketchLines(Input=ridge, FeatureType="Valley",
                                                    ElevationMode="Constant", Elevation=1200.0))
        np.testing.assert_array_equal(vtk_to_numpy(valley.GetCellData().GetArray("FeatureType")), [-1])
        self.assertTrue(np.all(point_array(valley, "Elevation") == 1200.0))
        free = sm.Fetch(simple.TerrainSketchLines(Input=ridge))
        self.assertTrue(np.all(np.isnan(point_array(free, "Elevation"))))
        # The synthesis meets the drawn crest's heights where they are set.
        colorado = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        synth = simple.TerrainSynthesis(Exemplars=[colorado], OutputSize=[128, 128], Backend="CPU",
                                        Sketch=simple.TerrainSketchLines(Input=ridge, ElevationMode="From Z"))
        synth.UpdatePipeline()
        terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        heights = point_array(terrain, "Elevation").reshape(128, 128)
        self.assertAlmostEqual(float(heights[10, 10]), 3500.0, delta=25.0)  # (900 m, 900 m): cell 10
        self.assertAlmostEqual(float(heights[100, 100]), 3900.0, delta=25.0)
        # Nothing to mark: the request fails.
        points_only = simple.PointSource(NumberOfPoints=5)
        empty = simple.TerrainSketchLines(Input=points_only)
        empty.UpdatePipeline()
        self.assertEqual(sm.Fetch(empty).GetNumberOfPoints(), 0)

    def test_sketch_lines_show_coloured_by_feature_type(self):
        """Shown, the marked lines are coloured by FeatureType (ridges red, valleys blue by the
        plugin's map), not the thin white line a Poly Line is."""
        line = simple.PolyLineSource(Points=[900.0, 900.0, 0.0, 9000.0, 9000.0, 0.0])
        view = simple.CreateRenderView()
        try:
            for kind in ("Ridge", "Valley"):
                shown = simple.Show(simple.TerrainSketchLines(Input=line, FeatureType=kind), view)
                self.assertEqual(list(shown.ColorArrayName), ["CELLS", "FeatureType"], kind)
            lut = simple.GetColorTransferFunction("FeatureType")
            self.assertEqual(lut.InterpretValuesAsCategories, 1)
            self.assertNotEqual(list(shown.ColorArrayName), list(simple.Show(line, view).ColorArrayName))
        finally:
            simple.Delete(view)

    def test_sketch_lines_and_feature_trees_are_shown_thick(self):
        """Shown in a view, marked lines and feature trees are 3 pixels wide (Plugin/
        TerrainLineWidths.xml), a plain Poly Line keeps ParaView's 1, and a width the script
        gives wins."""
        line = simple.PolyLineSource(Points=[900.0, 900.0, 0.0, 9000.0, 9000.0, 0.0])
        marked = simple.TerrainSketchLines(Input=line)
        colorado = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        synth = simple.TerrainSynthesis(Exemplars=[colorado], Sketch=marked, OutputSize=[128, 128], Backend="CPU")
        view = simple.CreateRenderView()
        try:
            thick = {
                "Sketch Lines": simple.Show(marked, view),
                "Sketch Features": simple.Show(simple.TerrainSketchFeatures(Input=marked), view),
                "synthesis's Sketch Features": simple.Show(simple.OutputPort(synth, 2), view),
                "synthesis's Seams": simple.Show(simple.OutputPort(synth, 3), view),
                "synthesis's Implied Lines": simple.Show(simple.OutputPort(synth, 6), view),
            }
            for what, shown in thick.items():
                self.assertEqual(shown.GetXMLName(), "GeometryRepresentation", what)
                self.assertEqual(shown.LineWidth, THICK_LINE_WIDTH, what)
            self.assertEqual(simple.Show(line, view).LineWidth, 1.0)  # not a sketch: ParaView's width
            explicit = simple.Show(simple.TerrainSketchLines(Input=line), view, LineWidth=5.0)
            self.assertEqual(explicit.LineWidth, 5.0)
        finally:
            simple.Delete(view)

    def test_a_line_width_saved_in_the_settings_wins_over_the_thick_default(self):
        """A LineWidth the user saved as the default (Properties panel, "Save current settings as
        default") is what sketch lines get too. In its own pvpython: settings cannot be taken back."""
        script = "\n".join([
            "from paraview import simple, servermanager as sm",
            "simple.LoadPlugin(%r, remote=False)" % PATHS.plugin,
            "sm.vtkSMSettings.GetInstance().AddCollectionFromString("
            "'{\"representations\": {\"GeometryRepresentation\": {\"LineWidth\": 2.0}}}', 10.0)",
            "view = simple.CreateRenderView()",
            "line = simple.PolyLineSource(Points=[900.0, 900.0, 0.0, 9000.0, 9000.0, 0.0])",
            "print('LineWidth', simple.Show(simple.TerrainSketchLines(Input=line), view).LineWidth)",
            "simple.Delete(view)",
        ])
        run = subprocess.run([shutil.which("pvpython") or "pvpython", "-c", script],
                             capture_output=True, text=True, timeout=120)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("LineWidth 2.0", run.stdout, run.stdout + run.stderr)

    def test_new_terrain_sketch_macro_sets_up_a_sketch_and_its_terrain(self):
        """Plugin/Macros/NewTerrainSketch.py, run as ParaView runs a macro (as __main__, with the
        exemplar selected): a ridge line across the exemplar, its terrain as large, and the
        ridge standing in it."""
        import runpy
        macro = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Plugin", "Macros",
                             "NewTerrainSketch.py")
        exemplar = simple.TerrainReader(FileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png"))
        simple.SetActiveSource(None)
        with self.assertRaises(RuntimeError):  # nothing selected: one sentence, nothing made
            runpy.run_path(macro, run_name="__main__")
        self.assertIsNone(simple.FindSource("Terrain"))
        simple.SetActiveSource(exemplar)
        view = simple.CreateRenderView()
        simple.SetActiveView(view)
        try:
            runpy.run_path(macro, run_name="__main__")
            line, terrain = simple.FindSource("Ridge line"), simple.FindSource("Terrain")
            self.assertEqual(simple.GetActiveSource(), line)  # ready to drag its points
            points = np.array(line.Points).reshape(-1, 3)
            dem = sm.Fetch(exemplar)
            width = (dem.GetDimensions()[0] - 1) * dem.GetSpacing()[0]
            self.assertAlmostEqual(points[0, 0], width / 3.0, delta=1.0)
            self.assertAlmostEqual(points[-1, 0], 2.0 * width / 3.0, delta=1.0)
            row = int(round(points[0, 1] / dem.GetSpacing()[1]))
            columns = slice(int(points[0, 0] / 90.0) + 20, int(points[-1, 0] / 90.0) - 20)

            def crest_and_flanks():
                out = sm.Fetch(terrain, arg1=None, arg2=None, idx=0)
                self.assertEqual(out.GetDimensions(), dem.GetDimensions())
                z = point_array(out, "Elevation").reshape(out.GetDimensions()[1], out.GetDimensions()[0])
                crest = float(np.median(z[row, columns]))
                flanks = float(np.median(np.concatenate([z[row - 60, columns], z[row + 60, columns]])))
                return crest, flanks

            # For dragging: the preview first, the ridge already in it, then the whole terrain.
            sys.path.insert(0, PATHS.python_dir)
            import terrainsynthesis  # noqa: F401  (the filter's own methods)
            filter_ = terrain.GetClientSideObject()
            self.assertEqual(filter_.GetOutputLevel(), "preview")
            crest, flanks = crest_and_flanks()
            print("macro ridge, preview: crest %.0f m, flanks %.0f m" % (crest, flanks))
            self.assertGreater(crest, flanks + 150.0)
            filter_.WaitForRefinement()
            self.assertTrue(filter_.GetNeedsUpdate())
            terrain.SMProxy.MarkModified(terrain.SMProxy)  # as ParaView's live-source poll does
            crest, flanks = crest_and_flanks()
            self.assertEqual(filter_.GetOutputLevel(), "final")
            print("macro ridge: crest %.0f m, flanks %.0f m" % (crest, flanks))
            self.assertGreater(crest, flanks + 150.0)  # a ridge along the drawn line
        finally:
            simple.Delete(view)

    def test_distance_command_takes_polylines_with_costs(self):
        # A .vtp ridge along y = 2000 m (cells of 10 m: row 200) with a cheaper (higher)
        # west end: heights peak on the line, fall away from it, and the west end is higher.
        from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
        from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataWriter

        points = vtkPoints()
        cost = vtkFloatArray()
        cost.SetName("Cost")
        line = vtkCellArray()
        line.InsertNextCell(9)
        for k in range(9):
            points.InsertNextPoint(500.0 + 375.0 * k, 2000.0, 0.0)
            cost.InsertNextValue(2.0 + 2.0 * k)
            line.InsertCellPoint(k)
        poly = vtkPolyData()
        poly.SetPoints(points)
        poly.SetLines(line)
        poly.GetPointData().AddArray(cost)
        with tempfile.TemporaryDirectory() as tmp:
            vtp = os.path.join(tmp, "ridge.vtp")
            writer = vtkXMLPolyDataWriter()
            writer.SetFileName(vtp)
            writer.SetInputData(poly)
            writer.Write()
            out = os.path.join(tmp, "ridge.vti")
            r = subprocess.run([PATHS.tsynth, "distance", "--generators", vtp, "-o", out, "--size", "400x400"],
                               capture_output=True, text=True, timeout=120)
            self.assertEqual(r.returncode, 0, r.stderr)
            reader = vtkXMLImageDataReader()
            reader.SetFileName(out)
            reader.Update()
            z = point_array(reader.GetOutput(), "Elevation").reshape(400, 400)
        profile = z[:, 200]  # across the line at x = 2000 m
        self.assertEqual(int(np.argmax(profile)), 200)
        self.assertGreater(profile[200] - profile[100], 50.0)
        self.assertGreater(profile[200] - profile[300], 50.0)
        self.assertGreater(z[200, 60], z[200, 340])  # the cheap west end stands higher

    def test_missing_file_gives_an_empty_output_not_a_crash(self):
        reader = simple.TerrainReader(FileName="/nonexistent/dem.tif")
        reader.UpdatePipeline()
        self.assertEqual(sm.Fetch(reader).GetNumberOfPoints(), 0)


if __name__ == "__main__":
    harness.run(__name__)
