"""Shared by the make_*_state.py scripts: where things are, and saving a state without
machine-specific paths.

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
