// The filters' options agree with the kernels' one table of them
// (Synthesis/SynthesisRequest.h, Core/PatchSize.h): each default and clamp in
// C++, and each default_values, range domain and enumeration in the plugin XML a
// ParaView user sees.
#include "PropertyEnums.h"
#include "vtkTerrainCandidateBuilder.h"
#include "vtkTerrainDistanceSynthesis.h"
#include "vtkTerrainFeatureExtractor.h"
#include "vtkTerrainGraphCutMerger.h"
#include "vtkTerrainHillshade.h"
#include "vtkTerrainOptimisation.h"
#include "vtkTerrainPatchExtractor.h"
#include "vtkTerrainPatchMatcher.h"
#include "vtkTerrainPitRemoval.h"
#include "vtkTerrainPoissonSolver.h"
#include "vtkTerrainReader.h"
#include "vtkTerrainSketchFeatures.h"
#include "vtkTerrainSketchLines.h"
#include "vtkTerrainSketchReader.h"
#include "vtkTerrainSynthesis.h"
#include "vtkTerrainTileWriter.h"

#include "Analysis/Hillshade.h"
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Core/PatchSize.h"
#include "Core/TileExport.h"
#include "Distance/DistanceSources.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "Hydrology/PitRemoval.h"
#include "Matching/PatchMatcher.h"
#include "Merging/PoissonEditing.h"
#include "Optimisation/TerrainOptimisation.h"
#include "Synthesis/PatchExtraction.h"
#include "Synthesis/SynthesisRequest.h"

#include <vtkNew.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{

struct XmlIntProperty
{
  int defaultValue = -1;
  int min = -1;
  int max = -1;
};

// The quoted value of `attribute` in text[from, to), or -1 if it is not there.
int attributeValue(const std::string& text,
  const std::string& attribute,
  std::size_t from,
  std::size_t to)
{
  const std::string key = attribute + "=\"";
  const std::size_t at = text.find(key, from);
  if (at == std::string::npos || at >= to)
  {
    return -1;
  }
  return std::stoi(text.substr(at + key.size()));
}

// The named IntVectorProperty of a plugin XML: its default and range domain
// (-1 for what it lacks).
XmlIntProperty xmlProperty(const std::string& xmlFile, const std::string& name)
{
  std::ifstream in(std::string(TSYNTH_PLUGIN_XML_DIR) + "/" + xmlFile);
  EXPECT_TRUE(in.good()) << xmlFile;
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::size_t begin = text.find("<IntVectorProperty name=\"" + name + "\"");
  const std::size_t end = text.find("</IntVectorProperty>", begin);
  if (begin == std::string::npos || end == std::string::npos)
  {
    ADD_FAILURE() << xmlFile << " has no " << name;
    return {};
  }
  const std::size_t domain = text.find("<IntRangeDomain", begin);
  return { attributeValue(text, "default_values", begin, domain),
    attributeValue(text, "min", domain, end),
    attributeValue(text, "max", domain, end) };
}

// The filter's default, and the range it takes: the kernels' check, because the setter keeps
// whatever is typed (a size out of range fails the request; it is never clamped).
template<class Filter>
XmlIntProperty filterProperty(int min, int max)
{
  vtkNew<Filter> f;
  XmlIntProperty p{ f->GetPatchSize(), min, max };
  for (int typed : { 0, 8, min - 1, max + 1, 600 })
  {
    f->SetPatchSize(typed);
    EXPECT_EQ(f->GetPatchSize(), typed) << f->GetClassName() << " changed the typed size";
  }
  return p;
}

void expectSame(const XmlIntProperty& a, const XmlIntProperty& b, const char* what)
{
  EXPECT_EQ(a.defaultValue, b.defaultValue) << what << ": default";
  EXPECT_EQ(a.min, b.min) << what << ": smallest";
  EXPECT_EQ(a.max, b.max) << what << ": largest";
}

} // namespace

