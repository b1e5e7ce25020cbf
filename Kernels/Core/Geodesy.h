// Metric size of a degree on an ellipsoid, for rasters in geographic coordinates.
#pragma once

namespace tsynth
{

struct MetresPerDegree
{
  double east = 0.0;  // along a parallel
  double north = 0.0; // along a meridian
};

// Lengths of one degree of longitude and latitude at a latitude (degrees) on an
// ellipsoid with semi-major axis a (metres) and inverse flattening invF
// (0 means a sphere). Uses the prime-vertical and meridional radii of curvature.
MetresPerDegree metresPerDegree(double latitudeDeg,
  double a = 6378137.0,
  double invF = 298.257223563);

} // namespace tsynth
