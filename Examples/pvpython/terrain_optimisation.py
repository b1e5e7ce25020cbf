"""Terrain optimisation (Scott & Dodgson 2021) from a source DEM and a stroke sketch, in pvpython.

    xvfb-run -a pvpython Examples/pvpython/terrain_optimisation.py [SOURCE] [GUIDE] [OUT.png]

Pipeline: Terrain Reader (the source) and a PNG reader (the guide: here the bundled valley-tree
stroke map) -> Terrain Optimisation (breaching on the coarse levels) -> Terrain Hillshade. The
plugin is looked up in ./build (override with TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so).
"""
import os
import sys

from paraview import servermanager as sm
from paraview import simple

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
plugin = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(root, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
source_dem = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "Data", "dems", "colorado.png")
guide_image = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
    root, "Data", "sketches", "strokes_valley_tree.png")
out = sys.argv[3] if len(sys.argv) > 3 else "terrain_optimisation.png"

simple.LoadPlugin(plugin, remote=False)
source = simple.TerrainReader(FileName=source_dem)
guide = simple.PNGSeriesReader(FileNames=[guide_image])
terrain = simple.TerrainOptimisation(Source=source, Guide=guide, PitRemoval="Breach", Seed=0)
shade = simple.TerrainHillshade(Input=terrain)

view = simple.CreateView("RenderView")
view.ViewSize = [900, 900]
view.OrientationAxesVisibility = 0
shaded = simple.Show(shade, view)
simple.ColorBy(shaded, ("POINTS", "Hillshade"))
shaded.Ambient = 1.0
shaded.Diffuse = 0.0
lut = simple.GetColorTransferFunction("Hillshade")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 1.0)
simple.ResetCamera(view)
view.CameraParallelProjection = 1
view.ResetCamera(True)
simple.SaveScreenshot(out, view, ImageResolution=[900, 900])
nx, ny, _ = sm.Fetch(terrain).GetDimensions()
print("Optimised %d x %d cells; wrote %s" % (nx, ny, out))