TEST(FilterOptions, EverySynthesisPatchSizeIsTheKernelsOne)
{
  const XmlIntProperty kernels{
    tsynth::kDefaultSynthesisPatch, tsynth::kMinSynthesisPatch, tsynth::kMaxSynthesisPatch
  };
  const int lo = tsynth::kMinSynthesisPatch;
  const int hi = tsynth::kMaxSynthesisPatch;
  // The Terrain Synthesis filter's own starts at kAutomaticPatch, which chooses
  // for the sketch: its table row (SynthesisRequest.h) and the tests below hold it.
  expectSame(
    filterProperty<vtkTerrainCandidateBuilder>(lo, hi), kernels, "vtkTerrainCandidateBuilder");
  expectSame(filterProperty<vtkTerrainPatchMatcher>(lo, hi), kernels, "vtkTerrainPatchMatcher");
  expectSame(filterProperty<vtkTerrainSketchFeatures>(lo, hi), kernels, "vtkTerrainSketchFeatures");
  for (const char* xml :
    { "TerrainCandidateBuilder.xml", "TerrainPatchMatcher.xml", "TerrainSketchFeatures.xml" })
  {
    expectSame(xmlProperty(xml, "PatchSize"), kernels, xml);
  }
}

TEST(FilterOptions, TheOptimisationPatchSizeIsItsKernelsOne)
{
  const tsynth::OptimisationOptions defaults;
  const XmlIntProperty kernel{ defaults.patchSize, tsynth::kMinPatchSize, tsynth::kMaxPatchSize };
  expectSame(filterProperty<vtkTerrainOptimisation>(tsynth::kMinPatchSize, tsynth::kMaxPatchSize),
    kernel,
    "vtkTerrainOptimisation");
  expectSame(
    xmlProperty("TerrainOptimisation.xml", "PatchSize"), kernel, "TerrainOptimisation.xml");
}

namespace
{

// A property of a plugin XML as ParaView reads it: its defaults, its range domain, whether it
// is a check box, and its enumeration's entries.
struct XmlDeclared
{
  std::vector<double> defaults;
  std::vector<double> mins; // empty: no bound
  std::vector<double> maxs;
  bool boolean = false;
  std::vector<std::pair<int, std::string>> entries;
};

std::vector<double> numbersIn(const std::string& text)
{
  std::vector<double> values;
  std::istringstream in(text);
  for (double v = 0.0; in >> v;)
  {
    values.push_back(v);
  }
  return values;
}

// The opening tag (up to its '>') of the first element of `text` whose name ends in `suffix`
// ("RangeDomain": IntRangeDomain or DoubleRangeDomain), or "". Plain string search: GCC 12's
// <regex> trips -Wmaybe-uninitialized in the sanitized build.
std::string openingTag(const std::string& text, const std::string& suffix)
{
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1))
  {
    const std::size_t nameEnd = text.find_first_of(" \t\n/>", at);
    const std::string name = text.substr(at + 1, nameEnd - at - 1);
    if (name.size() >= suffix.size() &&
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    {
      return text.substr(at, text.find('>', at) - at + 1);
    }
  }
  return "";
}

// The quoted value of attribute `name` in an opening tag, or "".
std::string attributeOf(const std::string& tag, const std::string& name)
{
  const std::string key = " " + name + "=\"";
  std::size_t at = tag.find(key);
  if (at == std::string::npos)
  {
    const std::string wrapped = "\n" + name + "=\"";
    at = tag.find(wrapped);
    if (at == std::string::npos)
    {
      return "";
    }
  }
  const std::size_t first = at + key.size();
  return tag.substr(first, tag.find('"', first) - first);
}

XmlDeclared declaredIn(const std::string& xmlFile, const std::string& property)
{
  std::ifstream in(std::string(TSYNTH_PLUGIN_XML_DIR) + "/" + xmlFile);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string xml = buffer.str();
  std::size_t begin = std::string::npos;
  for (const char* type : { "<IntVectorProperty name=\"", "<DoubleVectorProperty name=\"" })
  {
    begin = std::min(begin, xml.find(type + property + "\""));
  }
  if (begin == std::string::npos)
  {
    ADD_FAILURE() << xmlFile << " declares no " << property;
    return {};
  }
  const std::size_t end = xml.find("VectorProperty>", begin); // its closing tag
  const std::string text = xml.substr(begin, end - begin);
  XmlDeclared d;
  d.defaults = numbersIn(attributeOf(openingTag(text, "VectorProperty"), "default_values"));
  const std::string range = openingTag(text, "RangeDomain");
  d.mins = numbersIn(attributeOf(range, "min"));
  d.maxs = numbersIn(attributeOf(range, "max"));
  d.boolean = text.find("<BooleanDomain") != std::string::npos;
  for (std::size_t at = text.find("<Entry "); at != std::string::npos;
       at = text.find("<Entry ", at + 1))
  {
    const std::string entry = text.substr(at, text.find('>', at) - at + 1);
    d.entries.emplace_back(std::stoi(attributeOf(entry, "value")), attributeOf(entry, "text"));
  }
  return d;
}

