"""pvpython tests of pit removal and terrain optimisation through their front ends:
tsynth pits / tsynth optimise and the TerrainPitRemoval / TerrainOptimisation filters,
checked with numpy on the heights they write (an oracle written independently of the C++)."""
import os
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
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter  # noqa: E402


def tsynth(*args):
    return subprocess.run([PATHS.tsynth, *args], capture_output=True, text=True, timeout=240)


def write_vti(path, z, valid=None, spacing=90.0):
    ny, nx = z.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    image.SetSpacing(spacing, spacing, 1.0)
    elevation = numpy_to_vtk(np.ascontiguousarray(z.ravel(), dtype=np.float32), deep=1)
    elevation.SetName("Elevation")
    image.GetPointData().SetScalars(elevation)
    if valid is not None:
        mask = numpy_to_vtk(np.ascontiguousarray(valid.ravel(), dtype=np.uint8), deep=1)
        mask.SetName("Valid")
        image.GetPointData().AddArray(mask)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def read_vti(path, name="Elevation"):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    nx, ny, _ = data.GetDimensions()
    return vtk_to_numpy(data.GetPointData().GetArray(name)).reshape(ny, nx).astype(np.float64)


def sinks_of(z, user=None):
    """Outlets: the border, cells next to nodata (NaN), and user sinks."""
    valid = np.isfinite(z)
    padded = np.pad(valid, 1, constant_values=False)
    ny, nx = z.shape
    all_neighbours_valid = np.ones_like(valid)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            all_neighbours_valid &= padded[1 + dy:1 + dy + ny, 1 + dx:1 + dx + nx]
    sinks = valid & ~all_neighbours_valid
    if user is not None:
        sinks |= valid & (user != 0)
    return sinks


