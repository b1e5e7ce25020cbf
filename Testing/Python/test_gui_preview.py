"""Preview First in ParaView's GUI: the preview shows at once and the whole synthesis replaces it
by itself, through ParaView's live-source poll (the LiveSource hint and GetNeedsUpdate), with no
update asked by anyone. Runs `paraview --dr --script=gui_preview_script.py` under an X display
(with_display.sh)."""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

import harness
from harness import PATHS

STUCK_AFTER_S = 300


class GuiPreviewTest(unittest.TestCase):
    def test_the_gui_replaces_the_preview_by_the_whole_synthesis_by_itself(self):
        paraview = shutil.which("paraview")
        self.assertIsNotNone(paraview, "ParaView's GUI (paraview) is not on the PATH")
        tmp = tempfile.mkdtemp(prefix="tsynth-gui-preview-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        log = os.path.join(tmp, "record.json")
        env = dict(os.environ, HOME=tmp, XDG_CONFIG_HOME=os.path.join(tmp, ".config"),
                   TSYNTH_GUI_PREVIEW_LOG=log, TSYNTH_PLUGIN=PATHS.plugin,
                   TSYNTH_PYTHON_DIR=PATHS.python_dir, TSYNTH_BUNDLED_DATA=PATHS.bundled_data)
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gui_preview_script.py")
        run = subprocess.run([paraview, "--dr", "--script=" + script], env=env, capture_output=True,
                             text=True, timeout=STUCK_AFTER_S)
        self.assertTrue(os.path.exists(log), (run.returncode, (run.stdout + run.stderr)[-3000:]))
        with open(log) as f:
            record = json.load(f)
        print("levels over time:", list(zip(record["seconds"], record["levels"])))
        self.assertEqual(record["levels"][0], "preview")  # what the first render showed
        self.assertEqual(record["levels"][-1], "final", record)
        self.assertEqual(record["points"], 384 * 384)
        self.assertTrue(record["has_patch_ids"])  # the whole synthesis' arrays, not the preview's


if __name__ == "__main__":
    harness.run(__name__)
