#include "Hillshade.h"

#include "../Core/Constants.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

constexpr double kDegToRad = kPi / 180.0;

double lightOn(double p, double q, double azimuthDeg, double altitudeDeg)
{
  // Light direction (east, north, up) and the unnormalised normal (-p, -q, 1).
  const double az = azimuthDeg * kDegToRad;
  const double alt = altitudeDeg * kDegToRad;
  const double lx = std::sin(az) * std::cos(alt);
  const double ly = std::cos(az) * std::cos(alt);
  const double lz = std::sin(alt);
  const double dot = (-p * lx - q * ly + lz) / std::sqrt(1.0 + p * p + q * q);
  return std::max(0.0, dot);
}

} // namespace

ShadedRelief computeHillshade(const Heightfield& hf, const HillshadeOptions& options)
{
  ShadedRelief out;
  out.width = hf.width;
  out.height = hf.height;
  const std::size_t n = hf.size();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.shade.assign(n, nan);
  out.slopeDeg.assign(n, nan);
  const double sx = options.zFactor / (8.0 * hf.cellX);
  const double sy = options.zFactor / (8.0 * hf.cellY);
  const std::array<double, 4> azimuths = { 225.0, 270.0, 315.0, 360.0 };

  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      const std::size_t k = hf.index(i, j);
      if (!hf.isValid(k))
      {
        continue;
      }
      const double c = hf.z[k];
      auto usable = [&](int ii, int jj)
      { return ii >= 0 && jj >= 0 && ii < hf.width && jj < hf.height && hf.isValid(ii, jj); };
      // A missing neighbour (edge or nodata) is extrapolated linearly through
      // the centre from the opposite one; a missing diagonal with no opposite
      // comes from its two axis neighbours. Planes keep their exact gradient.
      auto direct = [&](int di, int dj, double& value)
      {
        if (usable(i + di, j + dj))
        {
          value = hf.at(i + di, j + dj);
          return true;
        }
        if (usable(i - di, j - dj))
        {
          value = 2.0 * c - hf.at(i - di, j - dj);
          return true;
        }
        return false;
      };
      auto axis = [&](int di, int dj)
      {
        double v = c;
        direct(di, dj, v);
        return v;
      };
      auto h = [&](int di, int dj)
      {
        double v = c;
        if (!direct(di, dj, v))
        {
          v = axis(di, 0) + axis(0, dj) - c;
        }
        return v;
      };
      // p = dz/dx (east), q = dz/dy (north); row j+1 is north of row j.
      const double p =
        ((h(1, 1) + 2.0 * h(1, 0) + h(1, -1)) - (h(-1, 1) + 2.0 * h(-1, 0) + h(-1, -1))) * sx;
      const double q =
        ((h(-1, 1) + 2.0 * h(0, 1) + h(1, 1)) - (h(-1, -1) + 2.0 * h(0, -1) + h(1, -1))) * sy;
      out.slopeDeg[k] = static_cast<float>(std::atan(std::hypot(p, q)) / kDegToRad);

      double shade = 0.0;
      if (options.multidirectional)
      {
        // Weight each light by sin^2 of its angle to the downhill direction
        // (Mark 1992): slopes facing across a light are lit by it the most.
        const double aspect = std::atan2(-p, -q);
        double weights = 0.0;
        for (double az : azimuths)
        {
          const double s = std::sin(aspect - az * kDegToRad);
          const double w = s * s;
          shade += w * lightOn(p, q, az, options.altitudeDeg);
          weights += w;
        }
        shade = weights > 0.0 ? shade / weights : lightOn(p, q, 315.0, options.altitudeDeg);
      }
      else
      {
        shade = lightOn(p, q, options.azimuthDeg, options.altitudeDeg);
      }
      out.shade[k] = static_cast<float>(shade);
    }
  }
  return out;
}

const std::vector<OptionRow>& hillshadeOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const HillshadeOptions d;
    using T = OptionType;
    return std::vector<OptionRow>{
      numberRow("Altitude", "--altitude", T::Real, d.altitudeDeg, 0.0, kMaxSunAltitudeDeg),
      numberRow("Azimuth", "--azimuth", T::Real, d.azimuthDeg, 0.0, kFullTurnDeg),
      switchRow("Multidirectional", "", d.multidirectional),
      numberRow("ZFactor", "--exaggeration", T::Real, d.zFactor, kMinZFactor, kMaxZFactor),
    };
  }();
  return rows;
}

} // namespace tsynth
