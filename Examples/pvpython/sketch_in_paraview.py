"""Sketch ridges and valleys with ParaView's Poly Line source and synthesise a terrain from them.

    xvfb-run -a pvpython Examples/pvpython/sketch_in_paraview.py [EXEMPLAR] [OUT.png]

What a user does in the GUI, scripted: Sources > Poly Line twice (a ridge and a valley, drawn in
metres over the exemplar opened with the Terrain Reader), Terrain Sketch Lines on each (Ridge with
its crest at 3900 m from the points' z, Valley with no height), Append Geometry, and Terrain
Synthesis with the appended lines as its Sketch. The picture shows the terrain, shaded, with
the ridge (red) and the valley (blue) drawn over its heights (yellow high, blue low). The plugin is looked up in ./build
(override with TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so).
"""
import os
import sys

from paraview import servermanager as sm
from paraview import simple

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
plugin = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(root, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
exemplar_dem = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "Data", "dems", "colorado.png")
out = sys.argv[2] if len(sys.argv) > 2 else "sketch_in_paraview.png"

SIZE = 320  # output cells a side
CELL = 90.0  # metres, Colorado's cells

simple.LoadPlugin(plugin, remote=False)
exemplar = simple.TerrainReader(FileName=exemplar_dem)

# A ridge from the south-west to the north-east, its crest at 3900 m (z), and a valley beside
# it that runs out through the north border; positions in metres in the output's raster frame.
ridge_points = [40 * CELL, 40 * CELL, 3900.0, 150 * CELL, 140 * CELL, 3900.0, 280 * CELL, 230 * CELL, 3900.0]
valley_points = [20 * CELL, 130 * CELL, 0.0, 100 * CELL, 220 * CELL, 0.0, 150 * CELL, 319 * CELL, 0.0]
ridge_line = simple.PolyLineSource(Points=ridge_points)
valley_line = simple.PolyLineSource(Points=valley_points)
ridge = simple.TerrainSketchLines(Input=ridge_line, FeatureType="Ridge", ElevationMode="From Z")
valley = simple.TerrainSketchLines(Input=valley_line, FeatureType="Valley")
sketch = simple.AppendGeometry(Input=[ridge, valley])
terrain = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[SIZE, SIZE],
                                  Backend="CPU", Seed=0)
shade = simple.TerrainHillshade(Input=terrain, ZFactor=2.0)

view = simple.CreateView("RenderView")
view.ViewSize = [900, 900]
view.OrientationAxesVisibility = 0
# Heights in colour, shaded: the terrain's elevation over its hillshade (drawn as a
# translucent grey layer on top).
coloured = simple.Show(terrain, view)
simple.ColorBy(coloured, ("POINTS", "Elevation"))
simple.GetColorTransferFunction("Elevation").ApplyPreset("Viridis (matplotlib)", True)
coloured.Ambient = 1.0
coloured.Diffuse = 0.0
shaded = simple.Show(shade, view)
simple.ColorBy(shaded, ("POINTS", "Hillshade"))
shaded.Ambient = 1.0
shaded.Diffuse = 0.0
shaded.Opacity = 0.5
shaded.Position = [0.0, 0.0, 1.0]
lut = simple.GetColorTransferFunction("Hillshade")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 1.0)
for line, colour in ((ridge, [0.9, 0.1, 0.1]), (valley, [0.1, 0.35, 0.9])):
    drawn = simple.Show(line, view)
    drawn.ColorArrayName = ['POINTS', '']
    drawn.AmbientColor = drawn.DiffuseColor = colour
    drawn.LineWidth = 3.0
    drawn.Position = [0.0, 0.0, 10000.0]  # above the shaded plane (the ridge's z is laid flat)
simple.ResetCamera(view)
view.CameraParallelProjection = 1
view.ResetCamera(True)
simple.SaveScreenshot(out, view, ImageResolution=[900, 900])
data = sm.Fetch(terrain, arg1=None, arg2=None, idx=0)
nx, ny, _ = data.GetDimensions()
print("Synthesised %d x %d cells from two drawn lines; wrote %s" % (nx, ny, out))
