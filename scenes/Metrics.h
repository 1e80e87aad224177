// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Ground-truth measures of a thin tool against a soft surface, computed from positions alone
/// and independent of ThinTool's detection code (their own geometry, their own tolerances), so
/// that they can judge stock Bullet and ThinTool alike.

#include <array>
#include <vector>

namespace thintool::scenes {

struct Point {
  double x = 0, y = 0, z = 0;
};

/// A box-shaped tool: its pose (rotation rows and origin) and half extents; y is the thin axis
/// the crossing measures use.
struct ToolBox {
  std::array<Point, 3> rotationRows{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Point origin;
  Point halfExtents;

  Point toLocal(const Point& world) const;
};

/// Whether point lies inside the closed surface (vertices, triangles), by the parity of the
/// crossings of a ray in a fixed, deliberately irregular direction, counted with signed volumes.
bool insideClosedSurface(const Point& point, const std::vector<Point>& vertices,
                         const std::vector<std::array<int, 3>>& triangles);

/// Measures of one run (baseline.md's definitions).
struct RunMetrics {
  int crossed = 0;      ///< nodes that went from below the tool's mid-plane to above it, inside its footprint
  int capNodes = 0;     ///< upper-cap nodes under the footprint when the tool started moving
  int capCrossed = 0;   ///< of those, how many crossed
  double maxPenetration = 0;  ///< deepest a node coming from below got past the underside (m)
  bool endsInside = false;    ///< the tool's centre ends inside the closed soft surface
  bool everInside = false;    ///< ... at the end of any step
  int insideSteps = 0;        ///< steps at whose end it was inside
  int stillCrossed = 0;       ///< crossed nodes that are on the far side of the mid-plane, in the footprint, at the end
};

/// Follows the soft nodes step by step in the tool's frame.
class CrossingTracker {
 public:
  /// Starts tracking; ballCentreHeight splits the ball's upper cap from the rest.
  void start(const ToolBox& tool, const std::vector<Point>& nodes, double ballCentreHeight);
  /// Call after every step with the tool's pose and the nodes' positions.
  void update(const ToolBox& tool, const std::vector<Point>& nodes, const std::vector<std::array<int, 3>>& faces);
  const RunMetrics& metrics() const { return m_metrics; }

 private:
  bool inFootprint(const ToolBox& tool, const Point& local) const;
  std::vector<Point> m_previousLocal;
  std::vector<char> m_crossed;
  std::vector<char> m_cap;
  RunMetrics m_metrics;
};

}  // namespace thintool::scenes
