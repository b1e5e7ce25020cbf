"""Writes Examples/states/patch_stages.pvsm: one patch placed by the stage filters, chained.

    pvpython Examples/states/make_patch_stages_state.py [OUT.pvsm]

(TSYNTH_PLUGIN=/path/to/TerrainSynthesis.so if the plugin is not in ./build.) The synthesis'
stages one after the other, each a filter whose output can be looked at, on the bundled DEM
(Data/dems/colorado.png) as both exemplar and target:

    Terrain Reader (Exemplar) -> Terrain Feature Extractor (FeatureTrees: ridges and valleys)
      -> Terrain Candidate Builder (Candidates: the pool, a table)
      -> Terrain Patch Matcher (Matcher: the best candidates for the ridge branch nearest the
         DEM's centre; its Candidate Pool is the builder's table)
      -> Terrain Patch Extractor (Patch: the second-best match cut from the exemplar, shifted to
         the terrain's level, with its core)
      -> Terrain Graph-Cut Merger (Merged: the patch merged into the DEM along the cheapest seam)
      -> Terrain Hillshade (grey), with the seam (a Threshold on SeamMask) in magenta.

The best match of a place against its own DEM is the place itself; the second best is another
ridge branch of Colorado, rotated or mirrored to fit, and the merged map shows where its seam
runs. Change the Matcher's Site or the Patch's Rank and Apply to place another patch.

Open it like the other states (the plugin first, then the state with the Data folder):

    pvpython Examples/states/open_state.py Examples/states/patch_stages.pvsm
    TSYNTH_STATE=Examples/states/patch_stages.pvsm paraview --script=Examples/states/open_state.py

See Examples/states/README.md.
"""
import os
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import state_files  # noqa: E402

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(state_files.STATES, "patch_stages.pvsm")

CPU = 2  # Backend enumeration: 0 Auto, 1 OpenCL, 2 CPU (the same costs everywhere)
BRANCH = 2  # the candidate table's Kind of a branch node
RIDGE = 1  # its FeatureType of a ridge
SECOND_BEST = 1  # the best match of a place in its own DEM is the place itself
SEAM_LIFT_M = 1.0  # the seam drawn just above the shaded map
VIEW_SIZE = [600, 600]
MAGENTA = [0.85, 0.0, 0.85]


def ridge_branch_near_centre(candidates, dem):
    """(x, y) in metres of the ridge branch among the candidates nearest the DEM's centre."""
    table = sm.Fetch(candidates)
    column = lambda name: vtk_to_numpy(table.GetColumnByName(name))  # noqa: E731
    x, y = column("X"), column("Y")
    chosen = (column("Kind") == BRANCH) & (column("FeatureType") == RIDGE)
    bounds = dem.GetDataInformation().GetBounds()
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    distance = np.where(chosen, np.hypot(x - cx, y - cy), np.inf)
    k = int(np.argmin(distance))
    return [float(x[k]), float(y[k])]


def main():
    simple.LoadPlugin(state_files.PLUGIN, remote=False)
    dem = simple.TerrainReader(registrationName="Exemplar",
                               FileName=state_files.data_file("dems", "colorado.png"))
    dem.UpdatePipeline()
    trees = simple.TerrainFeatureExtractor(registrationName="FeatureTrees", Input=dem, Features=2)
    candidates = simple.TerrainCandidateBuilder(registrationName="Candidates", Input=[dem],
                                                FeatureTrees=[trees])
    candidates.UpdatePipeline()
    matcher = simple.TerrainPatchMatcher(registrationName="Matcher", Input=dem, Exemplars=[dem],
                                         CandidatePool=candidates, Mode=0, Backend=CPU,
                                         Site=ridge_branch_near_centre(candidates, dem))
    patch = simple.TerrainPatchExtractor(registrationName="Patch", Input=dem, Exemplars=[dem],
                                         Matches=simple.OutputPort(matcher, 0), Rank=SECOND_BEST)
    merged = simple.TerrainGraphCutMerger(registrationName="Merged", Input=dem, Patch=patch)
    shade = simple.TerrainHillshade(registrationName="Hillshade", Input=merged)
    seam = simple.Threshold(registrationName="Seam", Input=merged, Scalars=["POINTS", "SeamMask"],
                            LowerThreshold=1, UpperThreshold=1, AllScalars=0)

    view = state_files.grey_hillshade_view(shade, VIEW_SIZE)
    state_files.show_in_colour(seam, view, MAGENTA, SEAM_LIFT_M)
    state_files.look_from_above(view)
    offset = sm.Fetch(patch).GetFieldData().GetArray("VerticalOffset").GetValue(0)
    print("Site %s; patch rank %d shifted by %.1f m" % (list(matcher.Site), SECOND_BEST, offset))
    state_files.save_portable_state(OUT)


if __name__ == "__main__":
    main()
