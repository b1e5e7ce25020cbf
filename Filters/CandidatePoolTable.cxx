#include "CandidatePoolTable.h"

#include "MatchingInputs.h"

#include "Core/Constants.h"
#include "Core/ContentHash.h"
#include "Core/Error.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkTable.h>
#include <vtkTypeUInt64Array.h>

#include <array>
#include <cmath>
#include <string>

namespace tsynth
{
namespace
{

// One of the pool's arrays as a table column: `components` values a row.
template<class T>
struct PoolColumn
{
  const char* name;
  int components;
  std::vector<T> CandidatePool::*values;
};

// The columns read back, written and read through this one list.
const std::array<PoolColumn<int>, 6> kIntColumns{ { { "Exemplar", 1, &CandidatePool::exemplar },
  { "Site", 1, &CandidatePool::site },
  { "Variant", 1, &CandidatePool::variant },
  { "Kind", 1, &CandidatePool::kind },
  { "FeatureType", 1, &CandidatePool::type },
  { "Arms", 1, &CandidatePool::arms } } };

const std::array<PoolColumn<float>, 7> kFloatColumns{ { { "CellX", 1, &CandidatePool::centreX },
  { "CellY", 1, &CandidatePool::centreY },
  { "Noise", kNoiseLevels, &CandidatePool::noise },
  { "Along", kMaxArms* kAlongSamples, &CandidatePool::along },
  { "Across", kMaxArms* kAcrossSamples, &CandidatePool::across },
  { "Descriptor", kDescriptorSize, &CandidatePool::descriptor },
  { "Landform", kLandformStride, &CandidatePool::landform } } };

// Arm directions are shown in degrees; radians to degrees and back in double
// precision returns every float exactly.
constexpr double kDegreesPerRadian = 180.0 / kPi;
std::string angleColumnName(int arm)
{
  return "Angle" + std::to_string(arm);
}

// The checksum of each exemplar's heights (hashHeightfield).
std::vector<std::uint64_t> heightChecksums(const ExemplarInputs& in)
{
  std::vector<std::uint64_t> sums;
  for (const Heightfield& h : in.heights)
  {
    ContentHasher hasher;
    hashHeightfield(hasher, h);
    sums.push_back(hasher.digest());
  }
  return sums;
}

template<class Array, class T>
void addColumn(vtkTable* table, const char* name, int components, const std::vector<T>& values)
{
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(
    static_cast<vtkIdType>(values.size() / static_cast<std::size_t>(components)));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  table->AddColumn(a);
}

template<class Array, class T>
void addFieldArray(vtkTable* table, const char* name, const std::vector<T>& values)
{
  vtkNew<Array> a;
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  table->GetFieldData()->AddArray(a);
}

// The table's column of this name, of this type and shape, for `rows` rows.
template<class Array>
Array* column(vtkTable* table, const std::string& name, int components, vtkIdType rows)
{
  auto* a = Array::SafeDownCast(table->GetColumnByName(name.c_str()));
  if (a == nullptr || a->GetNumberOfComponents() != components || a->GetNumberOfTuples() != rows)
  {
    throw Error("The candidate pool table has no column " + name + " of " +
      std::to_string(components) +
      " value(s) a row in the builder's number type: connect the "
      "Terrain Candidate Builder's output, unchanged.");
  }
  return a;
}

template<class Array>
Array* fieldArray(vtkTable* table, const char* name, vtkIdType values)
{
  auto* a = Array::SafeDownCast(table->GetFieldData()->GetAbstractArray(name));
  if (a == nullptr || a->GetNumberOfComponents() != 1 || a->GetNumberOfTuples() != values)
  {
    throw Error("The candidate pool table's field data lacks " + std::string(name) + " (" +
      std::to_string(values) +
      " value(s)): connect the Terrain Candidate Builder's output, unchanged.");
  }
  return a;
}

template<class Array, class T>
std::vector<T> valuesOf(Array* a)
{
  const auto n = static_cast<std::size_t>(a->GetNumberOfValues());
  return std::vector<T>(a->GetPointer(0), a->GetPointer(0) + n);
}

// The readable columns: the centre in metres and the arm directions in degrees.
void addReadableColumns(const CandidatePool& pool, const ExemplarInputs& in, vtkTable* table)
{
  const std::size_t n = pool.size();
  std::vector<double> x(n);
  std::vector<double> y(n);
  for (std::size_t c = 0; c < n; ++c)
  {
    const auto e = static_cast<std::size_t>(pool.exemplar[c]);
    x[c] = in.originX[e] + pool.centreX[c] * in.heights[e].cellX;
    y[c] = in.originY[e] + pool.centreY[c] * in.heights[e].cellY;
  }
  addColumn<vtkDoubleArray>(table, "X", 1, x);
  addColumn<vtkDoubleArray>(table, "Y", 1, y);
  for (int arm = 0; arm < kMaxArms; ++arm)
  {
    std::vector<double> degrees(n);
    for (std::size_t c = 0; c < n; ++c)
    {
      degrees[c] = arm < pool.arms[c]
        ? static_cast<double>(pool.angles[c * kMaxArms + static_cast<std::size_t>(arm)]) *
          kDegreesPerRadian
        : std::nan("");
    }
    addColumn<vtkDoubleArray>(table, angleColumnName(arm).c_str(), 1, degrees);
  }
}

// pool.angles from the degree columns: 0 past a candidate's arms, as built.
void readAngles(vtkTable* table, vtkIdType rows, CandidatePool& pool)
{
  const std::size_t n = pool.size();
  pool.angles.assign(n * kMaxArms, 0.0f);
  for (int arm = 0; arm < kMaxArms; ++arm)
  {
    const vtkDoubleArray* degrees = column<vtkDoubleArray>(table, angleColumnName(arm), 1, rows);
    for (std::size_t c = 0; c < n; ++c)
    {
      if (arm < pool.arms[c])
      {
        pool.angles[c * kMaxArms + static_cast<std::size_t>(arm)] =
          static_cast<float>(degrees->GetValue(static_cast<vtkIdType>(c)) / kDegreesPerRadian);
      }
    }
  }
}

// Each exemplar's size, checksum and run of candidates, from the field data
// and the Exemplar column (the builder writes each exemplar's candidates in one run).
void readExemplars(vtkTable* table, CandidatePool& pool)
{
  auto* widthArray =
    vtkIntArray::SafeDownCast(table->GetFieldData()->GetAbstractArray("ExemplarWidth"));
  if (widthArray == nullptr || widthArray->GetNumberOfTuples() == 0)
  {
    throw Error("The candidate pool table's field data lacks ExemplarWidth: connect the Terrain "
                "Candidate Builder's output, unchanged.");
  }
  const vtkIdType count = widthArray->GetNumberOfTuples();
  const vtkIntArray* widths = fieldArray<vtkIntArray>(table, "ExemplarWidth", count);
  const vtkIntArray* heights = fieldArray<vtkIntArray>(table, "ExemplarHeight", count);
  const vtkTypeUInt64Array* sums = fieldArray<vtkTypeUInt64Array>(table, "ExemplarChecksum", count);
  std::size_t first = 0;
  for (vtkIdType e = 0; e < count; ++e)
  {
    ExemplarInfo info;
    info.name = "exemplar " + std::to_string(e);
    info.width = widths->GetValue(e);
    info.height = heights->GetValue(e);
    info.heightsChecksum = sums->GetValue(e);
    info.firstCandidate = first;
    while (first < pool.size() && pool.exemplar[first] == static_cast<int>(e))
    {
      ++first;
    }
    info.candidateCount = first - info.firstCandidate;
    pool.exemplars.push_back(info);
  }
}

} // namespace

void writePoolTable(const CandidatePool& pool, const ExemplarInputs& in, vtkTable* table)
{
  table->Initialize();
  for (const PoolColumn<int>& c : kIntColumns)
  {
    addColumn<vtkIntArray>(table, c.name, c.components, pool.*c.values);
  }
  addReadableColumns(pool, in, table);
  for (const PoolColumn<float>& c : kFloatColumns)
  {
    addColumn<vtkFloatArray>(table, c.name, c.components, pool.*c.values);
  }
  addFieldArray<vtkDoubleArray>(table, "PatchSize", std::vector<double>{ 1.0 * pool.patchSize });
  addFieldArray<vtkDoubleArray>(table, "HeightScale", std::vector<double>{ pool.heightScale });
  std::vector<int> widths;
  std::vector<int> heights;
  for (const ExemplarInfo& e : pool.exemplars)
  {
    widths.push_back(e.width);
    heights.push_back(e.height);
  }
  addFieldArray<vtkIntArray>(table, "ExemplarWidth", widths);
  addFieldArray<vtkIntArray>(table, "ExemplarHeight", heights);
  addFieldArray<vtkTypeUInt64Array>(table, "ExemplarChecksum", heightChecksums(in));
}

CandidatePool poolFromTable(vtkTable* table)
{
  const vtkIdType rows = table->GetNumberOfRows();
  CandidatePool pool;
  pool.patchSize = static_cast<int>(fieldArray<vtkDoubleArray>(table, "PatchSize", 1)->GetValue(0));
  pool.heightScale = fieldArray<vtkDoubleArray>(table, "HeightScale", 1)->GetValue(0);
  for (const PoolColumn<int>& c : kIntColumns)
  {
    pool.*c.values =
      valuesOf<vtkIntArray, int>(column<vtkIntArray>(table, c.name, c.components, rows));
  }
  for (const PoolColumn<float>& c : kFloatColumns)
  {
    pool.*c.values =
      valuesOf<vtkFloatArray, float>(column<vtkFloatArray>(table, c.name, c.components, rows));
  }
  readAngles(table, rows, pool);
  readExemplars(table, pool);
  return pool;
}

} // namespace tsynth
