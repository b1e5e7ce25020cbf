// The Terrain Candidate Builder's table chained into the Terrain Patch Matcher
// (Filters/CandidatePoolTable.h): the matcher given the table matches exactly as
// the matcher that builds the pool itself, and refuses a table that was not
// built from its exemplars at its patch size.
#include "TestData.h"
#include "vtkTerrainCandidateBuilder.h"
#include "vtkTerrainPatchMatcher.h"
#include "vtkTerrainReader.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTable.h>
#include <vtkTrivialProducer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{

// Collects the error messages of the filters it watches, so that a failed
// request is seen, and what it said, without printing.
struct ErrorMessages
{
  std::string text;
  vtkNew<vtkCallbackCommand> callback;
  ErrorMessages()
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* message)
      { static_cast<ErrorMessages*>(self)->text += static_cast<const char*>(message); });
  }
  void watch(vtkObject* o) { o->AddObserver(vtkCommand::ErrorEvent, callback); }
};

// The bundled exemplar, read once for the tests of this file.
vtkImageData* colorado()
{
  static vtkNew<vtkTerrainReader> reader;
  static bool read = false;
  if (!read)
  {
    reader->SetFileName((tsynth::test::bundledData() / "dems" / "colorado.png").string().c_str());
    reader->Update();
    read = true;
  }
  return reader->GetOutput();
}

// The candidate table of `exemplar` at this patch size.
vtkSmartPointer<vtkTable> candidateTable(vtkImageData* exemplar, int patchSize)
{
  vtkNew<vtkTerrainCandidateBuilder> builder;
  builder->AddInputDataObject(0, exemplar);
  builder->SetPatchSize(patchSize);
  builder->Update();
  vtkSmartPointer<vtkTable> table = builder->GetOutput();
  return table;
}

// A matcher of `target` against `exemplar` at the site (metres), in feature
// mode on the CPU, given `pool` (nullptr: none, it builds its own).
vtkSmartPointer<vtkTerrainPatchMatcher> matcherFor(vtkImageData* target,
  vtkImageData* exemplar,
  vtkTable* pool,
  double siteX,
  double siteY)
{
  auto matcher = vtkSmartPointer<vtkTerrainPatchMatcher>::New();
  matcher->SetInputDataObject(0, target);
  matcher->AddInputDataObject(1, exemplar);
  if (pool != nullptr)
  {
    matcher->SetInputDataObject(3, pool);
  }
  matcher->SetBackend(vtkTerrainPatchMatcher::CPU);
  matcher->SetMode(vtkTerrainPatchMatcher::FEATURE);
  matcher->SetSite(siteX, siteY);
  return matcher;
}

// What a matcher said when it failed its update (empty: it did not fail).
std::string errorsOfUpdate(vtkTerrainPatchMatcher* matcher)
{
  ErrorMessages errors;
  errors.watch(matcher);
  matcher->Update();
  return errors.text;
}

// What a matcher of the exemplar against itself, given this table, said.
std::string errorsWithPool(vtkImageData* exemplar, vtkTable* pool)
{
  return errorsOfUpdate(matcherFor(exemplar, exemplar, pool, 5000.0, 5000.0));
}

void expectSameColumns(vtkTable* a, vtkTable* b)
{
  ASSERT_EQ(a->GetNumberOfColumns(), b->GetNumberOfColumns());
  ASSERT_EQ(a->GetNumberOfRows(), b->GetNumberOfRows());
  for (vtkIdType c = 0; c < a->GetNumberOfColumns(); ++c)
  {
    auto* x = vtkDataArray::SafeDownCast(a->GetColumn(c));
    auto* y = vtkDataArray::SafeDownCast(b->GetColumnByName(a->GetColumnName(c)));
    ASSERT_NE(x, nullptr);
    ASSERT_NE(y, nullptr) << a->GetColumnName(c);
    for (vtkIdType r = 0; r < a->GetNumberOfRows(); ++r)
    {
      EXPECT_EQ(x->GetComponent(r, 0), y->GetComponent(r, 0))
        << a->GetColumnName(c) << ", row " << r;
    }
  }
}

} // namespace

TEST(CandidatePoolTable, TheMatcherGivenTheBuildersTableMatchesAsIfItBuiltThePool)
{
  vtkImageData* exemplar = colorado();
  const vtkSmartPointer<vtkTable> pool = candidateTable(exemplar, 80);
  ASSERT_GT(pool->GetNumberOfRows(), 1000);
  // Every row a variant of a site; the readable columns beside the exact ones.
  EXPECT_EQ(pool->GetColumnByName("Descriptor")->GetNumberOfComponents(), 256);
  EXPECT_EQ(pool->GetColumnByName("Along")->GetNumberOfComponents(), 64);
  // A site of the exemplar's own features: the exemplar as its own target
  // has the same feature there, so the match is a feature match.
  const double siteX = pool->GetColumnByName("X")->GetVariantValue(500).ToDouble();
  const double siteY = pool->GetColumnByName("Y")->GetVariantValue(500).ToDouble();

  const auto built = matcherFor(exemplar, exemplar, nullptr, siteX, siteY);
  built->Update();
  const auto given = matcherFor(exemplar, exemplar, pool, siteX, siteY);
  EXPECT_EQ(errorsOfUpdate(given), "");

  vtkTable* expected = built->GetMatches();
  ASSERT_GT(expected->GetNumberOfRows(), 0);
  EXPECT_EQ(expected->GetColumnByName("Feature")->GetVariantValue(0).ToInt(), 1);
  expectSameColumns(expected, given->GetMatches());
  // The cost map scores every candidate of the pool: all of them the same.
  vtkDataArray* mapBuilt = built->GetCostMap()->GetPointData()->GetArray("MatchCost");
  vtkDataArray* mapGiven = given->GetCostMap()->GetPointData()->GetArray("MatchCost");
  ASSERT_EQ(mapBuilt->GetNumberOfTuples(), mapGiven->GetNumberOfTuples());
  vtkIdType scored = 0;
  for (vtkIdType k = 0; k < mapBuilt->GetNumberOfTuples(); ++k)
  {
    const double a = mapBuilt->GetComponent(k, 0);
    const double b = mapGiven->GetComponent(k, 0);
    EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "cell " << k;
    scored += std::isnan(a) ? 0 : 1;
  }
  EXPECT_GT(scored, 100);
}

