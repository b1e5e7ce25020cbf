"""Writes Examples/states/pit_removal.pvsm: pit removal and the stream network of the bundled DEM.

    pvpython Examples/states/make_pit_removal_state.py [OUT.pvsm]

(TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so if the plugin is not in ./build.) Pipeline: Terrain
Reader (Data/dems/colorado.png) -> Terrain Pit Removal (breach; Streams where at least 1 km^2
drains) -> Terrain Hillshade, seen from above in grey with the stream cells (a Threshold on
Streams) in blue on top, as Examples/pvpython/pit_removal_streams.py draws it.

Open it like the synthesis state (the plugin first, then the state with the Data folder):

    pvpython Examples/states/open_state.py Examples/states/pit_removal.pvsm
    TSYNTH_STATE=Examples/states/pit_removal.pvsm paraview --script=Examples/states/open_state.py

See Examples/states/README.md.
"""
import math
import os
import sys

from paraview import servermanager as sm
from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import state_files  # noqa: E402

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(state_files.STATES, "pit_removal.pvsm")

STREAM_AREA_M2 = 1.0e6  # channels begin where about 1 km^2 drains
STREAM_LIFT_M = 1.0  # streams drawn just above the shaded surface
VIEW_SIZE = [600, 600]
BLUE = [0.1, 0.35, 0.9]


def main():
    simple.LoadPlugin(state_files.PLUGIN, remote=False)
    dem = simple.TerrainReader(registrationName="DEM", FileName=state_files.data_file("dems", "colorado.png"))
    dem.UpdatePipeline()
    cell = sm.Fetch(dem).GetSpacing()
    threshold = int(math.ceil(STREAM_AREA_M2 / (cell[0] * cell[1])))
    pits = simple.TerrainPitRemoval(registrationName="PitRemoval", Input=dem, Method="Breach",
                                    StreamThreshold=threshold)
    shade = simple.TerrainHillshade(registrationName="Hillshade", Input=pits)
    # A cell is drawn if any of its corners is a stream cell (a stream is one cell wide).
    streams = simple.Threshold(registrationName="Streams", Input=pits, Scalars=["POINTS", "Streams"],
                               LowerThreshold=1, UpperThreshold=1, AllScalars=0)

    view = state_files.grey_hillshade_view(shade, VIEW_SIZE)
    state_files.show_in_colour(streams, view, BLUE, STREAM_LIFT_M)
    state_files.look_from_above(view)
    print("Streams from %d cells of accumulation" % threshold)
    state_files.save_portable_state(OUT)


if __name__ == "__main__":
    main()
