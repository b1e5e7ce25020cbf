// What ParaView does by default once the plugin is loaded, so a newcomer sees terrain as
// terrain without changing a setting: the colour maps of the plugin's arrays (chosen by array
// name, as ParaView's "save as default for arrays of this name" does) and the Terrain Reader as
// the reader File > Open uses for DEM files. They are a settings collection below the user's
// and the site's: a user's own choice (Settings, or "Set reader as default") always wins.
#include <vtkSMSettings.h>

namespace
{

// Below ParaView's user settings (loaded at the top priority) and any site settings.
constexpr double kPluginSettingsPriority = -1.0;

// Heights: low land green, then brown, grey rock and snow (the data range is mapped onto 0..1
// when an array is first coloured). Hillshade and Slope: grey, as a relief is read. PatchColour
// FeatureType and NodeKind: categories (patches that touch differ; ridges red, valleys blue;
// tree paths grey, ends red, branches yellow, as the synthesis state shows them).
// .png is left out of the reader patterns: sketches are PNGs too, and the PNG reader keeps
// their colours.
constexpr const char* kDefaults = R"json({
  "array_lookup_tables": {
    "Elevation": { "PVLookupTable": {
      "ColorSpace": 0,
      "RGBPoints": [0.0, 0.16, 0.36, 0.20,  0.3, 0.56, 0.62, 0.36,  0.55, 0.62, 0.48, 0.32,
                    0.8, 0.56, 0.52, 0.49,  1.0, 1.0, 1.0, 1.0] } },
    "Hillshade": { "PVLookupTable": {
      "ColorSpace": 0, "RGBPoints": [0.0, 0.0, 0.0, 0.0,  1.0, 1.0, 1.0, 1.0] } },
    "Slope": { "PVLookupTable": {
      "ColorSpace": 0, "RGBPoints": [0.0, 1.0, 1.0, 1.0,  1.0, 0.0, 0.0, 0.0] } },
    "PatchColour": { "PVLookupTable": {
      "IndexedLookup": 1,
      "Annotations": ["0", "0", "1", "1", "2", "2", "3", "3", "4", "4", "5", "5",
                      "6", "6", "7", "7", "8", "8", "9", "9", "10", "10", "11", "11"],
      "IndexedColors": [0.89, 0.10, 0.11,  0.22, 0.49, 0.72,  0.30, 0.69, 0.29,
                        0.60, 0.31, 0.64,  1.00, 0.50, 0.00,  1.00, 1.00, 0.20,
                        0.65, 0.34, 0.16,  0.97, 0.51, 0.75,  0.55, 0.55, 0.55,
                        0.40, 0.76, 0.65,  0.55, 0.63, 0.80,  0.65, 0.85, 0.33] } },
    "FeatureType": { "PVLookupTable": {
      "IndexedLookup": 1,
      "Annotations": ["1", "ridge", "-1", "valley"],
      "IndexedColors": [0.85, 0.15, 0.10,  0.10, 0.35, 0.85] } },
    "NodeKind": { "PVLookupTable": {
      "IndexedLookup": 1,
      "Annotations": ["0", "path", "1", "end", "2", "branch"],
      "IndexedColors": [0.35, 0.35, 0.35,  0.90, 0.10, 0.10,  1.00, 0.85, 0.00] } }
  },
  "settings": { "RepresentedArrayListSettings": {
    "ReaderDetails": ["*.tif *.tiff *.hgt *.asc", "Terrain Reader (DEM)", "TerrainReader"] } }
})json";

struct InstallPluginDefaults
{
  InstallPluginDefaults()
  {
    vtkSMSettings::GetInstance()->AddCollectionFromString(kDefaults, kPluginSettingsPriority);
  }
};

// Runs when ParaView (or pvpython's LoadPlugin) loads the plugin's library.
const InstallPluginDefaults installPluginDefaults;

} // namespace
