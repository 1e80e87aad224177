// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Continuous collision queries between a static feature and a linearly moving one, the form they
/// take in a tool's own frame: the tool does not move there, the soft surface does.
///
/// - A moving point against a convex solid: Cyrus & Beck, "Generalized two- and three-dimensional
///   clipping", Computers & Graphics 3(1), 1978, on the segment the point travels.
/// - A static point against a moving triangle, and a static edge against a moving edge: the time
///   the four points become coplanar is a root of a cubic (point–triangle) or of a quadratic
///   (edge–edge, since one edge does not move), after Provot, "Collision and self-collision
///   handling in cloth model dedicated to design garments", 1997. Roots are bracketed between the
///   polynomial's turning points and refined by regula falsi (the Illinois variant, which keeps the
///   root bracketed), so no root in [0, 1] is lost to a closed-form formula's cancellation; a turning point within kCoplanarTolerance of zero counts
///   as a (grazing) root. At each root the features must overlap within kOverlapTolerance of
///   their size.
/// Conservative by construction: a crossing is reported if the features meet within the
/// tolerances, so a miss is a bug and an extra hit only costs a constraint that is already met.

#include "geometry/ConvexMesh.h"

#include <thintool/core/Math.h>

#include <vector>

namespace thintool {

/// Relative tolerances of the continuous queries (fractions of the features' sizes).
inline constexpr Real kCoplanarTolerance = 1e-10;
inline constexpr Real kOverlapTolerance = 1e-6;

struct ClipResult {
  bool hit = false;       ///< the segment meets the solid
  Real enter = 0;         ///< fraction where it enters (0 when it starts inside)
  Real leave = 1;         ///< fraction where it leaves (1 when it ends inside)
  Index enterPlane = kInvalidIndex;  ///< plane it enters through; kInvalidIndex when it starts inside
  Index leavePlane = kInvalidIndex;  ///< plane it leaves through; kInvalidIndex when it ends inside
};

/// Clips the segment a → b against the convex solid {x : plane.signedDistance(x) <= grow, all planes}.
ClipResult clipSegmentConvex(const std::vector<Plane>& planes, Real grow, const Vec3& a, const Vec3& b);

struct PointTriangleCcd {
  bool hit = false;
  Real t = 0;         ///< fraction of the step at first contact
  Vec3 barycentric;   ///< where the point meets the triangle then
};

/// First time in [0, 1] at which the static point p lies on the triangle moving linearly from
/// (a0, b0, c0) to (a1, b1, c1).
PointTriangleCcd pointTriangleCcd(const Vec3& p, const Vec3& a0, const Vec3& b0, const Vec3& c0, const Vec3& a1,
                                  const Vec3& b1, const Vec3& c1);

struct EdgeEdgeCcd {
  bool hit = false;
  Real t = 0;  ///< fraction of the step at first contact
  Real s = 0;  ///< where on the moving edge (0 at its first end)
  Real u = 0;  ///< where on the static edge
};

/// First time in [0, 1] at which the static edge p0–p1 and the edge moving linearly from
/// e0a–e1a to e0b–e1b intersect.
EdgeEdgeCcd edgeEdgeCcd(const Vec3& p0, const Vec3& p1, const Vec3& e0a, const Vec3& e1a, const Vec3& e0b,
                        const Vec3& e1b);

/// Closest points of segments p0–p1 and q0–q1 (Ericson, "Real-Time Collision Detection" §5.1.9):
/// parameters u on p, s on q, both clamped to [0, 1].
void closestPointsOfSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Real& outU,
                             Real& outS);

/// Barycentric coordinates of p's projection onto the plane of (a, b, c); false for a degenerate triangle.
bool projectOntoTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& outBarycentric);

/// projectOntoTriangle for many points onto one triangle: what depends on the triangle alone is
/// computed once, the division included.
class TriangleProjector {
 public:
  TriangleProjector() = default;
  TriangleProjector(const Vec3& a, const Vec3& b, const Vec3& c);
  bool project(const Vec3& p, Vec3& outBarycentric) const;

 private:
  Vec3 m_a, m_ab, m_ac;
  Real m_abab = 0, m_abac = 0, m_acac = 0, m_inverseDenominator = 0;
  bool m_degenerate = true;
};

}  // namespace thintool