def lower_neighbour(z):
    ny, nx = z.shape
    padded = np.pad(z, 1, constant_values=np.nan)
    has_lower = np.zeros(z.shape, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                n = padded[1 + dy:1 + dy + ny, 1 + dx:1 + dx + nx]
                has_lower |= np.isfinite(n) & (n < z)
    return has_lower


def undrained_cells(z, user=None):
    """Valid non-sink cells from which water cannot reach a sink: with no strictly lower
    valid 8-neighbour, and not joined through cells of equal height to one that has one
    or to a sink (the flats a breach keeps)."""
    ny, nx = z.shape
    drains = np.isfinite(z) & (lower_neighbour(z) | sinks_of(z, user))
    while True:
        padded_z = np.pad(z, 1, constant_values=np.nan)
        padded_d = np.pad(drains, 1, constant_values=False)
        grown = drains.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                if dx or dy:
                    nz = padded_z[1 + dy:1 + dy + ny, 1 + dx:1 + dx + nx]
                    nd = padded_d[1 + dy:1 + dy + ny, 1 + dx:1 + dx + nx]
                    grown |= nd & (nz == z)
        if np.array_equal(grown, drains):
            break
        drains = grown
    return int(np.count_nonzero(np.isfinite(z) & ~drains))


def pits_of(z):
    """Strict local minima off the border (the count tsynth prints)."""
    c = z[1:-1, 1:-1]
    lower = np.ones(c.shape, dtype=bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dx or dy:
                lower &= z[1 + dy:z.shape[0] - 1 + dy, 1 + dx:z.shape[1] - 1 + dx] > c
    return int(np.count_nonzero(lower))


class PitsCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        cls.original = os.path.join(cls.tmp.name, "colorado.vti")
        subprocess.run([PATHS.tsynth, "convert", cls.colorado, "-o", cls.original], check=True,
                       stdout=subprocess.DEVNULL)
        cls.z = read_vti(cls.original)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def run_pits(self, method, *extra):
        out = os.path.join(self.tmp.name, "%s.vti" % method)
        r = tsynth("pits", self.original, "-o", out, "--method", method, *extra)
        self.assertEqual(r.returncode, 0, r.stderr)
        return read_vti(out), r.stdout

    def test_real_dem_has_pits_to_remove(self):
        # Guards the other tests: a DEM without pits would make them vacuous.
        self.assertGreater(pits_of(self.z), 100)
        self.assertGreater(undrained_cells(self.z), 100)

    def test_fill_drains_everywhere_and_never_lowers(self):
        filled, stdout = self.run_pits("fill")
        self.assertEqual(undrained_cells(filled), 0)
        self.assertTrue(np.all(filled >= self.z))
        self.assertGreater(np.count_nonzero(filled > self.z), 1000)
        self.assertIn("%d pits before, 0 after" % pits_of(self.z), stdout)

    def test_breach_drains_everywhere_and_never_raises(self):
        breached, _ = self.run_pits("breach")
        self.assertEqual(undrained_cells(breached), 0)
        self.assertTrue(np.all(breached <= self.z))
        lowered = np.count_nonzero(breached < self.z)
        # Channels are one cell wide: far fewer cells change than a fill raises.
        filled, _ = self.run_pits("fill")
        self.assertGreater(lowered, 100)
        self.assertLess(lowered, np.count_nonzero(filled > self.z))

    def test_hybrid_sits_between_breach_and_fill(self):
        tight, _ = self.run_pits("hybrid", "--max-depth", "0.001", "--max-length", "1")
        loose, _ = self.run_pits("hybrid", "--max-depth", "100000", "--max-length", "100000")
        breached, _ = self.run_pits("breach")
        mixed, _ = self.run_pits("hybrid")
        for result in (tight, loose, mixed):
            self.assertEqual(undrained_cells(result), 0)
        np.testing.assert_array_equal(loose, breached)
        self.assertTrue(np.all(tight >= self.z))  # nothing can be breached: all filled
        self.assertGreater(np.count_nonzero(mixed < self.z), 0)
        self.assertGreater(np.count_nonzero(mixed > self.z), 0)

    def test_flow_accumulation_counts_every_cell_once_at_its_outlet(self):
        flow = os.path.join(self.tmp.name, "acc.vti")
        streams = os.path.join(self.tmp.name, "streams.vti")
        out = os.path.join(self.tmp.name, "b.vti")
        r = tsynth("pits", self.original, "-o", out, "--flow", flow, "--streams", streams,
                   "--stream-area", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        z = read_vti(out)
        acc = read_vti(flow)
        # Outlets are the sinks with no strictly lower neighbour (flats are routed
        # across to their exits): they receive everything.
        outlets = sinks_of(z) & ~lower_neighbour(z)
        self.assertEqual(acc[outlets].sum(), z.size)
        self.assertEqual(acc.min(), 1.0)
        threshold = int(np.ceil(2.0e6 / (90.0 * 90.0)))
        np.testing.assert_array_equal(read_vti(streams), (acc >= threshold).astype(float))
        self.assertIn("%d cells or more drain" % threshold, r.stdout)

    def test_user_sinks_keep_their_water_and_nodata_is_an_outlet(self):
        z = self.z.copy()
        valid = np.ones(z.shape, dtype=np.uint8)
        valid[300:340, 300:340] = 0
        z[valid == 0] = 0.0
        dem = os.path.join(self.tmp.name, "holes.vti")
        write_vti(dem, z, valid)
        lake = np.zeros(z.shape, dtype=np.float32)
        lowest = np.unravel_index(np.argmin(np.where(valid == 1, z, np.inf)[100:200, 100:200]), (100, 100))
        lake[100 + lowest[0], 100 + lowest[1]] = 1.0
        mask = os.path.join(self.tmp.name, "lake.vti")
        write_vti(mask, lake)
        for method in ("fill", "breach"):
            out = os.path.join(self.tmp.name, "holes-%s.vti" % method)
            r = tsynth("pits", dem, "-o", out, "--method", method, "--sinks", mask)
            self.assertEqual(r.returncode, 0, r.stderr)
            result = read_vti(out)
            result[valid == 0] = np.nan
            self.assertEqual(undrained_cells(result, lake), 0, method)
            self.assertEqual(result[100 + lowest[0], 100 + lowest[1]], z[100 + lowest[0], 100 + lowest[1]])

    def test_bad_input_gives_one_sentence_and_writes_nothing(self):
        out = os.path.join(self.tmp.name, "never.vti")
        small = os.path.join(self.tmp.name, "small.vti")
        write_vti(small, np.zeros((10, 12), dtype=np.float32))
        empty = os.path.join(self.tmp.name, "empty.vti")
        write_vti(empty, np.zeros((10, 12), dtype=np.float32), np.zeros((10, 12), dtype=np.uint8))
        cases = [
            (["--method", "carve"], 2, '--method must be fill, breach or hybrid, not "carve".'),
            (["--sinks", small], 1, "give a mask of the DEM's size"),
            (["--max-depth", "-3"], 2, "--max-depth expects a number from 0.001 to 1000000, not -3."),
            (["--max-length", "0"], 2, "--max-length expects a whole number from 1 to 1000000, not 0."),
            (["--flow", "/nonexistent/acc.tif"], 1, "folder /nonexistent does not exist"),
            (["--stream-area", "1"], 2, "with --streams"),
        ]
        for extra, code, message in cases:
            r = tsynth("pits", self.original, "-o", out, *extra)
            self.assertEqual(r.returncode, code, (extra, r.stderr))
            self.assertIn(message, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertFalse(os.path.exists(out))
        r = tsynth("pits", empty, "-o", out)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no valid heights", r.stderr)
        self.assertFalse(os.path.exists(out))
        flat = os.path.join(self.tmp.name, "flat.vti")
        write_vti(flat, np.full((10, 12), 250.0, dtype=np.float32))
        r = tsynth("pits", flat, "-o", out)
        self.assertEqual(r.returncode, 1)
        self.assertIn("The DEM is flat (every valid cell at 250 m)", r.stderr)
        self.assertFalse(os.path.exists(out))


class PitRemovalFilterTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        simple.LoadPlugin(PATHS.plugin, remote=False)
        cls.colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")

    def test_filter_gives_the_command_lines_heights_and_flow(self):
        reader = simple.TerrainReader(FileName=self.colorado)
        for method, name in ((0, "fill"), (1, "breach"), (2, "hybrid")):
            pits = simple.TerrainPitRemoval(Input=reader, Method=method, StreamThreshold=124)
            data = sm.Fetch(pits)
            nx, ny, _ = data.GetDimensions()
            z = vtk_to_numpy(data.GetPointData().GetArray("Elevation")).reshape(ny, nx)
            with tempfile.TemporaryDirectory() as tmp:
                out = os.path.join(tmp, "out.vti")
                r = tsynth("pits", self.colorado, "-o", out, "--method", name)
                self.assertEqual(r.returncode, 0, r.stderr)
                np.testing.assert_array_equal(z, read_vti(out).astype(np.float32))
            changed = vtk_to_numpy(data.GetPointData().GetArray("Changed")).reshape(ny, nx)
            original = vtk_to_numpy(sm.Fetch(reader).GetPointData().GetArray("Elevation")).reshape(ny, nx)
            np.testing.assert_array_equal(changed == 1, z > original)
            np.testing.assert_array_equal(changed == 2, z < original)
            acc = vtk_to_numpy(data.GetPointData().GetArray("FlowAccumulation"))
            direction = vtk_to_numpy(data.GetPointData().GetArray("FlowDirection"))
            self.assertEqual(int(acc[direction == -1].sum()), nx * ny)
            streams = vtk_to_numpy(data.GetPointData().GetArray("Streams"))
            np.testing.assert_array_equal(streams, (acc >= 124).astype(np.uint8))

    def test_xml_defaults_are_the_class_defaults(self):
        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainPitRemoval

        direct = vtkTerrainPitRemoval()
        proxy = simple.TerrainPitRemoval(Input=simple.TerrainReader(FileName=self.colorado))
        self.assertEqual(proxy.SMProxy.GetProperty("Method").GetElement(0), direct.GetMethod())
        self.assertAlmostEqual(proxy.MaxBreachDepth, direct.GetMaxBreachDepth())
        self.assertEqual(proxy.MaxBreachLength, direct.GetMaxBreachLength())
        self.assertEqual(proxy.StreamThreshold, direct.GetStreamThreshold())

    def test_sink_mask_of_the_wrong_size_fails_the_request(self):
        from vtkmodules.vtkCommonCore import vtkCommand
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING

        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainPitRemoval, vtkTerrainReader

        reader = vtkTerrainReader()
        reader.SetFileName(self.colorado)
        image = vtkImageData()
        image.SetDimensions(10, 10, 1)
        values = numpy_to_vtk(np.ones(100, dtype=np.uint8), deep=1)
        values.SetName("Lakes")
        image.GetPointData().SetScalars(values)
        pits = vtkTerrainPitRemoval()
        pits.SetInputConnection(reader.GetOutputPort())
        pits.SetInputData(1, image)
        errors = []

        @calldata_type(VTK_STRING)
        def on_error(_caller, _event, message):
            errors.append(message)

        pits.AddObserver(vtkCommand.ErrorEvent, on_error)
        pits.Update()
        self.assertEqual(pits.GetOutput().GetNumberOfPoints(), 0)
        self.assertEqual(len(errors), 1, errors)
        self.assertIn("10 x 10 cells but the DEM is 648 x 648", errors[0])


class OptimiseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        simple.LoadPlugin(PATHS.plugin, remote=False)
        cls.tmp = tempfile.TemporaryDirectory()
        cls.colorado = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        cls.lambda_grey = os.path.join(PATHS.bundled_data, "sketches", "lambda_circle_grey.png")
        cls.tree = os.path.join(PATHS.bundled_data, "sketches", "strokes_valley_tree.png")
        cls.source = read_vti(cls.convert(cls.colorado, "colorado.vti"))

    @classmethod
    def convert(cls, path, name):
        out = os.path.join(cls.tmp.name, name)
        subprocess.run([PATHS.tsynth, "convert", path, "-o", out], check=True, stdout=subprocess.DEVNULL)
        return out

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_command_line_and_filter_give_the_same_terrain(self):
        out = os.path.join(self.tmp.name, "opt.vti")
        r = tsynth("optimise", "--exemplar", self.colorado, "--guide", self.lambda_grey, "-o", out,
                   "--size", "256x256", "--seed", "3", "--no-progress")
        self.assertEqual(r.returncode, 0, r.stderr)
        z = read_vti(out)
        self.assertEqual(z.shape, (256, 256))
        # Every height is an average of source heights.
        self.assertGreaterEqual(z.min(), self.source.min() - 1e-3)
        self.assertLessEqual(z.max(), self.source.max() + 1e-3)
        # The per-level table: the coarsest level first, the output last, energy falling.
        rows = [line.split() for line in r.stdout.splitlines() if line[:1].isdigit()]
        self.assertEqual(rows[-1][1:4], ["256", "x", "256"])
        energies = [float(v) for v in rows[-1][4:6]]
        self.assertLess(energies[1], energies[0])
        source = simple.TerrainReader(FileName=self.colorado)
        guide = simple.PNGSeriesReader(FileNames=[self.lambda_grey])
        opt = simple.TerrainOptimisation(Source=source, Guide=guide, OutputSize=[256, 256], Seed=3)
        data = sm.Fetch(opt)
        self.assertEqual(data.GetDimensions(), (256, 256, 1))
        filtered = vtk_to_numpy(data.GetPointData().GetArray("Elevation")).reshape(256, 256)
        np.testing.assert_array_equal(filtered, z.astype(np.float32))

    def test_a_stroke_sketch_guides_valleys_and_leaves_free_land_to_the_source(self):
        out = os.path.join(self.tmp.name, "tree.vti")
        r = tsynth("optimise", "--exemplar", self.colorado, "--guide", self.tree, "-o", out,
                   "--size", "384x384", "--no-progress")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("(guide: stroke map)", r.stdout)
        z = read_vti(out)
        # The sketched trunk (blue, down the middle of the sketch) lies lower than the
        # land a quarter of the terrain to either side of it.
        trunk = z[:, 180:204].mean()
        sides = 0.5 * (z[:, 60:84].mean() + z[:, 300:324].mean())
        self.assertLess(trunk, sides - 100.0)
        # Free land keeps relief of the source's kind (not a flat plain): its spread is
        # at least a third of the source's.
        self.assertGreater(z[:, :60].std(), self.source.std() / 3.0)

    def test_drain_makes_the_output_drain_with_a_small_change(self):
        # A real DEM as the guide (the lambda's ring is a closed basin by design, which
        # draining must cut through).
        alps = os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png")
        plain = os.path.join(self.tmp.name, "plain.vti")
        drained = os.path.join(self.tmp.name, "drained.vti")
        for out, extra in ((plain, []), (drained, ["--drain"])):
            r = tsynth("optimise", "--exemplar", self.colorado, "--guide", alps, "-o", out,
                       "--size", "256x256", "--no-progress", *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
        a, b = read_vti(plain), read_vti(drained)
        self.assertGreater(undrained_cells(a), 10)
        self.assertEqual(undrained_cells(b), 0)
        self.assertLess(np.sqrt(np.mean((a - b) ** 2)), 0.05 * a.std())

    def test_abort_stops_the_filter_promptly_with_an_empty_output(self):
        import time
        sys.path.insert(0, PATHS.python_dir)
        from terrainsynthesis import vtkTerrainOptimisation, vtkTerrainReader

        source = vtkTerrainReader()
        source.SetFileName(self.colorado)
        guide = vtkTerrainReader()
        guide.SetFileName(os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png"))
        source.Update()
        guide.Update()

        def optimisation():
            opt = vtkTerrainOptimisation()
            opt.SetSourceConnection(source.GetOutputPort())
            opt.SetGuideConnection(guide.GetOutputPort())
            opt.SetOutputSize(1024, 1024)
            return opt

        whole = harness.seconds_to_run(optimisation().Update)
        opt = optimisation()
        stopped_at = []

        def abort_after_a_fifth(caller, _event):
            if caller.GetProgress() > 0.2 and not stopped_at:
                stopped_at.append(time.monotonic())
                caller.SetAbortExecute(1)

        opt.AddObserver("ProgressEvent", abort_after_a_fifth)
        opt.Update()
        self.assertTrue(stopped_at, "no progress was reported")
        harness.assert_stopped_promptly(self, "the optimisation", time.monotonic() - stopped_at[0], whole)
        self.assertEqual(opt.GetOutput().GetNumberOfPoints(), 0)

    def test_ctrl_c_stops_the_command_promptly_and_writes_nothing(self):
        import signal
        import time
        out = os.path.join(self.tmp.name, "interrupted.tif")
        alps = os.path.join(PATHS.bundled_data, "dems", "alps-montblanc.png")
        command = [PATHS.tsynth, "optimise", "--exemplar", self.colorado, "--guide", alps,
                   "--size", "1024x1024", "--no-progress", "-o"]
        whole_out = os.path.join(self.tmp.name, "whole.tif")
        whole = harness.seconds_to_run(lambda: subprocess.run(command + [whole_out], check=True,
                                                              capture_output=True))
        os.remove(whole_out)
        p = subprocess.Popen(command + [out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        # Once it announces the optimisation (the guide is built), and a little into it.
        self.assertTrue(p.stdout.readline().startswith("Optimising 1024 x 1024 cells"))
        time.sleep(0.1 * whole)
        self.assertIsNone(p.poll(), "the optimisation ended before it could be interrupted")
        sent = time.monotonic()
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=30 + whole)
        harness.assert_stopped_promptly(self, "tsynth optimise", time.monotonic() - sent, whole)
        self.assertEqual(p.returncode, 130, err)
        self.assertIn("nothing was written", err)
        self.assertFalse(os.path.exists(out))

    def test_bad_input_gives_one_sentence_and_writes_nothing(self):
        out = os.path.join(self.tmp.name, "never.tif")
        tiny = os.path.join(self.tmp.name, "tiny.vti")
        write_vti(tiny, np.zeros((20, 20), dtype=np.float32))
        base = ["optimise", "--exemplar", self.colorado, "-o", out, "--no-progress"]
        cases = [
            (["--guide", self.lambda_grey, "--patch", "8"], 1, "odd"),
            (["--guide", self.lambda_grey, "--alpha", "1.5"], 2, "--alpha expects a number from 0 to 1, not 1.5."),
            (["--guide", self.lambda_grey, "--pits", "drain"], 2,
             '--pits must be off, fill, breach or hybrid, not "drain".'),
            (["--guide", "/nonexistent/guide.png"], 1, "/nonexistent/guide.png"),
            (["--guide", tiny], 1, "output of 20 x 20 cells, smaller than the 80 cells"),
            (["--guide", self.lambda_grey, "--levels", "9"], 1, "use fewer levels"),
            (["--guide", self.lambda_grey, "--size", "0x5"], 2, "--size expects"),
            ([], 2, "needs a source --exemplar DEM and a --guide"),
        ]
        flat = os.path.join(self.tmp.name, "flat-source.vti")
        write_vti(flat, np.full((200, 200), 900.0, dtype=np.float32))
        r = tsynth("optimise", "--exemplar", flat, "--guide", self.lambda_grey, "-o", out)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("The source DEM is flat", r.stderr)
        self.assertFalse(os.path.exists(out))
        for extra, code, message in cases:
            r = tsynth(*base, *extra)
            self.assertEqual(r.returncode, code, (extra, r.stdout, r.stderr))
            self.assertIn(message, r.stderr, extra)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    harness.run(__name__)
