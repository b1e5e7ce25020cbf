"""Loads the plugin and a state of Examples/states with the bundled data, in pvpython or the GUI.

    pvpython Examples/states/open_state.py [STATE.pvsm] [OUT.png]
    paraview --script=Examples/states/open_state.py          # TSYNTH_STATE=... for another state

(run from the repository's root: the GUI does not tell the script where it is).

The state names its data files relative to the repository (Data/dems/colorado.png); ParaView's
LoadState(..., data_directory=<repo>/Data) finds them under the repository's Data folder
wherever it is. Without arguments the synthesis state is opened; with OUT.png pvpython saves
a picture of the view. The plugin is looked up in ./build (TSYNTH_PLUGIN=/path/to/
TerrainSynthesis.so overrides).
"""
import os
import sys

from paraview import simple

try:
    STATES = os.path.dirname(os.path.abspath(__file__))
except NameError:  # the GUI's --script runs the text without a file name: start it in the repository
    STATES = os.path.join(os.getcwd(), "Examples", "states")
ROOT = os.path.dirname(os.path.dirname(STATES))
PLUGIN = os.environ.get(
    "TSYNTH_PLUGIN",
    os.path.join(ROOT, "build", "lib", "paraview-plugins", "TerrainSynthesis", "TerrainSynthesis.so"))
args = [a for a in getattr(sys, "argv", [])[1:] if a]  # the GUI's --script passes none
state = args[0] if args else os.environ.get("TSYNTH_STATE", os.path.join(STATES, "synthesis.pvsm"))

sys.path.insert(0, STATES)
import state_files  # noqa: E402

simple.LoadPlugin(PLUGIN, remote=False)
simple.LoadState(state, data_directory=os.path.join(ROOT, "Data"), restrict_to_data_directory=True)
simple._DisableFirstRenderCameraReset()  # the state's viewing direction, fitted below
view = simple.GetActiveView() or simple.GetRenderViews()[0]
simple.SetActiveView(view)
state_files.fit_camera_to_view(view)  # the pieces fill the window, whatever its size
if len(args) > 1:
    simple.SaveScreenshot(args[1], view, ImageResolution=list(view.ViewSize))
    print("Wrote", args[1])
