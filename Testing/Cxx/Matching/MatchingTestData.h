// Helpers shared by the Matching tests: crops of the bundled Colorado DEM and a hand-made
// one-candidate pool and query whose cost the formula gives term by term.
#pragma once

#include "Core/Constants.h"
#include "Core/HeightfieldIO.h"
#include "Matching/CandidatePool.h"
#include "TestData.h"

namespace tsynth::test::matching
{

inline Heightfield crop(const Heightfield& hf, int x0, int y0, int w, int h)
{
  Heightfield out(w, h);
  out.cellX = hf.cellX;
  out.cellY = hf.cellY;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      out.at(i, j) = hf.at(x0 + i, y0 + j);
    }
  }
  return out;
}

inline const Heightfield& colorado()
{
  static const Heightfield hf =
    readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  return hf;
}

// A one-candidate pool filled by hand, to check the cost formula term by term.
inline CandidatePool handPool()
{
  CandidatePool p;
  p.patchSize = 80;
  p.heightScale = 10.0;
  p.exemplars.push_back({ "hand", 100, 100, 0, 1 });
  p.exemplar = { 0 };
  p.site = { 0 };
  p.variant = { 0 };
  p.kind = { static_cast<int>(NodeKind::Path) };
  p.type = { 1 };
  p.arms = { 2 };
  p.centreX = { 50 };
  p.centreY = { 50 };
  p.angles = { 0.0f, static_cast<float>(kPi), 0.0f, 0.0f };
  p.along.assign(kMaxArms * kAlongSamples, 0.0f);
  p.across.assign(kMaxArms * kAcrossSamples, 0.0f);
  p.noise = { 100.0f, 0.0f, 0.0f };
  p.descriptor.assign(kDescriptorSize, 1000.0f);
  p.landform.assign(kLandformStride, 0.0f);
  p.landform[3] = 30.0f; // one landform sample 30 m above the centre
  return p;
}

// The hand pool with a second landform sample, in the second lane of 16.
inline CandidatePool handPoolWithLandform()
{
  CandidatePool p = handPool();
  p.landform[20] = -5.0f; // 5 m below the centre
  return p;
}

inline FeatureQuery handQuery()
{
  FeatureQuery q;
  q.type = 1;
  q.kind = static_cast<int>(NodeKind::Path);
  q.arms = 2;
  q.angles = { 0.1f, static_cast<float>(kPi) + 0.1f, 0.0f, 0.0f };
  q.along.fill(0.0f);
  q.across.fill(0.0f);
  for (int k = 0; k < 2 * kAlongSamples; ++k)
  {
    q.along[static_cast<std::size_t>(k)] = 2.0f;
  }
  for (int k = 0; k < 2 * kAcrossSamples; ++k)
  {
    q.across[static_cast<std::size_t>(k)] = 2.0f;
  }
  q.noise = { 0.0f, 0.0f, 0.0f };
  q.descriptor.fill(1005.0f);
  q.landform[3] = 10.0f; // the target has it 10 m above
  q.landformWeight.fill(0.0f);
  q.landformWeight[3] = 0.5f;
  q.weight.fill(1.0f);
  return q;
}

} // namespace tsynth::test::matching
