// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "geometry/Ccd.h"

#include <algorithm>
#include <cmath>

namespace thintool {

namespace {

constexpr int kRefinements = 60;  // at most; the Illinois method needs far fewer
constexpr int kCoplanarMotionSamples = 8;  // when the features stay coplanar all step

Real cube(Real x) { return x * x * x; }

// c[0] + c[1] t + c[2] t² + c[3] t³
Real evaluate(const Real (&c)[4], Real t) { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }

// The roots of f in [0, 1], ascending, up to three: bracketed between the turning points and
// refined by regula falsi; a turning point within tolerance of zero counts as a root.
int rootsInUnitInterval(const Real (&c)[4], Real tolerance, Real (&outRoots)[5]) {
  Real breaks[4] = {0, 1, 1, 1};
  int breakCount = 1;
  // Turning points: 3 c3 t² + 2 c2 t + c1 = 0.
  const Real qa = 3 * c[3];
  const Real qb = 2 * c[2];
  const Real qc = c[1];
  Real turning[2];
  int turningCount = 0;
  if (std::abs(qa) > 0) {
    const Real discriminant = qb * qb - 4 * qa * qc;
    if (discriminant >= 0) {
      // The cancellation-free pair of the quadratic formula.
      const Real q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
      turning[turningCount++] = q / qa;
      if (q != 0) turning[turningCount++] = qc / q;
    }
  } else if (std::abs(qb) > 0) {
    turning[turningCount++] = -qc / qb;
  }
  std::sort(turning, turning + turningCount);
  for (int k = 0; k < turningCount; ++k) {
    if (turning[k] > 0 && turning[k] < 1) breaks[breakCount++] = turning[k];
  }
  breaks[breakCount++] = 1;

  int count = 0;
  auto add = [&](Real t) {
    if (count == 0 || t > outRoots[count - 1]) outRoots[count++] = t;
  };
  for (int k = 0; k + 1 < breakCount; ++k) {
    Real low = breaks[k];
    Real high = breaks[k + 1];
    Real fLow = evaluate(c, low);
    const Real fHigh = evaluate(c, high);
    if (std::abs(fLow) <= tolerance) {
      add(low);
      continue;
    }
    if (std::abs(fHigh) <= tolerance) {
      add(high);
      continue;
    }
    if ((fLow < 0) == (fHigh < 0)) {
      continue;
    }
    // Illinois regula falsi: the bracket always holds the root, and halving the stale end's
    // value keeps it from converging from one side only.
    Real fHighBracket = fHigh;
    Real root = low;
    int staleSide = 0;
    for (int i = 0; i < kRefinements; ++i) {
      root = (low * fHighBracket - high * fLow) / (fHighBracket - fLow);
      const Real fRoot = evaluate(c, root);
      if (std::abs(fRoot) <= tolerance || high - low <= 1e-15) {
        break;
      }
      if ((fRoot < 0) == (fLow < 0)) {
        low = root;
        fLow = fRoot;
        if (staleSide == -1) fHighBracket *= 0.5;
        staleSide = -1;
      } else {
        high = root;
        fHighBracket = fRoot;
        if (staleSide == 1) fLow *= 0.5;
        staleSide = 1;
      }
    }
    add(root);
  }
  return count;
}

Real determinant(const Vec3& a, const Vec3& b, const Vec3& c) { return dot(a, cross(b, c)); }

// Calls meetsAt(t) at the coplanarity polynomial's roots in [0, 1], earliest first, until it
// returns true. Coplanar all step (the polynomial vanishes), the features can only meet within
// their common plane, and the motion is sampled instead.
template <class MeetsAt>
void firstMeeting(const Real (&c)[4], Real coplanarTolerance, MeetsAt& meetsAt) {
  if (std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]) <= coplanarTolerance) {
    for (int k = 0; k <= kCoplanarMotionSamples; ++k) {
      if (meetsAt(Real(k) / kCoplanarMotionSamples)) return;
    }
    return;
  }
  Real roots[5];
  const int count = rootsInUnitInterval(c, coplanarTolerance, roots);
  for (int k = 0; k < count; ++k) {
    if (meetsAt(roots[k])) return;
  }
}

}  // namespace

ClipResult clipSegmentConvex(const std::vector<Plane>& planes, Real grow, const Vec3& a, const Vec3& b) {
  ClipResult result;
  Real enter = 0;
  Real leave = 1;
  Index enterPlane = kInvalidIndex;
  Index leavePlane = kInvalidIndex;
  for (Index p = 0; p < planes.size(); ++p) {
    const Real da = planes[p].signedDistance(a) - grow;
    const Real db = planes[p].signedDistance(b) - grow;
    if (da > 0 && db > 0) {
      return result;  // entirely outside this face
    }
    if (da > 0) {  // entering through this face
      const Real t = da / (da - db);
      if (t >= enter) {
        enter = t;
        enterPlane = p;
      }
    } else if (db > 0) {  // leaving through it
      const Real t = da / (da - db);
      if (t < leave) {
        leave = t;
        leavePlane = p;
      }
    }
  }
  if (enter > leave) {
    return result;
  }
  result.hit = true;
  result.enter = enter;
  result.leave = leave;
  result.enterPlane = enterPlane;
  result.leavePlane = leavePlane;
  return result;
}

bool projectOntoTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& outBarycentric) {
  return TriangleProjector(a, b, c).project(p, outBarycentric);
}