TEST(CandidatePoolTable, AChangedDescriptorChangesTheMatch)
{
  // The matcher reads the table's values, not only its shape: the same table
  // with one candidate's overlap summary and profiles scaled gives other costs.
  vtkImageData* exemplar = colorado();
  const vtkSmartPointer<vtkTable> pool = candidateTable(exemplar, 80);
  const double siteX = pool->GetColumnByName("X")->GetVariantValue(500).ToDouble();
  const double siteY = pool->GetColumnByName("Y")->GetVariantValue(500).ToDouble();
  const auto before = matcherFor(exemplar, exemplar, pool, siteX, siteY);
  before->Update();
  vtkNew<vtkTable> changed;
  changed->DeepCopy(pool);
  auto* along = vtkFloatArray::SafeDownCast(changed->GetColumnByName("Along"));
  for (vtkIdType v = 0; v < along->GetNumberOfValues(); ++v)
  {
    along->SetValue(v, 3.0f * along->GetValue(v));
  }
  const auto after = matcherFor(exemplar, exemplar, changed, siteX, siteY);
  after->Update();
  vtkTable* a = before->GetMatches();
  vtkTable* b = after->GetMatches();
  ASSERT_GT(a->GetNumberOfRows(), 0);
  ASSERT_GT(b->GetNumberOfRows(), 0);
  EXPECT_NE(a->GetColumnByName("Cost")->GetVariantValue(0).ToDouble(),
    b->GetColumnByName("Cost")->GetVariantValue(0).ToDouble());
}

TEST(CandidatePoolTable, TheMatcherRefusesAPoolOfAnotherPatchSize)
{
  vtkImageData* exemplar = colorado();
  const vtkSmartPointer<vtkTable> pool = candidateTable(exemplar, 64);
  const auto matcher = matcherFor(exemplar, exemplar, pool, 5000.0, 5000.0);
  const std::string errors = errorsOfUpdate(matcher);
  EXPECT_NE(errors.find("built for patches of 64 cells, not 80"), std::string::npos) << errors;
  EXPECT_EQ(matcher->GetMatches()->GetNumberOfRows(), 0);
}

TEST(CandidatePoolTable, TheMatcherRefusesAPoolCutFromOtherHeights)
{
  vtkImageData* exemplar = colorado();
  const vtkSmartPointer<vtkTable> pool = candidateTable(exemplar, 80);
  // The same grid, one height a metre higher: not the exemplar the pool knows.
  vtkNew<vtkImageData> other;
  other->DeepCopy(exemplar);
  vtkDataArray* z = other->GetPointData()->GetArray("Elevation");
  z->SetComponent(0, 0, z->GetComponent(0, 0) + 1.0);
  const std::string errors = errorsWithPool(other, pool);
  EXPECT_NE(errors.find("cut from other heights than exemplar 0"), std::string::npos) << errors;
}

TEST(CandidatePoolTable, TheMatcherRefusesATableThatIsNotAWholePool)
{
  vtkImageData* exemplar = colorado();
  const vtkSmartPointer<vtkTable> pool = candidateTable(exemplar, 80);
  {
    vtkNew<vtkTable> noDescriptor;
    noDescriptor->DeepCopy(pool);
    noDescriptor->RemoveColumnByName("Descriptor");
    const std::string errors = errorsWithPool(exemplar, noDescriptor);
    EXPECT_NE(errors.find("no column Descriptor of 256"), std::string::npos) << errors;
  }
  {
    // A centre moved off its exemplar: the cost map would be written out of bounds.
    vtkNew<vtkTable> moved;
    moved->DeepCopy(pool);
    vtkFloatArray::SafeDownCast(moved->GetColumnByName("CellX"))->SetValue(7, 1.0e6f);
    const std::string errors = errorsWithPool(exemplar, moved);
    EXPECT_NE(errors.find("Candidate 7 of the candidate pool"), std::string::npos) << errors;
  }
  {
    vtkNew<vtkTable> noSizes;
    noSizes->DeepCopy(pool);
    noSizes->GetFieldData()->RemoveArray("ExemplarWidth");
    const std::string errors = errorsWithPool(exemplar, noSizes);
    EXPECT_NE(errors.find("lacks ExemplarWidth: connect"), std::string::npos) << errors;
  }
}
