// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The scenes' measures of a box-shaped tool against a soft surface: the evaluation suite's ground
/// truth (eval/GroundTruth.h), the one every table of the project is judged by, for one box. It
/// works from positions alone and never calls ThinTool's detection, so that it judges stock Bullet
/// and ThinTool alike.

#include "GroundTruth.h"

#include <array>
#include <optional>
#include <vector>

namespace thintool::scenes {

struct Point {
  double x = 0, y = 0, z = 0;
};

/// A box-shaped tool: its pose (rotation rows and origin) and half extents.
struct ToolBox {
  std::array<Point, 3> rotationRows{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Point origin;
  Point halfExtents;

  Point toLocal(const Point& world) const;
  Pose pose() const;
};

/// Measures of one run, as eval::GroundTruthRun defines them.
struct RunMetrics {
  int crossed = 0;             ///< distinct nodes that passed through the tool
  int stillCrossed = 0;        ///< of those, on the far side of the tool's mid-surface, within it, at the end
  double maxPenetration = 0;   ///< deepest a node or face centroid lay inside the tool after a step (m)
  bool endsInside = false;     ///< the tool's centre ends inside the closed soft surface
  bool everInside = false;     ///< ... at the end of any step
  int insideSteps = 0;         ///< steps at whose end it was inside
  int piercedSteps = 0;        ///< steps that ended with a soft face deeper than 0.1 mm in the tool
};

/// Follows the soft surface against one box, step by step.
class BoxGroundTruth {
 public:
  /// Starts tracking the surface (nodes, faces): closed (a ball, whose inside the tool must not
  /// reach) or open (a sheet).
  void start(const ToolBox& tool, const std::vector<Point>& nodes, const std::vector<std::array<int, 3>>& faces,
             bool closedSurface = true);
  /// Call after every step with the tool's pose and the nodes' positions.
  void update(const ToolBox& tool, const std::vector<Point>& nodes, const std::vector<std::array<int, 3>>& faces);
  const RunMetrics& metrics() const { return m_metrics; }

 private:
  std::optional<eval::GroundTruth> m_truth;
  std::vector<Vec3> m_nodes;
  RunMetrics m_metrics;
};

}  // namespace thintool::scenes
