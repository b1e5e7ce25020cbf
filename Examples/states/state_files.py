"""Shared by the make_*_state.py scripts and open_state.py: where things are, saving a state
without machine-specific paths, and fitting a loaded state's camera to the window it is shown in.

A state written by ParaView holds absolute file names. save_portable_state() writes them
relative to the repository ("Data/dems/colorado.png"), so the state names the bundled data
the same way on every machine; loading it with a data directory finds the files again:

    simple.LoadState("synthesis.pvsm", data_directory="<repo>/Data")
"""
import os

from paraview import simple

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "Data")
STATES = os.path.join(ROOT, "Examples", "states")
PLUGIN = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(ROOT, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))


def data_file(*parts):
    """The absolute name of a bundled data file, e.g. data_file("dems", "colorado.png")."""
    return os.path.join(DATA, *parts)


def save_portable_state(path):
    """Saves the current state to path with the repository's own prefix removed from file names.

    Fails if a machine-specific path (the repository root) is left in the written state."""
    simple.SaveState(path)
    with open(path) as f:
        text = f.read()
    text = text.replace(ROOT + os.sep, "")
    if ROOT in text:
        raise RuntimeError("the state %s still names %s; save it from a pipeline on the bundled data"
                           % (path, ROOT))
    with open(path, "w") as f:
        f.write(text)
    print("Wrote", path)


def grey_hillshade_view(shade, size):
    """A white render view of size (width, height) pixels showing the Terrain Hillshade `shade`
    in grey, lit flat (the hillshade is the light), with no orientation axes."""
    view = simple.GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    shaded = simple.Show(shade, view)
    simple.ColorBy(shaded, ("POINTS", "Hillshade"))
    shaded.Ambient = 1.0
    shaded.Diffuse = 0.0
    grey = simple.GetColorTransferFunction("Hillshade")
    grey.ApplyPreset("Grayscale", True)
    grey.RescaleTransferFunction(0.0, 1.0)
    grey.AutomaticRescaleRangeMode = "Never"
    return view


def show_in_colour(source, view, colour, lift_m):
    """Shows `source` in one flat colour, lifted lift_m metres above the map it marks."""
    drawn = simple.Show(source, view)
    simple.ColorBy(drawn, None)
    drawn.AmbientColor = drawn.DiffuseColor = colour
    drawn.Ambient = 1.0
    drawn.Diffuse = 0.0
    drawn.Position = [0.0, 0.0, lift_m]


def look_from_above(view):
    """A map view: parallel projection, the whole scene in view, rendered."""
    view.CameraParallelProjection = 1
    simple.ResetCamera(view)
    simple.Render(view)


# The share of the view's limiting side (height in a wide window, width in a tall one) the pieces
# span once fitted: a thin margin around them.
FIT_SHARE = 0.92
# Under perspective one pan and dolly lands near the fit, not on it; three passes settle it
# within a few pixels.
FIT_PASSES = 3


def _display_box(renderer, corners):
    """(x0, y0, x1, y1): the display-coordinate box around the projected world points."""
    xs, ys = [], []
    for corner in corners:
        renderer.SetWorldPoint(*corner, 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        xs.append(x)
        ys.append(y)
    return min(xs), min(ys), max(xs), max(ys)


def _display_to_world(renderer, x, y, depth):
    renderer.SetDisplayPoint(x, y, depth)
    renderer.DisplayToWorld()
    w = renderer.GetWorldPoint()
    return [w[i] / w[3] for i in range(3)]


def fit_camera_to_view(view):
    """Keeps the state's viewing direction and brings its pieces to fill the view at its current
    size: the state's camera was set for its 500 x 500 picture, and in a larger or wider window
    (ParaView keeps the vertical view angle) the pieces sat small in the middle. The pieces are
    fitted by their base (the lowest height of what is shown): the warped terrain's relief rises
    from it without adding an empty band above everything."""
    simple.Render(view)  # the renderer at the view's size
    renderer = view.GetRenderer()
    b = renderer.ComputeVisiblePropBounds()
    if b[0] > b[1]:
        return  # nothing shown
    corners = [(x, y, b[4]) for x in b[0:2] for y in b[2:4]]
    camera = view.GetActiveCamera()
    width, height = renderer.GetSize()
    for _ in range(FIT_PASSES):
        x0, y0, x1, y1 = _display_box(renderer, corners)
        renderer.SetWorldPoint(*camera.GetFocalPoint(), 1.0)
        renderer.WorldToDisplay()
        depth = renderer.GetDisplayPoint()[2]
        here = _display_to_world(renderer, 0.5 * (x0 + x1), 0.5 * (y0 + y1), depth)
        centre = _display_to_world(renderer, 0.5 * width, 0.5 * height, depth)
        shift = [h - c for h, c in zip(here, centre)]
        camera.SetFocalPoint(*[f + d for f, d in zip(camera.GetFocalPoint(), shift)])
        camera.SetPosition(*[p + d for p, d in zip(camera.GetPosition(), shift)])
        camera.Dolly(FIT_SHARE * min(width / (x1 - x0), height / (y1 - y0)))
        renderer.ResetCameraClippingRange()
    view.SMProxy.SynchronizeCameraProperties()
    simple.Render(view)
