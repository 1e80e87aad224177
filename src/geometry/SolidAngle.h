// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The signed solid angle of a triangle seen from a point, after Van Oosterom and Strackee, "The
/// solid angle of a plane triangle", IEEE Transactions on Biomedical Engineering 30(2), 1983. Summed
/// over a closed surface and divided by 4π it is the generalised winding number of the point
/// (Jacobson, Kavan and Sorkine-Hornung, "Robust inside-outside segmentation using generalized
/// winding numbers", 2013): near ±1 inside, near 0 outside, with no unlucky directions as a ray's
/// parity has. No deviation: atan2 of the published numerator and denominator keeps the sign and
/// the full range (−2π, 2π).

#include <thintool/core/Math.h>

#include <cmath>

namespace thintool {

/// The solid angle of triangle (a, b, c), each corner given relative to the viewpoint; positive
/// when the corners turn counter-clockwise seen from it.
inline Real triangleSolidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real la = length(a);
  const Real lb = length(b);
  const Real lc = length(c);
  const Real numerator = dot(a, cross(b, c));
  const Real denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * std::atan2(numerator, denominator);
}

}  // namespace thintool
