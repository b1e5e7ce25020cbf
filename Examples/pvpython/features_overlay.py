"""Overlay PPA ridge and valley trees on a shaded DEM in pvpython and save a picture.

    xvfb-run -a pvpython Examples/pvpython/features_overlay.py [DEM] [OUT.png]

Ridges are drawn red, valleys blue; branch nodes are the yellow dots.
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
out = sys.argv[2] if len(sys.argv) > 2 else "features_overlay.png"

simple.LoadPlugin(plugin, remote=False)
reader = simple.TerrainReader(FileName=dem)
shade = simple.TerrainHillshade(Input=reader)
features = simple.TerrainFeatureExtractor(Input=reader, Features=2)  # ridges and valleys
view = simple.CreateView("RenderView")
# Nodes are vertex cells too: keep the cells whose points all have NodeKind 2.
branches = simple.Threshold(Input=features, Scalars=["POINTS", "NodeKind"])
branches.LowerThreshold = 2
branches.UpperThreshold = 2

view.ViewSize = [1000, 1000]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]

ground = simple.Show(shade, view)
simple.ColorBy(ground, ("POINTS", "Hillshade"))
grey = simple.GetColorTransferFunction("Hillshade")
grey.ApplyPreset("Grayscale", True)
grey.RescaleTransferFunction(-0.3, 1.0)  # keep shadows mid-grey under the lines
ground.Ambient = 1.0
ground.Diffuse = 0.0

lines = simple.Show(features, view)
simple.ColorBy(lines, ("CELLS", "FeatureType"))
types = simple.GetColorTransferFunction("FeatureType")
types.RGBPoints = [-1.0, 0.1, 0.3, 1.0, 1.0, 0.9, 0.1, 0.1]
types.RescaleTransferFunction(-1.0, 1.0)
lines.LineWidth = 2.0
lines.Position = [0, 0, 1.0]  # just above the ground

dots = simple.Show(branches, view)
dots.SetRepresentationType("Points")
dots.PointSize = 7.0
simple.ColorBy(dots, None)
dots.AmbientColor = dots.DiffuseColor = [1.0, 0.85, 0.0]
dots.Ambient = 1.0
dots.Diffuse = 0.0
dots.Position = [0, 0, 2.0]

view.CameraParallelProjection = 1
simple.ResetCamera(view)
view.ResetCamera(True)
simple.SaveScreenshot(out, view, ImageResolution=[1000, 1000])
print("Wrote", out)
