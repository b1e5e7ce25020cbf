"""Writes Examples/states/synthesis.pvsm: the whole synthesis on the bundled data, ready to look at.

    pvpython Examples/states/make_synthesis_state.py [OUT.pvsm]

(TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so if the plugin is not in ./build.) The state shows,
in one 3D view, at the back (north) the exemplar (Data/dems/colorado.png through the Terrain
Reader, coloured by Elevation) with its ridge and valley trees on top (Terrain Feature
Extractor, coloured by NodeKind: 0 path grey, 1 end red, 2 branch yellow); the stroke sketch
(Data/sketches/strokes_y_ridges.png in its own colours, scaled to the terrain's size); and the
synthesised terrain (Terrain Synthesis, default properties except OutputSize 256 x 256 and
Backend CPU, so it runs in seconds and gives the same terrain everywhere) warped by its
Elevation at true scale (spacing and heights are both metres) with the seams between its patches
(the synthesis's Seams output, lines warped by their Elevation likewise) drawn over it in magenta.

Open it (file names in the state are relative to the repository; the plugin must be loaded first):

    pvpython Examples/states/open_state.py Examples/states/synthesis.pvsm      # checks and prints
    paraview --script=Examples/states/open_state.py                            # the GUI

or, in the GUI: Tools > Manage Plugins > Load New (build/lib/paraview-plugins/TerrainSynthesis/
TerrainSynthesis.so), then File > Load State, pick synthesis.pvsm, "Search files under specified
directory" and the repository's Data folder. See Examples/states/README.md.
"""
import os
import sys

from paraview import servermanager as sm
from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import state_files  # noqa: E402

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(state_files.STATES, "synthesis.pvsm")

TERRAIN_CELLS = [256, 256]  # small enough to synthesise in a few seconds
CPU = 2  # Backend enumeration: 0 Auto, 1 OpenCL, 2 CPU
SEAMS_PORT = 3  # the synthesis's outputs: Terrain, Placements, Sketch Features, Seams, ...
GAP_M = 5000.0  # between the pieces laid out side by side
SEAM_LIFT_M = 15.0  # seams drawn just above the surface they lie on
FEATURE_LIFT_M = 10.0  # feature trees just above the flat exemplar
VIEW_SIZE = [500, 500]  # the standard view; its baseline picture is about 210 KB
MAGENTA = [0.85, 0.0, 0.85]
NODE_KIND_COLOURS = [0, 0.35, 0.35, 0.35,  # path
                     1, 0.9, 0.1, 0.1,  # end
                     2, 1.0, 0.85, 0.0]  # branch


def build_pipeline():
    exemplar = simple.TerrainReader(registrationName="Exemplar",
                                    FileName=state_files.data_file("dems", "colorado.png"))
    sketch = simple.PNGSeriesReader(registrationName="Sketch",
                                    FileNames=[state_files.data_file("sketches", "strokes_y_ridges.png")])
    trees = simple.TerrainFeatureExtractor(registrationName="FeatureTrees", Input=exemplar,
                                           Features=2)  # ridges and valleys
    synth = simple.TerrainSynthesis(registrationName="Synthesis", Exemplars=[exemplar], Sketch=sketch,
                                    OutputSize=TERRAIN_CELLS, Backend=CPU)
    warped = simple.WarpByScalar(registrationName="Warped", Input=synth,
                                 Scalars=["POINTS", "Elevation"], ScaleFactor=1.0)
    seams = simple.WarpByScalar(registrationName="Seams", Input=simple.OutputPort(synth, SEAMS_PORT),
                                Scalars=["POINTS", "Elevation"], ScaleFactor=1.0)
    return exemplar, sketch, trees, synth, warped, seams