// Each of `values` is `expected`; none at all when `expected` is unbounded.
void expectBound(const std::vector<double>& values, double expected, const std::string& what)
{
  if (std::isinf(expected))
  {
    EXPECT_TRUE(values.empty()) << what << " should have no bound";
    return;
  }
  ASSERT_FALSE(values.empty()) << what << " has no bound";
  for (double v : values)
  {
    EXPECT_EQ(v, expected) << what;
  }
}

// The plugin XML declares `row`'s property as the table does.
void expectDeclaredAsRow(const std::string& xmlFile, const tsynth::OptionRow& row)
{
  SCOPED_TRACE(xmlFile + ": " + row.property);
  const XmlDeclared d = declaredIn(xmlFile, row.property);
  if (row.secondDefault)
  {
    EXPECT_EQ(d.defaults, std::vector<double>({ row.defaultValue, *row.secondDefault }));
  }
  else
  {
    expectBound(d.defaults, row.defaultValue, "default_values");
  }
  switch (row.type)
  {
    case tsynth::OptionType::Switch:
      EXPECT_TRUE(d.boolean) << "a check box";
      break;
    case tsynth::OptionType::Choice:
      ASSERT_EQ(d.entries.size(), row.labels.size());
      for (std::size_t i = 0; i < row.labels.size(); ++i)
      {
        EXPECT_EQ(d.entries[i].first, row.choices.valueAt(i));
        EXPECT_EQ(d.entries[i].second, row.labels[i]);
      }
      break;
    default:
      expectBound(d.mins, row.min, "the range's min");
      expectBound(d.maxs, row.max, "the range's max");
  }
}

// A filter's C++ side of each option: its value, and a setter.
template<class Filter>
struct FilterProperty
{
  std::function<double(Filter*)> get;
  std::function<void(Filter*, double)> set;
};

// A property read and set as an int, a bool or a double.
template<class Filter>
FilterProperty<Filter> countProperty(int (Filter::*get)(), void (Filter::*set)(int))
{
  return { [get](Filter* f) { return (f->*get)(); },
    [set](Filter* f, double v) { (f->*set)(static_cast<int>(v)); } };
}

template<class Filter>
FilterProperty<Filter> onOffProperty(bool (Filter::*get)(), void (Filter::*set)(bool))
{
  return { [get](Filter* f) { return (f->*get)() ? 1.0 : 0.0; },
    [set](Filter* f, double v) { (f->*set)(v != 0.0); } };
}

template<class Filter>
FilterProperty<Filter> realProperty(double (Filter::*get)(), void (Filter::*set)(double))
{
  return { [get](Filter* f) { return (f->*get)(); }, [set](Filter* f, double v) { (f->*set)(v); } };
}

// A new filter holds every row's default, and its setters keep a value inside the row's range,
// except the properties `checkedWhenRun` (refused when the filter runs, never clamped).
template<class Filter>
void expectDefaultsAndClamps(const std::vector<tsynth::OptionRow>& rows,
  const std::map<std::string, FilterProperty<Filter>>& properties,
  const std::set<std::string>& checkedWhenRun)
{
  for (const tsynth::OptionRow& row : rows)
  {
    SCOPED_TRACE(row.property);
    const auto p = properties.find(row.property);
    ASSERT_NE(p, properties.end()) << "the filter has no such property";
    vtkNew<Filter> filter;
    EXPECT_EQ(p->second.get(filter), row.defaultValue);
    if (row.type == tsynth::OptionType::Switch || checkedWhenRun.count(row.property) > 0)
    {
      continue;
    }
    p->second.set(filter, row.min - 1.0);
    EXPECT_EQ(p->second.get(filter), row.min);
    if (!std::isinf(row.max))
    {
      p->second.set(filter, row.max + 1.0);
      EXPECT_EQ(p->second.get(filter), row.max);
    }
  }
}

