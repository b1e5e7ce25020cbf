"""Tiled synthesis on ParaView's MPI engine (issue 22): `mpiexec -np N pvbatch
Examples/pvbatch/tiled_synthesis.py` writes the same heights for N = 1, 2 and 3 ranks, bit for bit,
and the same as `tsynth synth --tile-size` in one process; bad arguments get one sentence."""
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader  # noqa: E402

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "pvbatch",
                      "tiled_synthesis.py")
SIZE = 256
PATCH = 32
TILE = 96  # 3 x 3 tiles of 96 cells (three patches), the last ones 64 wide
SEED = 3
# Open MPI refuses root without these, and more ranks than cores without --oversubscribe.
MPI_FLAGS = ["--allow-run-as-root", "--oversubscribe"]
TIMEOUT_S = 600
STOP_SIZE = 1024  # 11 x 11 tiles: the fill on 2 ranks takes several seconds


def heights(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetArray("Elevation")).copy()


def processes_naming(path):
    """The ids of the processes whose command line holds `path` (from /proc: no procps needed)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                if path.encode() in f.read():
                    found.append(int(pid))
        except OSError:
            pass  # ended meanwhile
    return found


# A pvpython client of a pvserver, as the GUI would drive it: the view's update, then Save Data's
# Terrain tiles writer; again with another seed.
CLIENT = """
from paraview import simple
simple.Connect("localhost", %(port)d)
simple.LoadPlugin(%(plugin)r, remote=True)
exemplar = simple.TerrainReader(FileName=%(exemplar)r)
sketch = simple.TerrainSketchReader(FileName=%(sketch)r, ExemplarFileName=%(exemplar)r)
synthesis = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[%(size)d, %(size)d],
                                    PatchSize=%(patch)d, Seed=%(seed)d, TileSize=%(tile)d, Backend="CPU")
for seed in (%(seed)d, %(seed)d + 1):
    synthesis.Seed = seed
    synthesis.UpdatePipeline()
    simple.SaveData("%(folder)s/seed%%d.vrt" %% seed, proxy=synthesis, TileSize=65)
