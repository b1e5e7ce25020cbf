"""The seeded commands other than synth, through the command line: tsynth optimise and tsynth distance
give the same bytes for the same seed, again and on any thread count, and another terrain for another
seed. (tsynth synth's twin, across backends too, is in test_synth.py; the kernels' own ones with
omp_set_num_threads in Testing/Cxx/Optimisation/TestTerrainOptimisation.cxx and
Testing/Cxx/Distance/TestDistanceSynthesis.cxx.)"""
import filecmp
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np
from osgeo import gdal

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

gdal.UseExceptions()

# OpenMP thread counts besides the default (the cores): one, and three, which splits the work unevenly
# on two cores.
THREADS = (1, 3)
# Another seed draws other random choices everywhere (edge weights, PatchMatch's guesses): at least this
# share of the cells must change, measured 0.993-1.000 on the cases below.
MIN_CHANGED_SHARE = 0.9

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples", "distance")


def heights(path):
    return gdal.Open(path).ReadAsArray()


class SeededCommandTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="tsynth-determinism-")
        self.dems = os.path.join(PATHS.bundled_data, "dems")
        self.sketches = os.path.join(PATHS.bundled_data, "sketches")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def run_tsynth(self, name, args, seed, threads=None):
        """Runs tsynth ARGS --seed SEED -o NAME.tif (OMP_NUM_THREADS=threads unless None); the output."""
        out = os.path.join(self.tmp, name + ".tif")
        env = dict(os.environ)
        env.pop("OMP_NUM_THREADS", None)
        if threads is not None:
            env["OMP_NUM_THREADS"] = str(threads)
        result = subprocess.run([PATHS.tsynth, *args, "--seed", str(seed), "-o", out, "--no-progress"],
                                capture_output=True, text=True, timeout=300, env=env)
        self.assertEqual(result.returncode, 0, result.stderr)
        return out

    def assert_deterministic(self, name, args, seed, other_seed):
        first = self.run_tsynth(name, args, seed)
        runs = [("again", None)] + [("threads%d" % n, n) for n in THREADS]
        for tag, threads in runs:
            with self.subTest(run=tag):
                again = self.run_tsynth("%s-%s" % (name, tag), args, seed, threads)
                self.assertTrue(filecmp.cmp(first, again, shallow=False), "%s differs from %s" % (again, first))
        other = heights(self.run_tsynth(name + "-other", args, other_seed))
        z = heights(first)
        self.assertEqual(z.shape, other.shape)
        self.assertTrue(np.isfinite(z).all())
        changed = np.count_nonzero(z != other) / z.size
        self.assertGreater(changed, MIN_CHANGED_SHARE, "seed %d changed %.3f of the cells" % (other_seed, changed))

    def test_optimise_with_rotations_reflections_and_draining(self):
        self.assert_deterministic(
            "optimise",
            ["optimise", "--exemplar", os.path.join(self.dems, "colorado.png"),
             "--guide", os.path.join(self.sketches, "strokes_valley_tree.png"), "--size", "192x192",
             "--rotations", "--reflections", "--drain"],
            seed=4, other_seed=5)

    def test_optimise_with_a_dem_guide_and_fill(self):
        self.assert_deterministic(
            "optimise-dem",
            ["optimise", "--exemplar", os.path.join(self.dems, "alps-montblanc.png"),
             "--guide", os.path.join(self.dems, "mount_jackson_crop601.tif"), "--size", "160x160",
             "--pits", "fill"],
            seed=0, other_seed=1)

    def test_distance_with_profiles_and_dendritic_ridges(self):
        self.assert_deterministic(
            "distance-ridges",
            ["distance", "--generators", os.path.join(EXAMPLES, "mountain_range_strokes.png"),
             "--profiles", os.path.join(EXAMPLES, "mountain_profiles.csv"), "--ridges", "60"],
            seed=3, other_seed=4)

    def test_distance_with_region_profiles(self):
        self.assert_deterministic(
            "distance-craters",
            ["distance", "--generators", os.path.join(EXAMPLES, "crater_field_strokes.png"),
             "--profiles", os.path.join(EXAMPLES, "crater_profiles.csv"), "--region-profile", "2"],
            seed=1, other_seed=2)


if __name__ == "__main__":
    harness.run(__name__)
