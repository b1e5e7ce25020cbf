// The filters' options agree with the kernels' one table of them: each
// PatchSize's default and clamp in C++, and its default_values and
// IntRangeDomain in the plugin XML a ParaView user sees.
#include "vtkTerrainCandidateBuilder.h"
#include "vtkTerrainOptimisation.h"
#include "vtkTerrainPatchMatcher.h"
#include "vtkTerrainSketchFeatures.h"
#include "vtkTerrainSynthesis.h"

#include "Core/PatchSize.h"
#include "Optimisation/TerrainOptimisation.h"

#include <vtkNew.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

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
  expectSame(filterProperty<vtkTerrainSynthesis>(lo, hi), kernels, "vtkTerrainSynthesis");
  expectSame(
    filterProperty<vtkTerrainCandidateBuilder>(lo, hi), kernels, "vtkTerrainCandidateBuilder");
  expectSame(filterProperty<vtkTerrainPatchMatcher>(lo, hi), kernels, "vtkTerrainPatchMatcher");
  expectSame(filterProperty<vtkTerrainSketchFeatures>(lo, hi), kernels, "vtkTerrainSketchFeatures");
  for (const char* xml : { "TerrainSynthesis.xml",
         "TerrainCandidateBuilder.xml",
         "TerrainPatchMatcher.xml",
         "TerrainSketchFeatures.xml" })
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
