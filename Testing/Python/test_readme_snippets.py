"""Every Python block of the README runs as written (issue 23: the pvpython snippet failed with
NameError). Each block runs from a folder laid out as the repository's top: `build` is the
build under test and `Data` the bundled data. Blocks that use paraview.simple run in pvpython,
the others in this Python (Debian's /usr/bin/python3, which the README names)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import PATHS  # noqa: E402

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.M | re.S)


class ReadmeSnippetTest(unittest.TestCase):
    def setUp(self):
        self.top = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.top)
        build = PATHS.plugin
        for _ in range(4):  # build/lib/paraview-plugins/TerrainSynthesis/TerrainSynthesis.so
            build = os.path.dirname(build)
        os.symlink(build, os.path.join(self.top, "build"))
        os.symlink(PATHS.bundled_data, os.path.join(self.top, "Data"))
        self.assertTrue(os.path.exists(os.path.join(self.top, "build", "lib", "python3.11",
                                                    "site-packages", "terrainsynthesis")))

    def test_every_python_block_runs_as_written(self):
        with open(README) as f:
            blocks = python_blocks(f.read())
        self.assertGreaterEqual(len(blocks), 2)
        for number, code in enumerate(blocks):
            with self.subTest(block=number, first_line=code.splitlines()[0]):
                script = os.path.join(self.top, "block%d.py" % number)
                with open(script, "w") as f:
                    f.write(code)
                python = shutil.which("pvpython") if "paraview.simple" in code else sys.executable
                result = subprocess.run([python, script], cwd=self.top, capture_output=True,
                                        text=True, timeout=300)
                self.assertEqual(result.returncode, 0, result.stderr[-2000:])
                self.assertNotIn("Traceback", result.stderr)
                if "GetRange()" in code:  # the wrapped classes' block prints the shade's range
                    low, high = (float(v) for v in re.findall(r"[-\d.e]+", result.stdout)[-2:])
                    self.assertGreaterEqual(low, 0.0)
                    self.assertGreater(high, 0.5)


if __name__ == "__main__":
    harness.run(__name__)
