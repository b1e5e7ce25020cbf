"""The filters' half of the bad-input catalogue (issue 14): each case builds a filter (the wrapped VTK
class, as pvpython and ParaView run it) on a bad input or setting and must fail its request with
one error naming what is wrong: the executive's Update returns 0, an ErrorEvent matches the
regex, and the output is empty. A crash fails the whole test; nothing may hang (the test has a
CTest timeout).
"""
import os
import re
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

import numpy as np  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData, vtkPolyLine, vtkTable  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402


def image(z, spacing=(90.0, 90.0), arrays=None, elevation_values=None):
    """A 2D vtkImageData with an Elevation array (or one of other values, e.g. too short)."""
    ny, nx = z.shape
    out = vtkImageData()
    out.SetDimensions(nx, ny, 1)
    out.SetSpacing(spacing[0], spacing[1], 1.0)
    values = z.ravel() if elevation_values is None else elevation_values
    elevation = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float32), deep=1)
    elevation.SetName("Elevation")
    out.GetPointData().SetScalars(elevation)
    for name, v in (arrays or {}).items():
        a = numpy_to_vtk(np.ascontiguousarray(v), deep=1)
        a.SetName(name)
        out.GetPointData().AddArray(a)
    return out


def relief(n=120):
    y, x = np.mgrid[0:n, 0:n].astype(np.float64)
    return 1000.0 + 300.0 * np.sin(x / 9.0) * np.cos(y / 13.0) + 2.0 * x


def lines(points, cells, types=None):
    poly = vtkPolyData()
    pts = vtkPoints()
    pts.SetDataTypeToDouble()
    for p in points:
        pts.InsertNextPoint(*p)
    cell_array = vtkCellArray()
    for ids in cells:
        line = vtkPolyLine()
        line.GetPointIds().SetNumberOfIds(len(ids))
        for k, i in enumerate(ids):
            line.GetPointIds().SetId(k, i)
        cell_array.InsertNextCell(line)
    poly.SetPoints(pts)
    poly.SetLines(cell_array)
    if types is not None:
        t = numpy_to_vtk(np.array(types, dtype=np.int32), deep=1)
        t.SetName("FeatureType")
        poly.GetCellData().AddArray(t)
    return poly


def png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


class BadFilterInputTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        sys.path.insert(0, PATHS.python_dir)
        import terrainsynthesis
        cls.ts = terrainsynthesis
        cls.tmp = tempfile.TemporaryDirectory()
        sketches = os.path.join(PATHS.bundled_data, "sketches")
        cls.strokes = png(os.path.join(sketches, "strokes_y_ridges.png"))
        blank = np.full((256, 256, 3), 255, dtype=np.uint8)
        cls.blank = vtkImageData()
        cls.blank.SetDimensions(256, 256, 1)
        colours = numpy_to_vtk(blank.reshape(-1, 3), deep=1)
        colours.SetName("PNGImage")
        cls.blank.GetPointData().SetScalars(colours)
        cls.fifo = os.path.join(cls.tmp.name, "pipe.tif")
        os.mkfifo(cls.fifo)
        cls.rising = os.path.join(cls.tmp.name, "rising.csv")
        with open(cls.rising, "w") as f:
            f.write("0,1\n5,0.5\n7,0.8\n")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def make(self, name, **properties):
        algorithm = getattr(self.ts, name)()
        for key, value in properties.items():
            setter = getattr(algorithm, "Set" + key)
            setter(*value) if isinstance(value, tuple) else setter(value)
        return algorithm

    # Each returns a configured algorithm; the table below names the expected error.
    def port(self, data):
        """An output port holding `data`, for algorithms without SetInputData."""
        from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
        producer = vtkTrivialProducer()
        producer.SetOutput(data)
        self.producers.append(producer)
        return producer.GetOutputPort()

    def synthesis(self, sketch, exemplar=None, no_exemplar=False, **properties):
        properties.setdefault("PatchSize", 32)
        s = self.make("vtkTerrainSynthesis", **properties)
        if not no_exemplar:
            s.AddInputConnection(0, self.port(exemplar if exemplar is not None else image(relief())))
        if sketch is not None:
            s.SetInputConnection(1, self.port(sketch))
        return s

    def optimisation(self, source=None, guide=None, **properties):
        o = self.make("vtkTerrainOptimisation", **properties)
        o.SetInputData(0, source if source is not None else image(relief()))
        o.SetInputData(1, guide if guide is not None else self.strokes)
        return o

    def distance(self, generators, **properties):
        d = self.make("vtkTerrainDistanceSynthesis", **properties)
        d.SetInputData(0, generators)
        return d

    def single(self, name, data, **properties):
        a = self.make(name, **properties)
        a.SetInputData(0, data)
        return a

    def cases(self):
        z = relief()
        n = z.size
        nan = np.full((64, 64), np.nan)
        line = lines([(900, 900, 0), (9000, 5000, 0)], [[0, 1]], [1])
        return [
            # Terrain Synthesis
            ("synthesis-output-size-negative", lambda: self.synthesis(self.strokes, OutputSize=(-5, 100)),
             r"Give OutputSize as two positive numbers of cells, or neither"),
            ("synthesis-output-size-huge", lambda: self.synthesis(self.strokes, OutputSize=(99999999, 5)),
             r"OutputSize 99999999 x 5 is beyond any machine"),
            ("synthesis-memory-budget", lambda: self.synthesis(self.strokes, MemoryBudget=0.001),
             r"needs about \d+ MB but the memory budget is 1 MB; .* raise MemoryBudget"),
            ("synthesis-blank-sketch", lambda: self.synthesis(self.blank), r"The sketch has nothing drawn"),
            ("synthesis-lines-1e300", lambda: self.synthesis(lines([(0, 0, 0), (1e300, 1e300, 0)], [[0, 1]], [1])),
             r"poly-lines span 1e\+300 x 1e\+300 m"),
            ("synthesis-lines-nan", lambda: self.synthesis(lines([(0, 0, 0), (float("nan"), 5, 0)], [[0, 1]], [1])),
             r"not a finite number"),
            ("synthesis-lines-short-featuretype",
             lambda: self.synthesis(lines([(900, 900, 0), (9000, 900, 0), (900, 9000, 0)], [[0, 1], [1, 2]], [1])),
             r"FeatureType cell array has 1 values for 2 cells"),
            ("synthesis-exemplar-short-elevation",
             lambda: self.synthesis(self.strokes, exemplar=image(z, elevation_values=np.ones(10))),
             r"height array \"Elevation\" has 10 values for %d points" % n),
            ("synthesis-exemplar-short-valid",
             lambda: self.synthesis(self.strokes, exemplar=image(z, arrays={"Valid": np.ones(7, np.uint8)})),
             r"Valid array has 7 values for %d points" % n),
            ("synthesis-exemplar-all-nan", lambda: self.synthesis(self.strokes, exemplar=image(nan)),
             r"no valid"),
            ("synthesis-exemplar-infinite-spacing",
             lambda: self.synthesis(self.strokes, exemplar=image(z, spacing=(float("inf"), 90.0))),
             r"spacing must be finite and positive"),
            ("synthesis-exemplar-extreme-heights",
             lambda: self.synthesis(self.strokes, exemplar=image(np.full((120, 120), -3.0e38))),
             r"heights beyond \+-1e\+12 m"),
            ("synthesis-exemplar-one-cell", lambda: self.synthesis(self.strokes, exemplar=image(np.ones((1, 1)))),
             r"is 1 x 1 cells of 90 m, smaller than one patch"),
            ("synthesis-no-sketch", lambda: self.synthesis(None),
             r"No sketch is connected: give Sketch a stroke map"),
            ("synthesis-no-exemplar", lambda: self.synthesis(self.strokes, no_exemplar=True),
             r"No exemplar is connected: give Exemplars one or more DEMs"),
            # Patch sizes out of range are refused, never clamped (issue 23)
            ("synthesis-patch-8", lambda: self.synthesis(self.strokes, PatchSize=8),
             r"Patch Size must be a multiple of 4 from 16 to 512 cells, not 8\."),
            ("synthesis-patch-600", lambda: self.synthesis(self.strokes, PatchSize=600),
             r"Patch Size must be a multiple of 4 from 16 to 512 cells, not 600\."),
            ("sketch-features-patch-0",
             lambda: self.single("vtkTerrainSketchFeatures", self.strokes, PatchSize=0),
             r"Patch Size must be a multiple of 4 from 16 to 512 cells, not 0\."),
            ("candidates-patch-8",
             lambda: self.single("vtkTerrainCandidateBuilder", image(relief()), PatchSize=8),
             r"Patch Size must be from 16 to 512 cells, not 8\."),
            ("matcher-patch-600", lambda: self.matcher(image(z), PatchSize=600),
             r"Patch Size must be from 16 to 512 cells, not 600\."),
            ("optimisation-patch-17", lambda: self.optimisation(PatchSize=17), r"patch size must be odd"),
            # Terrain Optimisation
            ("optimisation-output-size-negative", lambda: self.optimisation(OutputSize=(-5, 100)),
             r"Give OutputSize as two positive numbers"),
            ("optimisation-memory-budget", lambda: self.optimisation(MemoryBudget=0.001),
             r"This optimisation of 512 x 512 cells .* needs about \d+ MB but the memory budget is 1 MB; "
             r"give a smaller OutputSize .* raise MemoryBudget"),
            ("optimisation-patch-even", lambda: self.optimisation(PatchSize=4), r"patch size must be odd"),
            ("optimisation-flat-source", lambda: self.optimisation(source=image(np.full((120, 120), 5.0))),
             r"source DEM is flat"),
            ("optimisation-blank-guide", lambda: self.optimisation(guide=self.blank), r"nothing drawn"),
            # Terrain Distance Synthesis
            ("distance-output-size-negative", lambda: self.distance(line, OutputSize=(-5, 100)),
             r"grid of two positive numbers of cells \(OutputSize, --size\), not -5 x 100"),
            ("distance-memory-budget", lambda: self.distance(line, MemoryBudget=0.0001),
             r"This distance synthesis of 512 x 512 cells needs about \d+ MB but the memory budget is 0\.1 MB; "
             r"give a smaller OutputSize, or raise MemoryBudget"),
            ("distance-lines-nan", lambda: self.distance(lines([(0, 0, 0), (float("nan"), 5, 0)], [[0, 1]])),
             r"not a finite number"),
            ("distance-no-strokes", lambda: self.distance(self.blank), r"no red ridge strokes"),
            ("distance-rising-profile", lambda: self.distance(self.strokes, ProfileFileName=self.rising),
             r"rises along profile 0"),
            # Terrain Pit Removal
            ("pits-memory-budget", lambda: self.single("vtkTerrainPitRemoval", image(z), MemoryBudget=0.0001),
             r"This pit removal of 120 x 120 cells with flow routing needs about \d+ MB but the memory budget is "
             r"0\.1 MB; give a smaller DEM, or raise MemoryBudget"),
            ("pits-flat", lambda: self.single("vtkTerrainPitRemoval", image(np.full((50, 50), 7.0))), r"flat"),
            ("pits-all-nan", lambda: self.single("vtkTerrainPitRemoval", image(nan)), r"no valid cell"),
            ("pits-short-elevation",
             lambda: self.single("vtkTerrainPitRemoval", image(z, elevation_values=np.ones(3))),
             r"has 3 values for %d points" % n),
            # Matcher, merger, Poisson: arrays of the wrong length
            ("matcher-short-known", lambda: self.matcher(image(z, arrays={"Known": np.ones(10, np.uint8)})),
             r"Known array has 10 values for %d points" % n),
            ("extractor-no-matches", lambda: self.extractor(image(z), vtkTable()),
             r"Rank 0 asks for a match past the 0 the matcher found"),
            ("extractor-exemplar-other-cells",
             lambda: self.extractor(image(z), self.matches(image(z)), exemplar=image(z, spacing=(30.0, 30.0))),
             r"Exemplar 0 has other cells than the terrain: resample it"),
            ("merger-short-filled", lambda: self.merger(image(z, arrays={"Filled": np.ones(5, np.uint8)})),
             r"Filled array has 5 values for %d points" % n),
            ("merger-patch-far-away", lambda: self.merger(image(z), patch_origin=(1e300, 0.0)),
             r"patch's origin lies .* cells from the terrain's"),
            ("poisson-short-mask",
             lambda: self.poisson(image(z), image(z + 5.0, arrays={"Mask": np.ones(10, np.uint8)})),
             r"Mask array has 10 values for %d points" % n),
            # Hillshade, features, sketches, reader
            ("hillshade-all-nan", lambda: self.single("vtkTerrainHillshade", image(nan)), r"no valid|nodata"),
            ("hillshade-short-elevation",
             lambda: self.single("vtkTerrainHillshade", image(z, elevation_values=np.ones(3))),
             r"has 3 values for %d points" % n),
            ("features-all-nan", lambda: self.single("vtkTerrainFeatureExtractor", image(nan)), r"no valid|nodata"),
            ("sketch-features-blank", lambda: self.single("vtkTerrainSketchFeatures", self.tiny_strokes()),
             r"smaller than one patch"),
            ("sketch-lines-no-lines", lambda: self.single("vtkTerrainSketchLines", vtkPolyData()), r"no lines"),
            # Between the clamp's ends, but neither a ridge nor a valley.
            ("sketch-lines-type-zero", lambda: self.single("vtkTerrainSketchLines", line, FeatureType=0),
             r"Feature type 0 is none of 1 ridge or -1 valley\."),
            ("reader-fifo", lambda: self.make("vtkTerrainReader", FileName=self.fifo), r"not a regular file"),
            # A state loaded by hand names its files relative to the repository: say where the
            # name was looked for and how ParaView looks elsewhere.
            ("reader-missing-relative",
             lambda: self.make("vtkTerrainReader", FileName=os.path.join("Data", "dems", "none.png")),
             r"No such file: Data/dems/none.png \(a relative name, looked for in the working folder "
             + re.escape(os.getcwd()) + r"\).*Search files under specified directory"),
            ("reader-missing-absolute",
             lambda: self.make("vtkTerrainReader", FileName=os.path.join(self.tmp.name, "none.tif")),
             r"No such file: " + re.escape(os.path.join(self.tmp.name, "none.tif")) + r"\.(?! \(a relative)"),
            ("sketch-reader-missing-exemplar",
             lambda: self.make("vtkTerrainSketchReader",
                               FileName=os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png"),
                               ExemplarFileName="colorado.png"),
             r"No such file: colorado.png \(a relative name"),
        ]

    def matcher(self, target, PatchSize=32):
        m = self.make("vtkTerrainPatchMatcher", PatchSize=PatchSize, Backend=2)
        m.SetInputConnection(0, self.port(target))
        m.AddInputConnection(1, self.port(image(relief())))
        return m

    def matches(self, target):
        """The matcher's table for this target against relief(), as the extractor takes it."""
        m = self.matcher(target)
        m.Update()
        return m.GetOutputDataObject(0)

    def extractor(self, terrain, matches, exemplar=None):
        e = self.make("vtkTerrainPatchExtractor")
        e.SetInputData(0, terrain)
        e.AddInputDataObject(1, exemplar if exemplar is not None else image(relief()))
        e.SetInputData(2, matches)
        return e

    def merger(self, terrain, patch_origin=None):
        m = self.make("vtkTerrainGraphCutMerger")
        m.SetInputData(0, terrain)
        patch = image(relief(40))
        if patch_origin is not None:
            patch.SetOrigin(patch_origin[0], patch_origin[1], 0.0)
            m.SetUsePatchOrigin(True)
        m.SetInputData(1, patch)
        return m

    def poisson(self, destination, source):
        p = self.make("vtkTerrainPoissonSolver")
        p.SetInputData(0, destination)
        p.SetInputData(1, source)
        return p

    def tiny_strokes(self):
        out = vtkImageData()
        out.SetDimensions(40, 40, 1)
        rgb = np.full((40, 40, 3), 255, dtype=np.uint8)
        for k in range(40):
            rgb[k, k] = (230, 20, 20)
        colours = numpy_to_vtk(rgb.reshape(-1, 3), deep=1)
        colours.SetName("PNGImage")
        out.GetPointData().SetScalars(colours)
        return out

    def test_a_refusal_is_said_once_until_something_changes(self):
        """ParaView updates a filter twice on Apply (the pipeline, then its representation): the
        same refusal with nothing changed is not said again; changed, it is."""
        self.producers = []
        synth = self.synthesis(None)
        errors = []

        @calldata_type(VTK_STRING)
        def on_error(_caller, _event, text):
            errors.append(text)

        synth.AddObserver(vtkCommand.ErrorEvent, on_error)
        self.assertEqual(synth.GetExecutive().Update(), 0)
        self.assertEqual(synth.GetExecutive().Update(), 0)  # failed, so run again: quietly
        self.assertEqual(len(errors), 1, errors)
        self.assertIn("No sketch is connected", errors[0])
        synth.SetSeed(3)  # a change: the refusal is news again
        self.assertEqual(synth.GetExecutive().Update(), 0)
        self.assertEqual(len(errors), 2, errors)
        # The readers too: a missing file is said once, not once per request.
        reader = self.make("vtkTerrainReader", FileName=os.path.join(self.tmp.name, "gone.tif"))
        reader.AddObserver(vtkCommand.ErrorEvent, on_error)
        self.assertEqual(reader.GetExecutive().Update(), 0)
        self.assertEqual(reader.GetExecutive().Update(), 0)
        self.assertEqual(len(errors), 3, errors)
        self.assertIn("gone.tif", errors[2])

    def test_patch_size_refusal_is_said_once_through_paraview(self):
        """The synthesis proxy as ParaView runs it: Apply updates the pipeline, then the view
        fetches the output; a Patch Size of 12, 30 or 600 is refused in one sentence, not one
        per update (it was said by RequestInformation and again by RequestData). (0 is not
        refused: it chooses the patch for the sketch.)"""
        from paraview import servermanager as sm
        from paraview import simple
        simple.LoadPlugin(PATHS.plugin, remote=False)
        dems, sketches = (os.path.join(PATHS.bundled_data, d) for d in ("dems", "sketches"))
        dem = simple.TerrainReader(FileName=os.path.join(dems, "colorado.png"))
        sketch = simple.TerrainSketchReader(FileName=os.path.join(sketches, "strokes_y_ridges.png"),
                                            ExemplarFileName=os.path.join(dems, "colorado.png"))
        for size in (12, 30, 600):
            with self.subTest(patch_size=size):
                synth = simple.TerrainSynthesis(Exemplars=[dem], Sketch=sketch, OutputSize=[128, 128])
                errors = []

                @calldata_type(VTK_STRING)
                def on_error(_caller, _event, text):
                    errors.append(text)

                synth.GetClientSideObject().AddObserver(vtkCommand.ErrorEvent, on_error)
                synth.PatchSize = size  # typed into the panel, then Apply
                synth.UpdatePipeline()
                self.assertEqual(sm.Fetch(synth).GetNumberOfPoints(), 0)
                sentence = "Patch Size must be a multiple of 4 from 16 to 512 cells, not %d." % size
                self.assertEqual(sum(sentence in e for e in errors), 1, errors)
                self.assertEqual(len(errors), 1, errors)
                simple.Delete(synth)

    def test_a_reader_that_failed_is_the_only_one_to_say_so(self):
        """A state loaded from another folder: its readers cannot find their files and say so;
        the synthesis fed by them says nothing more (it said the exemplar had no positive cell
        size, sending the user after a setting that was never the cause)."""
        self.producers = []
        missing = os.path.join("Data", "dems", "none.png")
        errors = {"reader": [], "sketch reader": [], "synthesis": []}

        def collect(algorithm, name):
            @calldata_type(VTK_STRING)
            def on_error(_caller, _event, text):
                errors[name].append(text)
            algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
            return algorithm

        for broken in ("reader", "sketch reader"):
            with self.subTest(failed=broken):
                for found in errors.values():
                    found.clear()
                reader = collect(self.make("vtkTerrainReader", FileName=missing if broken == "reader" else
                                           os.path.join(PATHS.bundled_data, "dems", "colorado.png")), "reader")
                sketch = collect(self.make("vtkTerrainSketchReader", FileName=missing if broken != "reader" else
                                           os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png"),
                                           ExemplarFileName=os.path.join(PATHS.bundled_data, "dems", "colorado.png")),
                                 "sketch reader")
                synth = collect(self.make("vtkTerrainSynthesis", PatchSize=32), "synthesis")
                synth.AddInputConnection(0, reader.GetOutputPort())
                synth.SetInputConnection(1, sketch.GetOutputPort())
                self.assertEqual(synth.GetExecutive().Update(), 0)
                self.assertEqual(synth.GetExecutive().Update(), 0)
                self.assertEqual(len(errors[broken]), 1, errors)
                self.assertIn("No such file: " + missing, errors[broken][0])
                self.assertEqual(errors["synthesis"], [], errors)

    def test_a_state_loaded_from_another_folder_names_only_its_missing_files(self):
        """The synthesis state's pipeline as proxies (ParaView puts a vtkPVPostFilter between a
        reader and the filter), its files named relative to the repository and looked for in
        another folder: the readers say which file is missing and how a state finds its files;
        the synthesis adds nothing (it said "The first exemplar has no positive cell size; give
        CellSize.", a setting that was never the cause)."""
        from paraview import simple
        from vtkmodules.vtkCommonCore import vtkOutputWindow
        simple.LoadPlugin(PATHS.plugin, remote=False)
        said = []

        @calldata_type(VTK_STRING)
        def on_error(_caller, _event, text):
            said.append(text)

        window = vtkOutputWindow.GetInstance()
        observer = window.AddObserver(vtkCommand.ErrorEvent, on_error)
        cwd = os.getcwd()
        os.chdir(self.tmp.name)
        try:
            exemplar = simple.TerrainReader(FileName=os.path.join("Data", "dems", "colorado.png"))
            sketch = simple.PNGSeriesReader(FileNames=[os.path.join("Data", "sketches", "strokes_y_ridges.png")])
            synth = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[256, 256])
            synth.UpdatePipeline()
        finally:
            os.chdir(cwd)
            window.RemoveObserver(observer)
        def said_by(name):  # "ERROR: In FILE, line N\nvtkName (0x...): sentence"
            return [e for e in said if e.split("\n")[1:2] and e.split("\n")[1].startswith(name + " (")]

        self.assertTrue(any("No such file: Data/dems/colorado.png" in e and "Search files under specified directory"
                            in e for e in said_by("vtkTerrainReader")), said)
        self.assertEqual(said_by("vtkTerrainSynthesis"), [], said)
        self.assertFalse(any("cell size" in e for e in said), said)
        simple.Delete(synth)

    def test_catalogue(self):
        self.producers = []
        cases = self.cases()
        self.assertGreaterEqual(len(cases), 30)
        self.assertEqual(len({c[0] for c in cases}), len(cases))
        only = os.environ.get("TSYNTH_BAD_INPUT_CASES")
        for case_id, build, pattern in cases:
            if only and case_id not in only.split(","):
                continue
            with self.subTest(case=case_id):
                algorithm = build()
                errors = []

                @calldata_type(VTK_STRING)
                def on_error(_caller, _event, text):
                    errors.append(text)

                algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
                ok = algorithm.GetExecutive().Update()
                # ParaView updates a filter twice on Apply (the pipeline, then its
                # representation): the refusal is still said once, whether it came from
                # RequestInformation (the patch sizes) or from RequestData.
                algorithm.GetExecutive().Update()
                if os.environ.get("TSYNTH_BAD_INPUT_VERBOSE"):
                    print("\n%-38s %d %s" % (case_id, ok, errors))
                self.assertEqual(ok, 0, "the request did not fail; errors %r" % errors)
                self.assertTrue(any(re.search(pattern, e) for e in errors), errors)
                self.assertEqual(len(errors), 1, "one sentence, not %r" % errors)
                output = algorithm.GetOutputDataObject(0)
                if output is not None:
                    count = (output.GetNumberOfPoints() if hasattr(output, "GetNumberOfPoints")
                             else output.GetNumberOfRows())
                    self.assertEqual(count, 0, "a failed request left an output")


if __name__ == "__main__":
    harness.run(__name__)
