"""ParaView's GUI as a newcomer meets it (issue 23), played by ParaView's own event player
(`paraview --test-script`, QtTesting XML): File > Open on a DEM, Apply; File > Open on a sketch
image (the Terrain Sketch Reader picked in ParaView's reader dialog, the exemplar picked with its
file button), Apply; Filters > Terrain Synthesis with the sketch picked in ParaView's input
dialog, the size and the Seed typed into their widgets, Apply; Macros > NewTerrainSketch on the
exemplar; a Poly Line and Terrain Sketch Lines on it from the menus; and File > Save State. The
saved state then says which reader File > Open picked, which colour maps the views use, what the
Seed widget set and how wide the lines are drawn.

Run with python3 and an X display (with_display.sh); ParaView runs with --dr (no user settings,
so the plugin's defaults are what a fresh install shows) and a private HOME holding the macro.
"""
import os
import shutil
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET

import harness
from harness import PATHS

# A modal dialog (a reader choice, an error) stops the event player until someone closes it: past
# this the run is taken as stuck. A normal run takes 10-20 s.
STUCK_AFTER_S = 300
SEED_TYPED = 7
PROPERTIES = "pqClientMainWindow/propertiesDock/propertiesPanel"
PANEL = (PROPERTIES + "/scrollArea/qt_scrollarea_viewport/scrollAreaWidgetContents/"
         "PropertiesFrame/ProxyPanel")
SIZE_TYPED = 256
PIPELINE = "pqClientMainWindow/pipelineBrowserDock/pipelineBrowser"
# Rows by position: the exemplar is the server's first source, the sketch its second.
EXEMPLAR_ROW = "/0/0|0"
SKETCH_ROW_IN_DIALOG = "/0:0/1:0"  # pqFlatTreeView's row:column path in the input dialog

# The plugin's maps (Plugin/TerrainSynthesisDefaults.cxx): the terrain map starts at low green;
# ParaView's own default, Cool to Warm, starts at (0.23, 0.30, 0.75).
TERRAIN_MAP_LOW = (0.16, 0.36, 0.20)
RIDGE_RED = (0.85, 0.15, 0.10)
VALLEY_BLUE = (0.10, 0.35, 0.85)
POINTS, CELLS = "0", "1"
THICK_LINE_WIDTH = 3.0  # marked lines and feature trees (Plugin/TerrainLineWidths.xml)


def menu(name, action):
    return [("pqClientMainWindow/menubar", "activate", name),
            ("pqClientMainWindow/menubar/" + name, "activate", action)]


def open_dem(dem):
    """File > Open on a DEM, then Apply: ParaView picks the reader."""
    return (menu("menu_File", "actionFileOpen")
            + [("pqClientMainWindow/FileOpenDialog", "filesSelected", dem),
               (PROPERTIES + "/Accept", "activate", "")])


def open_sketch(sketch, dem):
    """File > Open on a sketch image: ParaView asks which reader (PNGs are pictures too); the
    exemplar is picked with the Exemplar File Name's file button; then Apply."""
    return (menu("menu_File", "actionFileOpen")
            + [("pqClientMainWindow/FileOpenDialog", "filesSelected", sketch),
               ("pqClientMainWindow/pqSelectReaderDialog/listWidget", "currentChangedbyItemName",
                "Terrain Sketch Reader"),
               ("pqClientMainWindow/pqSelectReaderDialog/okButton", "activate", ""),
               (PANEL + "/ExemplarFileName/FileChooser/FileButton", "activate", ""),
               (PANEL + "/ExemplarFileName/FileChooser/pqFileDialog", "filesSelected", dem),
               (PROPERTIES + "/Accept", "activate", "")])


