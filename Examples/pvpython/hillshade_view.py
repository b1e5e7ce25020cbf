"""Load the TerrainSynthesis plugin in pvpython, read a DEM, shade it and save a picture.

    xvfb-run -a pvpython Examples/pvpython/hillshade_view.py [DEM] [OUT.png]

The plugin is looked up in ./build (override with TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so).
"""
import os
import sys

from paraview import simple

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
plugin = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(root, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
dem = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "Data", "dems", "alps-montblanc.png")
out = sys.argv[2] if len(sys.argv) > 2 else "hillshade_view.png"

simple.LoadPlugin(plugin, remote=False)
reader = simple.TerrainReader(FileName=dem)
shade = simple.TerrainHillshade(Input=reader, ZFactor=1.5)

view = simple.CreateView("RenderView")
view.ViewSize = [900, 900]
view.OrientationAxesVisibility = 0
display = simple.Show(shade, view)
simple.ColorBy(display, ("POINTS", "Hillshade"))
display.Ambient = 1.0  # show the hillshade itself, not a second lighting on top
display.Diffuse = 0.0
lut = simple.GetColorTransferFunction("Hillshade")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 1.0)
simple.ResetCamera(view)
view.CameraParallelProjection = 1
view.ResetCamera(True)
simple.SaveScreenshot(out, view, ImageResolution=[900, 900])
print("Wrote", out)
