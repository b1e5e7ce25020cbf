// The 10 patch variants of Tasse's thesis: 8 rotations by 45 degrees and the two
// unrotated mirrors. A variant maps an offset (u, v) from the centre of the
// placed patch to the offset in the exemplar it is read from.
#pragma once

#include "../Core/Heightfield.h"

#include <array>

namespace tsynth
{

constexpr int kVariantCount = 10;

struct Variant
{
  int id = 0;
  // source offset = m * (u, v): m = {m00, m01, m10, m11}
  std::array<double, 4> m{ 1.0, 0.0, 0.0, 1.0 };
  bool mirrored = false;
  bool exact = true; // multiples of 90 degrees and mirrors read cells without interpolation

  void toSource(double u, double v, double& su, double& sv) const
  {
    su = m[0] * u + m[1] * v;
    sv = m[2] * u + m[3] * v;
  }
  // The direction, in the placed patch, of a feature leaving at `angle` in the exemplar.
  double placedAngle(double exemplarAngle) const;
};

// Variant k: 0..7 rotate the exemplar content by k * 45 degrees counter-clockwise
// as placed; 8 mirrors x (east-west); 9 mirrors y (north-south).
Variant variant(int k);

// The whole exemplar as seen through a variant, on a grid large enough to hold
// it (rotations by 45 degrees enlarge the bounding box); cells that fall outside
// the exemplar or on its nodata are invalid. Bilinear for 45-degree rotations,
// exact copies otherwise. `centreX/Y` receive where the exemplar's centre lands.
Heightfield orientExemplar(const Heightfield& exemplar,
  const Variant& v,
  double* centreX = nullptr,
  double* centreY = nullptr);

} // namespace tsynth
