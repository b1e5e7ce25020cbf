#include "Geodesy.h"

#include "Constants.h"

#include <cmath>

namespace tsynth
{

MetresPerDegree metresPerDegree(double latitudeDeg, double a, double invF)
{
  const double f = invF > 0.0 ? 1.0 / invF : 0.0;
  const double e2 = f * (2.0 - f);
  const double phi = latitudeDeg * kPi / 180.0;
  const double s = std::sin(phi);
  const double w = 1.0 - e2 * s * s;
  const double primeVertical = a / std::sqrt(w);
  const double meridional = a * (1.0 - e2) / (w * std::sqrt(w));
  MetresPerDegree m;
  m.east = primeVertical * std::cos(phi) * kPi / 180.0;
  m.north = meridional * kPi / 180.0;
  return m;
}

} // namespace tsynth
