"""Loads the plugin built as a ParaView external plugin and checks it against the project's own
build: every proxy is there, and its pit removal gives the same heights as `tsynth pits`.

    pvpython check_external_plugin.py PLUGIN DEM REFERENCE_TIF
"""
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

EXPECTED_PROXIES = [
    "TerrainReader", "TerrainHillshade", "TerrainFeatureExtractor", "TerrainSketchFeatures",
    "TerrainSketchLines", "TerrainCandidateBuilder", "TerrainPatchMatcher",
    "TerrainGraphCutMerger", "TerrainPoissonSolver", "TerrainPitRemoval", "TerrainOptimisation",
    "TerrainDistanceSynthesis", "TerrainSynthesis",
]


def heights(data):
    return vtk_to_numpy(data.GetPointData().GetArray("Elevation")).astype(np.float64)


def main(plugin, dem, reference):
    simple.LoadPlugin(plugin, remote=False)
    pxm = sm.ProxyManager()
    missing = [name for name in EXPECTED_PROXIES
               if pxm.GetPrototypeProxy("sources", name) is None
               and pxm.GetPrototypeProxy("filters", name) is None]
    if missing:
        sys.exit("the external plugin lacks the proxies %s" % ", ".join(missing))
    original = heights(sm.Fetch(simple.TerrainReader(FileName=dem)))
    drained = heights(sm.Fetch(simple.TerrainPitRemoval(Input=simple.TerrainReader(FileName=dem))))
    expected = heights(sm.Fetch(simple.TerrainReader(FileName=reference)))
    if drained.shape != expected.shape or not np.array_equal(drained, expected):
        sys.exit("the external plugin's pit removal differs from tsynth pits in %d cells"
                 % int(np.count_nonzero(drained != expected)) if drained.shape == expected.shape
                 else "the external plugin's output has another size")
    changed = int(np.count_nonzero(drained != original))
    if changed == 0:
        sys.exit("the pit removal changed nothing, so the comparison proves nothing")
    print("external plugin: %d proxies, pit removal equal to tsynth pits (%d cells changed)"
          % (len(EXPECTED_PROXIES), changed))


if __name__ == "__main__":
    main(*sys.argv[1:4])
