#include "Orientation.h"

#include "../Core/Constants.h"
#include "../Features/Profiles.h"

#include <cmath>
#include <limits>

namespace tsynth
{

double Variant::placedAngle(double exemplarAngle) const
{
  // The placed direction d satisfies m * d = exemplar direction: d = m^-1 e.
  const double ex = std::cos(exemplarAngle);
  const double ey = std::sin(exemplarAngle);
  const double det = m[0] * m[3] - m[1] * m[2];
  const double dx = (m[3] * ex - m[1] * ey) / det;
  const double dy = (-m[2] * ex + m[0] * ey) / det;
  return std::atan2(dy, dx);
}

Variant variant(int k)
{
  Variant v;
  v.id = k;
  if (k < 8)
  {
    // Content rotated by +theta as placed is read through R(-theta).
    const double theta = k * kPi / 4.0;
    double c = std::cos(theta);
    double s = std::sin(theta);
    if (k % 2 == 0)
    {
      c = std::round(c);
      s = std::round(s);
    }
    v.m = { c, s, -s, c };
    v.exact = k % 2 == 0;
  }
  else if (k == 8)
  {
    v.m = { -1.0, 0.0, 0.0, 1.0 };
    v.mirrored = true;
  }
  else
  {
    v.m = { 1.0, 0.0, 0.0, -1.0 };
    v.mirrored = true;
  }
  return v;
}

Heightfield orientExemplar(const Heightfield& ex,
  const Variant& v,
  double* centreX,
  double* centreY)
{
  // Bounding box of the placed exemplar: corners mapped by m^-1.
  const double hw = 0.5 * (ex.width - 1);
  const double hh = 0.5 * (ex.height - 1);
  const double det = v.m[0] * v.m[3] - v.m[1] * v.m[2];
  double maxU = 0.0;
  double maxV = 0.0;
  for (int sx : { -1, 1 })
  {
    for (int sy : { -1, 1 })
    {
      const double a = sx * hw;
      const double b = sy * hh;
      maxU = std::max(maxU, std::abs((v.m[3] * a - v.m[1] * b) / det));
      maxV = std::max(maxV, std::abs((-v.m[2] * a + v.m[0] * b) / det));
    }
  }
  const int w = static_cast<int>(std::ceil(2.0 * maxU - 1e-9)) + 1;
  const int h = static_cast<int>(std::ceil(2.0 * maxV - 1e-9)) + 1;
  Heightfield out(w, h, std::numeric_limits<float>::quiet_NaN());
  out.cellX = ex.cellX;
  out.cellY = ex.cellY;
  out.valid.assign(out.size(), 0);
  const double cu = 0.5 * (w - 1);
  const double cv = 0.5 * (h - 1);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double su = 0.0;
      double sv = 0.0;
      v.toSource(i - cu, j - cv, su, sv);
      const double x = hw + su;
      const double y = hh + sv;
      float z = std::numeric_limits<float>::quiet_NaN();
      if (v.exact)
      {
        const long xi = std::lround(x);
        const long yi = std::lround(y);
        if (xi >= 0 && yi >= 0 && xi < ex.width && yi < ex.height &&
          ex.isValid(static_cast<int>(xi), static_cast<int>(yi)))
        {
          z = ex.at(static_cast<int>(xi), static_cast<int>(yi));
        }
      }
      else
      {
        z = sampleBilinear(ex, x, y);
      }
      if (!std::isnan(z))
      {
        out.at(i, j) = z;
        out.valid[out.index(i, j)] = 1;
      }
    }
  }
  if (centreX != nullptr)
  {
    *centreX = cu;
  }
  if (centreY != nullptr)
  {
    *centreY = cv;
  }
  normaliseMask(out);
  return out;
}

} // namespace tsynth
