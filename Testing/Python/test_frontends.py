"""pvpython: the command line and the Terrain Synthesis filter share one set-up (prepareSynthesis),
so the same inputs give the same terrain, bit for bit, and the same refusals."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402
from test_synth import crop_dem, write_polylines  # noqa: E402

import numpy as np  # noqa: E402
from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkCommonCore import vtkCommand  # noqa: E402
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader  # noqa: E402

PATCH = 32
SEED = 7
CPU = 2  # the filter's Backend value for the CPU


def read_vti(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


class FrontEndsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        simple.LoadPlugin(PATHS.plugin, remote=False)
        sys.path.insert(0, PATHS.python_dir)
        cls.colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        cls.strokes = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-frontends-")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def cli(self, exemplar, sketch, *extra):
        out = self.path("cli-%d.vti" % len(os.listdir(self.tmp)))
        result = subprocess.run([PATHS.tsynth, "synth", "--exemplar", exemplar, "--sketch", sketch, "-o", out,
                                 "--patch", str(PATCH), "--backend", "cpu", "--seed", str(SEED), "--no-progress",
                                 *extra], capture_output=True, text=True, timeout=300)
        self.assertEqual(result.returncode, 0, result.stderr)
        return read_vti(out)

    def assert_same_terrain(self, filtered, cli):
        self.assertGreater(filtered.GetNumberOfPoints(), 0)
        self.assertEqual(filtered.GetDimensions(), cli.GetDimensions())
        self.assertEqual(filtered.GetSpacing(), cli.GetSpacing())
        self.assertEqual(filtered.GetOrigin(), cli.GetOrigin())
        a = vtk_to_numpy(filtered.GetPointData().GetArray("Elevation"))
        b = vtk_to_numpy(cli.GetPointData().GetArray("Elevation"))
        self.assertGreater(float(a.max() - a.min()), 100.0)  # real relief, not a flat field
        np.testing.assert_array_equal(a, b)

    def wrapped_synthesis(self, sketch_port, **settings):
        from terrainsynthesis import vtkTerrainReader, vtkTerrainSynthesis

        self.reader = vtkTerrainReader()
        self.reader.SetFileName(settings.pop("exemplar", self.colorado))
        synth = vtkTerrainSynthesis()
        synth.AddInputConnection(0, self.reader.GetOutputPort())
        synth.SetSketchConnection(sketch_port)
        synth.SetPatchSize(PATCH)
        synth.SetBackend(synth.CPU)
        synth.SetSeed(SEED)
        for name, value in settings.items():
            getattr(synth, "Set" + name)(*value)
        return synth

    def test_a_stroke_sketch_gives_the_same_terrain(self):
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[160, 160],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED)
        synth.UpdatePipeline()
        self.assert_same_terrain(sm.Fetch(synth, arg1=None, arg2=None, idx=0),
                                 self.cli(self.colorado, self.strokes, "--size", "160x160"))

    def test_the_implied_lines_output_is_the_command_lines_implied_features(self):
        """A valley tree implies divides between its branches: the Implied Lines output holds
        them, point for point as --debug-dir's implied-features.vtp, and keeps them apart from
        Sketch Features."""
        tree = os.path.join(PATHS.bundled_data, "sketches", "strokes_valley_tree.png")
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[tree])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[256, 256],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED)
        synth.UpdatePipeline()
        implied = sm.Fetch(synth, arg1=None, arg2=None, idx=6)
        debug = self.path("implied-debug")
        self.cli(self.colorado, tree, "--size", "256x256", "--debug-dir", debug)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(debug, "implied-features.vtp"))
        reader.Update()
        self.assertGreater(implied.GetNumberOfLines(), 0)
        self.assertEqual(implied.GetNumberOfLines(), reader.GetOutput().GetNumberOfLines())
        np.testing.assert_array_equal(vtk_to_numpy(implied.GetPoints().GetData()),
                                      vtk_to_numpy(reader.GetOutput().GetPoints().GetData()))
        ridge = 1  # implied divides are ridges
        types = vtk_to_numpy(implied.GetCellData().GetArray("FeatureType"))
        self.assertTrue(np.all(types[-implied.GetNumberOfLines():] == ridge))
        drawn = sm.Fetch(synth, arg1=None, arg2=None, idx=2)
        self.assertNotEqual(drawn.GetNumberOfPoints(), implied.GetNumberOfPoints())

    def test_the_debug_outputs_are_the_command_lines_debug_files_and_report(self):
        """Sketch Features, Seams, Report and Construction (issue 23): what --debug-dir and
        --report write, inside ParaView, for the same synthesis."""
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[160, 160],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED)
        synth.UpdatePipeline()
        fetch = lambda port: sm.Fetch(synth, arg1=None, arg2=None, idx=port)  # noqa: E731
        self.assertEqual(fetch(4).GetNumberOfRows(), 0)  # Debug Outputs off: empty
        self.assertEqual(fetch(5).GetNumberOfPoints(), 0)
        synth.DebugOutputs = 1
        synth.UpdatePipeline()
        debug = self.path("debug")
        report_path = self.path("report.json")
        cli = self.cli(self.colorado, self.strokes, "--size", "160x160", "--debug-dir", debug,
                       "--report", report_path)
        terrain = fetch(0)
        self.assert_same_terrain(terrain, cli)

        # The report: every figure as the CLI's JSON has it.
        import json
        with open(report_path) as f:
            report = json.load(f)
        table = fetch(4)
        rows = {table.GetValue(i, 0).ToString(): table.GetValue(i, 1).ToDouble()
                for i in range(table.GetNumberOfRows())}
        self.assertGreater(len(rows), 30)
        for name, value in rows.items():
            node = report
            for key in name.split("."):
                if key.startswith("sigma_"):
                    node = next(b["correlation"] for b in node if b["sigma_cells"] == float(key[6:]))
                else:
                    node = node[key]
            if node is None:
                self.assertTrue(np.isnan(value), name)
            else:
                self.assertAlmostEqual(value, node, places=9, msg=name)
        self.assertGreater(rows["legibility.legible_share"], 0.0)

        # The construction image: target.tif, target-confidence.tif and patches.tif.
        construction = fetch(5)
        self.assertEqual(construction.GetDimensions(), terrain.GetDimensions())
        for array, name in (("Target", "target"), ("TargetConfidence", "target-confidence"),
                            ("Patches", "patches")):
            ours = vtk_to_numpy(construction.GetPointData().GetArray(array))
            theirs = vtk_to_numpy(sm.Fetch(simple.TerrainReader(
                FileName=os.path.join(debug, name + ".tif"))).GetPointData().GetArray("Elevation"))
            np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-3, err_msg=array)
        patches = vtk_to_numpy(construction.GetPointData().GetArray("Patches"))
        self.assertGreater(float(np.abs(patches - vtk_to_numpy(
            terrain.GetPointData().GetArray("Elevation"))).max()), 1.0)  # before the corrections

        # The sketch's feature tree: sketch-features.vtp, in metres on the terrain's grid.
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(debug, "sketch-features.vtp"))
        reader.Update()
        features = fetch(2)
        self.assertGreater(features.GetNumberOfLines(), 0)
        self.assertEqual(features.GetNumberOfPoints(), reader.GetOutput().GetNumberOfPoints())
        np.testing.assert_array_equal(vtk_to_numpy(features.GetPoints().GetData()),
                                      vtk_to_numpy(reader.GetOutput().GetPoints().GetData()))

        # The seams: lines along the borders of PatchId, each step one cell border.
        seams = fetch(3)
        self.assertGreater(seams.GetNumberOfLines(), 3)
        ids = vtk_to_numpy(terrain.GetPointData().GetArray("PatchId")).reshape(160, 160)
        dx = terrain.GetSpacing()[0]
        points = vtk_to_numpy(seams.GetPoints().GetData())
        corners = np.rint(points[:, :2] / dx + 0.5).astype(int)  # corner (i, j) at (i - 0.5) cells
        np.testing.assert_allclose(points[:, :2], (corners - 0.5) * dx, atol=1e-6)
        lines = seams.GetLines()
        lines.InitTraversal()
        from vtkmodules.vtkCommonCore import vtkIdList
        cell = vtkIdList()
        borders = 0
        while lines.GetNextCell(cell):
            for k in range(1, cell.GetNumberOfIds()):
                (i0, j0), (i1, j1) = corners[cell.GetId(k - 1)], corners[cell.GetId(k)]
                self.assertEqual(abs(i1 - i0) + abs(j1 - j0), 1)
                if i0 == i1:  # a border between cells (i - 1, j) and (i, j)
                    j = min(j0, j1)
                    self.assertNotEqual(ids[j, i0 - 1], ids[j, i0])
                else:  # between cells (i, j - 1) and (i, j)
                    i = min(i0, i1)
                    self.assertNotEqual(ids[j0 - 1, i], ids[j0, i])
                borders += 1
        expected = int(np.count_nonzero(ids[:, 1:] != ids[:, :-1]) + np.count_nonzero(ids[1:] != ids[:-1]))
        self.assertEqual(borders, expected)  # every border drawn, none twice

    def test_every_option_of_the_command_line_maps_to_the_filter(self):
        # The options beyond the defaults, in both: the same terrain, unlike the default one.
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[160, 160],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED, VerticalOffset=0,
                                        Repetition=0.0, Drainage="Breach", MergeMode="Poisson",
                                        FillOrder="Concentric", LandformRelief=2.0)
        synth.UpdatePipeline()
        filtered = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        self.assert_same_terrain(filtered, self.cli(
            self.colorado, self.strokes, "--size", "160x160", "--no-vertical-offset", "--repetition", "0",
            "--drainage", "breach", "--merge", "poisson", "--fill", "concentric", "--landform-relief", "2"))
        default = self.cli(self.colorado, self.strokes, "--size", "160x160")
        self.assertFalse(np.array_equal(vtk_to_numpy(filtered.GetPointData().GetArray("Elevation")),
                                        vtk_to_numpy(default.GetPointData().GetArray("Elevation"))))

    def test_a_synthesis_stopped_after_some_placements_is_the_same_in_both(self):
        # Stepping through the synthesis: Placement Limit N in ParaView is --placements N.
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[160, 160],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED, PlacementLimit=7)
        synth.UpdatePipeline()
        self.assertEqual(synth.GetClientSideObject().GetOutputLevel(), "placements")
        self.assertEqual(sm.Fetch(synth, arg1=None, arg2=None, idx=1).GetNumberOfRows(), 7)
        stopped = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        z = vtk_to_numpy(stopped.GetPointData().GetArray("Elevation"))
        self.assertTrue(np.isnan(z).any())  # land no patch has reached yet
        self.assertGreater(int(np.isfinite(z).sum()), 1000)
        cli = self.cli(self.colorado, self.strokes, "--size", "160x160", "--placements", "7")
        np.testing.assert_array_equal(z, vtk_to_numpy(cli.GetPointData().GetArray("Elevation")))

    def test_a_tiled_synthesis_gives_the_same_terrain(self):
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        tile = 3 * PATCH  # 2 x 2 tiles over 160 x 160 cells
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[160, 160],
                                        PatchSize=PATCH, Backend=CPU, Seed=SEED, TileSize=tile)
        synth.UpdatePipeline()
        tiled = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        self.assert_same_terrain(tiled, self.cli(self.colorado, self.strokes, "--size", "160x160",
                                                 "--tile-size", str(tile)))
        whole = self.cli(self.colorado, self.strokes, "--size", "160x160")
        self.assertFalse(np.array_equal(vtk_to_numpy(tiled.GetPointData().GetArray("Elevation")),
                                        vtk_to_numpy(whole.GetPointData().GetArray("Elevation"))))

    def test_a_patch_size_off_the_step_is_refused_by_the_filter_too(self):
        exemplar = simple.TerrainReader(FileName=self.colorado)
        sketch = simple.PNGSeriesReader(FileNames=[self.strokes])
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, PatchSize=42)
        synth.UpdatePipeline()
        self.assertEqual(sm.Fetch(synth, arg1=None, arg2=None, idx=0).GetNumberOfPoints(), 0)
        result = subprocess.run([PATHS.tsynth, "synth", "--exemplar", self.colorado, "--sketch", self.strokes,
                                 "-o", self.path("x.tif"), "--patch", "42"], capture_output=True, text=True)
        self.assertEqual(result.returncode, 2)
        self.assertIn("--patch must be a multiple of 4 from 16 to 512 cells, not 42.", result.stderr)

    def test_a_polyline_sketch_in_metres_gives_the_same_terrain(self):
        # Metres on colorado's 90 m cells, reaching x = 14310 m (cell 159) and y = 12600 m (cell 140),
        # in an output half a patch larger; both carry height constraints.
        vtp = self.path("lines.vtp")
        write_polylines(vtp, [(1800, 6300), (14310, 7200), (900, 12600), (12600, 11700)],
                        elevation=[3600, 3200, 2600, 2600])
        lines = vtkXMLPolyDataReader()
        lines.SetFileName(vtp)
        synth = self.wrapped_synthesis(lines.GetOutputPort())
        synth.UpdateInformation()
        announced = synth.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT())
        margin = PATCH // 2
        self.assertEqual(tuple(announced), (0, 159 + margin, 0, 140 + margin, 0, 0))
        synth.Update()
        terrain = synth.GetOutputDataObject(0)
        self.assertEqual(terrain.GetExtent(), tuple(announced))  # RequestInformation was honest
        self.assert_same_terrain(terrain, self.cli(self.colorado, vtp))

    def test_a_feature_tree_is_a_sketch_of_its_dem_in_both(self):
        dem = crop_dem(self.tmp, "colorado.png", (200, 200, 192, 160))
        exemplar = simple.TerrainReader(FileName=dem)
        tree = simple.TerrainFeatureExtractor(Input=exemplar, Features=2)
        synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=tree, PatchSize=PATCH, Backend=CPU,
                                        Seed=SEED)
        synth.UpdatePipeline()
        terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
        self.assertEqual(terrain.GetDimensions(), (192, 160, 1))
        self.assertEqual(terrain.GetSpacing()[:2], (90.0, 90.0))
        # The command line on `tsynth features` output: the same tree, the same terrain.
        features = self.path("features.vtp")
        subprocess.run([PATHS.tsynth, "features", dem, "-o", features, "--both"], check=True,
                       stdout=subprocess.DEVNULL)
        self.assert_same_terrain(terrain, self.cli(dem, features))

    def test_polylines_in_cells_are_refused_by_the_filter_too(self):
        vtp = self.path("cells.vtp")
        write_polylines(vtp, [(20, 100), (180, 100), (10, 190), (190, 150)])
        lines = vtkXMLPolyDataReader()
        lines.SetFileName(vtp)
        synth = self.wrapped_synthesis(lines.GetOutputPort())
        errors = []

        @calldata_type(VTK_STRING)
        def on_error(_obj, _event, message):
            errors.append(message)

        synth.AddObserver(vtkCommand.ErrorEvent, on_error)
        synth.Update()
        self.assertTrue(any("span 180 x 90 m" in e and "are they in cells" in e and "OutputSize" in e
                            for e in errors), errors)
        self.assertEqual(synth.GetOutputDataObject(0).GetNumberOfPoints(), 0)
        # No grid announced either (not the exemplar's, which the pipeline copies by default).
        self.assertFalse(synth.GetOutputInformation(0).Has(vtkStreamingDemandDrivenPipeline.WHOLE_EXTENT()))

    def test_the_memory_budget_refuses_in_the_filter(self):
        vtp = self.path("lines.vtp")
        write_polylines(vtp, [(1800, 6300), (14310, 7200)], types=(1,))
        lines = vtkXMLPolyDataReader()
        lines.SetFileName(vtp)
        synth = self.wrapped_synthesis(lines.GetOutputPort(), MemoryBudget=(0.01,))
        errors = []

        @calldata_type(VTK_STRING)
        def on_error(_obj, _event, message):
            errors.append(message)

        synth.AddObserver(vtkCommand.ErrorEvent, on_error)
        synth.Update()
        self.assertTrue(any("memory budget is 10 MB" in e and "raise MemoryBudget" in e for e in errors), errors)
        self.assertEqual(synth.GetOutputDataObject(0).GetNumberOfPoints(), 0)


if __name__ == "__main__":
    harness.run(__name__)