std::map<std::string, FilterProperty<vtkTerrainSynthesis>> synthesisFilterProperties()
{
  using F = vtkTerrainSynthesis*;
  return {
    { "PatchSize",
      { [](F f) { return f->GetPatchSize(); },
        [](F f, double v) { f->SetPatchSize(static_cast<int>(v)); } } },
    { "OutputSize",
      { [](F f)
        { return f->GetOutputSize()[0] == f->GetOutputSize()[1] ? f->GetOutputSize()[0] : -1; },
        [](F f, double v) { f->SetOutputSize(static_cast<int>(v), static_cast<int>(v)); } } },
    { "CellSize",
      { [](F f) { return f->GetCellSize(); }, [](F f, double v) { f->SetCellSize(v); } } },
    { "Seed",
      { [](F f) { return static_cast<double>(f->GetSeed()); },
        [](F f, double v) { f->SetSeed(static_cast<vtkIdType>(v)); } } },
    { "LandformRelief",
      { [](F f) { return f->GetLandformRelief(); },
        [](F f, double v) { f->SetLandformRelief(v); } } },
    { "MemoryBudget",
      { [](F f) { return f->GetMemoryBudget(); }, [](F f, double v) { f->SetMemoryBudget(v); } } },
    { "Backend",
      { [](F f) { return f->GetBackend(); },
        [](F f, double v) { f->SetBackend(static_cast<int>(v)); } } },
    { "MergeMode",
      { [](F f) { return f->GetMergeMode(); },
        [](F f, double v) { f->SetMergeMode(static_cast<int>(v)); } } },
    { "FillOrder",
      { [](F f) { return f->GetFillOrder(); },
        [](F f, double v) { f->SetFillOrder(static_cast<int>(v)); } } },
    { "Drainage",
      { [](F f) { return f->GetDrainage(); },
        [](F f, double v) { f->SetDrainage(static_cast<int>(v)); } } },
    { "VerticalOffset",
      { [](F f) { return f->GetVerticalOffset() ? 1.0 : 0.0; },
        [](F f, double v) { f->SetVerticalOffset(v != 0.0); } } },
    { "Repetition",
      { [](F f) { return f->GetRepetition(); }, [](F f, double v) { f->SetRepetition(v); } } },
    { "TileSize",
      { [](F f) { return f->GetTileSize(); },
        [](F f, double v) { f->SetTileSize(static_cast<int>(v)); } } },
    { "PlacementLimit",
      { [](F f) { return f->GetPlacementLimit(); },
        [](F f, double v) { f->SetPlacementLimit(static_cast<int>(v)); } } },
    { "UseExemplarCache",
      { [](F f) { return f->GetUseExemplarCache() ? 1.0 : 0.0; },
        [](F f, double v) { f->SetUseExemplarCache(v != 0.0); } } },
  };
}

} // namespace

TEST(FilterOptions, TheSynthesisXmlDeclaresEveryOptionAsTheTableDoes)
{
  for (const tsynth::OptionRow& row : tsynth::synthesisOptionRows())
  {
    expectDeclaredAsRow("TerrainSynthesis.xml", row);
  }
  // The stage filters that take the same option offer the same choices.
  expectDeclaredAsRow("TerrainPatchMatcher.xml", tsynth::synthesisOption("Backend"));
  for (const tsynth::OptionRow& row : tsynth::mergeOptionRows())
  {
    expectDeclaredAsRow("TerrainGraphCutMerger.xml", row);
  }
}

TEST(FilterOptions, TheSynthesisFilterStartsAtTheTablesDefaultsAndKeepsToItsRanges)
{
  // A size typed wrong fails the request when the filter runs.
  expectDefaultsAndClamps<vtkTerrainSynthesis>(
    tsynth::synthesisOptionRows(), synthesisFilterProperties(), { "PatchSize", "OutputSize" });
}

TEST(FilterOptions, APropertyValueWithoutAWordFailsRatherThanPickingOne)
{
  EXPECT_EQ(tsynth::mergeModeFromProperty(2), tsynth::MergeMode::Shepard);
  EXPECT_THROW(tsynth::mergeModeFromProperty(4), tsynth::Error);
  EXPECT_EQ(tsynth::pitRemovalMethodFromProperty(2), tsynth::PitRemovalMethod::Hybrid);
  EXPECT_THROW(tsynth::pitRemovalMethodFromProperty(3), tsynth::Error); // was taken as breach
  EXPECT_THROW(tsynth::backendFromProperty(-1), tsynth::Error);
  EXPECT_FALSE(tsynth::drainageFromProperty(0).has_value());
  EXPECT_THROW(tsynth::drainageFromProperty(-1), tsynth::Error); // was taken as off
}