"""


class MpiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="tsynth-mpi-")
        cls.exemplar = os.path.join(PATHS.bundled_data, "dems", "colorado.png")
        cls.sketch = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        cls.mpiexec = shutil.which("mpiexec")
        cls.pvbatch = shutil.which("pvbatch")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp)

    def one_process_heights(self):
        """The dimensions and heights `tsynth synth --tile-size` makes of the test's inputs in one
        process: what every rank count must give (made once for the tests that compare with it)."""
        if not hasattr(MpiTest, "_one"):
            one = os.path.join(self.tmp, "one.vti")
            result = subprocess.run(
                [PATHS.tsynth, "synth", "--exemplar", self.exemplar, "--sketch", self.sketch, "--size",
                 "%dx%d" % (SIZE, SIZE), "--tile-size", str(TILE), "--patch", str(PATCH), "--seed", str(SEED),
                 "--backend", "cpu", "--no-progress", "-o", one], capture_output=True, text=True,
                timeout=TIMEOUT_S)
            self.assertEqual(result.returncode, 0, result.stderr)
            MpiTest._one = heights(vtkXMLImageDataReader, one)
        return MpiTest._one

    def command(self, ranks, output, size=SIZE):
        return [self.mpiexec, *MPI_FLAGS, "-np", str(ranks), self.pvbatch, SCRIPT, "--exemplar", self.exemplar,
                "--sketch", self.sketch, "--size", "%dx%d" % (size, size), "--tile-size", str(TILE),
                "--patch", str(PATCH), "--seed", str(SEED), "-o", output]

    @staticmethod
    def environment():
        # pvpython runs as an MPI singleton: its Open MPI and PMIx variables would make mpiexec's
        # ranks join this process's job instead of their own.
        env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
        env["TSYNTH_PLUGIN"] = PATHS.plugin
        return env

    def on_ranks(self, ranks, output):
        return subprocess.run(self.command(ranks, output), capture_output=True, text=True,
                              timeout=TIMEOUT_S, env=self.environment())

    def until_rank_fills(self, output):
        """Starts a run of 2 ranks on STOP_SIZE cells and waits for rank 1 to start its fill."""
        run = subprocess.Popen(self.command(2, output, STOP_SIZE), stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, env=self.environment())
        for line in run.stdout:
            if "rank 1 of 2: fill" in line:
                return run
        run.wait()
        self.fail("rank 1 never reached its fill")

    def test_every_rank_count_writes_the_heights_of_one_process(self):
        dims, expected = self.one_process_heights()
        self.assertEqual(dims, (SIZE, SIZE, 1))
        self.assertGreater(float(expected.max() - expected.min()), 100.0)  # real relief
        for ranks in (1, 2, 3):
            with self.subTest(ranks=ranks):
                out = os.path.join(self.tmp, "ranks%d.pvti" % ranks)
                result = self.on_ranks(ranks, out)
                self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
                self.assertIn("on %d rank" % ranks, result.stdout)
                if ranks > 1:  # every rank says how far it is
                    for rank in range(ranks):
                        self.assertIn("rank %d of %d: fill" % (rank, ranks), result.stdout)
                        self.assertRegex(result.stdout, r"rank %d of %d: \d+ feature and \d+ fill tile "
                                         r"passes in [\d.]+ s \(CPU [\d.]+ s\), waited" % (rank, ranks))
                self.assertEqual([n for n in os.listdir(self.tmp) if ".tmp-" in n], [],
                                 "the temporary folder is left behind")
                pieces = os.listdir(os.path.join(self.tmp, "ranks%d" % ranks))
                self.assertEqual(len(pieces), ranks, "one piece per rank: %s" % pieces)
                got_dims, got = heights(vtkXMLPImageDataReader, out)
                self.assertEqual(got_dims, dims)
                np.testing.assert_array_equal(got, expected)

    def test_ctrl_c_on_mpiexec_stops_every_rank(self):
        # The bound comes from this run: how long an uninterrupted run goes on past the point where
        # the other is stopped. A rank that ignored the stop would take about that long.
        run = self.until_rank_fills(os.path.join(self.tmp, "whole.pvti"))
        reached = time.monotonic()
        run.stdout.read()
        self.assertEqual(run.wait(timeout=TIMEOUT_S), 0)
        remaining = time.monotonic() - reached
        stopped = os.path.join(self.tmp, "stopped.pvti")
        run = self.until_rank_fills(stopped)
        interrupted = time.monotonic()
        run.send_signal(signal.SIGINT)
        run.stdout.read()
        code = run.wait(timeout=TIMEOUT_S)
        took = time.monotonic() - interrupted
        print("stopped in %.2f s; %.2f s were left" % (took, remaining))
        self.assertNotEqual(code, 0, "a stopped run must not report success")
        self.assertLess(took, 0.5 * remaining, "ranks went on after Ctrl-C: %.1f s against %.1f s left"
                        % (took, remaining))
        self.assertEqual(processes_naming(stopped), [], "a rank outlived mpiexec")
        self.assertFalse(os.path.exists(stopped), "a stopped run left a mosaic under the final name")
        # The stopped run's temporary folder goes with the next run to that output.
        self.assertEqual(self.on_ranks(1, stopped).returncode, 0)
        self.assertEqual([n for n in os.listdir(self.tmp) if n.startswith(".stopped.tmp-")], [])

    def test_a_mosaic_of_geotiff_tiles_written_by_every_rank_holds_the_heights_of_one_process(self):
        _, expected = self.one_process_heights()
        # 256 samples in tiles of 65 that share their edges: 4 x 4 tiles; 3 ranks write 1, 1 and 2
        # tile rows (Kernels/Core/TileExport.h tileRowsOf).
        names = sorted("mosaic_x%d_y%d.tif" % (c, r) for c in range(4) for r in range(4))
        for ranks in (2, 3):
            with self.subTest(ranks=ranks):
                folder = os.path.join(self.tmp, "mosaic%d" % ranks)
                os.mkdir(folder)
                out = os.path.join(folder, "mosaic.vrt")
                result = subprocess.run(self.command(ranks, out) + ["--file-tile-size", "65"], capture_output=True,
                                        text=True, timeout=TIMEOUT_S, env=self.environment())
                self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
                self.assertIn("(16 GeoTIFF tiles)", result.stdout)
                # One synthesis per rank: the writer's request for its rows is the only one.
                self.assertEqual(len(re.findall(r"rank 0 of %d: \d+ feature" % ranks, result.stdout)), 1,
                                 result.stdout)
                self.assertEqual(sorted(n for n in os.listdir(folder) if n.endswith(".tif")), names)
                self.assertEqual(len([n for n in os.listdir(folder) if n.endswith(".json")]), 16)
                back = os.path.join(self.tmp, "back%d.vti" % ranks)
                converted = subprocess.run([PATHS.tsynth, "convert", out, "-o", back], capture_output=True, text=True)
                self.assertEqual(converted.returncode, 0, converted.stderr)
                dims, got = heights(vtkXMLImageDataReader, back)
                self.assertEqual(dims, (SIZE, SIZE, 1))
                np.testing.assert_array_equal(got, expected)

    def test_a_pvserver_on_two_ranks_synthesises_once_for_the_view_and_the_writer(self):
        """As in the GUI connected to `mpiexec -np 2 pvserver`: the view asks for each rank's piece,
        then File > Save Data's tile writer for its tile rows. The second request is cut from the
        first synthesis, not synthesised again; a changed property synthesises anew."""
        _, expected = self.one_process_heights()
        with socket.socket() as probe:  # a free port
            probe.bind(("localhost", 0))
            port = probe.getsockname()[1]
        server = subprocess.Popen([self.mpiexec, *MPI_FLAGS, "-np", "2", shutil.which("pvserver"),
                                   "--server-port=%d" % port], stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, text=True, env=self.environment())
        try:
            for line in server.stdout:
                if "Accepting connection" in line:
                    break
            folder = os.path.join(self.tmp, "served")
            os.mkdir(folder)
            client = os.path.join(self.tmp, "client.py")
            with open(client, "w") as f:
                f.write(CLIENT % dict(port=port, plugin=PATHS.plugin, exemplar=self.exemplar,
                                      sketch=self.sketch, size=SIZE, patch=PATCH, seed=SEED, tile=TILE,
                                      folder=folder))
            result = subprocess.run([shutil.which("pvpython"), client], capture_output=True, text=True,
                                    timeout=TIMEOUT_S, env=self.environment())
            self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        finally:
            server.terminate()
            served = server.communicate(timeout=60)[0]
        # Two saves, one synthesis each: the first for seed 3, the second for seed 4.
        self.assertEqual(len(re.findall(r"rank 0 of 2: \d+ feature", served)), 2, served)
        self.assertEqual(len(re.findall(r"rank 1 of 2: \d+ feature", served)), 2, served)
        mosaics = []
        for name in ("seed3", "seed4"):
            back = os.path.join(self.tmp, "%s.vti" % name)
            converted = subprocess.run([PATHS.tsynth, "convert", os.path.join(folder, name + ".vrt"), "-o", back],
                                       capture_output=True, text=True)
            self.assertEqual(converted.returncode, 0, converted.stderr)
            mosaics.append(heights(vtkXMLImageDataReader, back)[1])
        np.testing.assert_array_equal(mosaics[0], expected)
        self.assertGreater(float(np.abs(mosaics[1] - expected).max()), 10.0, "seed 4 gave seed 3's terrain")

    def test_bad_arguments_get_one_sentence(self):
        out = os.path.join(self.tmp, "bad.pvti")
        result = self.on_ranks(1, os.path.join(self.tmp, "bad.tif"))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("-o OUT.vrt or -o OUT.pvti, not", result.stderr)
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    harness.run(__name__)
