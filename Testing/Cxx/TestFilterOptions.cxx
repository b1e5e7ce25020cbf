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