TEST(FilterOptions, ThePitRemovalFilterAndItsXmlAreItsTables)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::pitRemovalOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainPitRemoval.xml", row);
  }
  // The synthesis' Drainage offers the same methods after Off.
  const tsynth::OptionRow& drainage = tsynth::synthesisOption("Drainage");
  const tsynth::OptionRow& method = tsynth::optionRow(rows, "Method");
  ASSERT_EQ(drainage.labels.size(), method.labels.size() + 1);
  EXPECT_TRUE(std::equal(method.labels.begin(), method.labels.end(), drainage.labels.begin() + 1));

  using F = vtkTerrainPitRemoval*;
  const std::map<std::string, FilterProperty<vtkTerrainPitRemoval>> properties = {
    { "Method",
      { [](F f) { return f->GetMethod(); },
        [](F f, double v) { f->SetMethod(static_cast<int>(v)); } } },
    { "MaxBreachDepth",
      { [](F f) { return f->GetMaxBreachDepth(); },
        [](F f, double v) { f->SetMaxBreachDepth(v); } } },
    { "MaxBreachLength",
      { [](F f) { return f->GetMaxBreachLength(); },
        [](F f, double v) { f->SetMaxBreachLength(static_cast<int>(v)); } } },
    { "MemoryBudget",
      { [](F f) { return f->GetMemoryBudget(); }, [](F f, double v) { f->SetMemoryBudget(v); } } },
  };
  expectDefaultsAndClamps<vtkTerrainPitRemoval>(rows, properties, {});
}

TEST(FilterOptions, TheOptimisationFilterAndItsXmlAreItsTables)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::optimisationOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainOptimisation.xml", row);
  }
  using F = vtkTerrainOptimisation*;
  using O = vtkTerrainOptimisation;
  const std::map<std::string, FilterProperty<vtkTerrainOptimisation>> properties = {
    { "PatchSize", countProperty(&O::GetPatchSize, &O::SetPatchSize) },
    { "Levels", countProperty(&O::GetLevels, &O::SetLevels) },
    { "Alpha", { [](F f) { return f->GetAlpha(); }, [](F f, double v) { f->SetAlpha(v); } } },
    { "IterationsPerLevel", countProperty(&O::GetIterationsPerLevel, &O::SetIterationsPerLevel) },
    { "SearchIterations", countProperty(&O::GetSearchIterations, &O::SetSearchIterations) },
    { "Rotations", onOffProperty(&O::GetRotations, &O::SetRotations) },
    { "Reflections", onOffProperty(&O::GetReflections, &O::SetReflections) },
    { "PitRemoval", countProperty(&O::GetPitRemoval, &O::SetPitRemoval) },
    { "DrainOutput", onOffProperty(&O::GetDrainOutput, &O::SetDrainOutput) },
    { "Seed",
      { [](F f) { return static_cast<double>(f->GetSeed()); },
        [](F f, double v) { f->SetSeed(static_cast<vtkIdType>(v)); } } },
    { "OutputSize",
      { [](F f)
        { return f->GetOutputSize()[0] == f->GetOutputSize()[1] ? f->GetOutputSize()[0] : -1; },
        [](F f, double v) { f->SetOutputSize(static_cast<int>(v), static_cast<int>(v)); } } },
    { "MemoryBudget",
      { [](F f) { return f->GetMemoryBudget(); }, [](F f, double v) { f->SetMemoryBudget(v); } } },
  };
  // Sizes typed wrong fail the request when the filter runs (the patch must also be odd).
  expectDefaultsAndClamps<vtkTerrainOptimisation>(rows, properties, { "PatchSize", "OutputSize" });
}

