"""Remove the pits of a DEM by breaching, then show its stream network over the hillshade.

    xvfb-run -a pvpython Examples/pvpython/pit_removal_streams.py [DEM] [OUT.png]

Pipeline: Terrain Reader -> Terrain Pit Removal (breach; "Streams" where at least 1 km^2
drains) -> Terrain Hillshade, with the stream cells drawn in blue on top. The plugin is looked
up in ./build (override with TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so).
"""
import math
import os
import sys

from paraview import servermanager as sm
from paraview import simple

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
plugin = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(root, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
dem = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "Data", "dems", "colorado.png")
out = sys.argv[2] if len(sys.argv) > 2 else "pit_removal_streams.png"

STREAM_AREA_M2 = 1.0e6  # channels begin where about 1 km^2 drains

simple.LoadPlugin(plugin, remote=False)
reader = simple.TerrainReader(FileName=dem)
reader.UpdatePipeline()
cell = sm.Fetch(reader).GetSpacing()
threshold = int(math.ceil(STREAM_AREA_M2 / (cell[0] * cell[1])))
pits = simple.TerrainPitRemoval(Input=reader, Method="Breach", StreamThreshold=threshold)
shade = simple.TerrainHillshade(Input=pits)
# A cell is drawn if any of its corners is a stream cell (a stream is one cell wide).
streams = simple.Threshold(Input=pits, Scalars=["POINTS", "Streams"], LowerThreshold=1,
                           UpperThreshold=1, AllScalars=0)

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
drawn = simple.Show(streams, view)
simple.ColorBy(drawn, None)
drawn.AmbientColor = drawn.DiffuseColor = [0.1, 0.35, 0.9]
drawn.Ambient = 1.0
drawn.Diffuse = 0.0
drawn.Position = [0.0, 0.0, 1.0]  # above the shaded surface
simple.ResetCamera(view)
view.CameraParallelProjection = 1
view.ResetCamera(True)
simple.SaveScreenshot(out, view, ImageResolution=[900, 900])
print("Streams from %d cells of accumulation; wrote %s" % (threshold, out))