TriangleProjector::TriangleProjector(const Vec3& a, const Vec3& b, const Vec3& c)
    : m_a(a), m_ab(b - a), m_ac(c - a) {
  m_abab = dot(m_ab, m_ab);
  m_abac = dot(m_ab, m_ac);
  m_acac = dot(m_ac, m_ac);
  const Real denominator = m_abab * m_acac - m_abac * m_abac;
  m_degenerate = !(denominator > 1e-24 * m_abab * m_acac);
  m_inverseDenominator = m_degenerate ? 0 : 1 / denominator;
}

bool TriangleProjector::project(const Vec3& p, Vec3& outBarycentric) const {
  if (m_degenerate) {
    return false;
  }
  const Vec3 ap = p - m_a;
  const Real apab = dot(ap, m_ab);
  const Real apac = dot(ap, m_ac);
  const Real wb = (m_acac * apab - m_abac * apac) * m_inverseDenominator;
  const Real wc = (m_abab * apac - m_abac * apab) * m_inverseDenominator;
  outBarycentric = {1 - wb - wc, wb, wc};
  return true;
}

void closestPointsOfSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Real& outU,
                             Real& outS) {
  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const Real a = dot(d1, d1);
  const Real e = dot(d2, d2);
  const Real f = dot(d2, r);
  Real u = 0;
  Real s = 0;
  if (a <= 0 && e <= 0) {
    outU = 0;
    outS = 0;
    return;
  }
  if (a <= 0) {
    s = std::clamp(f / e, Real(0), Real(1));
  } else {
    const Real c = dot(d1, r);
    if (e <= 0) {
      u = std::clamp(-c / a, Real(0), Real(1));
    } else {
      const Real b = dot(d1, d2);
      const Real denominator = a * e - b * b;
      u = denominator > 0 ? std::clamp((b * f - c * e) / denominator, Real(0), Real(1)) : 0;
      s = (b * u + f) / e;
      if (s < 0) {
        s = 0;
        u = std::clamp(-c / a, Real(0), Real(1));
      } else if (s > 1) {
        s = 1;
        u = std::clamp((b - c) / a, Real(0), Real(1));
      }
    }
  }
  outU = u;
  outS = s;
}

PointTriangleCcd pointTriangleCcd(const Vec3& p, const Vec3& a0, const Vec3& b0, const Vec3& c0, const Vec3& a1,
                                  const Vec3& b1, const Vec3& c1) {
  PointTriangleCcd result;
  // Relative to the point, the triangle's corners move linearly; the four points are coplanar
  // where det(A, B, C) vanishes, a cubic in t.
  const Vec3 A0 = a0 - p, B0 = b0 - p, C0 = c0 - p;
  const Vec3 dA = a1 - a0, dB = b1 - b0, dC = c1 - c0;
  const Real c[4] = {determinant(A0, B0, C0),
                     determinant(dA, B0, C0) + determinant(A0, dB, C0) + determinant(A0, B0, dC),
                     determinant(dA, dB, C0) + determinant(dA, B0, dC) + determinant(A0, dB, dC),
                     determinant(dA, dB, dC)};
  const Real size = std::max({length(A0), length(B0), length(C0), length(A0 + dA), length(B0 + dB),
                              length(C0 + dC), Real(1e-300)});
  const Real coplanarTolerance = kCoplanarTolerance * cube(size);

  auto meetsAt = [&](Real t) {
    const Vec3 a = a0 + dA * t, b = b0 + dB * t, cc = c0 + dC * t;
    Vec3 barycentric;
    if (!projectOntoTriangle(p, a, b, cc, barycentric)) {
      return false;
    }
    const Real slack = kOverlapTolerance;
    if (barycentric.x < -slack || barycentric.y < -slack || barycentric.z < -slack) {
      return false;
    }
    const Vec3 onTriangle = a * barycentric.x + b * barycentric.y + cc * barycentric.z;
    if (length(onTriangle - p) > kOverlapTolerance * size) {
      return false;
    }
    result.hit = true;
    result.t = t;
    result.barycentric = barycentric;
    return true;
  };

  firstMeeting(c, coplanarTolerance, meetsAt);
  return result;
}

EdgeEdgeCcd edgeEdgeCcd(const Vec3& p0, const Vec3& p1, const Vec3& e0a, const Vec3& e1a, const Vec3& e0b,
                        const Vec3& e1b) {
  EdgeEdgeCcd result;
  // With the first edge still, coplanarity det(D, E0(t), E1(t)) is quadratic in t.
  const Vec3 D = p1 - p0;
  const Vec3 E0 = e0a - p0, E1 = e1a - p0;
  const Vec3 dE0 = e0b - e0a, dE1 = e1b - e1a;
  const Real c[4] = {determinant(D, E0, E1), determinant(D, E0, dE1) + determinant(D, dE0, E1),
                     determinant(D, dE0, dE1), 0};
  const Real size = std::max({length(D), length(E0), length(E1), length(E0 + dE0), length(E1 + dE1),
                              Real(1e-300)});
  const Real coplanarTolerance = kCoplanarTolerance * cube(size);

  auto meetsAt = [&](Real t) {
    const Vec3 q0 = e0a + dE0 * t, q1 = e1a + dE1 * t;
    Real u = 0, s = 0;
    closestPointsOfSegments(p0, p1, q0, q1, u, s);
    const Vec3 onStatic = p0 + D * u;
    const Vec3 onMoving = q0 + (q1 - q0) * s;
    if (length(onStatic - onMoving) > kOverlapTolerance * size) {
      return false;
    }
    result.hit = true;
    result.t = t;
    result.s = s;
    result.u = u;
    return true;
  };

  firstMeeting(c, coplanarTolerance, meetsAt);
  return result;
}

}  // namespace thintool