TEST(FilterOptions, TheDistanceSynthesisFilterAndItsXmlAreItsTables)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::distanceOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainDistanceSynthesis.xml", row);
  }
  using D = vtkTerrainDistanceSynthesis;
  using F = D*;
  const std::map<std::string, FilterProperty<D>> properties = {
    { "OutputSize",
      { [](F f)
        { return f->GetOutputSize()[0] == f->GetOutputSize()[1] ? f->GetOutputSize()[0] : -1; },
        [](F f, double v) { f->SetOutputSize(static_cast<int>(v), static_cast<int>(v)); } } },
    { "CellSize", realProperty(&D::GetCellSize, &D::SetCellSize) },
    { "HeightScale", realProperty(&D::GetHeightScale, &D::SetHeightScale) },
    { "Seed",
      { [](F f) { return static_cast<double>(f->GetSeed()); },
        [](F f, double v) { f->SetSeed(static_cast<vtkIdType>(v)); } } },
    { "MeanWeight", realProperty(&D::GetMeanWeight, &D::SetMeanWeight) },
    { "Roughness", realProperty(&D::GetRoughness, &D::SetRoughness) },
    { "Sqrt2Diagonals", onOffProperty(&D::GetSqrt2Diagonals, &D::SetSqrt2Diagonals) },
    { "SeaLevelScale", realProperty(&D::GetSeaLevelScale, &D::SetSeaLevelScale) },
    { "BlendBias", realProperty(&D::GetBlendBias, &D::SetBlendBias) },
    { "ProfileScale", realProperty(&D::GetProfileScale, &D::SetProfileScale) },
    { "ProfileAssignment", countProperty(&D::GetProfileAssignment, &D::SetProfileAssignment) },
    { "RegionProfile", countProperty(&D::GetRegionProfile, &D::SetRegionProfile) },
    { "ProfileBins", countProperty(&D::GetProfileBins, &D::SetProfileBins) },
    { "FbmH", realProperty(&D::GetFbmH, &D::SetFbmH) },
    { "FbmLacunarity", realProperty(&D::GetFbmLacunarity, &D::SetFbmLacunarity) },
    { "FbmOctaves", countProperty(&D::GetFbmOctaves, &D::SetFbmOctaves) },
    { "FbmDomain", realProperty(&D::GetFbmDomain, &D::SetFbmDomain) },
    { "FbmScale", realProperty(&D::GetFbmScale, &D::SetFbmScale) },
    { "FbmRange",
      { [](F f) { return f->GetFbmRange()[0]; },
        [](F f, double v) { f->SetFbmRange(v, f->GetFbmRange()[1]); } } },
    { "RidgeCount", countProperty(&D::GetRidgeCount, &D::SetRidgeCount) },
    { "RidgeFraction", realProperty(&D::GetRidgeFraction, &D::SetRidgeFraction) },
    { "RidgeCost", countProperty(&D::GetRidgeCost, &D::SetRidgeCost) },
    { "SeaLevelEpsilon", realProperty(&D::GetSeaLevelEpsilon, &D::SetSeaLevelEpsilon) },
    { "ApproximateFraction", realProperty(&D::GetApproximateFraction, &D::SetApproximateFraction) },
    { "MinScaling", realProperty(&D::GetMinScaling, &D::SetMinScaling) },
    { "ApproximateOnly", onOffProperty(&D::GetApproximateOnly, &D::SetApproximateOnly) },
    { "MemoryBudget", realProperty(&D::GetMemoryBudget, &D::SetMemoryBudget) },
  };
  // Sizes, and the fBm range's ends (whose order only the kernel can judge), are checked when
  // the filter runs.
  expectDefaultsAndClamps<D>(rows, properties, { "OutputSize", "FbmRange" });
  vtkNew<D> filter;
  EXPECT_EQ(filter->GetFbmRange()[1], *tsynth::optionRow(rows, "FbmRange").secondDefault);
}

TEST(FilterOptions, TheFeatureExtractorAndItsXmlArePpasTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::ppaOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainFeatureExtractor.xml", row);
  }
  using E = vtkTerrainFeatureExtractor;
  const std::map<std::string, FilterProperty<E>> properties = {
    { "Features", countProperty(&E::GetFeatures, &E::SetFeatures) },
    { "HalfProfileLength", countProperty(&E::GetHalfProfileLength, &E::SetHalfProfileLength) },
    { "MinimumDip", realProperty(&E::GetMinimumDip, &E::SetMinimumDip) },
    { "RelativeDip", realProperty(&E::GetRelativeDip, &E::SetRelativeDip) },
    { "Significance", realProperty(&E::GetSignificance, &E::SetSignificance) },
    { "SignificanceNoise", realProperty(&E::GetSignificanceNoise, &E::SetSignificanceNoise) },
    { "SignificanceRadius", countProperty(&E::GetSignificanceRadius, &E::SetSignificanceRadius) },
    { "PresmoothSigma", realProperty(&E::GetPresmoothSigma, &E::SetPresmoothSigma) },
    { "EndReductions", countProperty(&E::GetEndReductions, &E::SetEndReductions) },
    { "MinimumBranchLength",
      countProperty(&E::GetMinimumBranchLength, &E::SetMinimumBranchLength) },
    { "MinimumTreeSize", countProperty(&E::GetMinimumTreeSize, &E::SetMinimumTreeSize) },
    { "SmoothingPasses", countProperty(&E::GetSmoothingPasses, &E::SetSmoothingPasses) },
    { "ControlRadius", realProperty(&E::GetControlRadius, &E::SetControlRadius) },
  };
  expectDefaultsAndClamps<E>(rows, properties, {});
}

