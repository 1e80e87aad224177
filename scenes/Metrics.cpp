// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "Metrics.h"

#include <algorithm>
#include <cmath>

namespace thintool::scenes {

namespace {

Point minus(const Point& a, const Point& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dotP(const Point& a, const Point& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point crossP(const Point& a, const Point& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Six times the signed volume of tetrahedron (a, b, c, d).
double orient(const Point& a, const Point& b, const Point& c, const Point& d) {
  return dotP(minus(b, a), crossP(minus(c, a), minus(d, a)));
}
int sign(double v) { return (v > 0) - (v < 0); }

}  // namespace

Point ToolBox::toLocal(const Point& world) const {
  // rotationRows are the rows of the tool's rotation R; local = Rᵀ·(world - origin).
  const Point d = minus(world, origin);
  const auto& r = rotationRows;
  return {r[0].x * d.x + r[1].x * d.y + r[2].x * d.z, r[0].y * d.x + r[1].y * d.y + r[2].y * d.z,
          r[0].z * d.x + r[1].z * d.y + r[2].z * d.z};
}

bool insideClosedSurface(const Point& point, const std::vector<Point>& vertices,
                         const std::vector<std::array<int, 3>>& triangles) {
  // An irregular direction makes passing exactly through an edge or a vertex improbable.
  const Point far{point.x + 1000 * 0.2360679, point.y + 1000 * 0.9417518, point.z + 1000 * 0.2393041};
  int crossings = 0;
  for (const auto& t : triangles) {
    const Point& a = vertices[t[0]];
    const Point& b = vertices[t[1]];
    const Point& c = vertices[t[2]];
    if (sign(orient(point, a, b, c)) == sign(orient(far, a, b, c))) {
      continue;
    }
    const int s0 = sign(orient(point, far, a, b));
    const int s1 = sign(orient(point, far, b, c));
    const int s2 = sign(orient(point, far, c, a));
    if (s0 != 0 && s0 == s1 && s1 == s2) {
      ++crossings;
    }
  }
  return crossings % 2 == 1;
}

bool CrossingTracker::inFootprint(const ToolBox& tool, const Point& local) const {
  // A node on a side face (to a micrometre) is beside the tool, not over it: one held there with
  // no skin slides up the rim without crossing.
  constexpr double kOnSide = 1e-6;  // m
  return std::abs(local.x) < tool.halfExtents.x - kOnSide && std::abs(local.z) < tool.halfExtents.z - kOnSide;
}

void CrossingTracker::start(const ToolBox& tool, const std::vector<Point>& nodes, double ballCentreHeight) {
  m_metrics = RunMetrics{};
  m_previousLocal.resize(nodes.size());
  m_crossed.assign(nodes.size(), 0);
  m_cap.assign(nodes.size(), 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    m_previousLocal[i] = tool.toLocal(nodes[i]);
    if (inFootprint(tool, m_previousLocal[i]) && nodes[i].y > ballCentreHeight) {
      m_cap[i] = 1;
      ++m_metrics.capNodes;
    }
  }
}

void CrossingTracker::update(const ToolBox& tool, const std::vector<Point>& nodes,
                             const std::vector<std::array<int, 3>>& faces) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Point now = tool.toLocal(nodes[i]);
    const Point& before = m_previousLocal[i];
    if (before.y < 0 && inFootprint(tool, now)) {
      // Still on the contact side a step ago: how far past the underside is it now?
      m_metrics.maxPenetration = std::max(m_metrics.maxPenetration, now.y + tool.halfExtents.y);
    }
    if (before.y < 0 && now.y > 0 && !m_crossed[i]) {
      // Where the node passed the mid-plane, by linear interpolation between the two steps.
      const double s = before.y / (before.y - now.y);
      const Point at{before.x + s * (now.x - before.x), 0, before.z + s * (now.z - before.z)};
      if (inFootprint(tool, at)) {
        m_crossed[i] = 1;
        ++m_metrics.crossed;
        m_metrics.capCrossed += m_cap[i];
      }
    }
    m_previousLocal[i] = now;
  }
  m_metrics.stillCrossed = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    m_metrics.stillCrossed += m_crossed[i] && m_previousLocal[i].y > 0 && inFootprint(tool, m_previousLocal[i]);
  }
  m_metrics.endsInside = insideClosedSurface(tool.origin, nodes, faces);
  m_metrics.everInside = m_metrics.everInside || m_metrics.endsInside;
  m_metrics.insideSteps += m_metrics.endsInside ? 1 : 0;
}

}  // namespace thintool::scenes
