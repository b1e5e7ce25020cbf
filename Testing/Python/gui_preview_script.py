"""Run inside ParaView's GUI (paraview --script=...) by test_gui_preview.py: a Terrain Synthesis
with Preview First on, shown in a render view, then left to ParaView's event loop. A repeating
timer of the view's interactor (the GUI's own main thread) records what the filter's output holds
every 0.2 s, with nothing else asking for an update: the whole synthesis can only replace the
preview through ParaView's live-source poll of GetNeedsUpdate. The record goes to the JSON file
named by TSYNTH_GUI_PREVIEW_LOG; ParaView is then closed."""
import json
import os
import sys
import time

from paraview import servermanager, simple

sys.path.insert(0, os.environ["TSYNTH_PYTHON_DIR"])
simple.LoadPlugin(os.environ["TSYNTH_PLUGIN"], remote=False)
import terrainsynthesis  # noqa: E402,F401  (the filter's own methods)

GIVE_UP_AFTER_S = 120.0
data = os.environ["TSYNTH_BUNDLED_DATA"]
exemplar = simple.TerrainReader(FileName=os.path.join(data, "dems", "colorado.png"))
sketch = simple.PNGSeriesReader(FileNames=[os.path.join(data, "sketches", "strokes_y_ridges.png")])
terrain = simple.TerrainSynthesis(Exemplars=[exemplar], Sketch=sketch, OutputSize=[384, 384],
                                  PreviewFirst=1, UseExemplarCache=0)
view = simple.GetActiveViewOrCreate("RenderView")
simple.Show(terrain, view)
simple.Render(view)
synthesis = terrain.GetClientSideObject()
record = {"levels": [synthesis.GetOutputLevel()], "seconds": [0.0]}
start = time.monotonic()


def finish():
    shown = servermanager.Fetch(terrain)
    record["points"] = shown.GetNumberOfPoints()
    record["has_patch_ids"] = shown.GetPointData().GetArray("PatchId") is not None
    with open(os.environ["TSYNTH_GUI_PREVIEW_LOG"], "w") as f:
        json.dump(record, f)
    os._exit(0)


def tick(_caller, _event):
    record["levels"].append(synthesis.GetOutputLevel())
    record["seconds"].append(time.monotonic() - start)
    if record["levels"][-1] == "final" or record["seconds"][-1] > GIVE_UP_AFTER_S:
        finish()


interactor = view.GetInteractor()
interactor.AddObserver("TimerEvent", tick)
interactor.CreateRepeatingTimer(200)
