// smoothLarge (Kernels/Core/Smoothing.cxx) on a real terrain mirror-tiled to
// 1024 x 1024 and 4096 x 4096, against the way it smoothed before, written
// here as the reference: a plane of weights summed beside the values, and the
// column passes on one thread. Checks the two give the same heights to the bit
// and prints their ratio; once more on a terrain with nodata (where the
// weights still take a plane).
// Usage: tsynth_bench_smoothing [DEM] [repetitions]
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Core/Smoothing.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace tsynth;
using bench::bestSeconds;

namespace
{

void referenceLine(double* v, std::size_t n, std::size_t stride, int width)
{
  std::vector<double> sum(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k)
  {
    sum[k + 1] = sum[k] + v[k * stride];
  }
  const std::size_t r = static_cast<std::size_t>(width / 2);
  for (std::size_t k = 0; k < n; ++k)
  {
    v[k * stride] = sum[std::min(n, k + r + 1)] - sum[k >= r ? k - r : 0];
  }
}

// Every column at once, one thread, a ring of the rows the window drops.
void referenceColumns(std::vector<double>& v, std::size_t w, std::size_t h, int width)
{
  const std::size_t r = static_cast<std::size_t>(width / 2);
  const std::size_t kept = r + 1;
  const bool drops = kept < h;
  std::vector<double> sum(w, 0.0);
  std::vector<double> ring(drops ? kept * w : 0, 0.0);
  for (std::size_t j = 0; j < std::min(h, r); ++j)
  {
    for (std::size_t i = 0; i < w; ++i)
    {
      sum[i] += v[j * w + i];
    }
  }
  for (std::size_t j = 0; j < h; ++j)
  {
    double* row = v.data() + j * w;
    if (j + r < h)
    {
      for (std::size_t i = 0; i < w; ++i)
      {
        sum[i] += v[(j + r) * w + i];
      }
    }
    if (drops)
    {
      double* slot = ring.data() + (j % kept) * w;
      for (std::size_t i = 0; j >= kept && i < w; ++i)
      {
        sum[i] -= slot[i];
      }
      std::copy(row, row + w, slot);
    }
    std::copy(sum.begin(), sum.end(), row);
  }
}

Heightfield referenceSmooth(const Heightfield& hf, double sigma)
{
  const std::size_t w = static_cast<std::size_t>(hf.width);
  const std::size_t h = static_cast<std::size_t>(hf.height);
  std::vector<double> value(hf.size());
  std::vector<double> weight(hf.size());
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    const bool ok = hf.isValid(k) && std::isfinite(hf.z[k]);
    value[k] = ok ? hf.z[k] : 0.0;
    weight[k] = ok ? 1.0 : 0.0;
  }
  const std::array<int, kBoxPasses> widths = boxWidths(sigma); // the same boxes
#pragma omp parallel for schedule(static)
  for (std::size_t j = 0; j < h; ++j)
  {
    for (int width : widths)
    {
      referenceLine(value.data() + j * w, w, 1, width);
      referenceLine(weight.data() + j * w, w, 1, width);
    }
  }
  for (int width : widths)
  {
    referenceColumns(value, w, h, width);
    referenceColumns(weight, w, h, width);
  }
  Heightfield out = hf;
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    if (hf.isValid(k) && weight[k] > 0.0)
    {
      out.z[k] = static_cast<float>(value[k] / weight[k]);
    }
  }
  return out;
}

bool sameBits(const Heightfield& a, const Heightfield& b)
{
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (a.isValid(k) && std::memcmp(&a.z[k], &b.z[k], sizeof(float)) != 0)
    {
      return false;
    }
  }
  return true;
}

// Nodata in a few blocks, as a DEM's sea or voids.
Heightfield withHoles(Heightfield hf)
{
  hf.valid.assign(hf.size(), 1);
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      if ((i / 97 + j / 131) % 7 == 0)
      {
        hf.valid[hf.index(i, j)] = 0;
        hf.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  return hf;
}

void compare(const char* label, const Heightfield& hf, double sigma, int repetitions)
{
  Heightfield ours, theirs;
  const double a = bestSeconds(repetitions, [&] { ours = smoothLarge(hf, sigma); });
  const double b = bestSeconds(repetitions, [&] { theirs = referenceSmooth(hf, sigma); });
  std::printf("%-22s %5d x %-5d sigma %5.1f: %7.1f ms, reference %7.1f ms, ratio %.2f, %s\n",
    label,
    hf.width,
    hf.height,
    sigma,
    1e3 * a,
    1e3 * b,
    a / b,
    sameBits(ours, theirs) ? "same bits" : "DIFFERENT");
}

} // namespace

int main(int argc, char** argv)
{
  const std::string path =
    argc > 1 ? argv[1] : std::string(TSYNTH_BUNDLED_DATA) + "/dems/colorado.png";
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  Heightfield dem;
  try
  {
    dem = readHeightfield(path);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tsynth_bench_smoothing: %s\n", e.what());
    return 1;
  }
  std::printf("smoothLarge against the reference (weights in a plane, columns on one thread), "
              "best of %d, %d threads\n",
    repetitions,
    omp_get_max_threads());
  for (int size : { 1024, 4096 })
  {
    const Heightfield tile = bench::mirrorTile(dem, size);
    for (double sigma : { 4.0, 40.0 })
    {
      compare("no nodata", tile, sigma, size > 1024 ? std::min(repetitions, 3) : repetitions);
    }
    compare("nodata in blocks", withHoles(tile), 16.0, size > 1024 ? 1 : repetitions);
  }
  return 0;
}