TEST(FilterOptions, TheHillshadeFilterAndItsXmlAreItsTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::hillshadeOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainHillshade.xml", row);
  }
  using H = vtkTerrainHillshade;
  const std::map<std::string, FilterProperty<H>> properties = {
    { "Altitude", realProperty(&H::GetAltitude, &H::SetAltitude) },
    { "Azimuth", realProperty(&H::GetAzimuth, &H::SetAzimuth) },
    { "Multidirectional", onOffProperty(&H::GetMultidirectional, &H::SetMultidirectional) },
    { "ZFactor", realProperty(&H::GetZFactor, &H::SetZFactor) },
  };
  expectDefaultsAndClamps<H>(rows, properties, {});
}

TEST(FilterOptions, TheTerrainReaderAndItsXmlAreTheReadTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::readOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainReader.xml", row);
  }
  using R = vtkTerrainReader;
  const std::map<std::string, FilterProperty<R>> properties = {
    { "ZUnit", countProperty(&R::GetZUnit, &R::SetZUnit) },
    { "CellSize", realProperty(&R::GetCellSize, &R::SetCellSize) },
    { "UseSidecar", onOffProperty(&R::GetUseSidecar, &R::SetUseSidecar) },
    { "UseNormalisedRange", onOffProperty(&R::GetUseNormalisedRange, &R::SetUseNormalisedRange) },
    { "ZMin", realProperty(&R::GetZMin, &R::SetZMin) },
    { "ZMax", realProperty(&R::GetZMax, &R::SetZMax) },
  };
  expectDefaultsAndClamps<R>(rows, properties, {});
  // The reader's ZUnit values are the kernel's, whose words --z-unit takes.
  EXPECT_EQ(tsynth::parseZUnit(tsynth::kZUnitWords[R::ZUNIT_FEET]), tsynth::ZUnit::Feet);
  EXPECT_EQ(tsynth::parseZUnit(tsynth::kZUnitWords[R::ZUNIT_METRES]), tsynth::ZUnit::Metres);
  EXPECT_EQ(tsynth::parseZUnit(tsynth::kZUnitWords[R::ZUNIT_AUTO]), tsynth::ZUnit::Auto);
}

TEST(FilterOptions, ThePoissonSolverAndItsXmlAreTheEditTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::poissonEditOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainPoissonSolver.xml", row);
  }
  using P = vtkTerrainPoissonSolver;
  const std::map<std::string, FilterProperty<P>> properties = {
    { "Mode", countProperty(&P::GetMode, &P::SetMode) },
    { "Tolerance", realProperty(&P::GetTolerance, &P::SetTolerance) },
  };
  expectDefaultsAndClamps<P>(rows, properties, {});
}

TEST(FilterOptions, TheTileWriterAndItsXmlAreTheTileExportTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::tileExportOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainTileWriter.xml", row);
  }
  using W = vtkTerrainTileWriter;
  const std::map<std::string, FilterProperty<W>> properties = {
    { "TileSize", countProperty(&W::GetTileSize, &W::SetTileSize) },
  };
  expectDefaultsAndClamps<W>(rows, properties, {});
}

TEST(FilterOptions, TheSketchFeaturesFilterAndItsXmlAreTheSketchTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::sketchOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainSketchFeatures.xml", row);
  }
  using S = vtkTerrainSketchFeatures;
  const std::map<std::string, FilterProperty<S>> properties = {
    { "PatchSize", countProperty(&S::GetPatchSize, &S::SetPatchSize) },
    { "ControlRadius", realProperty(&S::GetControlRadius, &S::SetControlRadius) },
    { "CellSize", realProperty(&S::GetCellSize, &S::SetCellSize) },
    { "SnapTolerance", realProperty(&S::GetSnapTolerance, &S::SetSnapTolerance) },
    { "SmoothingPasses", countProperty(&S::GetSmoothingPasses, &S::SetSmoothingPasses) },
  };
  expectDefaultsAndClamps<S>(rows, properties, { "PatchSize" });
}

