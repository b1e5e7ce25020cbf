"""pvpython tests: the plugin loads, its proxies and wrapped classes run on real DEMs."""
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
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402


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

    def test_missing_file_gives_an_empty_output_not_a_crash(self):
        reader = simple.TerrainReader(FileName="/nonexistent/dem.tif")
        reader.UpdatePipeline()
        self.assertEqual(sm.Fetch(reader).GetNumberOfPoints(), 0)


if __name__ == "__main__":
    harness.run(__name__)