def show_all(view, exemplar, sketch, trees, synth, warped, seams):
    exemplar.UpdatePipeline()
    synth.UpdatePipeline()
    sketch.UpdatePipeline()
    dem = sm.Fetch(exemplar)
    width = (dem.GetDimensions()[0] - 1) * dem.GetSpacing()[0]
    z_range = dem.GetPointData().GetArray("Elevation").GetRange()
    terrain = sm.Fetch(synth, arg1=None, arg2=None, idx=0)
    terrain_width = (terrain.GetDimensions()[0] - 1) * terrain.GetSpacing()[0]
    sketch_cells = sm.Fetch(sketch).GetDimensions()[0] - 1

    heights = simple.GetColorTransferFunction("Elevation")
    heights.ApplyPreset("Viridis (matplotlib)", True)
    heights.RescaleTransferFunction(z_range[0], z_range[1])
    heights.AutomaticRescaleRangeMode = "Never"

    shown = simple.Show(exemplar, view)
    simple.ColorBy(shown, ("POINTS", "Elevation"))

    lines = simple.Show(trees, view)
    simple.ColorBy(lines, ("POINTS", "NodeKind"))
    kinds = simple.GetColorTransferFunction("NodeKind")
    kinds.InterpretValuesAsCategories = 1
    kinds.Annotations = ["0", "path", "1", "end", "2", "branch"]
    kinds.IndexedColors = [c for k in range(3) for c in NODE_KIND_COLOURS[4 * k + 1:4 * k + 4]]
    lines.LineWidth = 2.0
    lines.PointSize = 3.0
    back = terrain_width + GAP_M  # the exemplar sits behind the sketch and the terrain
    shown.Position = [0.0, back, 0.0]
    lines.Position = [0.0, back, FEATURE_LIFT_M]

    drawn = simple.Show(sketch, view)
    simple.ColorBy(drawn, ("POINTS", "PNGImage"))
    drawn.MapScalars = 0  # the stroke colours themselves
    scale = terrain_width / sketch_cells
    drawn.Scale = [scale, scale, 1.0]
    drawn.Position = [0.0, 0.0, 0.0]

    surface = simple.Show(warped, view)
    simple.ColorBy(surface, ("POINTS", "Elevation"))
    offset = [terrain_width + GAP_M, 0.0, 0.0]
    surface.Position = offset
    lines_on_top = simple.Show(seams, view)
    lines_on_top.ColorArrayName = ["POINTS", ""]  # one colour
    lines_on_top.AmbientColor = lines_on_top.DiffuseColor = MAGENTA
    lines_on_top.LineWidth = 2.0
    lines_on_top.Position = [offset[0], offset[1], SEAM_LIFT_M]
    simple.Hide(synth, view)
    return [max(width, 2.0 * terrain_width + GAP_M), back + width], z_range


# The camera's distance from the pieces' centre, in their north-south extent: back to the south
# and up. Close enough that the pieces fill the height of the view with a small margin (ParaView's
# GUI keeps the vertical view angle, so a wider window adds room at the sides only; open_state.py
# fits the camera to the window it opens in, keeping this direction).
CAMERA_BACK = 1.25
CAMERA_UP = 0.95


def set_camera(view, extent, z_range):
    """A fixed oblique camera from the south, looking north over the pieces."""
    centre = [0.5 * extent[0], 0.4 * extent[1], 0.5 * (z_range[0] + z_range[1])]
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - CAMERA_BACK * extent[1],
                           centre[2] + CAMERA_UP * extent[1]]
    view.CameraViewUp = [0.0, 0.63, 0.78]
    view.CameraViewAngle = 30.0
    view.CameraParallelProjection = 0


def main():
    simple.LoadPlugin(state_files.PLUGIN, remote=False)
    pieces = build_pipeline()
    view = simple.GetActiveViewOrCreate("RenderView")
    view.ViewSize = VIEW_SIZE
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    extent, z_range = show_all(view, *pieces)
    simple.Render(view)  # the first render resets the camera: set ours after it
    set_camera(view, extent, z_range)
    simple.Render(view)
    state_files.save_portable_state(OUT)


if __name__ == "__main__":
    main()
