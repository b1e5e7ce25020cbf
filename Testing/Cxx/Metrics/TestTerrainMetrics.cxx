// Tests of Kernels/Metrics/TerrainMetrics.cxx.
#include "Metrics/TerrainMetrics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tsynth;

namespace
{

// z = c x^2 (cells of 1 m): Laplacian 2c everywhere, slopes growing with x.
Heightfield parabola(int w, int h, double c)
{
  Heightfield hf(w, h);
  hf.cellX = 1.0;
  hf.cellY = 1.0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(c * i * i);
    }
  }
  return hf;
}

} // namespace

TEST(Metrics, SeamIndexAgainstPooledExemplars)
{
  const Heightfield gentle = parabola(60, 40, 0.01);
  const Heightfield sharp = parabola(60, 40, 0.03);
  // Three times the curvature of its only exemplar; as curved as the pool's most curved.
  EXPECT_NEAR(seamIndex(sharp, gentle), 3.0, 1e-3);
  EXPECT_NEAR(seamIndex(sharp, { &gentle, &sharp }), 1.0, 1e-3);
  EXPECT_NEAR(seamIndex(gentle, { &gentle, &gentle }), 1.0, 1e-6);
}

TEST(Metrics, SlopeDistanceAgainstPooledExemplars)
{
  const Heightfield a = parabola(60, 40, 0.01);
  const Heightfield b = parabola(60, 40, 0.05);
  EXPECT_NEAR(slopeDistance(a, a), 0.0, 1e-12);
  EXPECT_NEAR(slopeDistance(a, { &a, &a }), 0.0, 1e-12); // pooling copies changes nothing
  const double alone = slopeDistance(a, b);
  const double pooled = slopeDistance(a, { &a, &b });
  EXPECT_GT(alone, 0.5);
  // Half of the pool is a itself: the CDF gap halves, the reference mean slope
  // falls to the pool's, so the distance is between zero and the distance to b.
  EXPECT_GT(pooled, 0.05);
  EXPECT_LT(pooled, alone);
}

TEST(Metrics, ExemplarPitDensityIsAreaWeighted)
{
  Heightfield flat(50, 50, 10.0f);
  Heightfield pitted(50, 100, 10.0f);
  for (int j = 2; j < 98; j += 4)
  {
    for (int i = 2; i < 48; i += 4)
    {
      pitted.at(i, j) = 0.0f;
    }
  }
  const double p = pitDensity(pitted);
  ASSERT_GT(p, 0.0);
  const TerrainEvaluation e = evaluateTerrain(flat, { &flat, &pitted }, nullptr);
  EXPECT_NEAR(e.exemplarPitDensity, p * 5000.0 / 7500.0, 1e-9);
  EXPECT_EQ(e.pitDensity, 0.0);
}
