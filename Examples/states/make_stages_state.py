"""Writes Examples/states/stages.pvsm: the synthesis assembled from its stage filters.

    pvpython Examples/states/make_stages_state.py [OUT.pvsm]

(TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so if the plugin is not in ./build.) Pipeline:

    Terrain Reader (Exemplar: Data/dems/colorado.png)
      -> Terrain Candidate Builder (Candidates: the exemplar's feature candidate pool, a table,
         its ridges and valleys found as the synthesis finds them)
    PNG reader (Sketch: Data/sketches/strokes_y_ridges.png)
    Terrain Synthesis (Synthesis: Exemplars, Sketch, and Candidate Pool the builder's table; every
      other property its default) -> Terrain Hillshade (grey), seen from above.

The Terrain Synthesis owns the placement loop (feature patches breadth-first along the sketch's
lines, then the best-first fill) and matches its feature patches from the builder's pool; each
placement calls the kernels the Terrain Patch Matcher, Terrain Patch Extractor and Terrain
Graph-Cut Merger call (see patch_stages.pvsm for one placement done by those filters). The
heights are those of `tsynth synth --exemplar Data/dems/colorado.png --sketch
Data/sketches/strokes_y_ridges.png`, bit for bit (python.states checks it).

Open it like the other states (the plugin first, then the state with the Data folder):

    pvpython Examples/states/open_state.py Examples/states/stages.pvsm
    TSYNTH_STATE=Examples/states/stages.pvsm paraview --script=Examples/states/open_state.py

See Examples/states/README.md.
"""
import os
import sys

from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import state_files  # noqa: E402

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(state_files.STATES, "stages.pvsm")
VIEW_SIZE = [600, 600]


def main():
    simple.LoadPlugin(state_files.PLUGIN, remote=False)
    exemplar = simple.TerrainReader(registrationName="Exemplar",
                                    FileName=state_files.data_file("dems", "colorado.png"))
    candidates = simple.TerrainCandidateBuilder(registrationName="Candidates", Input=[exemplar])
    sketch = simple.PNGSeriesReader(registrationName="Sketch",
                                    FileNames=[state_files.data_file("sketches", "strokes_y_ridges.png")])
    synth = simple.TerrainSynthesis(registrationName="Synthesis", Exemplars=[exemplar], Sketch=sketch,
                                    CandidatePool=candidates)
    shade = simple.TerrainHillshade(registrationName="Hillshade", Input=synth)

    view = state_files.grey_hillshade_view(shade, VIEW_SIZE)
    state_files.look_from_above(view)
    state_files.save_portable_state(OUT)


if __name__ == "__main__":
    main()
