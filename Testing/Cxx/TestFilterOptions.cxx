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
#include <regex>
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

// The named IntVectorProperty of a plugin XML: its default and range domain.
XmlIntProperty xmlProperty(const std::string& xmlFile, const std::string& name)
{
  std::ifstream in(std::string(TSYNTH_PLUGIN_XML_DIR) + "/" + xmlFile);
  EXPECT_TRUE(in.good()) << xmlFile;
  std::stringstream text;
  text << in.rdbuf();
  const std::regex property("<IntVectorProperty name=\"" + name +
    "\"[^>]*default_values=\"([0-9]+)\">\\s*<IntRangeDomain name=\"range\" min=\"([0-9]+)\" "
    "max=\"([0-9]+)\"/>");
  std::smatch m;
  const std::string s = text.str();
  if (!std::regex_search(s, m, property))
  {
    ADD_FAILURE() << xmlFile << " has no " << name << " with a default and a range domain";
    return {};
  }
  return { std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]) };
}

// The filter's default, and what its setter clamps 0 and a huge value to.
template<class Filter>
XmlIntProperty filterProperty()
{
  vtkNew<Filter> f;
  XmlIntProperty p;
  p.defaultValue = f->GetPatchSize();
  f->SetPatchSize(0);
  p.min = f->GetPatchSize();
  f->SetPatchSize(1 << 20);
  p.max = f->GetPatchSize();
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
  expectSame(filterProperty<vtkTerrainSynthesis>(), kernels, "vtkTerrainSynthesis");
  expectSame(filterProperty<vtkTerrainCandidateBuilder>(), kernels, "vtkTerrainCandidateBuilder");
  expectSame(filterProperty<vtkTerrainPatchMatcher>(), kernels, "vtkTerrainPatchMatcher");
  expectSame(filterProperty<vtkTerrainSketchFeatures>(), kernels, "vtkTerrainSketchFeatures");
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
  expectSame(filterProperty<vtkTerrainOptimisation>(), kernel, "vtkTerrainOptimisation");
  expectSame(
    xmlProperty("TerrainOptimisation.xml", "PatchSize"), kernel, "TerrainOptimisation.xml");
}