def synthesis_from_the_filters_menu():
    """With the exemplar selected, Filters > Alphabetical > Terrain Synthesis; in ParaView's
    input dialog the sketch for Sketch; the size and the Seed typed into their widgets; Apply."""
    dialog = "pqClientMainWindow/SelectInputDialog"
    return ([(PIPELINE, "currentChanged", EXEMPLAR_ROW)]
            + [("pqClientMainWindow/menubar", "activate", "menuFilters"),
               ("pqClientMainWindow/menubar/menuFilters/Alphabetical", "activate", "TerrainSynthesis"),
               (dialog + "/buttonFrame/Sketch", "set_boolean", "true"),
               (dialog + "/pipelineView", "mousePress", "1,1,0,36,6," + SKETCH_ROW_IN_DIALOG),
               (dialog + "/pipelineView", "mouseRelease", "1,0,0,36,6," + SKETCH_ROW_IN_DIALOG),
               (dialog + "/buttonBox/1QPushButton0", "activate", ""),
               (PANEL + "/OutputSize/LineEdit0", "set_string", str(SIZE_TYPED)),
               (PANEL + "/OutputSize/LineEdit1", "set_string", str(SIZE_TYPED)),
               (PANEL + "/Seed/LineEdit0", "set_string", str(SEED_TYPED)),
               (PROPERTIES + "/Accept", "activate", "")])


def sketch_lines_by_hand():
    """Sources > Alphabetical > Poly Line, Apply; Filters > Alphabetical > Terrain Sketch Lines
    on it, Apply: a stroke drawn by hand, as the README describes."""
    return [("pqClientMainWindow/menubar", "activate", "menuSources"),
            ("pqClientMainWindow/menubar/menuSources/Alphabetical", "activate", "PolyLineSource"),
            (PROPERTIES + "/Accept", "activate", ""),
            ("pqClientMainWindow/menubar", "activate", "menuFilters"),
            ("pqClientMainWindow/menubar/menuFilters/Alphabetical", "activate", "TerrainSketchLines"),
            (PROPERTIES + "/Accept", "activate", "")]


def events(dem, sketch, state):
    """The newcomer's steps as QtTesting events (object, command, arguments)."""
    return (open_dem(dem) + open_sketch(sketch, dem) + synthesis_from_the_filters_menu()
            + [(PIPELINE, "currentChanged", EXEMPLAR_ROW)]
            + menu("menu_Macros", "NewTerrainSketch")
            + sketch_lines_by_hand()
            + menu("menu_File", "actionFileSaveServerState")
            + [("pqClientMainWindow/FileSaveServerStateDialog", "filesSelected", state)])


def write_events(path, steps):
    root = ET.Element("pqevents")
    for obj, command, arguments in steps:
        ET.SubElement(root, "pqevent", object=obj, command=command, arguments=arguments)
    ET.ElementTree(root).write(path, xml_declaration=True, encoding="utf-8")


class State:
    """A saved ParaView state: proxies by id, collections by name."""

    def __init__(self, path):
        root = ET.parse(path).getroot()
        self.proxies = {p.get("id"): p for p in root.iter("Proxy")}
        self.collections = {c.get("name"): {i.get("name"): i.get("id") for i in c.findall("Item")}
                            for c in root.iter("ProxyCollection")}

    def proxy(self, collection, name):
        return self.proxies[self.collections[collection][name]]

    @staticmethod
    def _property(proxy, name):
        for p in proxy.findall("Property"):
            if p.get("name") == name:
                return p
        raise KeyError("%s has no property %s" % (proxy.get("type"), name))

    def values(self, proxy, name):
        return [e.get("value") for e in self._property(proxy, name).findall("Element")]

    def numbers(self, proxy, name):
        return [float(v) for v in self.values(proxy, name)]

    def links(self, proxy, name):
        return [p.get("value") for p in self._property(proxy, name).findall("Proxy")]

    def representation_of(self, source_id, port="0"):
        for rid in self.collections["representations"].values():
            rep = self.proxies[rid]
            inputs = self._property(rep, "Input").findall("Proxy")
            if inputs and inputs[0].get("value") == source_id and inputs[0].get("output_port", "0") == port:
                return rep
        raise KeyError("no representation shows proxy %s port %s" % (source_id, port))

    def coloured_by(self, rep):
        """(association, array name, lookup table proxy or None) of a representation."""
        colour = self.values(rep, "ColorArrayName")
        lut = self.links(rep, "LookupTable")
        return colour[3], colour[4], self.proxies[lut[0]] if lut else None


class GuiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="tsynth-gui-")
        # A GeoTIFF DEM: File > Open gives .tif files to the Terrain Reader (PNGs may be sketches).
        cls.dem = os.path.join(cls.tmp, "colorado.tif")
        subprocess.run([PATHS.tsynth, "convert", os.path.join(PATHS.bundled_data, "dems", "colorado.png"),
                        "-o", cls.dem], check=True, capture_output=True)
        config = os.path.join(cls.tmp, "home", ".config")
        os.makedirs(os.path.join(config, "ParaView", "Macros"))
        macro = os.path.join(os.path.dirname(__file__), "..", "..", "Plugin", "Macros", "NewTerrainSketch.py")
        shutil.copy(macro, os.path.join(config, "ParaView", "Macros"))
        script = os.path.join(cls.tmp, "newcomer.xml")
        cls.state_path = os.path.join(cls.tmp, "newcomer.pvsm")
        cls.sketch = os.path.join(PATHS.bundled_data, "sketches", "strokes_y_ridges.png")
        write_events(script, events(cls.dem, cls.sketch, cls.state_path))
        env = dict(os.environ, HOME=os.path.join(cls.tmp, "home"), XDG_CONFIG_HOME=config,
                   PV_PLUGIN_PATH=os.path.dirname(PATHS.plugin))
        paraview = shutil.which("paraview")
        if paraview is None:
            raise RuntimeError("ParaView's GUI (paraview) is not on the PATH; scripts/setup.sh installs it.")
        try:
            run = subprocess.run([paraview, "--dr", "--test-script=" + script, "--exit"], env=env,
                                 capture_output=True, text=True, timeout=STUCK_AFTER_S)
            cls.log, cls.status = run.stdout + run.stderr, run.returncode
        except subprocess.TimeoutExpired as e:
            cls.log = ((e.stdout or b"") + (e.stderr or b"")).decode(errors="replace")
            cls.status = "stuck after %d s: a dialog waits for an answer (did File > Open ask which reader?)" % STUCK_AFTER_S
        print(cls.log[-3000:])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def state(self):
        self.assertEqual(self.status, 0, self.log[-3000:])
        self.assertIn("Success =  true", self.log)
        return State(self.state_path)

    def assertColour(self, found, expected):
        for f, e in zip(found, expected):
            self.assertAlmostEqual(f, e, places=4)

    def test_file_open_gives_a_dem_to_the_terrain_reader(self):
        s = self.state()
        readers = [p for p in s.proxies.values() if p.get("group") == "sources" and p.get("type") == "TerrainReader"]
        self.assertEqual(len(readers), 1)
        self.assertEqual(s.values(readers[0], "FileName"), [self.dem])
        self.assertEqual(s.collections["sources"]["colorado.tif"], readers[0].get("id"))

    def test_file_open_gives_a_sketch_to_the_sketch_reader_with_its_own_name(self):
        s = self.state()
        sketch = s.proxy("sources", os.path.basename(self.sketch))
        self.assertEqual(sketch.get("type"), "TerrainSketchReader")
        self.assertEqual(s.values(sketch, "FileName"), [self.sketch])
        self.assertEqual(s.values(sketch, "ExemplarFileName"), [self.dem])
        self.assertNotIn("ERR|", self.log)  # nothing in the steps failed a request
        # The exemplar was given before Apply: no warning that it is missing (File > Open asks
        # the reader for its information before the panel could be filled in).
        self.assertNotIn("No ExemplarFileName", self.log)

    def test_the_filters_menu_and_its_input_dialog_wire_a_synthesis_and_its_widgets_set_it(self):
        s = self.state()
        terrain = s.proxy("sources", "TerrainSynthesis1")
        self.assertEqual(terrain.get("type"), "TerrainSynthesis")
        self.assertEqual(s.links(terrain, "Exemplars"), [s.collections["sources"]["colorado.tif"]])
        self.assertEqual(s.links(terrain, "Sketch"), [s.collections["sources"][os.path.basename(self.sketch)]])
        self.assertEqual(s.values(terrain, "OutputSize"), [str(SIZE_TYPED)] * 2)
        self.assertEqual(s.values(terrain, "Seed"), [str(SEED_TYPED)])
        # The heights selection (NoDefault in the XML) names the exemplar's heights.
        self.assertEqual(s.values(terrain, "SelectExemplarScalars")[3:], [POINTS, "Elevation"])
        # Shown once applied: the terrain in the terrain map, as the exemplar.
        association, array, lut = s.coloured_by(s.representation_of(terrain.get("id")))
        self.assertEqual((association, array), (POINTS, "Elevation"))
        self.assertColour(s.numbers(lut, "RGBPoints")[1:4], TERRAIN_MAP_LOW)

    def test_the_macro_sets_up_sketch_and_terrain(self):
        s = self.state()
        terrain = s.proxy("sources", "Terrain")
        self.assertEqual(terrain.get("type"), "TerrainSynthesis")
        self.assertEqual(s.links(terrain, "Exemplars"), [s.collections["sources"]["colorado.tif"]])
        self.assertEqual(s.links(terrain, "Sketch"), [s.collections["sources"]["Ridge"]])
        from osgeo import gdal
        dem = gdal.Open(self.dem)
        self.assertEqual(s.values(terrain, "OutputSize"), [str(dem.RasterXSize), str(dem.RasterYSize)])
        self.assertEqual(s.proxy("sources", "Ridge").get("type"), "TerrainSketchLines")

    def test_sketch_lines_are_drawn_thick(self):
        """Marked lines and feature trees are shown 3 pixels wide (Plugin/TerrainLineWidths.xml):
        Terrain Sketch Lines added by hand from the Filters menu, and the macro's ridge and the
        synthesis's Sketch Features; the Poly Line itself keeps ParaView's 1."""
        s = self.state()
        by_hand = s.proxy("sources", "TerrainSketchLines1")
        self.assertEqual(by_hand.get("type"), "TerrainSketchLines")
        self.assertEqual(s.numbers(s.representation_of(by_hand.get("id")), "LineWidth"), [THICK_LINE_WIDTH])
        line_id = s.links(by_hand, "Input")[0]
        self.assertEqual(s.proxies[line_id].get("type"), "PolyLineSource")
        self.assertEqual(s.numbers(s.representation_of(line_id), "LineWidth"), [1.0])
        for rep in (s.representation_of(s.collections["sources"]["Ridge"]),
                    s.representation_of(s.collections["sources"]["Terrain"], port="2")):
            self.assertEqual(s.numbers(rep, "LineWidth"), [THICK_LINE_WIDTH])

    def test_heights_and_hillshades_open_in_the_plugins_maps(self):
        s = self.state()
        association, array, lut = s.coloured_by(s.representation_of(s.collections["sources"]["colorado.tif"]))
        self.assertEqual((association, array), (POINTS, "Elevation"))
        self.assertColour(s.numbers(lut, "RGBPoints")[1:4], TERRAIN_MAP_LOW)
        association, array, lut = s.coloured_by(s.representation_of(s.collections["sources"]["Terrain hillshade"]))
        self.assertEqual((association, array), (POINTS, "Hillshade"))
        points = s.numbers(lut, "RGBPoints")
        self.assertGreaterEqual(len(points), 8)
        for k in range(0, len(points), 4):  # grey: red, green and blue equal at every point
            self.assertAlmostEqual(points[k + 1], points[k + 2], places=6)
            self.assertAlmostEqual(points[k + 2], points[k + 3], places=6)

    def test_lines_and_feature_trees_show_ridges_red_and_valleys_blue(self):
        s = self.state()
        terrain_id = s.collections["sources"]["Terrain"]
        for rep in (s.representation_of(s.collections["sources"]["Ridge"]),
                    s.representation_of(terrain_id, port="2")):  # Sketch Features
            association, array, lut = s.coloured_by(rep)
            self.assertEqual((association, array), (CELLS, "FeatureType"))
            self.assertEqual(s.values(lut, "IndexedLookup"), ["1"])
            colours = s.numbers(lut, "IndexedColors")
            self.assertColour(colours[0:3], RIDGE_RED)
            self.assertColour(colours[3:6], VALLEY_BLUE)


if __name__ == "__main__":
    harness.run(__name__)