TEST(FilterOptions, ThePatchMatcherAndItsXmlAreTheMatchersTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::matcherOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainPatchMatcher.xml", row);
  }
  // It matches with the synthesis' own weights (its noise weight was Tasse's 0.001 until the
  // table was its default).
  EXPECT_EQ(tsynth::optionRow(rows, "NoiseWeight").defaultValue, tsynth::MatchWeights{}.noise);
  using M = vtkTerrainPatchMatcher;
  const std::map<std::string, FilterProperty<M>> properties = {
    { "PatchSize", countProperty(&M::GetPatchSize, &M::SetPatchSize) },
    { "K", countProperty(&M::GetK, &M::SetK) },
    { "Backend", countProperty(&M::GetBackend, &M::SetBackend) },
    { "FeatureWeight", realProperty(&M::GetFeatureWeight, &M::SetFeatureWeight) },
    { "AngleWeight", realProperty(&M::GetAngleWeight, &M::SetAngleWeight) },
    { "NoiseWeight", realProperty(&M::GetNoiseWeight, &M::SetNoiseWeight) },
    { "OverlapWeight", realProperty(&M::GetOverlapWeight, &M::SetOverlapWeight) },
    { "VerticalOffset", onOffProperty(&M::GetVerticalOffset, &M::SetVerticalOffset) },
  };
  expectDefaultsAndClamps<M>(rows, properties, { "PatchSize" });
}

TEST(FilterOptions, TheGraphCutMergerStartsAtTheMergersTable)
{
  using G = vtkTerrainGraphCutMerger;
  const std::map<std::string, FilterProperty<G>> properties = {
    { "Mode", countProperty(&G::GetMode, &G::SetMode) },
    { "ShepardRadius", realProperty(&G::GetShepardRadius, &G::SetShepardRadius) },
  };
  expectDefaultsAndClamps<G>(tsynth::mergeOptionRows(), properties, {});
  // The synthesis offers the same modes under the same labels.
  EXPECT_EQ(tsynth::synthesisOption("MergeMode").labels,
    tsynth::optionRow(tsynth::mergeOptionRows(), "Mode").labels);
}

TEST(FilterOptions, TheSketchLinesFilterAndItsXmlAreItsTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::sketchLineOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainSketchLines.xml", row);
  }
  using L = vtkTerrainSketchLines;
  const std::map<std::string, FilterProperty<L>> properties = {
    { "FeatureType", countProperty(&L::GetFeatureType, &L::SetFeatureType) },
    { "ElevationMode", countProperty(&L::GetElevationMode, &L::SetElevationMode) },
    { "Elevation", realProperty(&L::GetElevation, &L::SetElevation) },
  };
  expectDefaultsAndClamps<L>(rows, properties, {});
  // The filter's values are the kernel's feature types, by word.
  const tsynth::Choices& types = tsynth::optionRow(rows, "FeatureType").choices;
  EXPECT_EQ(types.valueOf("valley", "type"), L::VALLEY);
  EXPECT_EQ(types.valueOf("ridge", "type"), L::RIDGE);
  EXPECT_THROW(types.wordOf(0, "Feature type"), tsynth::Error);
}

TEST(FilterOptions, TheSketchReaderTakesTheSketchTablesCellSize)
{
  const tsynth::OptionRow& cell = tsynth::optionRow(tsynth::sketchOptionRows(), "CellSize");
  expectDeclaredAsRow("TerrainSketchReader.xml", cell);
  using R = vtkTerrainSketchReader;
  const std::map<std::string, FilterProperty<R>> properties = {
    { "CellSize", realProperty(&R::GetCellSize, &R::SetCellSize) },
  };
  expectDefaultsAndClamps<R>({ cell }, properties, {});
}

TEST(FilterOptions, ThePatchExtractorAndItsXmlAreItsTable)
{
  const std::vector<tsynth::OptionRow>& rows = tsynth::patchExtractionOptionRows();
  for (const tsynth::OptionRow& row : rows)
  {
    expectDeclaredAsRow("TerrainPatchExtractor.xml", row);
  }
  // It shifts patches as the synthesis places them.
  EXPECT_EQ(tsynth::optionRow(rows, "VerticalOffset").defaultValue,
    tsynth::synthesisOption("VerticalOffset").defaultValue);
  using X = vtkTerrainPatchExtractor;
  const std::map<std::string, FilterProperty<X>> properties = {
    { "Rank", countProperty(&X::GetRank, &X::SetRank) },
    { "VerticalOffset", onOffProperty(&X::GetVerticalOffset, &X::SetVerticalOffset) },
  };
  expectDefaultsAndClamps<X>(rows, properties, {});
}
