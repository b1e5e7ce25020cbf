"""ParaView macro "NewTerrainSketch": a sketch to draw on, and the terrain synthesised from it,
in one click.

Select an exemplar DEM in the Pipeline Browser (opened with the Terrain Reader), then run this
macro (Macros > NewTerrainSketch; add it once with Macros > Import new macro..., picking this
file). It makes:

- "Ridge line": a Poly Line across the middle third of the exemplar, from west to east, whose
  points you drag in the 3D view (or type in the panel; add points with the + button);
- "Ridge": Terrain Sketch Lines marking it as a ridge (switch Feature Type to Valley for a
  valley; copy the pair for more strokes and combine them with Append Geometry);
- "Terrain": Terrain Synthesis from the exemplar and the ridge, as large as the exemplar,
  shown as a grey hillshade ("Terrain hillshade") with its Sketch Features (its Seams output is
  there to switch on).

Change a point and press Apply (or switch on Auto Apply, the toolbar button next to Apply's
settings): the terrain follows the line. It shows a quick preview at once (Preview First: cells 4
times coarser, a fraction of a second) and the whole synthesis replaces it when it is done; a
further change stops that and starts again from a preview. The same steps by hand are in the
README ("Sketching in ParaView").
"""
from paraview import simple

# The stroke starts a third of the way across and ends two thirds across, on the middle row:
# long enough to read in the terrain, clear of the borders.
STROKE_START = 1.0 / 3.0
STROKE_END = 2.0 / 3.0
STROKE_POINTS = 5  # a few points to drag into a curve


def plugin_filter(name):
    """The plugin's filter `name` as a paraview.simple function: ParaView's GUI adds a plugin's
    filters to paraview.simple only when it imports it, and a plugin may be loaded later."""
    if not hasattr(simple, name):
        simple._add_functions(vars(simple))  # pylint: disable=protected-access
    if not hasattr(simple, name):
        raise RuntimeError("NewTerrainSketch: load the TerrainSynthesis plugin first (Tools > "
                           "Manage Plugins > Load New, TerrainSynthesis.so).")
    return getattr(simple, name)


def exemplar_grid(exemplar):
    """The exemplar's extent in metres and its size in cells; one sentence if it is not a DEM."""
    info = exemplar.GetDataInformation()
    if info.GetDataSetTypeAsString() != "vtkImageData" or "Elevation" not in exemplar.PointData.keys():
        raise RuntimeError("NewTerrainSketch: select an exemplar DEM opened with the Terrain Reader "
                           "(an image with Elevation) in the Pipeline Browser first.")
    extent = info.GetExtent()
    return info.GetBounds(), [extent[1] - extent[0] + 1, extent[3] - extent[2] + 1]


def new_terrain_sketch(exemplar):
    """The poly-line, its Sketch Lines and the synthesis from `exemplar`; returns all three."""
    exemplar.UpdatePipeline()
    bounds, cells = exemplar_grid(exemplar)
    x0 = bounds[0] + STROKE_START * (bounds[1] - bounds[0])
    x1 = bounds[0] + STROKE_END * (bounds[1] - bounds[0])
    y = 0.5 * (bounds[2] + bounds[3])
    points = []
    for k in range(STROKE_POINTS):
        points += [x0 + (x1 - x0) * k / (STROKE_POINTS - 1), y, 0.0]
    line = simple.PolyLineSource(registrationName="Ridge line", Points=points)
    ridge = plugin_filter("TerrainSketchLines")(registrationName="Ridge", Input=line, FeatureType="Ridge")
    terrain = plugin_filter("TerrainSynthesis")(registrationName="Terrain", Exemplars=[exemplar],
                                                Sketch=ridge, OutputSize=cells, PreviewFirst=1)
    return line, ridge, terrain


def show(exemplar, line, ridge, terrain):
    view = simple.GetActiveViewOrCreate("RenderView")
    simple.Hide(exemplar, view)
    # The terrain as a grey hillshade: relief reads at a glance in the flat 2D view.
    shade = plugin_filter("TerrainHillshade")(registrationName="Terrain hillshade", Input=terrain)
    shown = simple.Show(shade, view)
    simple.ColorBy(shown, ("POINTS", "Hillshade"))
    # The lines are drawn 3 pixels wide by the plugin's default (Plugin/TerrainLineWidths.xml),
    # or as wide as the user's saved LineWidth setting.
    simple.Show(simple.OutputPort(terrain, 2), view)
    seams = simple.Show(simple.OutputPort(terrain, 3), view)
    seams.AmbientColor = seams.DiffuseColor = [0.85, 0.0, 0.85]
    seams.ColorArrayName = ["POINTS", ""]
    simple.Hide(simple.OutputPort(terrain, 3), view)  # on the Eye in the Pipeline Browser
    simple.Show(ridge, view)
    simple.SetActiveSource(line)  # its points are the ones to drag
    view.InteractionMode = "2D"
    simple.ResetCamera(view)
    simple.Render(view)


def main():
    exemplar = simple.GetActiveSource()
    if exemplar is None:
        raise RuntimeError("NewTerrainSketch: select an exemplar DEM opened with the Terrain Reader "
                           "in the Pipeline Browser first.")
    pieces = new_terrain_sketch(exemplar)
    show(exemplar, *pieces)


if __name__ == "__main__" or __name__ == "__vtkconsole__":
    main()
